"""`hardware.run`: one run end to end from a typed request to a typed report."""

import math
import re

import numpy as np
import pytest

from hardware import CANTimeoutError, RunReport, RunRequest, read_run_log, run
from iik import THESIS_ARM
from iik.errors import IIKError, InvalidInputError

ARM = THESIS_ARM  # a trajectory file and the demo do not name their arm


def test_run_demo_on_the_simulated_arm(tmp_path):
    notes, steps = [], []
    report = run(RunRequest(demo=True, sim_start="plan", out=tmp_path, figures=False, arm=ARM),
                 notify=notes.append, progress=lambda k, n: steps.append((k, n)))
    assert isinstance(report, RunReport)
    n = len(report.targets)
    assert steps == [(k, n - 1) for k in range(1, n)]
    assert any("validated" in t for t in notes) and not any("watchdog" in t for t in notes)
    assert read_run_log(report.result.log_path).status == "ok"
    assert read_run_log(report.result.log_path).header["watchdog"] is False  # off when simulated
    a = report.analysis
    assert len(a.steps) == n and a.start_ee_error < 1e-4 and a.final_ee_error < 1e-4
    assert report.rests is not None and 0 <= report.rests <= report.step_changes == 6 * (n - 2)
    assert report.figures == ()
    assert report.zone == 0.010 and report.ok == (a.max_ee_error <= 0.010)
    text = report.summary()
    assert "end-effector error: max" in text and str(report.result.log_path) in text
    assert text.splitlines()[-1].startswith(f"status: {report.status} (max end-effector error")


def test_an_error_beyond_the_zone_is_not_ok(tmp_path):
    """The run goes to the end, but its error leaves the zone: status 'outside zone'."""
    report = run(RunRequest(demo=True, sim_start="plan", lag=0.2, out=tmp_path, figures=False, arm=ARM))
    assert read_run_log(report.result.log_path).status == "ok"  # executed to the end ...
    assert report.analysis.max_ee_error > 0.010  # ... 0.2 s behind the set-point: far off
    assert not report.ok and report.status == "outside zone"
    assert "status: outside zone" in report.summary() and "OUTSIDE the 10 mm zone" in report.summary()
    wide = run(RunRequest(demo=True, sim_start="plan", lag=0.2, zone=1.0, out=tmp_path, figures=False,
                          arm=ARM))
    assert wide.ok == (wide.analysis.max_ee_error <= 1.0)


@pytest.mark.parametrize(("kwargs", "argument"), [
    ({}, "run"),
    ({"demo": True, "scenario": "j"}, "run"),
    ({"demo": True, "early": 0.0}, "early"),
    ({"demo": True, "early": math.nan}, "early"),
    ({"demo": True, "speed": 1.5}, "speed"),
    ({"demo": True, "speed": 0.0}, "speed"),
    ({"demo": True, "speed": math.nan}, "speed"),
    ({"demo": True, "margin": -0.01}, "margin"),
    ({"demo": True, "margin": math.nan}, "margin"),
    ({"demo": True, "margin": math.inf}, "margin"),
    ({"demo": True, "lag": -1.0}, "lag"),
    ({"demo": True, "lag": math.nan}, "lag"),
    ({"demo": True, "lag": 5.0}, "lag"),
    ({"demo": True, "timeout": 0.0}, "timeout"),
    ({"demo": True, "timeout": math.inf}, "timeout"),
    ({"demo": True, "timeout": 1e6}, "timeout"),
    ({"demo": True, "bitrate": -5}, "bitrate"),
    ({"demo": True, "bitrate": 300_000}, "bitrate"),
    ({"demo": True, "port": 0}, "port"),
    ({"demo": True, "port": 70_000}, "port"),
    ({"demo": True, "zone": 0.0}, "zone"),
    ({"demo": True, "zone": math.nan}, "zone"),
    ({"demo": True, "watchdog": "yes"}, "watchdog"),
    ({"demo": True, "modules": (1, 2, 3, 4, 5)}, "modules"),
    ({"demo": True, "modules": (0, 1, 2, 3, 4, 5)}, "modules"),
    ({"demo": True, "update": "eager"}, "update"),
    ({"demo": True, "sim_start": "middle"}, "sim_start"),
])
def test_request_refuses_bad_options_by_name(kwargs, argument):
    with pytest.raises(InvalidInputError) as info:
        RunRequest(**kwargs)
    assert info.value.argument == argument


@pytest.mark.parametrize(("kwargs", "unit"), [
    ({"timeout": 0.0}, " s,"), ({"lag": -1.0}, " s,"), ({"zone": 2.0}, " m,"), ({"margin": -0.01}, "deg"),
    ({"bitrate": -5}, "bit/s"),
])
def test_option_errors_state_the_units(kwargs, unit):
    with pytest.raises(InvalidInputError, match=re.escape(unit)):
        RunRequest(demo=True, **kwargs)


def test_watchdog_is_on_by_default_on_a_bus_only():
    assert RunRequest(demo=True, arm=ARM).watchdog_on is False  # in-process simulation
    assert RunRequest(demo=True, interface="socketcan", channel="can0", arm=ARM).watchdog_on is True
    off = RunRequest(demo=True, interface="socketcan", channel="can0", watchdog=False, arm=ARM)
    assert off.watchdog_on is False


def test_run_logs_are_never_overwritten_unless_a_file_is_named(tmp_path):
    first = run(RunRequest(demo=True, sim_start="plan", out=tmp_path, figures=False, arm=ARM))
    second = run(RunRequest(demo=True, sim_start="plan", out=tmp_path, figures=False, arm=ARM))
    a, b = first.result.log_path, second.result.log_path
    assert a != b and a.parent == b.parent == tmp_path and a.exists() and b.exists()
    assert re.fullmatch(r"demo-\d{8}-\d{6}(-\d+)?\.jsonl", a.name), a.name
    named = tmp_path / "sub" / "mine.jsonl"
    third = run(RunRequest(demo=True, sim_start="plan", out=named, arm=ARM))
    assert third.result.log_path == named and read_run_log(named).status == "ok"
    stems = ("joint_error", "ee_error", "velocity")
    assert {p.name for p in third.figures} == {f"mine_{s}.png" for s in stems}
    assert all(p.parent == named.parent for p in third.figures)


def test_speed_slows_every_source(tmp_path):
    fast = run(RunRequest(demo=True, sim_start="plan", out=tmp_path, figures=False, arm=ARM))
    slow = run(RunRequest(demo=True, sim_start="plan", speed=0.5, out=tmp_path, figures=False, arm=ARM))
    np.testing.assert_allclose(np.diff(slow.targets.times), 2 * np.diff(fast.targets.times), atol=1e-9)
    header = read_run_log(slow.result.log_path).header
    np.testing.assert_allclose(header["times"], slow.targets.times - slow.targets.times[0])


def test_run_refuses_before_touching_the_bus(tmp_path):
    """A trajectory outside Table I is refused by validation: no log, no bus opened."""
    q = np.zeros((3, 6))
    q[2, 0] = 4.0  # rad, outside Table I
    path = tmp_path / "bad.csv"
    np.savetxt(path, np.column_stack([np.arange(3) * 1.0, q]), delimiter=",",
               header="t,q1,q2,q3,q4,q5,q6", comments="")
    with pytest.raises(IIKError, match="Table I"):
        run(RunRequest(trajectory=path, interface="no-such-interface", channel="x", out=tmp_path, arm=ARM))
    assert not list(tmp_path.glob("*.jsonl"))


def test_run_on_an_empty_bus_raises_a_typed_timeout(tmp_path):
    req = RunRequest(demo=True, interface="virtual", channel=f"empty-{tmp_path.name}", timeout=0.05,
                     out=tmp_path, arm=ARM)
    assert req.where == f"virtual:empty-{tmp_path.name}" and not req.simulated
    with pytest.raises(CANTimeoutError):
        run(req)
    assert not list(tmp_path.glob("*.jsonl"))  # the reserved log name is given back: nothing ran


def test_rests_count_only_between_planned_steps(tmp_path):
    """From the home pose the arm approaches the start and settles there: that rest is by design, not a
    rest between two planned steps. With one planned step there is no step change at all, so nothing
    to count, whatever the machine's load (it used to say '6 times (of 0 step changes)')."""
    path = tmp_path / "one.csv"
    path.write_text("t,q1,q2,q3,q4,q5,q6\n0,0.1,0.1,0,0.4,1,0\n0.5,0.15,0.1,0,0.4,1,0\n")
    one = run(RunRequest(trajectory=path, sim_start="home", out=tmp_path, figures=False, arm=ARM))
    assert 0 in read_run_log(one.result.log_path).command_k  # the approach from home was commanded
    assert one.step_changes == 0 and one.rests == 0
    assert "one planned step: no step change for a joint to rest at" in one.summary()
    assert "of 0 step changes" not in one.summary()
    demo = run(RunRequest(demo=True, sim_start="home", update="buffered", out=tmp_path, figures=False,
                          arm=ARM))
    assert 0 <= demo.rests <= demo.step_changes == 6 * (len(demo.targets) - 2)
    assert f"came to rest between two planned steps {demo.rests} times (of {demo.step_changes} step changes" \
        in demo.summary()
