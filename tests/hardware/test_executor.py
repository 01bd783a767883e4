"""Validation and execution: the early update, faults (halt + complete log), and a
property test that no out-of-limit target ever reaches the bus.

Executions run on a virtual clock shared by the simulated modules and the executor
(:class:`hardware.clock.VirtualClock`), so their timelines are exact whatever the machine's load;
only the watchdog (refreshed by python-can's own thread) and a killed process run on real time."""

import math
import threading
import time
from dataclasses import dataclass
from pathlib import Path

import can
import numpy as np
import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

import iik
from hardware import PowerCubeArm, SimulatedArm, execute, read_run_log, validate
from hardware import protocol as P
from hardware.clock import VirtualClock
from hardware.errors import (
    BusError,
    CANTimeoutError,
    DuplicateModuleError,
    ModuleFault,
    SafetyError,
    StopSignal,
)
from hardware.executor import ExecutionOptions, ValidatedTrajectory, ValidationOptions, time_steps
from iik import THESIS_ARM
from iik.files import PARTIAL_PREFIX
from verification.testing.polling import wait_until

ARM = iik.THESIS_ARM
QA = np.array([0.1, -0.3, 0.4, 0.5, -0.2, 0.7])
QB = np.array([0.3, -0.1, 0.2, 0.6, 0.1, 0.5])


def line(n=6, qa=QA, qb=QB, speed=0.5):
    q = qa + (qb - qa) * np.linspace(0, 1, n)[:, None]
    return time_steps(q, speed_fraction=speed, min_step=0.05, arm=ARM), q, iik.fk(q, THESIS_ARM)


FAST = ExecutionOptions(settle=0.05, sample_period=0.005)


# ----------------------------------------------------------------------------- validation
def test_validate_accepts_a_planned_line():
    t, q, T = line()
    tr = validate(t, q, T, arm=ARM)
    assert isinstance(tr, ValidatedTrajectory) and len(tr) == 6
    assert tr.times[0] == 0 and np.all(tr.step_ms >= 50)
    with pytest.raises(ValueError):
        tr.q[0, 0] = 1.0  # read-only
    with pytest.raises(AttributeError):
        tr.q = q


def test_validated_trajectory_cannot_be_built_directly():
    t, q, T = line()
    with pytest.raises(SafetyError):
        ValidatedTrajectory(_token=object(), times=t, q=q, poses=T, step_ms=t, arm=ARM, options=None)


@pytest.mark.parametrize("mutate,step,joint", [
    (lambda t, q, T: q.__setitem__((2, 1), math.nan), 2, 1),
    (lambda t, q, T: q.__setitem__((3, 3), ARM.upper[3] - 0.001), 3, 3),  # in Table I, not margin
    (lambda t, q, T: q.__setitem__((4, 0), ARM.upper[0] + 0.1), 4, 0),
    (lambda t, q, T: T.__setitem__((2, 0, 3), T[2, 0, 3] + 0.001), 2, None),  # FK != planned pose
    (lambda t, q, T: t.__setitem__(slice(3, None), t[3:] - t[3] + t[2] + 0.005), 3, None),  # 5 ms step
])
def test_validate_rejects(mutate, step, joint):
    """The refused target is named by step-point (counting from 0) and joint name (q1..q6)."""
    t, q, T = line()
    t, q, T = t.copy(), q.copy(), T.copy()
    mutate(t, q, T)
    if joint is not None and np.all(np.isfinite(q[step])):
        T[step] = iik.fk(q[step], THESIS_ARM)
    with pytest.raises(SafetyError) as ei:
        validate(t, q, T, arm=ARM)
    assert (ei.value.step, ei.value.joint) == (step, joint)
    named = f"step-point {step} (counting from 0)" + ("" if joint is None else f", joint q{joint + 1}")
    assert str(ei.value).startswith(named + ": ")


def test_step_times_are_compared_in_whole_milliseconds():
    """A step of 9.985 ms is 10 ms on the wire: accepted at a 10 ms minimum (the issue's
    "0.009985 s is shorter than 0.01 s"); 9.4 ms is 9 ms and refused, saying both."""
    t, q, T = line()
    q = q[0] + (q - q[0]) * 0.01  # slow enough for 10 ms steps
    T = iik.fk(q, THESIS_ARM)
    tr = validate(np.arange(len(t)) * 0.009985, q, T, arm=ARM)
    assert list(tr.step_ms) == [10] * (len(t) - 1)
    with pytest.raises(SafetyError, match=r"9\.400 ms, 9 ms on the wire \(whole ms\): shorter than the 10"):
        validate(np.arange(len(t)) * 0.0094, q, T, arm=ARM)


def test_validate_rejects_too_fast():
    t, q, T = line()
    t = t * 0.05  # 20x faster than half speed
    t[1:] = np.maximum(t[1:], np.arange(1, len(t)) * 0.011)
    with pytest.raises(SafetyError, match="rad/s"):
        validate(t, q, T, arm=ARM)


def test_execute_refuses_anything_else():
    t, q, T = line()
    with pytest.raises(SafetyError):
        execute(None, (t, q, T), "/dev/null")


# ----------------------------------------------------------------------------- execution
@dataclass
class Rig:
    """Simulated modules at QA and a host arm on a private virtual bus, one virtual clock for both."""

    sim: SimulatedArm
    arm: PowerCubeArm
    log: Path
    clock: VirtualClock

    def execute(self, tr, options=FAST, **kwargs):
        return execute(self.arm, tr, self.log, options=options, clock=self.clock.now, sleep=self.clock.sleep,
                       **kwargs)


@pytest.fixture
def rig(new_channel, tmp_path, virtual_clock, baseline_timeout, reply_timeout):
    """The fault tests wait out ACK timeouts in real time: the host's timeout is derived from round
    trips measured now (a loaded machine gets more), so that load never looks like a fault."""
    ch = new_channel()
    sim = SimulatedArm.virtual(ch, lag=0.01, initial=QA, arm=ARM, clock=virtual_clock.now)
    bus = can.Bus(interface="virtual", channel=ch)
    arm = PowerCubeArm(bus, (1, 2, 3, 4, 5, 6), timeout=reply_timeout, arm=ARM)
    arm.link.timeout = baseline_timeout(arm.get_pos, margin=25, floor=0.25)
    yield Rig(sim, arm, tmp_path / "run.jsonl", virtual_clock)
    sim.close()
    bus.shutdown()
    assert not sim.errors, sim.errors


def test_execute_streams_with_the_early_update(new_channel, tmp_path, virtual_clock):
    """On one virtual clock (round trips take no simulated time), so the schedule is exact
    whatever the machine's load."""
    clk = virtual_clock
    ch = new_channel()
    t, q, T = line()
    tr = validate(t, q, T, arm=ARM)
    with SimulatedArm.virtual(ch, lag=0.01, initial=QA, clock=clk.now, arm=ARM) as sim, \
            can.Bus(interface="virtual", channel=ch) as bus:
        arm = PowerCubeArm(bus, (1, 2, 3, 4, 5, 6), timeout=2.0, arm=ARM)
        res = execute(arm, tr, tmp_path / "run.jsonl", options=FAST, clock=clk.now, sleep=clk.sleep)
        run = read_run_log(tmp_path / "run.jsonl")
        assert run.status == "ok" and run.fault is None
        assert res.commands == len(tr) - 1 and list(run.command_k) == list(range(1, len(tr)))
        # Sec 4.3: each command follows the previous after exactly 95 % of its time
        gaps = np.diff(run.command_t)
        np.testing.assert_allclose(gaps, 0.95 * tr.step_ms[:-1] / 1000.0, atol=1e-9)
        np.testing.assert_allclose(sim.positions(), q[-1], atol=1e-6)
    # every FSTEP on the bus carried a validated target and its time
    steps = [m for _, m in sim.received() if isinstance(m, P.SetMove)]
    assert all(m.mode is P.Mode.FSTEP_EXT for m in steps) and len(steps) == 6 * (len(tr) - 1)
    starts = [m for _, m in sim.received() if isinstance(m, P.Broadcast) and m.cmd is P.Cmd.STARTMOVE]
    assert len(starts) == 6 * (len(tr) - 1)  # every module saw every STARTMOVE


def test_execute_approaches_the_start_first(new_channel, tmp_path, virtual_clock, reply_timeout):
    ch, clk = new_channel(), virtual_clock
    with SimulatedArm.virtual(ch, lag=0.01, arm=ARM, clock=clk.now) as sim, \
            can.Bus(interface="virtual", channel=ch) as bus:
        arm = PowerCubeArm(bus, (1, 2, 3, 4, 5, 6), timeout=reply_timeout, arm=ARM)
        t, q, T = line(4, qa=np.full(6, 0.05), qb=np.full(6, 0.1))
        tr = validate(t, q, T, arm=ARM)
        with pytest.raises(SafetyError):
            execute(arm, tr, tmp_path / "a.jsonl", options=ExecutionOptions(approach=False), clock=clk.now,
                    sleep=clk.sleep)
        execute(arm, tr, tmp_path / "b.jsonl", options=ExecutionOptions(settle=0.05, approach_speed=0.5),
                clock=clk.now, sleep=clk.sleep)
        np.testing.assert_allclose(sim.positions(), q[-1], atol=1e-6)
        run = read_run_log(tmp_path / "b.jsonl")
        assert run.command_k[0] == 0 and run.status == "ok"


def assert_halted_and_logged(sim, log, error, skip=()):
    def halted():  # HALT is a broadcast, without a reply: wait until the modules have read it
        return all(s & P.State.HALTED for mid, s in zip(sim.module_ids, sim.states(), strict=True)
                   if mid not in skip)

    assert wait_until(halted, 30.0, 0.002), f"not halted: {sim.states()!r}"
    run = read_run_log(log)  # parses: every line complete
    assert run.status == "fault" and run.complete
    assert run.fault["error"] == error and run.fault["halted"] is True
    assert run.records[-1]["type"] == "end"
    return run


@pytest.mark.parametrize("kind,kw,error", [
    ("drop_ack", {}, "CANTimeoutError"),
    ("late_ack", {"delay": 1.5}, "CANTimeoutError"),
    ("error", {"bits": P.State.POW_FET_TEMP}, "ModuleFault"),
])
def test_fault_halts_all_and_logs(rig, kind, kw, error):
    sim, log = rig.sim, rig.log
    tr = validate(*line(8), arm=ARM)
    sim.inject(3, kind, after_moves=3, **kw)  # late_ack: 1.5 s of the modules' time, which stands still
    # while a request waits
    exc_type = CANTimeoutError if error == "CANTimeoutError" else ModuleFault
    with pytest.raises(exc_type):
        rig.execute(tr)
    run = assert_halted_and_logged(sim, log, error)
    assert 2 <= len(run.command_k) <= 4  # stopped at the faulty command
    if kind == "error":
        assert sim.states()[2] & P.State.POW_FET_TEMP


def test_vanished_module_others_halted_and_it_stops_by_itself(rig):
    sim, log = rig.sim, rig.log
    tr = validate(*line(8), arm=ARM)
    sim.inject(4, "vanish", after_moves=3)
    with pytest.raises(CANTimeoutError):
        rig.execute(tr)
    assert_halted_and_logged(sim, log, "CANTimeoutError", skip=(4,))
    rig.clock.sleep(max(tr.step_ms) / 1000.0 + 0.05)  # a short FSTEP horizon: it finishes and stops
    assert not sim.moving()[3]


def test_keyboard_interrupt_halts_and_logs(rig):
    sim, log = rig.sim, rig.log
    tr = validate(*line(8), arm=ARM)

    def progress(k, n):
        if k == 3:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        rig.execute(tr, progress=progress)
    assert_halted_and_logged(sim, log, "KeyboardInterrupt")


def test_can_error_halts_and_logs(rig):
    sim, arm, log = rig.sim, rig.arm, rig.log
    tr = validate(*line(8), arm=ARM)
    real_send = arm.bus.send
    calls = {"n": 0}

    def flaky_send(msg, timeout=None):
        calls["n"] += 1
        if calls["n"] == 60:
            raise can.CanOperationError("simulated controller error")
        return real_send(msg, timeout)

    arm.bus.send = flaky_send
    with pytest.raises(BusError):
        rig.execute(tr)
    assert_halted_and_logged(sim, log, "BusError")


def test_duplicate_module_mid_run_halts_and_logs(rig):
    sim, arm, log = rig.sim, rig.arm, rig.log
    tr = validate(*line(8), arm=ARM)
    extra = []

    def progress(k, n):
        if k == 2:  # a second module with id 4 appears on the bus (a wiring fault)
            extra.append(SimulatedArm.virtual(arm.bus.channel_id, (4,), initial=tr.q[2, 3:4], arm=ARM))

    try:
        with pytest.raises(DuplicateModuleError) as info:
            rig.execute(tr, progress=progress)
    finally:
        for s in extra:
            s.close()
    assert info.value.module_id == 4
    assert_halted_and_logged(sim, log, "DuplicateModuleError")


def test_stop_signal_halts_and_logs(rig):
    """SIGTERM during execute() takes the Ctrl-C path: HALT, fault and end records."""
    import os
    import signal

    if threading.current_thread() is not threading.main_thread():
        pytest.skip("signal handlers can only be installed in the main thread")
    sim, log = rig.sim, rig.log
    tr = validate(*line(8), arm=ARM)

    def progress(k, n):
        if k == 3:
            os.kill(os.getpid(), signal.SIGTERM)

    before = signal.getsignal(signal.SIGTERM)
    with pytest.raises(StopSignal) as info:
        rig.execute(tr, progress=progress)
    assert info.value.signum == signal.SIGTERM and isinstance(info.value, KeyboardInterrupt)
    run = assert_halted_and_logged(sim, log, "StopSignal")
    assert run.fault["message"] == "stopped by SIGTERM"
    assert signal.getsignal(signal.SIGTERM) is before  # the previous handler is back


def test_a_trajectory_faster_than_a_modules_own_limit_is_refused_before_start(rig):
    sim, arm, log = rig.sim, rig.arm, rig.log
    tr = validate(*line(6, speed=0.8), arm=ARM)
    arm.modules[2].set_max_vel(0.05)  # module 3 configured far below Sec 3.2
    with pytest.raises(SafetyError, match=r"joint q3: the step to it needs more than module 3's speed limit"):
        rig.execute(tr)
    assert not log.exists() and not [m for _, m in sim.received() if isinstance(m, P.SetMove)]


def test_run_log_survives_without_end_record(rig):
    log = rig.log
    tr = validate(*line(4), arm=ARM)
    rig.execute(tr)
    lines = log.read_text().splitlines()
    log.write_text("\n".join(lines[:-1]) + "\n")  # as if the process died
    run = read_run_log(log)
    assert not run.complete and len(run.samples_t) > 0


# ----------------------------------------------------------------------------- property
def _spy(bus, sent):
    real = bus.send

    def send(msg, timeout=None):
        sent.append(msg)
        return real(msg, timeout)

    bus.send = send


def _joint_value(j):
    """Mostly inside Table I, sometimes within 0.03 rad of a limit (inside or outside it)."""
    lo, hi = float(ARM.q_min[j]), float(ARM.q_max[j])
    return st.one_of(st.floats(lo - 0.03, lo + 0.03), st.floats(hi - 0.03, hi + 0.03))


@settings(max_examples=20, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(data=st.data())
def test_no_out_of_limit_target_is_ever_sent(new_channel, tmp_path, reply_timeout, data):
    n = data.draw(st.integers(2, 4))
    dt = data.draw(st.floats(0.01, 0.06))
    q = np.empty((n, 6))
    q[0] = [data.draw(st.sampled_from([0, 0, 0, 0, 1]).flatmap(
        lambda edge, j=j: _joint_value(j) if edge else st.floats(float(ARM.q_min[j]) + 0.05,
                                                                 float(ARM.q_max[j]) - 0.05)))
            for j in range(6)]
    vmax = np.asarray(ARM.velocity)
    for k in range(1, n):  # mostly within the speed limits, sometimes up to 1.3x too fast
        scale = data.draw(st.sampled_from([0.9, 0.9, 0.9, 1.3]))
        q[k] = q[k - 1] + [data.draw(st.floats(-scale, scale)) * vmax[j] * dt for j in range(6)]
    t = np.arange(n) * dt
    T = iik.fk(q, THESIS_ARM)
    if data.draw(st.booleans()):
        T[-1, 2, 3] += data.draw(st.floats(-1e-3, 1e-3))  # sometimes a pose that q does not reach
    opts = ValidationOptions()
    try:
        tr = validate(t, q, T, options=opts, arm=ARM)
    except SafetyError as exc:
        event(f"refused: {exc.reason.split()[-1] if 'FK' not in exc.reason else 'FK'}")
        return  # refused before any bus existed
    event("executed")
    ch, clk = new_channel(), VirtualClock()
    sent = []
    with SimulatedArm.virtual(ch, lag=0.0, initial=q[0], arm=ARM, clock=clk.now), \
            can.Bus(interface="virtual", channel=ch) as bus:
        _spy(bus, sent)
        arm = PowerCubeArm(bus, (1, 2, 3, 4, 5, 6), timeout=reply_timeout, arm=ARM)
        execute(arm, tr, tmp_path / f"{ch}.jsonl", options=ExecutionOptions(settle=0.0, sample_period=0.01),
                clock=clk.now, sleep=clk.sleep)
    moves = [P.decode(f) for f in sent if (f.arbitration_id & ~0x1F) == P.ID_SET]
    moves = [m for m in moves if isinstance(m, P.SetMove)]
    assert moves, "a valid trajectory sends steps"
    for m in moves:
        j = m.module - 1
        assert ARM.lower[j] + opts.margin - 1e-6 <= m.value <= ARM.upper[j] - opts.margin + 1e-6
        assert m.time_ms >= 10
    # and the speeds implied on the wire respect Sec 3.2
    for j in range(6):
        tj = [m for m in moves if m.module == j + 1]
        prev = q[0, j]
        for m in tj:
            assert abs(m.value - prev) / (m.time_ms / 1000.0) <= ARM.velocity[j] + 1e-4
            prev = m.value


def test_threads_are_cleaned_up():
    assert not [t for t in threading.enumerate() if t.name == "SimulatedArm"]


def test_orientation_free_steps_check_position_only():
    t, q, T = line()
    T = T.copy()
    c, s = math.cos(0.2), math.sin(0.2)
    T[2, :3, :3] = T[2, :3, :3] @ np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])  # planner changed alpha here
    with pytest.raises(SafetyError, match="FK does not match"):
        validate(t, q, T, arm=ARM)
    free = np.zeros(len(t), bool)
    free[2] = True
    validate(t, q, T, orientation_free=free, arm=ARM)
    T[2, 0, 3] += 0.001  # the position is still checked
    with pytest.raises(SafetyError, match="FK does not match"):
        validate(t, q, T, orientation_free=free, arm=ARM)


def test_bus_open_failure_is_typed():
    with pytest.raises(BusError):
        PowerCubeArm.from_interface(interface="no-such-interface", channel="x", arm=ARM)


def test_can_error_frame_halts_and_logs(rig):
    sim, arm, log = rig.sim, rig.arm, rig.log
    tr = validate(*line(8), arm=ARM)
    noisy = can.Bus(interface="virtual", channel=arm.bus.channel_id)  # another node on the same bus

    def progress(k, n):
        if k == 3:  # an error frame on the bus, as a controller reports bus errors
            noisy.send(can.Message(is_error_frame=True, arbitration_id=0, data=[0] * 8))

    try:
        with pytest.raises(BusError, match="error frame"):
            rig.execute(tr, progress=progress)
    finally:
        noisy.shutdown()
    assert_halted_and_logged(sim, log, "BusError")


def test_watchdog_during_the_run(new_channel, tmp_path, reply_timeout):
    """Real time: python-can's own thread refreshes the watchdog while the run goes on."""
    ch = new_channel()
    with SimulatedArm.virtual(ch, lag=0.01, initial=QA, arm=ARM) as sim, \
            can.Bus(interface="virtual", channel=ch) as bus:
        arm = PowerCubeArm(bus, (1, 2, 3, 4, 5, 6), timeout=reply_timeout, arm=ARM)
        tr = validate(*line(6, speed=0.25), arm=ARM)
        res = execute(arm, tr, tmp_path / "run.jsonl",
                      options=ExecutionOptions(settle=0.05, sample_period=0.005, watchdog=True))
        wd = [m for _, m in sim.received() if isinstance(m, P.Broadcast) and m.cmd is P.Cmd.WATCHDOG]
        assert res.duration > 0.5 and len(wd) >= 6 * 5  # refreshed every 40 ms on every module
        cfg = [m.get_param(P.Param.CONFIG) for m in arm.modules]
        assert not any(c & P.CONFIG_WATCHDOG for c in cfg)  # cleared at the end
        time.sleep(1.5 * sim.module(1).watchdog_timeout)  # no refresh now, but no watchdog either
        assert not any(s & P.State.ERROR for s in sim.states())


_CRASH_SCRIPT = r"""
import sys, time, can, numpy as np, iik, iik.arms
from hardware import PowerCubeArm, SimulatedArm, execute, validate
from hardware.executor import ExecutionOptions, time_steps
ch = sys.argv[1]
q = np.full(6, 0.1) + np.linspace(0, 1, 40)[:, None] * 0.3
A = iik.arms.get("thesis")
sim = SimulatedArm.virtual(ch, initial=q[0], arm=A)
bus = can.Bus(interface="virtual", channel=ch)
arm = PowerCubeArm(bus, (1, 2, 3, 4, 5, 6), timeout=5.0, arm=A)  # generous: the run is killed, not faulted
def progress(k, n):
    if k == 5:
        print("running", flush=True)
execute(arm, validate(time_steps(q, min_step=0.1, arm=A), q, iik.fk(q, A), arm=A), sys.argv[2],
        progress=progress,
        options=ExecutionOptions(sample_period=0.005))
"""


def test_log_survives_a_killed_process(new_channel, tmp_path):
    import subprocess
    import sys

    log = tmp_path / "crash.jsonl"
    proc = subprocess.Popen([sys.executable, "-c", _CRASH_SCRIPT, new_channel(), str(log)],
                            stdout=subprocess.PIPE, text=True)
    try:
        assert proc.stdout.readline().strip() == "running"
        time.sleep(0.1)
        proc.kill()  # SIGKILL: no cleanup, no flush at exit
        proc.wait(timeout=5)
    finally:
        if proc.poll() is None:
            proc.kill()
    # the log moves to its name only when closed: the records of the killed run are on disk in its
    # temporary sibling, every line a complete record (iik.files, hardware.runlog)
    assert not log.exists()
    (partial,) = tmp_path.glob(f"{PARTIAL_PREFIX}*-crash.jsonl")
    run = read_run_log(partial)
    assert not run.complete and len(run.command_k) >= 5 and len(run.samples_t) > 5


def test_buffered_update_cuts_no_step(new_channel, tmp_path, virtual_clock):
    """Improvement over Sec 4.3: queue each step in the modules' buffer instead of
    replacing the current one at 95 %: every step-point is reached, nothing stops.

    On one virtual clock shared by simulator and executor (round trips take no
    simulated time), so the machine's load cannot shift the two timelines apart."""
    qa, qb = QA, QA + np.array([0.25, -0.2, 0.15, 0.2, -0.25, 0.3])
    tr = validate(*line(6, qa=qa, qb=qb, speed=0.8), arm=ARM)
    out = {}
    clk = virtual_clock
    for update in ("thesis", "buffered"):
        ch = new_channel()
        with SimulatedArm.virtual(ch, lag=0.0, initial=tr.q[0], clock=clk.now, arm=ARM) as sim, \
                can.Bus(interface="virtual", channel=ch) as bus:
            arm = PowerCubeArm(bus, (1, 2, 3, 4, 5, 6), timeout=2.0, arm=ARM)
            execute(arm, tr, tmp_path / f"{update}.jsonl", clock=clk.now, sleep=clk.sleep,
                    options=ExecutionOptions(update=update, settle=0.05, sample_period=0.003))
            starts = [m for _, m in sim.received() if isinstance(m, P.Broadcast) and m.cmd is P.Cmd.STARTMOVE]
            out[update] = (read_run_log(tmp_path / f"{update}.jsonl"), len(starts) // 6,
                           sum(len(m.stops) for m in sim.modules.values()), sim.positions())
    from hardware.analysis import analyse

    thesis, buffered = (analyse(out[u][0]) for u in ("thesis", "buffered"))
    assert out["thesis"][1] == len(tr) - 1 and out["buffered"][1] == 1  # one STARTMOVE to begin
    assert out["buffered"][2] == 0  # no joint ever rests between steps
    np.testing.assert_allclose(out["buffered"][3], tr.q[-1], atol=1e-6)
    # without lag the buffered run passes through every step-point; the thesis update
    # leaves ~5 % of each step (the "added error" of Sec 4.3)
    assert buffered.max_ee_error < 0.25 * thesis.max_ee_error
    assert thesis.max_ee_error > 1e-3
    assert buffered.max_ee_error < 1e-6  # on one exact timeline: every step-point reached
