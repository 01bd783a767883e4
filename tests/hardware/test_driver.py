"""Driver against the simulated arm on ``virtual``: every Table V function, the echo
rule, the halt latch, scan, STARTMOVE and the watchdog.

The simulated modules run on a virtual clock where the test measures motion (``virtual_clock.sleep``
moves their time on), so the machine's load cannot move a sample; where real time is the point (homing
polled by the driver, a scan waiting out absent ids, the watchdog refreshed by python-can's thread)
the waits are conditions or margins from a baseline measured in the test."""

import math
import threading
import time

import can
import numpy as np
import pytest

import iik
from hardware import PowerCubeArm, PowerCubeModule, SimulatedArm, scan
from hardware import protocol as P
from hardware.errors import (
    CANTimeoutError,
    DuplicateModuleError,
    ModuleHalted,
    SafetyError,
    SecondControllerError,
)
from iik import THESIS_ARM
from iik.errors import InvalidInputError
from verification.testing.polling import wait_until

ARM = THESIS_ARM  # the modules' limits in these tests


def test_open_close_and_reads(arm, sim):
    states = arm.open()  # PCube_openDevice: every module answers
    assert all(s & P.State.HOME_OK for s in states)
    np.testing.assert_allclose(arm.get_pos(), 0.0)
    np.testing.assert_allclose(arm.get_vel(), 0.0)
    cur = arm.get_cur()
    assert cur.shape == (6,) and np.all(np.isfinite(cur))
    arm.close()


def test_from_interface_owns_and_closes_bus(new_channel, reply_timeout):
    ch = new_channel()
    with SimulatedArm.virtual(ch, (1, 2), arm=ARM):
        with PowerCubeArm.from_interface((1, 2), interface="virtual", channel=ch, timeout=reply_timeout,
                                         arm=ARM) as a:
            assert len(a.open()) == 2
        with pytest.raises(Exception):  # noqa: B017 - python-can raises on a closed bus
            a.bus.send(can.Message(arbitration_id=1, data=[0]))


def test_set_max_cur_is_written(arm, sim):
    arm.set_max_cur(2.5)
    for m in arm.modules:
        assert m.get_param(P.Param.FMAXCUR) == pytest.approx(2.5)
    with pytest.raises(SafetyError):
        arm.set_max_cur(math.nan)


def test_home_and_home_all(new_channel, reply_timeout):
    """Real time: the driver polls the modules until they are homed (a homing takes about 0.5 s; the
    generous limit of the polling costs nothing when it succeeds)."""
    ch = new_channel()
    with SimulatedArm.virtual(ch, (1, 2), homed=False, initial=[0.2, -0.1], arm=ARM) as sim, \
            can.Bus(interface="virtual", channel=ch) as bus:
        a = PowerCubeArm(bus, (1, 2), timeout=reply_timeout, arm=ARM)
        assert not any(s & P.State.HOME_OK for s in a.states())
        a.modules[0].home()
        a.modules[0].wait_homed(timeout=30.0)
        assert abs(a.modules[0].get_pos()) < 1e-6
        a.home_all()  # broadcast, no reply
        a.wait_homed(timeout=30.0)
        np.testing.assert_allclose(a.get_pos(), 0.0, atol=1e-6)
        assert all(s & P.State.HOME_OK for s in sim.states())


def test_move_ramp_respects_velocity_and_reaches_target(arm, sim, virtual_clock):
    target = np.array([0.3, -0.2, 0.1, 0.25, -0.3, 0.2])
    arm.move_ramp(target, 0.5, 1.0)
    peak = np.zeros(6)
    for _ in range(75):  # 1.5 s of the modules' time
        peak = np.maximum(peak, np.abs(arm.get_vel()))
        virtual_clock.sleep(0.02)
    np.testing.assert_allclose(arm.get_pos(), target, atol=1e-6)
    assert np.all(peak <= 0.5 + 1e-6)
    assert peak[0] > 0.4  # the long joints do reach the ramp speed
    assert all(s & P.State.RAMP_END for s in arm.states())


def test_move_step_takes_its_time(new_channel, virtual_clock):
    """FSTEP moves at constant speed over its time: half way at half time, there at the end. Time is
    the simulator's injectable clock, advanced by hand, so the machine's load cannot move a sample."""
    ch, ids = new_channel(), (1, 2, 3, 4, 5, 6)
    with SimulatedArm.virtual(ch, ids, lag=0.01, clock=virtual_clock.now, arm=ARM) as sim, \
            can.Bus(interface="virtual", channel=ch) as bus:
        arm = PowerCubeArm(bus, ids, timeout=2.0, arm=ARM)
        arm.move_step(np.full(6, 0.1), 0.3)
        virtual_clock.sleep(0.15)
        mid = arm.get_pos()
        assert np.all((mid > 0.04) & (mid < 0.055)), mid  # half way, less the 10 ms tracking lag
        np.testing.assert_allclose(arm.get_vel(), 0.1 / 0.3, rtol=1e-3)
        virtual_clock.sleep(0.25)
        np.testing.assert_allclose(arm.get_pos(), 0.1, atol=1e-6)
        assert not sim.errors, sim.errors


def test_move_step_extended_reply(arm, sim):
    pos, short = arm.move_step(np.full(6, 0.05), 0.1, extended=True)
    assert pos.shape == (6,) and all(isinstance(s, P.ShortState) for s in short)
    assert not any(s & P.ShortState.NOT_OK for s in short)


def test_speed_limit_of_sec_3_2_slows_a_too_fast_step(new_channel, virtual_clock, reply_timeout):
    ch = new_channel()
    with SimulatedArm.virtual(ch, (1,), lag=0.0, arm=ARM, clock=virtual_clock.now) as sim, \
            can.Bus(interface="virtual", channel=ch) as bus:
        m = PowerCubeModule(bus, 1, timeout=reply_timeout)  # no local limits: the module's FMAXVEL is read
        vmax = iik.THESIS_ARM.velocity[0]
        with pytest.raises(SafetyError, match="FMAXVEL"):
            m.move_step(0.6, 0.1)  # asks for 6 rad/s: the driver refuses it
        assert not [x for _, x in sim.received() if isinstance(x, P.SetMove)]
        m.link.request(P.SetMove(1, P.Mode.FSTEP, 0.6, 100))  # behind the driver's back
        virtual_clock.sleep(0.2)  # not there after 100 ms: moving at the joint's limit
        assert m.get_vel() == pytest.approx(vmax) and m.get_pos() == pytest.approx(0.2 * vmax, abs=1e-6)
        assert sim.module(1).motion.end - sim.module(1).motion.t0 == pytest.approx(0.6 / vmax)


def test_move_vel_and_move_cur(arm, sim, virtual_clock):
    arm.move_vel(np.full(6, 0.3))
    virtual_clock.sleep(0.4)
    np.testing.assert_allclose(arm.get_vel(), 0.3, atol=1e-6)
    arm.move_vel(np.zeros(6))
    virtual_clock.sleep(0.3)
    np.testing.assert_allclose(arm.get_vel(), 0.0, atol=1e-9)
    arm.move_cur(np.full(6, 1.0))
    virtual_clock.sleep(0.4)
    v = arm.get_vel()
    assert np.all(v > 0.05)
    arm.move_vel(np.zeros(6))


def test_halt_latches_until_reset(arm, sim, virtual_clock):
    arm.move_vel(np.full(6, 0.2))
    virtual_clock.sleep(0.1)
    arm.modules[0].halt()
    virtual_clock.sleep(0.03)
    assert arm.modules[0].state() & P.State.HALTED
    assert arm.modules[0].get_vel() == 0.0
    with pytest.raises(ModuleHalted):
        arm.modules[0].move_step(0.0, 0.1)  # refused locally, nothing sent
    # bypass the driver: the module itself ignores motion while halted
    arm.link.request(P.SetMove(1, P.Mode.FVEL, 0.3))
    virtual_clock.sleep(0.05)
    assert arm.modules[0].get_vel() == 0.0
    arm.halt()  # broadcast reaches the others (no reply: wait until they have read it)
    assert wait_until(lambda: all(s & P.State.HALTED for s in sim.states()), 30.0, 0.002)
    assert arm.halted
    arm.reset()
    assert not arm.halted and not any(s & P.State.HALTED for s in arm.states())
    arm.modules[0].move_vel(0.1)
    virtual_clock.sleep(0.2)
    assert arm.modules[0].get_vel() == pytest.approx(0.1)
    arm.move_vel(np.zeros(6))


def test_halt_latch_observed_from_state(arm, sim):
    arm.link.send(P.Broadcast(P.Cmd.HALT))  # halted behind the driver's back
    arm.states()  # read after the broadcast: the modules take frames in the order sent
    with pytest.raises(ModuleHalted):
        arm.move_step(np.zeros(6), 0.1)


class _Rogue:
    """Another node that answers every request with non-matching frames first."""

    def __init__(self, channel, delay_real=False):
        self.bus = can.Bus(interface="virtual", channel=channel)
        self.stop = threading.Event()
        self.thread = threading.Thread(target=self.run, daemon=True)
        self.thread.start()

    def run(self):
        while not self.stop.is_set():
            f = self.bus.recv(0.01)
            if f is None or f.arbitration_id == 0x100 or not (0x0C0 <= f.arbitration_id < 0x100):
                continue
            mid = f.arbitration_id & 0x1F
            for junk in (P.ParamReply(mid, P.Param.ACT_FVEL, 99.0),        # wrong parameter
                         P.ParamReply(mid % 31 + 1, P.Param.ACT_FPOS, 99.0),  # wrong module
                         P.CommandAck(mid, P.Cmd.HOME),                     # wrong command
                         P.MoveAck(mid, P.Mode.FRAMP)):                     # wrong mode
                self.bus.send(P.encode(junk))
            self.bus.send(can.Message(arbitration_id=0x0A0 + mid, data=[0x0A], is_extended_id=False))

    def close(self):
        self.stop.set()
        self.thread.join()
        self.bus.shutdown()


def test_echo_rule_discards_non_matching_replies(new_channel):
    """The module answers 0.3 s late, the rogue at once: its five wrong frames reach the
    host before every real reply and must be discarded, whatever the machine's load."""
    ch = new_channel()
    rogue = _Rogue(ch)
    try:
        with SimulatedArm.virtual(ch, (1,), initial=[0.3], arm=ARM) as sim, \
                can.Bus(interface="virtual", channel=ch) as bus:
            sim.inject(1, "late_ack", delay=0.3, count=-1)
            m = PowerCubeModule(bus, 1, timeout=5.0)  # the echo rule is under test, not the timeout
            for _ in range(3):
                assert m.get_pos() == pytest.approx(0.3, abs=1e-6)  # never the rogue's 99
            m.move_step(0.31, 0.05)
            assert m.link.discarded >= 5 * 3
    finally:
        rogue.close()


def test_only_non_matching_replies_time_out(new_channel):
    ch = new_channel()
    rogue = _Rogue(ch)
    try:
        with can.Bus(interface="virtual", channel=ch) as bus:  # no simulated module at all
            m = PowerCubeModule(bus, 1, timeout=0.05)
            t0 = time.monotonic()
            with pytest.raises(CANTimeoutError) as ei:
                m.get_pos()
            assert time.monotonic() - t0 >= 0.05
            assert ei.value.module_id == 1 and isinstance(ei.value, TimeoutError)
    finally:
        rogue.close()


def test_late_ack_is_discarded_by_the_next_request(arm, sim, virtual_clock):
    """The reply comes 0.3 s (of the modules' time) late: the request times out (no reply in 50 ms of
    real time either, the modules' clock standing still); once their time has passed and they sent it,
    the stale ACT_FPOS reply is discarded by the next request, not taken for its answer."""
    sim.inject(1, "late_ack", delay=0.3)
    with pytest.raises(CANTimeoutError):
        arm.link.request(P.GetParam(1, P.Param.ACT_FPOS), timeout=0.05)
    sent = sim.sent
    virtual_clock.sleep(0.3)
    assert wait_until(lambda: sim.sent > sent, 30.0, 0.002)  # the late reply is on the bus now
    assert arm.modules[0].get_vel() == 0.0  # not the stale ACT_FPOS reply
    assert arm.link.discarded >= 1


def test_scan_finds_exactly_the_modules(new_channel, baseline_timeout, reply_timeout):
    """A scan waits out its timeout at every absent id, in real time: the timeout is derived from round
    trips measured now (a module that answers must do so within it, whatever the load)."""
    ch = new_channel()
    with SimulatedArm.virtual(ch, (2, 5, 9), arm=ARM), can.Bus(interface="virtual", channel=ch) as bus:
        probe = PowerCubeModule(bus, 2, timeout=reply_timeout)
        timeout = baseline_timeout(probe.get_pos, margin=20, floor=0.05)
        found = scan(bus, timeout=timeout)
    assert sorted(found) == [2, 5, 9]
    assert set(found.values()) == {0x5151}


def test_start_move_starts_a_buffered_step(arm, sim, virtual_clock):
    m = arm.modules[0]
    m.move_step(0.2, 1.0)
    virtual_clock.sleep(0.05)
    m.move_step(-0.1, 0.5)  # arrives while in progress: buffered
    assert m.state() & P.State.FULLBUFFER
    virtual_clock.sleep(0.05)
    assert m.get_vel() > 0  # still on the first step
    arm.start_move()  # a broadcast, no reply ...
    m.state()  # ... taken by the modules before this request (frames keep their order), at the same time
    virtual_clock.sleep(0.05)
    assert m.get_vel() < 0 and not m.state() & P.State.FULLBUFFER


def test_buffered_step_starts_when_the_current_one_ends(arm, sim, virtual_clock):
    m = arm.modules[0]
    m.move_step(0.05, 0.1)
    m.move_step(0.0, 0.1)
    virtual_clock.sleep(0.3)
    assert abs(m.get_pos()) < 1e-6
    kinds = [x.kind for x in sim.module(1).history]
    assert kinds[-2:] == ["step", "step"]


def test_soft_limits_default_to_table_i_and_refuse_targets(sim, host_bus, reply_timeout):
    m = PowerCubeModule(host_bus, 2, timeout=reply_timeout)  # joint 2, no local check
    lo, hi = m.soft_limits()
    assert lo == pytest.approx(iik.THESIS_ARM.lower[1]) and hi == pytest.approx(iik.THESIS_ARM.upper[1])
    m.move_step(hi + 0.1, 5.0)
    s = m.state()  # read after the state frame the module announced its error with (frames keep their order)
    assert s & P.State.ERROR and s & P.State.BEYOND_SOFT
    assert m.link.faults.get(2, 0) & P.State.BEYOND_SOFT  # announced by a state frame
    m.reset()
    assert not m.state() & P.State.ERROR
    guarded = PowerCubeModule(host_bus, 2, timeout=reply_timeout, limits=(lo, hi))
    with pytest.raises(SafetyError):
        guarded.move_step(hi + 0.1, 5.0)


def test_watchdog(new_channel, baseline_timeout, reply_timeout):
    """Real time: python-can's own thread refreshes the watchdog, the modules time the gaps on real time.
    Their watchdog time is derived from a baseline measured now (1 s on an idle machine; more if round
    trips are slow), so that a loaded machine's scheduling is not taken for a missing refresh."""
    ch = new_channel()
    with can.Bus(interface="virtual", channel=ch) as bus:
        with SimulatedArm.virtual(ch, arm=ARM):
            arm = PowerCubeArm(bus, (1, 2, 3, 4, 5, 6), timeout=reply_timeout, arm=ARM)
            timeout = baseline_timeout(arm.get_pos, margin=50, floor=1.0, ceiling=10.0)
        with SimulatedArm.virtual(ch, arm=ARM, watchdog_timeout=timeout) as sim:
            arm = PowerCubeArm(bus, (1, 2, 3, 4, 5, 6), timeout=reply_timeout, arm=ARM)
            arm.start_watchdog(period=0.02)
            assert all(m.get_param(P.Param.CONFIG) & P.CONFIG_WATCHDOG for m in arm.modules)
            time.sleep(1.5 * timeout)  # longer than the watchdog time, but refreshed: no trip
            assert not any(s & P.State.ERROR for s in arm.states())
            arm.stop_watchdog(disable=False)  # refresh stops, bit stays: the modules must stop
            assert wait_until(lambda: all(s & P.State.COMM_ERROR for s in sim.states()), 30.0, 0.005)
            arm.reset()
            arm.start_watchdog(period=0.02)
            arm.stop_watchdog(disable=True)  # clean stop: bit cleared first
            time.sleep(1.5 * timeout)
            assert not any(s & P.State.ERROR for s in arm.states())


def test_bad_arguments_are_typed_errors(arm, sim):
    with pytest.raises(InvalidInputError, match="module_id"):
        PowerCubeModule(arm.bus, 0)
    with pytest.raises(InvalidInputError, match="module_ids"):
        PowerCubeArm(arm.bus, (1, 1), arm=ARM)
    with pytest.raises(InvalidInputError, match="timeout"):
        PowerCubeArm(arm.bus, (1, 2), arm=ARM, timeout=0.0)
    with pytest.raises(SafetyError):
        arm.move_step(np.zeros(5), 0.1)
    with pytest.raises(SafetyError):
        arm.move_step(np.zeros(6), 0.0)
    with pytest.raises(SafetyError):
        arm.move_step(np.zeros(6), 70.0)
    with pytest.raises(SafetyError):
        arm.move_step(np.full(6, 4.0), 1.0)  # outside Table I
    with pytest.raises(SafetyError):
        arm.move_vel(np.full(6, math.inf))


# ----------------------------------------------------------------------------- duplicate module ids
def test_two_modules_with_one_id_are_a_fault_at_open(new_channel, reply_timeout):
    """Two simulated arms on one channel (as two `iik sim-arm` on one bus): every id answers twice."""
    ch = new_channel()
    with SimulatedArm.virtual(ch, arm=ARM), SimulatedArm.virtual(ch, arm=ARM), \
            can.Bus(interface="virtual", channel=ch) as bus:
        arm = PowerCubeArm(bus, (1, 2, 3, 4, 5, 6), timeout=reply_timeout, arm=ARM)
        with pytest.raises(DuplicateModuleError) as info:
            arm.open()
        assert info.value.module_id in range(1, 7) and "two answers to GETPARAM VERSION" in str(info.value)
        with pytest.raises(DuplicateModuleError):
            scan(bus, range(1, 4), timeout=reply_timeout)  # every id answers: the timeout is never waited out


def test_one_module_each_opens_cleanly(new_channel, baseline_timeout, reply_timeout):
    ch = new_channel()
    with SimulatedArm.virtual(ch, (1, 2, 3), arm=ARM), SimulatedArm.virtual(ch, (4, 5, 6), arm=ARM), \
            can.Bus(interface="virtual", channel=ch) as bus:
        arm = PowerCubeArm(bus, (1, 2, 3, 4, 5, 6), timeout=reply_timeout, arm=ARM)
        assert len(arm.open()) == 6
        timeout = baseline_timeout(arm.get_pos, margin=20, floor=0.05)  # id 7 is waited out
        assert sorted(scan(bus, range(1, 8), timeout=timeout)) == [1, 2, 3, 4, 5, 6]


def test_two_controllers_on_one_bus_are_named_as_such(new_channel, reply_timeout):
    """Two hosts driving one arm (two `iik run` on one channel): each sees requests it did not send,
    a SecondControllerError naming them, not "more than one module with id N"."""
    ch = new_channel()
    with SimulatedArm.virtual(ch, arm=ARM), can.Bus(interface="virtual", channel=ch) as bus_a, \
            can.Bus(interface="virtual", channel=ch) as bus_b:
        a, b = (PowerCubeArm(bus, (1, 2, 3, 4, 5, 6), timeout=reply_timeout, arm=ARM)
                for bus in (bus_a, bus_b))
        a.open()
        with pytest.raises(SecondControllerError) as info:
            b.open()
        e = info.value
        assert e.frame_id == P.ID_GET + 1 and e.request == "GETPARAM VERSION to module 1"
        assert str(e).startswith("two controllers on one bus: another host sent GETPARAM VERSION to module 1")
        b.link.send(P.GetParam(2, P.Param.ACT_FPOS))  # the second host goes on commanding regardless
        with pytest.raises(SecondControllerError, match="GETPARAM ACT_FPOS to module 2"):
            a.get_pos()  # and the first host sees its requests


def test_frames_a_host_sent_itself_are_not_another_controller(new_channel, reply_timeout):
    """An interface that loops a host's own frames back (receive_own_messages) is one controller, its
    periodic watchdog refresh included; a frame it never sent is another one."""
    ch = new_channel()
    loopback = can.Bus(interface="virtual", channel=ch, receive_own_messages=True)
    with SimulatedArm.virtual(ch, arm=ARM), loopback as bus, \
            can.Bus(interface="virtual", channel=ch) as other:
        arm = PowerCubeArm(bus, (1, 2, 3, 4, 5, 6), timeout=reply_timeout, arm=ARM)
        arm.open()
        arm.start_watchdog()
        time.sleep(0.2)  # a few refreshes come back
        arm.get_pos()
        arm.stop_watchdog()
        other.send(P.encode(P.GetParam(7, P.Param.ACT_FPOS)))
        with pytest.raises(SecondControllerError, match="GETPARAM ACT_FPOS to module 7"):
            arm.get_pos()


def test_a_second_answer_during_requests_is_a_fault(arm, sim, channel):
    arm.open()
    with SimulatedArm.virtual(channel, (3,), arm=ARM):  # a module with id 3 appears on the bus
        with pytest.raises(DuplicateModuleError) as info:
            for _ in range(20):
                arm.get_pos()
        assert info.value.module_id == 3


# ----------------------------------------------------------------------------- the module's limits
def test_motion_beyond_the_modules_limits_is_refused_before_sending(arm, sim):
    vmax = np.asarray(iik.THESIS_ARM.velocity)
    sent = len(sim.received())

    def moves():
        return [m for _, m in sim.received()[sent:] if isinstance(m, P.SetMove)]

    with pytest.raises(SafetyError, match=r"exceeds the module's limit .*FMAXVEL"):
        arm.move_step(np.full(6, 1.5), 0.1)  # 15 rad/s
    with pytest.raises(SafetyError, match="FMAXVEL"):
        arm.move_vel(vmax * 1.01)
    with pytest.raises(SafetyError, match="FMAXCUR"):
        arm.move_cur(np.full(6, 100.0))
    with pytest.raises(SafetyError, match="FMAXACC"):
        arm.move_ramp(np.full(6, 0.1), 0.1, 1e3)
    with pytest.raises(SafetyError, match="Sec 3.2"):
        arm.modules[0].set_max_vel(vmax[0] * 2)
    assert moves() == []  # nothing reached the bus
    arm.modules[0].set_max_vel(0.1)  # a module configured slower than Sec 3.2
    with pytest.raises(SafetyError, match=r"module 1 joint q1 step of 500 ms: 0\.2000 rad/s .* 0\.1000"):
        arm.move_step(np.array([0.1, 0, 0, 0, 0, 0]), 0.5)
    arm.move_step(np.full(6, 0.05), 0.5)  # within every limit
    assert len(moves()) == 6


def test_step_speed_is_measured_from_the_previous_target(arm, sim):
    m = arm.modules[0]
    m.move_step(0.3, 0.5)  # 0.6 rad/s from the measured 0
    with pytest.raises(SafetyError, match="FMAXVEL"):
        m.move_step(-0.3, 0.2)  # 3 rad/s from the previous target 0.3
    m.move_step(-0.3, 0.6)  # 1 rad/s: fine
