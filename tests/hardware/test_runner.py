"""`hardware.run(targets, bus, options, log)`: one run end to end, from step targets to a typed report.

The simulated arm is just another bus (``BusConfig.simulated``); its clock is a :class:`VirtualClock`
shared with the executor, so the runs are exact and take the time of their requests, not of their motion.
"""

import math
import re

import numpy as np
import pytest

from hardware import (
    BusConfig,
    CANTimeoutError,
    ExecutionOptions,
    RunOptions,
    RunReport,
    SimConfig,
    ValidationOptions,
    VirtualClock,
    read_run_log,
    run,
)
from hardware.sources import csv_trajectory, demo_trajectory
from iik import THESIS_ARM
from iik.errors import IIKError, InvalidInputError

ARM = THESIS_ARM  # a trajectory file and the demo do not name their arm
#: Samples every 30 ms of simulated time (as iik verify's runs): each costs 24 round trips of real time.
SAMPLED = ExecutionOptions(sample_period=0.03)
QUIET = RunOptions(execution=SAMPLED, figures=False)


@pytest.fixture(scope="module")
def demo():
    return demo_trajectory(ARM)


def simulated(targets=None, *, lag: float = 0.02, **kwargs) -> BusConfig:
    """Simulated modules on a private virtual channel and a virtual clock, starting at the first target
    (``targets``) or at home (None)."""
    initial = None if targets is None else tuple(targets.q[0])
    return BusConfig.simulated(SimConfig(lag=lag, initial=initial, clock=VirtualClock()), **kwargs)


def test_run_demo_on_the_simulated_arm(tmp_path, demo):
    notes, steps = [], []
    report = run(demo, simulated(demo), QUIET, tmp_path, notify=notes.append,
                 progress=lambda k, n: steps.append((k, n)))
    assert isinstance(report, RunReport)
    n = len(report.targets)
    assert steps == [(k, n - 1) for k in range(1, n)]
    assert any("validated" in t for t in notes) and not any("watchdog" in t for t in notes)
    log = read_run_log(report.result.log_path)
    assert log.status == "ok" and log.header["watchdog"] is False  # the default option
    a = report.analysis
    assert len(a.steps) == n and a.start_ee_error < 1e-4 and a.final_ee_error < 1e-4
    assert report.rests is not None and 0 <= report.rests <= report.step_changes == 6 * (n - 2)
    assert report.figures == ()
    assert report.zone == 0.010 and report.ok == (a.max_ee_error <= 0.010)
    text = report.summary()
    assert "end-effector error: max" in text and str(report.result.log_path) in text
    assert text.splitlines()[-1].startswith(f"status: {report.status} (max end-effector error")


def test_the_executor_runs_on_the_simulators_clock(tmp_path, demo):
    """The run's duration is the schedule of Sec 4.3 exactly (every command after 95 % of the previous
    step, the last step whole, then the settle time): host and modules share the virtual clock, on which
    round trips take no time. On real time it would be longer by every round trip."""
    report = run(demo, simulated(demo), QUIET, tmp_path)
    dt = np.diff(report.targets.times)
    settle = SAMPLED.settle
    expected = 0.95 * dt[:-1].sum() + dt[-1] + settle
    assert report.result.duration == pytest.approx(expected, abs=1e-6)
    assert report.rests == 0  # commands arrive exactly at 95 %: no joint ever stops between steps


def test_an_error_beyond_the_zone_is_not_ok(tmp_path, demo):
    """The run goes to the end, but its error leaves the zone: status 'outside zone'."""
    report = run(demo, simulated(demo, lag=0.2), QUIET, tmp_path)
    assert read_run_log(report.result.log_path).status == "ok"  # executed to the end ...
    assert report.analysis.max_ee_error > 0.010  # ... 0.2 s behind the set-point: far off
    assert not report.ok and report.status == "outside zone"
    assert "status: outside zone" in report.summary() and "OUTSIDE the 10 mm zone" in report.summary()
    wide = run(demo, simulated(demo, lag=0.2), RunOptions(execution=SAMPLED, zone=1.0, figures=False),
               tmp_path)
    assert wide.analysis.max_ee_error == pytest.approx(report.analysis.max_ee_error, abs=1e-9)  # exact
    assert wide.ok == (wide.analysis.max_ee_error <= 1.0)


@pytest.mark.parametrize(("build", "argument"), [
    (lambda: ExecutionOptions(early=0.0), "early"),
    (lambda: ExecutionOptions(early=math.nan), "early"),
    (lambda: ExecutionOptions(update="eager"), "update"),
    (lambda: ExecutionOptions(watchdog="yes"), "watchdog"),
    (lambda: ValidationOptions(margin=-0.01), "margin"),
    (lambda: ValidationOptions(margin=math.nan), "margin"),
    (lambda: ValidationOptions(margin=math.inf), "margin"),
    (lambda: RunOptions(zone=0.0), "zone"),
    (lambda: RunOptions(zone=math.nan), "zone"),
    (lambda: RunOptions(reset="no"), "reset"),
    (lambda: RunOptions(execution={"early": 0.9}), "execution"),
    (lambda: SimConfig(lag=-1.0), "lag"),
    (lambda: SimConfig(lag=math.nan), "lag"),
    (lambda: SimConfig(lag=5.0), "lag"),
    (lambda: SimConfig(initial=(0.0, math.nan)), "initial"),
    (lambda: SimConfig(clock=lambda: 0.0), "clock"),
    (lambda: BusConfig.simulated(SimConfig(initial=(0.0,) * 5)), "initial"),
    (lambda: BusConfig("virtual", timeout=0.0), "timeout"),
    (lambda: BusConfig("virtual", timeout=math.inf), "timeout"),
    (lambda: BusConfig("virtual", timeout=1e6), "timeout"),
    (lambda: BusConfig("virtual", bitrate=-5), "bitrate"),
    (lambda: BusConfig("virtual", bitrate=300_000), "bitrate"),
    (lambda: BusConfig("virtual", port=0), "port"),
    (lambda: BusConfig("virtual", port=70_000), "port"),
    (lambda: BusConfig("virtual", module_ids=(1, 1, 2, 3, 4, 5)), "module_ids"),
    (lambda: BusConfig("virtual", module_ids=(0, 1, 2, 3, 4, 5)), "module_ids"),
    (lambda: BusConfig("virtual", module_ids=()), "module_ids"),
    (lambda: BusConfig(""), "interface"),
    (lambda: BusConfig("virtual", channel=1.5), "channel"),
    (lambda: BusConfig("virtual", sim={"lag": 0.1}), "sim"),
])
def test_options_and_bus_configs_refuse_bad_values_by_name(build, argument):
    with pytest.raises(InvalidInputError) as info:
        build()
    assert info.value.argument == argument


@pytest.mark.parametrize(("build", "unit"), [
    (lambda: BusConfig("virtual", timeout=0.0), " s,"), (lambda: SimConfig(lag=-1.0), " s,"),
    (lambda: RunOptions(zone=2.0), " m,"), (lambda: ValidationOptions(margin=-0.01), "deg"),
    (lambda: BusConfig("virtual", bitrate=-5), "bit/s"),
])
def test_option_errors_state_the_units(build, unit):
    with pytest.raises(InvalidInputError, match=re.escape(unit)):
        build()


def test_bus_configs_say_where_the_modules_are():
    sim = BusConfig.simulated()
    assert sim.ack_timeout == 2.0 and sim.where == "simulated arm (in-process, virtual bus)"
    assert sim.private().channel.startswith("iik-sim-") and sim.private() != sim.private()  # fresh each time
    can0 = BusConfig("socketcan", "can0", bitrate=500_000)
    assert can0.ack_timeout == 0.1 and can0.where == "socketcan:can0" and can0.private() is can0
    assert BusConfig("socketcan", "can0", timeout=0.5).ack_timeout == 0.5


def test_run_refuses_what_it_cannot_run_by_name(tmp_path, demo):
    with pytest.raises(InvalidInputError) as info:
        run(demo, simulated(module_ids=(1, 2, 3, 4, 5)), QUIET, tmp_path)
    assert info.value.argument == "module_ids" and "one module per joint" in info.value.reason
    with pytest.raises(InvalidInputError) as info:
        run(demo, {"interface": "virtual"}, QUIET, tmp_path)
    assert info.value.argument == "bus"
    assert not list(tmp_path.iterdir())


def test_a_named_log_is_written_exactly_and_a_folder_gets_new_names(tmp_path, demo):
    first = run(demo, simulated(demo), QUIET, tmp_path)
    second = run(demo, simulated(demo), QUIET, tmp_path)
    a, b = first.result.log_path, second.result.log_path
    assert a != b and a.parent == b.parent == tmp_path and a.exists() and b.exists()
    assert re.fullmatch(r"demo-\d{8}-\d{6}(-\d+)?\.jsonl", a.name), a.name
    named = tmp_path / "sub" / "mine.jsonl"
    third = run(demo, simulated(demo), RunOptions(execution=SAMPLED), named)
    assert third.result.log_path == named and read_run_log(named).status == "ok"
    stems = ("joint_error", "ee_error", "velocity")
    assert {p.name for p in third.figures} == {f"mine_{s}.png" for s in stems}
    assert all(p.parent == named.parent for p in third.figures)


def test_the_log_records_the_targets_times(tmp_path, demo):
    slow = demo.slowed(0.5)
    report = run(slow, simulated(slow), QUIET, tmp_path)
    assert report.targets is slow
    header = read_run_log(report.result.log_path).header
    np.testing.assert_allclose(header["times"], slow.times - slow.times[0])


def test_run_refuses_before_touching_the_bus(tmp_path):
    """A trajectory outside Table I is refused by validation: no log, no bus opened."""
    q = np.zeros((3, 6))
    q[2, 0] = 4.0  # rad, outside Table I
    path = tmp_path / "bad.csv"
    np.savetxt(path, np.column_stack([np.arange(3) * 1.0, q]), delimiter=",",
               header="t,q1,q2,q3,q4,q5,q6", comments="")
    with pytest.raises(IIKError, match="Table I"):
        run(csv_trajectory(path, ARM), BusConfig("no-such-interface", "x"), RunOptions(), tmp_path)
    assert not list(tmp_path.glob("*.jsonl"))


def test_run_on_an_empty_bus_raises_a_typed_timeout(tmp_path, demo):
    bus = BusConfig("virtual", f"empty-{tmp_path.name}", timeout=0.05)
    assert bus.where == f"virtual:empty-{tmp_path.name}" and bus.sim is None
    with pytest.raises(CANTimeoutError):
        run(demo, bus, QUIET, tmp_path)
    assert not list(tmp_path.glob("*.jsonl"))  # the reserved log name is given back: nothing ran


def test_rests_count_only_between_planned_steps(tmp_path, demo):
    """From the home pose the arm approaches the start and settles there: that rest is by design, not a
    rest between two planned steps. With one planned step there is no step change at all, so nothing
    to count (it used to say '6 times (of 0 step changes)')."""
    path = tmp_path / "one.csv"
    path.write_text("t,q1,q2,q3,q4,q5,q6\n0,0.1,0.1,0,0.4,1,0\n0.5,0.15,0.1,0,0.4,1,0\n")
    one = run(csv_trajectory(path, ARM), simulated(), QUIET, tmp_path)
    assert 0 in read_run_log(one.result.log_path).command_k  # the approach from home was commanded
    assert one.step_changes == 0 and one.rests == 0
    assert "one planned step: no step change for a joint to rest at" in one.summary()
    assert "of 0 step changes" not in one.summary()
    buffered = RunOptions(execution=ExecutionOptions(update="buffered", sample_period=0.03), figures=False)
    report = run(demo, simulated(), buffered, tmp_path)
    assert 0 in read_run_log(report.result.log_path).command_k
    assert report.rests == 0 <= report.step_changes == 6 * (len(demo) - 2)  # exact: no step is cut
    assert f"came to rest between two planned steps {report.rests} times (of {report.step_changes} step " \
           "changes; update buffered" in report.summary()
