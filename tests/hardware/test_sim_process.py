"""The simulated arm in a separate process (``iik sim-arm``) on ``udp_multicast``."""

import numpy as np

import iik
from hardware import PowerCubeArm, execute, read_run_log, validate
from hardware.executor import ExecutionOptions, time_steps
from iik import THESIS_ARM


def test_separate_process_on_udp_multicast(udp_bus, tmp_path):
    udp_bus.start_sim()
    with PowerCubeArm.from_interface(interface="udp_multicast", channel=udp_bus.group, port=udp_bus.port,
                                     timeout=0.2, arm=THESIS_ARM) as arm:
        assert len(arm.open()) == 6
        assert sorted(arm.scan(range(1, 9), timeout=0.1)) == [1, 2, 3, 4, 5, 6]
        q0 = arm.get_pos()
        np.testing.assert_allclose(q0, 0.0)
        q = np.linspace(0, 1, 4)[:, None] * np.array([0.05, -0.05, 0.05, 0.05, 0.1, 0.05])
        tr = validate(time_steps(q, min_step=0.05, arm=THESIS_ARM), q, iik.fk(q, THESIS_ARM), arm=THESIS_ARM)
        execute(arm, tr, tmp_path / "udp.jsonl", options=ExecutionOptions(settle=0.1))
        np.testing.assert_allclose(arm.get_pos(), q[-1], atol=1e-6)
    run = read_run_log(tmp_path / "udp.jsonl")
    assert run.status == "ok"
