"""`hardware.run`: one run end to end from a typed request to a typed report."""

import math

import numpy as np
import pytest

from hardware import CANTimeoutError, RunReport, RunRequest, read_run_log, run
from iik.errors import IIKError, InvalidInputError


def test_run_demo_on_the_simulated_arm(tmp_path):
    notes, steps = [], []
    report = run(RunRequest(demo=True, sim_start="plan", out=tmp_path, figures=False),
                 notify=notes.append, progress=lambda k, n: steps.append((k, n)))
    assert isinstance(report, RunReport)
    n = len(report.targets)
    assert steps == [(k, n - 1) for k in range(1, n)]
    assert any("validated" in t for t in notes)
    assert read_run_log(report.result.log_path).status == "ok"
    a = report.analysis
    assert len(a.steps) == n and a.start_ee_error < 1e-4 and a.final_ee_error < 1e-4
    assert report.rests is not None and 0 <= report.rests <= report.step_changes == 6 * (n - 2)
    assert report.figures == ()
    text = report.summary()
    assert "end-effector error: max" in text and str(report.result.log_path) in text


@pytest.mark.parametrize(("kwargs", "argument"), [
    ({}, "run"),
    ({"demo": True, "scenario": "j"}, "run"),
    ({"demo": True, "early": 0.0}, "early"),
    ({"demo": True, "early": math.nan}, "early"),
    ({"demo": True, "speed": 1.5}, "speed"),
    ({"demo": True, "margin": -0.01}, "margin"),
    ({"demo": True, "lag": -1.0}, "lag"),
    ({"demo": True, "timeout": 0.0}, "timeout"),
    ({"demo": True, "modules": (1, 2, 3, 4, 5)}, "modules"),
    ({"demo": True, "modules": (0, 1, 2, 3, 4, 5)}, "modules"),
    ({"demo": True, "update": "eager"}, "update"),
    ({"demo": True, "sim_start": "middle"}, "sim_start"),
])
def test_request_refuses_bad_options_by_name(kwargs, argument):
    with pytest.raises(InvalidInputError) as info:
        RunRequest(**kwargs)
    assert info.value.argument == argument


def test_run_refuses_before_touching_the_bus(tmp_path):
    """A trajectory outside Table I is refused by validation: no log, no bus opened."""
    q = np.zeros((3, 6))
    q[2, 0] = 4.0  # rad, outside Table I
    path = tmp_path / "bad.csv"
    np.savetxt(path, np.column_stack([np.arange(3) * 1.0, q]), delimiter=",",
               header="t,q1,q2,q3,q4,q5,q6", comments="")
    with pytest.raises(IIKError, match="Table I"):
        run(RunRequest(trajectory=path, interface="no-such-interface", channel="x", out=tmp_path))
    assert not (tmp_path / "bad.jsonl").exists()


def test_run_on_an_empty_bus_raises_a_typed_timeout(tmp_path):
    req = RunRequest(demo=True, interface="virtual", channel=f"empty-{tmp_path.name}", timeout=0.05,
                     out=tmp_path)
    assert req.where == f"virtual:empty-{tmp_path.name}" and not req.simulated
    with pytest.raises(CANTimeoutError):
        run(req)
