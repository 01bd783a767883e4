"""The simulated arm in a separate process (``iik sim-arm``) on ``udp_multicast``."""

import os
import random
import subprocess
import sys
import time

import numpy as np
import pytest

import iik
from hardware import PowerCubeArm, execute, read_run_log, validate
from hardware.executor import ExecutionOptions, time_steps

GROUP = "239.74.163.2"


def _multicast_available(port: int) -> str | None:
    try:
        import can

        a = can.Bus(interface="udp_multicast", channel=GROUP, port=port)
        b = can.Bus(interface="udp_multicast", channel=GROUP, port=port)
        try:
            a.send(can.Message(arbitration_id=0x7FF, data=[1], is_extended_id=False))
            t0 = time.monotonic()
            while time.monotonic() - t0 < 1.0:
                f = b.recv(0.2)
                if f is not None and f.arbitration_id == 0x7FF:
                    return None
            return "multicast loopback delivers nothing"
        finally:
            a.shutdown()
            b.shutdown()
    except (OSError, ImportError) as exc:
        return f"udp_multicast unavailable: {exc}"


@pytest.fixture
def sim_process():
    port = random.randint(20000, 60000)
    reason = _multicast_available(port)
    if reason:
        pytest.skip(reason)
    env = dict(os.environ, PYTHONUNBUFFERED="1")
    proc = subprocess.Popen(
        [sys.executable, "-m", "iik.cli", "sim-arm", "--interface", "udp_multicast", "--channel", GROUP,
         "--port", str(port), "--lag", "0.01", "--duration", "60"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    try:
        line = proc.stdout.readline()
        assert "sim-arm ready" in line, (line, proc.stderr.read() if proc.poll() is not None else "")
        yield port
    finally:
        proc.terminate()
        try:
            proc.wait(timeout=5)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()


def test_separate_process_on_udp_multicast(sim_process, tmp_path):
    port = sim_process
    with PowerCubeArm.from_interface(interface="udp_multicast", channel=GROUP, port=port,
                                     timeout=0.2) as arm:
        assert len(arm.open()) == 6
        assert sorted(arm.scan(range(1, 9), timeout=0.1)) == [1, 2, 3, 4, 5, 6]
        q0 = arm.get_pos()
        np.testing.assert_allclose(q0, 0.0)
        q = np.linspace(0, 1, 4)[:, None] * np.array([0.05, -0.05, 0.05, 0.05, 0.1, 0.05])
        tr = validate(time_steps(q, min_step=0.05), q, iik.fk(q))
        execute(arm, tr, tmp_path / "udp.jsonl", options=ExecutionOptions(settle=0.1))
        np.testing.assert_allclose(arm.get_pos(), q[-1], atol=1e-6)
    run = read_run_log(tmp_path / "udp.jsonl")
    assert run.status == "ok"
