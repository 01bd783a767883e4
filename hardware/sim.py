"""Simulated PowerCube modules answering the protocol on any python-can bus.

:class:`SimulatedArm` attaches :class:`SimModule` objects to a
:class:`can.BusABC` and serves them from a thread until :meth:`SimulatedArm.close`
(also a context manager). It answers exactly as ``docs/POWERCUBE.md`` says:
GETPARAM/SETPARAM/SETMOVE/RESET/HOME/HALT are acknowledged by an echo on
``0x0A0 + id``; broadcasts on 0x100 get no reply; errors are announced by an
unsolicited state frame on ``0x060 + id``.

Motion model (each module independently; time ``t`` [s] from the server's clock):

* **FRAMP**: time-optimal profile from the current set-point state to the target
  with velocity ``min(FRAMPVEL, FMAXVEL)`` and acceleration ``min(FRAMPACC, FMAXACC)``
  (Ruckig, jerk 50x the acceleration, i.e. practically trapezoidal).
* **FSTEP**: constant velocity from the current set-point to the target in the
  given time (Sec 4.3: "receives the desired goal position and time, and computes
  the constant velocity required"); slower if that velocity exceeds the limit.
  A step that arrives while a motion is in progress is buffered (FULLBUFFER) and
  starts when the current one ends or at a broadcast STARTMOVE, whichever is first.
  A step that arrives after the previous one ended starts from rest; every such
  rest is recorded in :attr:`SimModule.stops`.
* **FVEL / FCUR**: ramp to a constant velocity (FCUR: velocity proportional to
  current / FMAXCUR, a crude model); stopped with ERROR|BEYOND_SOFT at a soft limit.
* Speeds never exceed the joint's limit from ``arm.velocity`` (Sec 3.2).
* The measured position/velocity lag the set-point by ``lag`` seconds (pure delay).
* The current is an illustrative friction + viscous + inertial model, clipped at FMAXCUR.
* Soft limits FMINPOS/FMAXPOS default to Table I; a position target outside them
  is refused with ERROR|BEYOND_SOFT and the module stops.
* HALT stops at once and latches (HALTED) until RESET; motion commands are still
  acknowledged but ignored while halted or in error.
* Watchdog: once the CONFIG watchdog bit is set and a WATCHDOG broadcast has been
  seen, a gap longer than ``watchdog_timeout`` stops the module with ERROR|COMM_ERROR.

Faults (:meth:`SimulatedArm.inject`): ``"drop_ack"``, ``"late_ack"``, ``"error"``,
``"vanish"``, immediately or after a given number of motion commands.
"""

from __future__ import annotations

import contextlib
import heapq
import itertools
import math
import sys
import threading
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass

import can
import numpy as np
from ruckig import ControlInterface, InputParameter, Result, Ruckig, Trajectory

from iik.arm import Arm
from iik.errors import InvalidInputError

from . import protocol as P
from .bus import SIM_TIMEOUT, BusConfig, SimConfig, check_module_ids, open_bus
from .clock import FunctionClock
from .driver import PowerCubeArm
from .errors import ProtocolError, SafetyError

__all__ = ["SimulatedArm", "SimModule", "FAULTS", "SIM_VERSION", "connect", "simulated_arm", "serve"]

#: VERSION reported by simulated modules (an arbitrary marker, not a real firmware).
SIM_VERSION = 0x5151
#: Fault kinds accepted by :meth:`SimulatedArm.inject`.
FAULTS = ("drop_ack", "late_ack", "error", "vanish")
_DEFAULT_MAX_CUR = 8.0  # [A], assumed (the thesis gives no currents)
#: Limits that must stay positive; a non-positive write is acknowledged but not applied.
_POSITIVE = frozenset({P.Param.FMAXVEL, P.Param.FMAXACC, P.Param.FMAXCUR, P.Param.FRAMPVEL,
                       P.Param.FRAMPACC})
_EPS_V = 1e-9
_MIN_VEL, _MIN_ACC = 1e-4, 1e-3  # floors of ramp limits [rad/s, rad/s^2] (numerics)


# ----------------------------------------------------------------------------- motions
class _Hold:
    kind = "hold"

    def __init__(self, p: float, t0: float):
        self.p, self.t0, self.end = p, t0, t0

    def at(self, t: float):
        return self.p, 0.0, 0.0


class _Linear:
    kind = "step"

    def __init__(self, p0: float, p1: float, t0: float, duration: float):
        self.p0, self.p1, self.t0 = p0, p1, t0
        self.T = max(duration, 1e-9)
        self.end = t0 + self.T
        self.v = (p1 - p0) / self.T

    def at(self, t: float):
        if t >= self.end:
            return self.p1, 0.0, 0.0
        if t <= self.t0:
            return self.p0, 0.0, 0.0
        return self.p0 + self.v * (t - self.t0), self.v, 0.0


class _Ruckig:
    """A Ruckig profile (position interface: to a target at rest; velocity
    interface: to a constant velocity, then on at that velocity)."""

    def __init__(self, kind: str, p0, v0, a0, target, vmax, amax, t0):
        self.kind, self.t0 = kind, t0
        vmax, amax = max(vmax, _MIN_VEL), max(amax, _MIN_ACC)  # numerical floors
        inp = InputParameter(1)
        # start at zero acceleration (trapezoidal re-targeting): keeps |v| <= max(|v0|, vmax)
        # even when the new acceleration limit is below the current acceleration
        inp.current_position, inp.current_velocity, inp.current_acceleration = [p0], [v0], [0.0]
        inp.max_velocity, inp.max_acceleration, inp.max_jerk = [vmax], [amax], [50.0 * amax]
        if kind == "vel":
            inp.control_interface = ControlInterface.Velocity
            inp.target_velocity, inp.target_acceleration = [target], [0.0]
        else:
            inp.target_position, inp.target_velocity, inp.target_acceleration = [target], [0.0], [0.0]
        self.traj = Trajectory(1)
        try:
            result = Ruckig(1).calculate(inp, self.traj)
        except Exception as exc:  # noqa: BLE001 - ruckig.RuckigError derives from Exception only
            raise SafetyError("motion", f"no profile ({exc})") from None
        if result not in (Result.Working, Result.Finished):
            raise SafetyError("motion", f"no profile ({result})")
        self.duration = self.traj.duration
        self.end = math.inf if kind == "vel" else t0 + self.duration
        self._pend, self._vend, _ = (x[0] for x in self.traj.at_time(self.duration))

    def at(self, t: float):
        tau = t - self.t0
        if tau >= self.duration:
            if self.kind == "vel":
                return self._pend + self._vend * (tau - self.duration), self._vend, 0.0
            return self._pend, 0.0, 0.0
        p, v, a = self.traj.at_time(max(tau, 0.0))
        return p[0], v[0], a[0]


# ----------------------------------------------------------------------------- module
@dataclass
class _Fault:
    kind: str
    after_moves: int
    count: int
    delay: float
    bits: int


class SimModule:
    """One simulated module. Pure state machine: :meth:`handle` and :meth:`advance`
    take the time ``now`` [s] explicitly, so it can be driven by a simulated clock.

    Args:
        module_id: 1..31.
        lower, upper: Soft limits [rad] (defaults of FMINPOS/FMAXPOS).
        vmax: Hardware speed limit [rad/s] (Sec 3.2); FMAXVEL cannot exceed it.
        amax: Acceleration limit [rad/s^2] (default FMAXACC).
        lag: Tracking lag of the measured signals behind the set-point [s].
        initial: Initial position [rad].
        homed: Start with HOME_OK set.
        watchdog_timeout: Watchdog gap that stops the module [s] (assumed: the public sources give
            none; 1 s, 25 refresh periods, so a loaded host does not trip it by accident).
    """

    def __init__(self, module_id: int, *, lower: float = -math.pi, upper: float = math.pi,
                 vmax: float = 1.2, amax: float = 2.0, lag: float = 0.02, initial: float = 0.0,
                 homed: bool = True, watchdog_timeout: float = 1.0, now: float = 0.0):
        self.id = module_id
        self.vmax_hw = float(vmax)
        self.lag = float(lag)
        self.watchdog_timeout = float(watchdog_timeout)
        self.params: dict[P.Param, float | int] = {
            P.Param.FMINPOS: float(lower), P.Param.FMAXPOS: float(upper),
            P.Param.FMAXVEL: float(vmax), P.Param.FMAXACC: float(amax),
            P.Param.FMAXCUR: _DEFAULT_MAX_CUR, P.Param.FRAMPVEL: 0.5 * float(vmax),
            P.Param.FRAMPACC: 0.5 * float(amax), P.Param.CONFIG: 0,
            P.Param.SERIALNO: 100_000 + module_id, P.Param.VERSION: SIM_VERSION,
        }
        self.flags = P.State.HOME_OK if homed else P.State(0)
        self.history: list = [_Hold(float(initial), now)]
        self.buffer: tuple[float, float] | None = None  # (target, duration) of a buffered step
        self.vanished = False
        self.faults: list[_Fault] = []
        self.active: list[_Fault] = []
        self.moves_received = 0
        self.received: list[tuple[float, P.Message]] = []
        #: (time [s], duration [s]) of every rest between two consecutive steps: the
        #: "stoppage of motion at each step-point" that Sec 4.3's early update removes.
        self.stops: list[tuple[float, float]] = []
        self._wd_last: float | None = None
        self._homing = False

    # -- kinematics of the set-point and of the measurement
    @property
    def motion(self):
        return self.history[-1]

    def setpoint(self, now: float) -> tuple[float, float, float]:
        """Set-point (position [rad], velocity [rad/s], acceleration [rad/s^2]) at ``now``."""
        return self.motion.at(now)

    def measured(self, now: float) -> tuple[float, float, float]:
        """Measured (position, velocity, current [A]) at ``now``: the set-point ``lag`` s ago."""
        t = now - self.lag
        seg = self.history[0]
        for m in reversed(self.history):
            if m.t0 <= t:
                seg = m
                break
        p, v, a = seg.at(max(t, seg.t0))
        return p, v, self._current(v, a)

    def _current(self, v: float, a: float) -> float:
        cur = 0.4 * math.tanh(v / 0.01) + 0.8 * v + 0.3 * a + 0.5  # illustrative model [A]
        cmax = float(self.params[P.Param.FMAXCUR])
        return max(-cmax, min(cmax, cur))

    def _start(self, motion, now: float) -> None:
        self.history.append(motion)
        horizon = now - self.lag - 1.0
        while len(self.history) > 2 and self.history[1].t0 < horizon:
            self.history.pop(0)

    def _stop(self, now: float) -> None:
        p, _, _ = self.setpoint(now)
        self._start(_Hold(p, now), now)
        self.buffer = None
        self._homing = False

    @property
    def vmax(self) -> float:
        return min(float(self.params[P.Param.FMAXVEL]), self.vmax_hw)

    # -- state
    def state(self, now: float) -> P.State:
        """Full state bits (parameter 0x27) at ``now``."""
        s = P.State(self.flags)
        m = self.motion
        _, v, a = m.at(now)
        in_progress = now < m.end
        if in_progress:
            s |= P.State.INPROGRESS
        if abs(v) > _EPS_V:
            s |= P.State.MOTION
            if a * v > 0:
                s |= P.State.RAMP_ACC
            elif a * v < 0:
                s |= P.State.RAMP_DEC
            else:
                s |= P.State.RAMP_STEADY
        if not in_progress and m.kind in ("step", "pos"):
            s |= P.State.RAMP_END
        if self.buffer is not None:
            s |= P.State.FULLBUFFER
        _, mv, cur = self.measured(now)
        if abs(cur) >= float(self.params[P.Param.FMAXCUR]) - 1e-9:
            s |= P.State.CURLIMIT
        return s

    def _fail(self, bits: int, now: float) -> list[P.Message]:
        self._stop(now)
        self.flags |= P.State.ERROR | P.State(bits)
        return [P.StateFrame(self.id, self.state(now))]

    @property
    def halted(self) -> bool:
        return bool(self.flags & P.State.HALTED)

    # -- time
    def advance(self, now: float) -> list[P.Message]:
        """Move the model to ``now``; returns unsolicited frames (watchdog trip, soft limit)."""
        out: list[P.Message] = []
        if self.vanished:
            return out
        m = self.motion
        if self.buffer is not None and now >= m.end:
            target, duration = self.buffer
            self.buffer = None
            self._start_step(target, duration, m.end)
        m = self.motion
        if self._homing and now - self.lag >= m.end:
            self._homing = False
            self.flags |= P.State.HOME_OK
        if m.kind == "vel":
            p, _, _ = m.at(now)
            lo, hi = self.params[P.Param.FMINPOS], self.params[P.Param.FMAXPOS]
            if p < lo or p > hi:
                self._start(_Hold(min(max(p, lo), hi), now), now)
                self.flags |= P.State.ERROR | P.State.BEYOND_SOFT
                out.append(P.StateFrame(self.id, self.state(now)))
        cfg = int(self.params[P.Param.CONFIG])
        if cfg & P.CONFIG_WATCHDOG and self._wd_last is not None \
                and now - self._wd_last > self.watchdog_timeout and not self.flags & P.State.ERROR:
            self._wd_last = None
            out += self._fail(P.State.COMM_ERROR, now)
        return out

    def _start_step(self, target: float, duration: float, t0: float) -> None:
        prev = self.motion
        if prev.kind == "step" and t0 > prev.end + 1e-9:
            self.stops.append((prev.end, t0 - prev.end))  # came to rest between two steps
        p0, _, _ = prev.at(t0)
        duration = max(duration, abs(target - p0) / self.vmax)  # Sec 3.2 speed limit
        self._start(_Linear(p0, target, t0, duration), t0)

    # -- protocol
    def inject(self, kind: str, *, after_moves: int = 0, count: int = 1, delay: float = 0.0,
               bits: int = P.State.ERROR) -> None:
        if kind not in FAULTS:
            raise SafetyError("kind", f"unknown fault {kind!r}; one of {FAULTS}")
        self.faults.append(_Fault(kind, int(after_moves), int(count), float(delay), int(bits)))

    def _trigger(self, now: float) -> list[P.Message]:
        out: list[P.Message] = []
        for f in list(self.faults):
            if self.moves_received >= f.after_moves:
                self.faults.remove(f)
                if f.kind == "vanish":
                    self.vanished = True
                elif f.kind == "error":
                    out += self._fail(f.bits, now)
                else:
                    self.active.append(f)
        return out

    def arm_faults(self, now: float) -> list[P.Message]:
        """Fire faults due without a motion command (``after_moves=0``)."""
        return self._trigger(now)

    def reply_policy(self) -> tuple[bool, float]:
        """(drop, delay) for the next reply, consuming active reply faults."""
        drop, delay = False, 0.0
        for f in list(self.active):
            if f.kind == "drop_ack":
                drop = True
            else:
                delay = max(delay, f.delay)
            if f.count > 0:
                f.count -= 1
                if f.count == 0:
                    self.active.remove(f)
        return drop, delay

    def handle(self, msg: P.Message, now: float) -> list[P.Message]:
        """Process one request or broadcast; returns the frames to send (replies first)."""
        if self.vanished:
            return []
        self.received.append((now, msg))
        out: list[P.Message] = []
        if isinstance(msg, P.SetMove):
            self.moves_received += 1
            out += self._trigger(now)
            if self.vanished:
                return []
        out += self.advance(now)
        if isinstance(msg, P.Broadcast):
            self._broadcast(msg.cmd, now)
            return out
        if isinstance(msg, P.GetParam):
            return [self._read(msg.param, now)] + out
        if isinstance(msg, P.SetParam):
            if msg.param in _POSITIVE and not msg.value > 0:
                return [P.SetParamAck(self.id, msg.param)] + out  # acknowledged, not applied
            self.params[msg.param] = msg.value
            return [P.SetParamAck(self.id, msg.param)] + out
        if isinstance(msg, P.Command):
            self._plain(msg.cmd, now)
            return [P.CommandAck(self.id, msg.cmd)] + out
        if isinstance(msg, P.SetMove):
            out = self._move(msg, now) + out
            if msg.mode.extended:
                p, _, _ = self.measured(now)
                ack = P.MoveAck(self.id, msg.mode, p, P.short_state(self.state(now)), 0)
            else:
                ack = P.MoveAck(self.id, msg.mode)
            return [ack] + out
        return out  # replies and state frames of other nodes: ignored

    def _read(self, par: P.Param, now: float) -> P.ParamReply:
        p, v, cur = self.measured(now)
        value = {
            P.Param.STATE: lambda: int(self.state(now)),
            P.Param.ACT_FPOS: lambda: p,
            P.Param.ACT_FVEL: lambda: v,
            P.Param.ACT_FCUR: lambda: cur,
            P.Param.FPOSSTATEDIO: lambda: (p, P.short_state(self.state(now)), 0),
        }.get(par, lambda: self.params[par])()
        return P.ParamReply(self.id, par, value)

    def _plain(self, cmd: P.Cmd, now: float) -> None:
        if cmd is P.Cmd.HALT:
            self._stop(now)
            self.flags |= P.State.HALTED
        elif cmd is P.Cmd.RESET:
            keep = self.flags & P.State.HOME_OK
            self._stop(now)
            self.flags = P.State(keep)
            self._wd_last = None
        elif cmd is P.Cmd.HOME:
            if self.flags & (P.State.HALTED | P.State.ERROR):
                return
            self.flags &= ~P.State.HOME_OK
            p, v, a = self.setpoint(now)
            self._start(_Ruckig("pos", p, v, a, 0.0, 0.5 * self.vmax,
                                float(self.params[P.Param.FMAXACC]), now), now)
            self._homing = True

    def _broadcast(self, cmd: P.Cmd, now: float) -> None:
        if cmd in (P.Cmd.HALT, P.Cmd.RESET, P.Cmd.HOME):
            self._plain(cmd, now)
        elif cmd is P.Cmd.WATCHDOG:
            self._wd_last = now
        elif cmd is P.Cmd.STARTMOVE and self.buffer is not None:
            target, duration = self.buffer
            self.buffer = None
            self._start_step(target, duration, now)

    def _move(self, msg: P.SetMove, now: float) -> list[P.Message]:
        if self.flags & (P.State.HALTED | P.State.ERROR):
            return []  # acknowledged, ignored: HALT latches until RESET
        mode = msg.mode.plain
        lo, hi = self.params[P.Param.FMINPOS], self.params[P.Param.FMAXPOS]
        if mode in (P.Mode.FRAMP, P.Mode.FSTEP) and not lo <= msg.value <= hi:
            return self._fail(P.State.BEYOND_SOFT, now)
        p, v, a = self.setpoint(now)
        amax = float(self.params[P.Param.FMAXACC])
        if mode is P.Mode.FSTEP:
            duration = msg.time_ms / 1000.0
            if now < self.motion.end:
                self.buffer = (msg.value, duration)
            else:
                self._start_step(msg.value, duration, now)
        elif mode is P.Mode.FRAMP:
            vel = min(float(self.params[P.Param.FRAMPVEL]), self.vmax)
            acc = min(float(self.params[P.Param.FRAMPACC]), amax)
            self._start(_Ruckig("pos", p, v, a, msg.value, vel, acc, now), now)
            self.buffer = None
        else:
            if mode is P.Mode.FVEL:
                target = msg.value
            else:  # FCUR: crude, velocity proportional to current
                target = msg.value / float(self.params[P.Param.FMAXCUR]) * self.vmax
            target = max(-self.vmax, min(self.vmax, target))
            self._start(_Ruckig("vel", p, v, a, target, self.vmax, amax, now), now)
            self.buffer = None
        return []


# ----------------------------------------------------------------------------- server
def _module_joints(n: int) -> tuple[int, ...]:
    """The arm joint (from 0) whose limits, speed and acceleration each of ``n`` simulated modules
    takes, in order: joints 1..6 for the first six, joint 1 for any further module."""
    return tuple(j if j < 6 else 0 for j in range(n))


def _checked_modules(module_ids, sim: SimConfig, arm: Arm) -> tuple[tuple[int, ...], np.ndarray]:
    """Module ids (:func:`hardware.bus.check_module_ids`) and the initial positions [rad] of ``sim`` (one
    per module, inside the modules' soft limits: the arm's limits for the first six)."""
    ids = check_module_ids(module_ids)
    q0 = np.zeros(len(ids)) if sim.initial is None else np.array(sim.initial, dtype=float)
    if q0.shape != (len(ids),):
        raise InvalidInputError("initial", f"need {len(ids)} finite positions [rad], one per module, got "
                                           f"{len(q0)}")
    for j, (p, k) in enumerate(zip(q0, _module_joints(len(ids)), strict=True)):
        for v in arm.limit_violations([p], joints=(k,)):  # the soft limits SimulatedArm gives module j
            raise InvalidInputError("initial", f"joint q{j + 1} at {p:g} rad is outside its soft limits "
                                               f"[{v.lower:.4f}, {v.upper:.4f}] rad ({arm.limits_name})")
    return ids, q0


class SimulatedArm:
    """Simulated PowerCube modules served on a python-can bus by a thread.

    Args:
        bus: The bus the modules listen on. On ``virtual`` use a separate bus
            object (same channel) from the host's: python-can's virtual bus does not
            deliver a frame to the object that sent it.
        module_ids: Module ids in joint order.
        arm: Supplies per-joint soft limits (Table I), speed limits (Sec 3.2) and
            acceleration limits for the first six modules.
        lag: Tracking lag [s]. ``initial``: initial joint positions [rad].
        tick: Server period [s]. ``clock``: time source [s] (default monotonic).
        owns_bus: Shut ``bus`` down in :meth:`close`.
    """

    def __init__(self, bus: can.BusABC, module_ids: Sequence[int] = (1, 2, 3, 4, 5, 6), *,
                 arm: Arm, lag: float = 0.02, initial=None, homed: bool = True,
                 tick: float = 0.002, watchdog_timeout: float = 1.0,
                 clock: Callable[[], float] = time.monotonic, owns_bus: bool = False,
                 start: bool = True):
        try:
            sim = SimConfig(lag, initial, homed)  # validated as a simulated bus's modules are
            ids, q0 = _checked_modules(module_ids, sim, arm)
        except InvalidInputError:
            if owns_bus:
                bus.shutdown()
            raise
        self.bus = bus
        self.clock = clock
        self.tick = float(tick)
        now = clock()
        self.modules: dict[int, SimModule] = {}
        for j, (i, k) in enumerate(zip(ids, _module_joints(len(ids)), strict=True)):
            self.modules[i] = SimModule(
                i, lower=arm.lower[k], upper=arm.upper[k], vmax=arm.velocity[k],
                amax=arm.acceleration[k], lag=sim.lag, initial=float(q0[j]), homed=homed,
                watchdog_timeout=watchdog_timeout, now=now)
        self.module_ids = tuple(ids)
        self.malformed = 0
        self.sent = 0
        #: Exceptions raised while serving a frame (a bug or an impossible motion); the
        #: server keeps going and the frame goes unanswered.
        self.errors: list[str] = []
        self._owns_bus = owns_bus
        self._lock = threading.RLock()
        self._pending: list = []
        self._seq = itertools.count()
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        if start:
            self.start()

    @classmethod
    def virtual(cls, channel: str, module_ids: Sequence[int] = (1, 2, 3, 4, 5, 6), **kwargs):
        """A simulated arm on its own ``virtual`` bus object on ``channel``."""
        return cls(open_bus("virtual", channel, receive_own_messages=False), module_ids, owns_bus=True,
                   **kwargs)

    @classmethod
    def attach(cls, config: BusConfig, *, arm: Arm, **kwargs) -> SimulatedArm:
        """The simulated modules ``config.sim`` describes (default :class:`~hardware.bus.SimConfig`), with
        ``config.module_ids`` and ``arm``'s limits, on their own bus object on ``config``'s bus (which
        :meth:`close` shuts down). Their ids and initial positions are checked before the bus is opened.
        ``kwargs``: ``tick``, ``watchdog_timeout``."""
        sim = config.sim if config.sim is not None else SimConfig()
        _checked_modules(config.module_ids, sim, arm)
        return cls(config.open(), config.module_ids, arm=arm, lag=sim.lag, initial=sim.initial,
                   homed=sim.homed, clock=sim.clock.now, owns_bus=True, **kwargs)

    def __enter__(self) -> SimulatedArm:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def __repr__(self) -> str:
        return f"SimulatedArm(module_ids={self.module_ids}, running={self.running})"

    @property
    def running(self) -> bool:
        return self._thread is not None and self._thread.is_alive()

    def start(self) -> None:
        if self.running:
            return
        self._stop.clear()
        self._thread = threading.Thread(target=self._serve, name="SimulatedArm", daemon=True)
        self._thread.start()

    def close(self) -> None:
        """Stop serving (and shut the bus down if this object owns it)."""
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout=2.0)
            self._thread = None
        if self._owns_bus:
            self.bus.shutdown()
            self._owns_bus = False

    def module(self, module_id: int) -> SimModule:
        return self.modules[int(module_id)]

    # -- observation (thread-safe)
    def positions(self) -> np.ndarray:
        """Measured joint positions [rad] now, in joint order."""
        with self._lock:
            now = self.clock()
            return np.array([self.modules[i].measured(now)[0] for i in self.module_ids])

    def setpoints(self) -> np.ndarray:
        with self._lock:
            now = self.clock()
            return np.array([self.modules[i].setpoint(now)[0] for i in self.module_ids])

    def states(self) -> list[P.State]:
        with self._lock:
            now = self.clock()
            return [self.modules[i].state(now) for i in self.module_ids]

    def moving(self) -> list[bool]:
        with self._lock:
            now = self.clock()
            return [abs(self.modules[i].setpoint(now)[1]) > _EPS_V or now < self.modules[i].motion.end
                    for i in self.module_ids]

    def received(self) -> list[tuple[float, P.Message]]:
        """Every request and broadcast the modules have decoded, in order."""
        with self._lock:
            out = [r for m in self.modules.values() for r in m.received]
        return sorted(out, key=lambda r: r[0])

    # -- faults
    def inject(self, module_id: int, kind: str, *, after_moves: int = 0, count: int = 1,
               delay: float = 0.0, bits: int = P.State.ERROR) -> None:
        """Inject a fault into one module.

        Args:
            kind: ``"drop_ack"`` (no reply, ``count`` times; -1 forever), ``"late_ack"``
                (replies ``delay`` s late, ``count`` times), ``"error"`` (set ``bits`` plus
                ERROR, stop, announce a state frame) or ``"vanish"`` (the module goes
                silent and deaf; it finishes its current motion and stops).
            after_moves: Fire when the module has received this many more motion
                commands (0 = now). The fault applies to that command.
        """
        with self._lock:
            m = self.modules[int(module_id)]
            m.inject(kind, after_moves=m.moves_received + after_moves, count=count, delay=delay,
                     bits=bits)
            if after_moves == 0:
                self._queue(m, m.arm_faults(self.clock()), self.clock(), unsolicited=True)

    # -- serving
    def _queue(self, m: SimModule, msgs, now: float, unsolicited: bool = False) -> None:
        for msg in msgs:
            if isinstance(msg, P.StateFrame) or unsolicited:
                drop, delay = False, 0.0
            else:
                drop, delay = m.reply_policy()
            if not drop:
                heapq.heappush(self._pending, (now + delay, next(self._seq), msg))

    def _serve(self) -> None:
        while not self._stop.is_set():
            wait = self.tick
            if self._pending:
                wait = min(wait, max(self._pending[0][0] - self.clock(), 0.0))
            try:
                frame = self.bus.recv(timeout=wait)
            except (can.CanError, OSError, ValueError):
                if self._stop.is_set():
                    return
                time.sleep(self.tick)
                continue
            with self._lock:
                now = self.clock()
                for m in self.modules.values():
                    self._queue(m, m.advance(now), now, unsolicited=True)
                if frame is not None:
                    try:
                        self._dispatch(frame, now)
                    except Exception as exc:  # noqa: BLE001 - keep serving the other modules
                        self.errors.append(f"{type(exc).__name__}: {exc}")
                self._flush(self.clock())

    def _dispatch(self, frame: can.Message, now: float) -> None:
        try:
            msg = P.decode(frame)
        except ProtocolError:
            self.malformed += 1
            return
        if isinstance(msg, P.Broadcast):
            for m in self.modules.values():
                self._queue(m, m.handle(msg, now), now, unsolicited=True)
        elif isinstance(msg, (P.GetParam, P.SetParam, P.SetMove, P.Command)):
            m = self.modules.get(msg.module)
            if m is not None:
                out = m.handle(msg, now)
                if out:
                    self._queue(m, out[:1], now)
                    self._queue(m, out[1:], now, unsolicited=True)

    def _flush(self, now: float) -> None:
        while self._pending and self._pending[0][0] <= now:
            _, _, msg = heapq.heappop(self._pending)
            try:
                self.bus.send(P.encode(msg))
                self.sent += 1
            except (can.CanError, OSError, ValueError):
                pass


@contextlib.contextmanager
def _short_switch_interval(seconds: float = 0.0005) -> Iterator[None]:
    """Host and simulated modules are threads of one interpreter: switch between them often meanwhile, so
    request round trips stay short."""
    switch = sys.getswitchinterval()
    sys.setswitchinterval(seconds)
    try:
        yield
    finally:
        sys.setswitchinterval(switch)


@contextlib.contextmanager
def connect(config: BusConfig, *, arm: Arm) -> Iterator[tuple[PowerCubeArm, SimulatedArm | None]]:
    """Yield ``(host, sim)``: a :class:`hardware.PowerCubeArm` of ``config``'s modules on its bus (its
    local target check with ``arm``'s limits), and the simulated modules ``config.sim`` attaches to that
    bus in this process (:meth:`SimulatedArm.attach`, ``arm``'s limits, speeds and accelerations), or
    None if the modules are elsewhere. With simulated modules on ``virtual`` and no channel, the channel
    is a private one (:meth:`hardware.bus.BusConfig.private`). Everything is closed on exit.
    """
    config = config.private()
    with contextlib.ExitStack() as stack:
        sim = None
        if config.sim is not None:
            stack.enter_context(_short_switch_interval())
            sim = stack.enter_context(SimulatedArm.attach(config, arm=arm))
        host = stack.enter_context(PowerCubeArm.from_config(config, arm=arm))
        yield host, sim


@contextlib.contextmanager
def simulated_arm(module_ids=(1, 2, 3, 4, 5, 6), *, arm: Arm, lag: float = 0.02, initial=None,
                  timeout: float = SIM_TIMEOUT, clock: Callable[[], float] = time.monotonic):
    """Yield ``(sim, arm)``: an in-process :class:`hardware.sim.SimulatedArm` of ``arm`` (its limits,
    speeds and accelerations) on a private ``virtual`` channel and a :class:`hardware.PowerCubeArm`
    talking to it (its local target check with the same limits): :func:`connect` of
    ``BusConfig.simulated(SimConfig(lag, initial, clock=...), module_ids=..., timeout=...)``.

    ``clock`` is the simulator's time source [s] (pass the same one to ``execute``). ``timeout``
    is the arm's ACK timeout [s], generous because host and modules share one interpreter.
    """
    sim = SimConfig(lag, initial, clock=FunctionClock(clock))
    config = BusConfig.simulated(sim, module_ids=tuple(module_ids), timeout=timeout)
    with connect(config, arm=arm) as (host, modules):
        yield modules, host


def serve(config: BusConfig, *, arm: Arm, duration: float | None = None, stop: threading.Event | None = None,
          ready: Callable[[SimulatedArm], None] | None = None) -> None:
    """Serve simulated modules on the bus ``config`` names (e.g. ``udp_multicast`` on 239.74.163.2, so a
    host in another process can reach them) in real time until ``stop`` is set or ``duration`` [s] has
    passed (blocking; Ctrl-C propagates). The modules are ``config.module_ids`` of ``arm`` (its limits,
    speeds and accelerations, e.g. ``iik.arms.get("crx10ia")``) as ``config.sim`` describes them (lag,
    initial positions, homed; default :class:`~hardware.bus.SimConfig`); :meth:`SimulatedArm.attach`
    opens the bus and :meth:`SimulatedArm.close` shuts it down on return.

    Args:
        ready: Called with the running arm once it serves.

    Raises:
        InvalidInputError: initial positions outside the arm's limits, or a duration that is not a
            positive finite number of seconds (before any bus is opened). BusError: the bus could not be
            opened.
    """
    if duration is not None and (isinstance(duration, bool) or not isinstance(duration, (int, float))
                                 or not (math.isfinite(duration) and duration > 0)):
        raise InvalidInputError("duration", f"must be a positive finite number of seconds, got {duration!r}")
    with SimulatedArm.attach(config, arm=arm) as sim:
        if ready is not None:
            ready(sim)
        (stop if stop is not None else threading.Event()).wait(duration)
