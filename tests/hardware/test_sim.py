"""The simulated module as a pure state machine on an explicit clock (deterministic)."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import iik
import iik.arms
from hardware import protocol as P
from hardware.errors import SafetyError
from hardware.sim import SimModule, SimulatedArm
from iik import THESIS_ARM
from iik.errors import InvalidInputError


def module(**kw):
    kw.setdefault("lag", 0.0)
    return SimModule(1, lower=-1.0, upper=1.0, vmax=1.2, amax=2.0, **kw)


def test_fstep_is_linear_and_takes_its_time():
    m = module()
    (ack,) = m.handle(P.SetMove(1, P.Mode.FSTEP, 0.3, 500), 0.0)
    assert ack == P.MoveAck(1, P.Mode.FSTEP)
    assert m.setpoint(0.25) == pytest.approx((0.15, 0.6, 0.0))
    assert m.state(0.25) & P.State.INPROGRESS and m.state(0.25) & P.State.MOTION
    assert m.setpoint(0.5)[0] == pytest.approx(0.3)
    s = m.state(0.6)
    assert not s & P.State.INPROGRESS and s & P.State.RAMP_END


def test_ramp_profile_limits_and_duration():
    m = module()
    m.handle(P.SetParam(1, P.Param.FRAMPVEL, 0.5), 0.0)
    m.handle(P.SetParam(1, P.Param.FRAMPACC, 1.0), 0.0)
    m.handle(P.SetMove(1, P.Mode.FRAMP, 0.8), 0.0)
    ts = [i * 0.01 for i in range(300)]
    v = [m.setpoint(t)[1] for t in ts]
    a = [m.setpoint(t)[2] for t in ts]
    assert max(v) == pytest.approx(0.5, abs=1e-6) and max(abs(x) for x in a) <= 1.0 + 1e-6
    # jerk-limited trapezoid (jerk 50 rad/s^3): T = d/v + v/a + a/j = 1.6 + 0.5 + 0.02 s
    assert m.motion.end == pytest.approx(0.8 / 0.5 + 0.5 / 1.0 + 1.0 / 50.0, abs=1e-6)
    assert m.setpoint(2.2)[0] == pytest.approx(0.8)


def test_tracking_lag_is_a_pure_delay():
    m = module(lag=0.05)
    m.handle(P.SetMove(1, P.Mode.FSTEP, 0.2, 200), 0.0)
    assert m.measured(0.15)[0] == pytest.approx(m.setpoint(0.10)[0])
    assert m.measured(0.03)[0] == 0.0


def test_buffer_and_startmove():
    m = module()
    m.handle(P.SetMove(1, P.Mode.FSTEP, 0.2, 400), 0.0)
    m.handle(P.SetMove(1, P.Mode.FSTEP, 0.0, 200), 0.1)
    assert m.state(0.1) & P.State.FULLBUFFER
    m.handle(P.Broadcast(P.Cmd.STARTMOVE), 0.2)
    p0 = m.setpoint(0.2)[0]
    assert p0 == pytest.approx(0.1) and m.setpoint(0.3)[0] == pytest.approx(0.05)
    assert not m.state(0.25) & P.State.FULLBUFFER


def test_soft_limit_and_error_state_frame():
    m = module()
    out = m.handle(P.SetMove(1, P.Mode.FSTEP, 1.5, 100), 0.0)
    assert out[0] == P.MoveAck(1, P.Mode.FSTEP)
    assert isinstance(out[1], P.StateFrame) and out[1].state & P.State.BEYOND_SOFT
    assert m.setpoint(0.5)[0] == 0.0


def test_velocity_mode_stops_at_soft_limit():
    m = module()
    m.handle(P.SetMove(1, P.Mode.FVEL, 1.0), 0.0)
    out = []
    t = 0.0
    while t < 3.0 and not out:
        t += 0.01
        out = m.advance(t)
    assert out and out[0].state & P.State.BEYOND_SOFT
    assert m.setpoint(t + 1.0)[0] <= 1.0


def test_halt_latch_in_the_module():
    m = module()
    m.handle(P.Command(1, P.Cmd.HALT), 0.0)
    assert m.handle(P.SetMove(1, P.Mode.FSTEP, 0.2, 100), 0.1) == [P.MoveAck(1, P.Mode.FSTEP)]
    assert m.setpoint(0.5)[0] == 0.0 and m.state(0.5) & P.State.HALTED
    m.handle(P.Command(1, P.Cmd.RESET), 0.6)
    m.handle(P.SetMove(1, P.Mode.FSTEP, 0.2, 100), 0.6)
    assert m.setpoint(0.8)[0] == pytest.approx(0.2)


def test_watchdog_trips_on_silence():
    m = module(watchdog_timeout=0.1)
    m.handle(P.SetParam(1, P.Param.CONFIG, P.CONFIG_WATCHDOG), 0.0)
    m.handle(P.Broadcast(P.Cmd.WATCHDOG), 0.0)
    assert m.advance(0.05) == []
    out = m.advance(0.2)
    assert out and out[0].state & P.State.COMM_ERROR and m.state(0.2) & P.State.ERROR


@pytest.mark.parametrize("name", ["thesis", "crx10ia"])
def test_the_modules_are_the_arms(name):
    """Soft limits, speeds and accelerations of the simulated modules are the given arm's (the CRX's
    J3 reaches 251 deg and its joints 2.09-3.14 rad/s, the thesis arm's Table I and 1.2 rad/s)."""
    arm = iik.arms.get(name)
    sim = SimulatedArm(bus=None, module_ids=(1, 2, 3, 4, 5, 6), start=False, arm=arm)  # type: ignore[arg-type]
    for j, i in enumerate(sim.module_ids):
        m = sim.module(i)
        assert m.params[P.Param.FMINPOS] == arm.lower[j] and m.params[P.Param.FMAXPOS] == arm.upper[j]
        assert m.vmax == arm.velocity[j] and m.params[P.Param.FMAXACC] == arm.acceleration[j]
    with pytest.raises(InvalidInputError, match="initial: joint q3 at .* outside its soft limits"):
        SimulatedArm(bus=None, start=False, arm=arm, initial=np.r_[0, 0, arm.upper[2] + 0.01, 0, 0, 0])  # type: ignore[arg-type]


def test_bad_fault_kind():
    with pytest.raises(SafetyError):
        module().inject("explode")


def test_extended_reply_reports_position_and_short_state():
    m = module(initial=0.25, homed=False)
    (ack,) = m.handle(P.SetMove(1, P.Mode.FVEL_EXT, 0.0), 0.0)
    assert ack.position == pytest.approx(0.25) and ack.short & P.ShortState.NOT_OK
    assert not math.isnan(ack.position)


def test_stops_between_steps_are_recorded():
    m = module()
    m.handle(P.SetMove(1, P.Mode.FSTEP, 0.1, 100), 0.0)
    m.handle(P.SetMove(1, P.Mode.FSTEP, 0.2, 100), 0.095)  # early (95 %): buffered, no stop
    m.advance(0.2)
    assert m.stops == []
    m.handle(P.SetMove(1, P.Mode.FSTEP, 0.3, 100), 0.21)  # late: rests 10 ms at 0.2 rad
    assert m.stops == [(pytest.approx(0.2), pytest.approx(0.01))]


def test_non_positive_limits_are_not_applied():
    m = module()
    m.handle(P.SetParam(1, P.Param.FMAXVEL, -1.0), 0.0)
    m.handle(P.SetParam(1, P.Param.FRAMPACC, 0.0), 0.0)
    assert m.params[P.Param.FMAXVEL] == 1.2 and m.params[P.Param.FRAMPACC] == 1.0
    m.handle(P.SetMove(1, P.Mode.FRAMP, 0.5), 0.0)  # still a valid profile
    assert m.motion.end < 5.0


_values = st.floats(-1e6, 1e6, allow_nan=False, width=32)
_requests = st.one_of(
    st.builds(P.GetParam, st.just(1), st.sampled_from(sorted(P.READABLE))),
    st.sampled_from(sorted(P.WRITABLE)).flatmap(lambda par: st.builds(
        P.SetParam, st.just(1), st.just(par),
        st.integers(0, 2**32 - 1) if P.PARAM_TYPES[par] is P.ParamType.U32 else _values)),
    st.sampled_from(list(P.Mode)).flatmap(lambda m: st.builds(
        P.SetMove, st.just(1), st.just(m), _values,
        st.integers(0, 0xFFFF) if m.plain is P.Mode.FSTEP else st.none())),
    st.builds(P.Command, st.just(1), st.sampled_from([P.Cmd.RESET, P.Cmd.HOME, P.Cmd.HALT])),
    st.sampled_from([P.Cmd.RESET, P.Cmd.HOME, P.Cmd.HALT, P.Cmd.WATCHDOG, P.Cmd.STARTMOVE]).map(P.Broadcast),
)


@given(st.lists(st.tuples(_requests, st.floats(0.0, 0.5)), max_size=25))
def test_any_request_sequence_is_served(seq):
    """Whatever a host sends, the module answers every request with its echo and its
    state stays finite (no exception inside the simulated module)."""
    m = module()
    now = 0.0
    for req, dt in seq:
        now += dt
        out = m.handle(req, now)
        if not isinstance(req, P.Broadcast):
            assert out and P.is_echo(req, P.encode(out[0]))
        p, v, a = m.setpoint(now)
        assert all(math.isfinite(x) for x in (p, v, a)) and abs(v) <= 1.2 + 1e-9
        assert all(math.isfinite(x) for x in m.measured(now))


def test_serve_until_stopped(new_channel):
    """`serve` (behind `iik sim-arm`) opens the bus its config names, serves until stopped, shuts it down."""
    import threading

    from hardware import BusConfig, PowerCubeArm, SimConfig
    from hardware.sim import serve
    from verification.testing.polling import wait_until

    ch, stop, ready = new_channel(), threading.Event(), []
    config = BusConfig("virtual", ch, sim=SimConfig(initial=(0.1,) * 6))
    th = threading.Thread(target=serve, args=(config,), daemon=True,
                          kwargs={"stop": stop, "ready": ready.append, "arm": THESIS_ARM})
    th.start()
    assert wait_until(lambda: ready, 30.0, 0.01) and ready[0].running
    with PowerCubeArm.from_interface(interface="virtual", channel=ch, timeout=5.0, arm=THESIS_ARM) as arm:
        assert len(arm.open()) == 6
        assert all(arm.get_pos() == np.float32(0.1))  # f32 on the wire
    stop.set()
    th.join(30.0)
    assert not th.is_alive() and not ready[0].running


def test_serve_refuses_bad_input_and_leaves_no_open_bus(new_channel, caplog):
    import gc

    from hardware import BusConfig, SimConfig
    from hardware.errors import BusError
    from hardware.sim import serve

    with pytest.raises(BusError, match="cannot open no-such-interface"):
        serve(BusConfig("no-such-interface", "x"), duration=0.1, arm=THESIS_ARM)
    with pytest.raises(InvalidInputError, match="module_ids"):
        serve(BusConfig("virtual", new_channel(), module_ids=[0]), duration=0.1, arm=THESIS_ARM)
    with pytest.raises(InvalidInputError, match="initial"):
        serve(BusConfig("virtual", new_channel(), sim=SimConfig(initial=[0.0, float("nan")])), duration=0.1,
              arm=THESIS_ARM)
    with pytest.raises(InvalidInputError, match="initial: joint q2 at 3 rad is outside its soft limits"):
        serve(BusConfig("virtual", new_channel(), sim=SimConfig(initial=[0.0, 3.0, 0, 0, 0, 0])),
              duration=0.1, arm=THESIS_ARM)
    with pytest.raises(InvalidInputError, match="duration"):
        serve(BusConfig("virtual", new_channel()), duration=-1.0, arm=THESIS_ARM)
    gc.collect()
    assert "not properly shut down" not in caplog.text
