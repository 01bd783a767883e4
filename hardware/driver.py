"""PowerCube driver on any :class:`can.BusABC`: one module, or an arm of modules.

Methods take and return SI units (rad, rad/s, rad/s^2, A, s). They cover every
function of the thesis's Appendix A, Table V (``PCube_*``) under Pythonic names:

==========================  =====================================================
Table V                     here
==========================  =====================================================
PCube_openDevice/close      :meth:`PowerCubeArm.open` / :meth:`PowerCubeArm.close`
                            (and :meth:`PowerCubeArm.from_config` to open a bus)
PCube_getPos/getVel/getCur  ``get_pos`` / ``get_vel`` / ``get_cur``
PCube_setMaxCur             ``set_max_cur`` (A; Table V prints "rad/s", a typo)
PCube_homeModule/homeAll    ``home`` / ``home_all``
PCube_moveRamp/Step/Vel/Cur ``move_ramp`` / ``move_step`` / ``move_vel`` / ``move_cur``
==========================  =====================================================

plus ``halt``, ``reset``, ``state``, :func:`scan` (VERSION read on ids 1..31),
``start_move`` (broadcast STARTMOVE) and the watchdog (CONFIG bit + a periodic
broadcast 0x07 every 40 ms, sent by python-can's ``send_periodic``).

Every request waits for its echoing ACK (:func:`hardware.protocol.is_echo`)
until a timeout; every other frame read meanwhile is discarded (unsolicited
state frames are remembered as faults), except a second echo of a request already
answered: two modules share an id, a :class:`~hardware.errors.DuplicateModuleError`
(:meth:`PowerCubeArm.open` also listens for such answers), and a frame to the modules
(a request or a broadcast) that this host did not send: another controller commands
them, a :class:`~hardware.errors.SecondControllerError`. HALT latches until RESET:
after :meth:`halt` the driver refuses motion commands locally until :meth:`reset`.

Motion commands are checked before they are sent: finite; position targets inside
the module's limits; speeds (an FSTEP's distance over its time, a ramp's or a
velocity command's speed) within the module's speed limit (its FMAXVEL, and the
joint's Sec 3.2 limit when the arm is known), ramp accelerations within its FMAXACC,
currents within its FMAXCUR (each read once from the module, updated when set here).
The protocol is described in ``docs/POWERCUBE.md``.
"""

from __future__ import annotations

import math
import threading
import time
from collections import deque
from collections.abc import Iterable, Sequence

import can
import numpy as np

from iik.arm import Arm
from iik.errors import InvalidInputError

from . import protocol as P
from .bus import BUS_TIMEOUT, BusConfig, check_module_id, check_module_ids, check_timeout
from .errors import (
    BusError,
    CANTimeoutError,
    DuplicateModuleError,
    ModuleHalted,
    ProtocolError,
    SafetyError,
    SecondControllerError,
)

__all__ = ["PowerCubeModule", "PowerCubeArm", "Link", "scan", "DEFAULT_TIMEOUT",
           "WATCHDOG_PERIOD", "DUPLICATE_WINDOW", "SPEED_TOLERANCE"]

#: Default time to wait for an ACK [s] (:data:`hardware.bus.BUS_TIMEOUT`).
DEFAULT_TIMEOUT = BUS_TIMEOUT
#: Watchdog refresh period [s]: a WATCHDOG broadcast every 40 ms, as the C drivers send it
#: (docs/POWERCUBE.md). The modules stop by themselves when it stays away longer than
#: their watchdog time (not in the public sources; the simulator uses 1 s).
WATCHDOG_PERIOD = 0.040
#: A second echo of a request answered this recently [s] is a duplicate module id.
DUPLICATE_WINDOW = 2.0
#: :meth:`PowerCubeArm.open` listens this long [s] for second answers to its VERSION reads.
OPEN_LISTEN = 0.05
#: Relative tolerance of the speed, acceleration and current checks (f32 values on the wire).
SPEED_TOLERANCE = 1e-6


class Link:
    """One host's request/reply channel on a bus, shared by the modules on it.

    Serialises requests (a lock), applies the echo rule, remembers unsolicited
    state frames in :attr:`faults` (module id -> :class:`~hardware.protocol.State`)
    and counts CAN error frames in :attr:`error_frames`. It remembers the frames it sent
    (and :meth:`own` periodic ones), so that a frame to the modules it did not send, which
    only another controller can have sent, is told from its own on an interface that
    loops them back.
    """

    def __init__(self, bus: can.BusABC, timeout: float = DEFAULT_TIMEOUT):
        if not isinstance(bus, can.BusABC):
            raise InvalidInputError("bus", f"expected a can.BusABC, got {type(bus).__name__}")
        self.bus = bus
        self.timeout = check_timeout(timeout)
        self.faults: dict[int, P.State] = {}
        self.discarded = 0
        self.error_frames = 0  # CAN error frames seen (bus errors reported by the interface)
        self._lock = threading.RLock()
        self._answered: deque[tuple[float, P.Request]] = deque(maxlen=64)  # (when, request) answered
        self._sent: dict[tuple[int, bytes], float] = {}  # (identifier, data) sent -> when (inf: periodic)

    def own(self, frame: can.Message, when: float = math.inf) -> None:
        """Remember ``frame`` as sent by this host at ``when`` [monotonic s] (forgotten after
        :data:`DUPLICATE_WINDOW`; ``inf``, a periodic frame: kept)."""
        if len(self._sent) > 512:
            old = time.monotonic() - DUPLICATE_WINDOW
            self._sent = {k: t for k, t in self._sent.items() if t >= old}
        self._sent[(frame.arbitration_id, bytes(frame.data))] = when

    def send(self, msg: P.Message) -> None:
        """Encode and send one frame; python-can errors become :class:`BusError`."""
        frame = P.encode(msg)
        self.own(frame, time.monotonic())
        try:
            self.bus.send(frame, timeout=self.timeout)
        except can.CanError as exc:
            raise BusError(f"CAN send failed: {exc}") from exc

    def _recv(self, timeout: float):
        try:
            return self.bus.recv(timeout=max(timeout, 0.0))
        except can.CanError as exc:
            raise BusError(f"CAN receive failed: {exc}") from exc

    def _observe(self, frame: can.Message) -> None:
        """Account for a frame that answers no pending request: error frame, state frame,
        a stale reply; a second answer to an answered request raises DuplicateModuleError."""
        self.discarded += 1
        if frame.is_error_frame:
            self.error_frames += 1
            return
        if (foreign := self._foreign(frame)) is not None:
            raise SecondControllerError(frame.arbitration_id, foreign)
        recent = time.monotonic() - DUPLICATE_WINDOW
        for when, req in self._answered:
            if when >= recent and P.is_echo(req, frame):
                raise DuplicateModuleError(req.module, P.describe(req))
        if P.ID_STATE < frame.arbitration_id < P.ID_STATE + 32 and not frame.is_extended_id:
            try:
                msg = P.decode(frame)
            except ProtocolError:
                return
            if isinstance(msg, P.StateFrame):
                self.faults[msg.module] = msg.state

    def _foreign(self, frame: can.Message) -> str | None:
        """What ``frame`` is if it goes to the modules and this host did not send it, else None."""
        arb = frame.arbitration_id
        to_modules = not frame.is_extended_id and (
            arb == P.ID_ALL or P.ID_GET < arb < P.ID_GET + 32 or P.ID_SET < arb < P.ID_SET + 32)
        if not to_modules or (arb, bytes(frame.data)) in self._sent:
            return None
        try:
            msg = P.decode(frame)
        except ProtocolError:
            return "a frame to the modules"
        module = getattr(msg, "module", None)
        return P.describe(msg) + (" (broadcast)" if module is None else f" to module {module}")

    def drain(self, wait: float = 0.0) -> None:
        """Read and discard whatever is queued (late ACKs of earlier requests), listening
        ``wait`` s for more. Raises :class:`DuplicateModuleError` on a second answer."""
        deadline = time.monotonic() + wait
        with self._lock:
            while (frame := self._recv(max(deadline - time.monotonic(), 0.0))) is not None \
                    or time.monotonic() < deadline:
                if frame is not None:
                    self._observe(frame)

    def request(self, req: P.Request, timeout: float | None = None) -> P.Reply:
        """Send ``req`` and return its decoded echoing reply.

        Raises:
            CANTimeoutError: no echo within ``timeout`` (default :attr:`timeout`).
            ProtocolError: the echo is malformed.
            BusError: the interface failed.
        """
        wait = self.timeout if timeout is None else float(timeout)
        with self._lock:
            self.drain()
            self.send(req)
            deadline = time.monotonic() + wait
            while True:
                remaining = deadline - time.monotonic()
                if remaining <= 0:
                    raise CANTimeoutError(req.module, P.describe(req), wait)
                frame = self._recv(remaining)
                if frame is None:
                    continue
                if P.is_echo(req, frame):
                    reply = P.decode(frame)
                    self._answered.append((time.monotonic(), req))
                    return reply
                self._observe(frame)


def _check_positive(value, name: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) \
            or value <= 0:
        raise SafetyError(name, f"must be a positive finite number, got {value!r}")
    return float(value)


def _finite(value, name: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)) \
            or not math.isfinite(float(value)):
        raise SafetyError(name, f"must be a finite number, got {value!r}")
    return float(value)


class PowerCubeModule:
    """One PowerCube module (id 1..31) on a CAN bus.

    Args:
        bus: Any python-can bus (``virtual``, ``socketcan``, ``pcan``, ``kvaser``...).
        module_id: 1..31.
        timeout: Time to wait for each ACK [s].
        limits: Optional ``(lower, upper)`` [rad]; position targets outside are
            refused with :class:`SafetyError` before anything is sent.
        max_vel: Optional speed limit of the joint [rad/s] (Sec 3.2); motion needing more
            is refused, as is motion beyond the module's own FMAXVEL, FMAXACC, FMAXCUR.
        link: Share a :class:`Link` with other modules on the same bus (the arm does).

    Attributes:
        halted: True after :meth:`halt` (or a state read showing HALTED) until :meth:`reset`.
    """

    def __init__(self, bus: can.BusABC, module_id: int, *, timeout: float = DEFAULT_TIMEOUT,
                 limits: tuple[float, float] | None = None, max_vel: float | None = None,
                 link: Link | None = None):
        self.id = check_module_id(module_id)
        self.link = link if link is not None else Link(bus, timeout)
        self.limits = None
        if limits is not None:
            lo, hi = (_finite(v, "limits") for v in limits)
            if not lo < hi:
                raise SafetyError("limits", f"need lower < upper, got {limits!r}")
            self.limits = (lo, hi)
        self.max_vel = None if max_vel is None else _check_positive(max_vel, "max_vel")
        self.halted = False
        self.last_short: P.ShortState | None = None
        self._target: float | None = None  # last position target commanded (reference of the next step)
        self._fmax: dict[P.Param, float] = {}  # the module's FMAXVEL/FMAXACC/FMAXCUR, read once

    def __repr__(self) -> str:
        return f"PowerCubeModule(id={self.id}, halted={self.halted})"

    # -- parameters
    def get_param(self, param: P.Param):
        """Read a parameter (GETPARAM); returns its decoded value."""
        reply = self.link.request(P.GetParam(self.id, P.Param(param)))
        return reply.value

    def set_param(self, param: P.Param, value) -> None:
        """Write a parameter (SETPARAM) and wait for its ACK."""
        self.link.request(P.SetParam(self.id, P.Param(param), value))
        self._fmax.pop(P.Param(param), None)  # a limit written here is read again when needed

    def module_limit(self, param: P.Param) -> float:
        """The module's own limit FMAXVEL [rad/s], FMAXACC [rad/s^2] or FMAXCUR [A]; for
        FMAXVEL also at most ``max_vel``. Read from the module once, then remembered."""
        if param not in self._fmax:
            self._fmax[param] = float(self.get_param(param))
        value = self._fmax[param]
        return min(value, self.max_vel) if param is P.Param.FMAXVEL and self.max_vel is not None else value

    def check_limit(self, value: float, param: P.Param, what: str, unit: str) -> None:
        """Refuse ``|value|`` above the module's limit ``param`` (:meth:`module_limit`): SafetyError."""
        limit = self.module_limit(param)
        if abs(value) > limit * (1.0 + SPEED_TOLERANCE):
            raise SafetyError(f"module {self.id} {what}", f"{abs(value):.4f} {unit} exceeds the module's "
                              f"limit of {limit:.4f} {unit} ({P.Param(param).name})")

    def get_pos(self) -> float:
        """Actual position [rad] (``PCube_getPos``)."""
        return self.get_param(P.Param.ACT_FPOS)

    def get_vel(self) -> float:
        """Actual velocity [rad/s] (``PCube_getVel``)."""
        return self.get_param(P.Param.ACT_FVEL)

    def get_cur(self) -> float:
        """Actual current [A] (``PCube_getCur``)."""
        return self.get_param(P.Param.ACT_FCUR)

    def get_pos_state_dio(self) -> tuple[float, P.ShortState, int]:
        """Position [rad], short state and digital I/O in one reply (FPOSSTATEDIO)."""
        pos, short, dio = self.get_param(P.Param.FPOSSTATEDIO)
        self.last_short = short
        return pos, short, dio

    def state(self) -> P.State:
        """The module's state bits (parameter 0x27). Observes the halt latch."""
        s = P.State(self.get_param(P.Param.STATE))
        if s & P.State.HALTED:
            self.halted = True
        return s

    def version(self) -> int:
        return self.get_param(P.Param.VERSION)

    def serial(self) -> int:
        return self.get_param(P.Param.SERIALNO)

    def set_max_cur(self, current: float) -> None:
        """Maximum current [A] (``PCube_setMaxCur``; Table V says rad/s, a typo)."""
        self.set_param(P.Param.FMAXCUR, _check_positive(current, "current"))

    def set_max_vel(self, velocity: float) -> None:
        """Maximum speed [rad/s]; refused above the joint's Sec 3.2 limit ``max_vel``."""
        v = _check_positive(velocity, "velocity")
        if self.max_vel is not None and v > self.max_vel * (1.0 + SPEED_TOLERANCE):
            raise SafetyError(f"module {self.id} velocity", f"{v:.4f} rad/s exceeds the joint's speed "
                              f"limit of {self.max_vel:.4f} rad/s (Sec 3.2)")
        self.set_param(P.Param.FMAXVEL, v)

    def set_max_acc(self, acceleration: float) -> None:
        self.set_param(P.Param.FMAXACC, _check_positive(acceleration, "acceleration"))

    def set_soft_limits(self, lower: float, upper: float) -> None:
        lo, hi = _finite(lower, "lower"), _finite(upper, "upper")
        if not lo < hi:
            raise SafetyError("limits", f"need lower < upper, got ({lo}, {hi})")
        self.set_param(P.Param.FMINPOS, lo)
        self.set_param(P.Param.FMAXPOS, hi)

    def soft_limits(self) -> tuple[float, float]:
        return self.get_param(P.Param.FMINPOS), self.get_param(P.Param.FMAXPOS)

    # -- plain commands
    def _command(self, cmd: P.Cmd) -> None:
        self.link.request(P.Command(self.id, cmd))

    def home(self) -> None:
        """Start homing (``PCube_homeModule``); see :meth:`wait_homed`."""
        self._refuse_if_halted()
        self._target = None
        self._command(P.Cmd.HOME)

    def halt(self) -> None:
        """Stop now. Latches: no motion is accepted until :meth:`reset`."""
        self.halted = True
        self._target = None
        self._command(P.Cmd.HALT)

    def reset(self) -> None:
        """Clear an error or a halt."""
        self._target = None
        self._command(P.Cmd.RESET)
        self.halted = False
        self.link.faults.pop(self.id, None)

    def wait_homed(self, timeout: float = 30.0, poll: float = 0.02) -> P.State:
        """Poll STATE until HOME_OK (raises :class:`CANTimeoutError` after ``timeout`` s)."""
        deadline = time.monotonic() + timeout
        while True:
            s = self.state()
            if s & P.State.HOME_OK and not s & P.State.MOTION:
                return s
            if time.monotonic() > deadline:
                raise CANTimeoutError(self.id, "HOME (HOME_OK never set)", timeout)
            time.sleep(poll)

    # -- motion
    def _refuse_if_halted(self) -> None:
        if self.halted:
            raise ModuleHalted(self.id)

    def check_target(self, pos, name: str = "pos") -> float:
        """``pos`` [rad] as a float if it is finite and inside this module's limits;
        else :class:`SafetyError` naming ``name``. Sends nothing."""
        p = _finite(pos, name)
        if self.limits is not None and not self.limits[0] <= p <= self.limits[1]:
            raise SafetyError(f"module {self.id} {name}",
                              f"{p:.6f} rad outside [{self.limits[0]:.6f}, {self.limits[1]:.6f}]")
        return p

    def _move(self, mode: P.Mode, value: float, time_ms: int | None, extended: bool):
        self._refuse_if_halted()
        self._target = None  # unknown until acknowledged
        ack = self.link.request(P.SetMove(self.id, mode.as_extended() if extended else mode, value, time_ms))
        if mode in (P.Mode.FSTEP, P.Mode.FRAMP):
            self._target = value
        if extended:
            self.last_short = ack.short
            return ack.position, ack.short, ack.dio
        return None

    def check_ramp(self, pos, vel, acc, name: str = "pos") -> tuple[float, float, float]:
        """``(pos, vel, acc)`` of a ramp if finite, inside the limits and within the module's
        FMAXVEL/FMAXACC; else :class:`SafetyError`. Sends nothing but the limit reads."""
        p = self.check_target(pos, name)
        v, a = _check_positive(vel, "vel"), _check_positive(acc, "acc")
        self.check_limit(v, P.Param.FMAXVEL, "ramp speed", "rad/s")
        self.check_limit(a, P.Param.FMAXACC, "ramp acceleration", "rad/s^2")
        return p, v, a

    def move_ramp(self, pos: float, vel: float, acc: float, *, extended: bool = False):
        """Ramp (trapezoidal) motion to ``pos`` [rad] with ``vel`` [rad/s], ``acc`` [rad/s^2]
        (``PCube_moveRamp``: SETPARAM FRAMPVEL, FRAMPACC, then SETMOVE FRAMP).

        With ``extended`` the reply's (position, short state, dio) is returned.
        """
        self._refuse_if_halted()
        p, v, a = self.check_ramp(pos, vel, acc)
        self.set_param(P.Param.FRAMPVEL, v)
        self.set_param(P.Param.FRAMPACC, a)
        return self._move(P.Mode.FRAMP, p, None, extended)

    def check_step(self, pos, time_s: float, name: str = "pos") -> tuple[float, int]:
        """``(pos, ms)`` of an FSTEP if the target is finite and inside the limits, the time
        is 1..65535 whole ms and the speed it needs (distance from the previous target, or
        from the measured position, over the time on the wire) is within the module's
        speed limit; else :class:`SafetyError`. Sends nothing but reads."""
        p = self.check_target(pos, name)
        ms = step_ms(time_s)
        ref = self._target if self._target is not None else self.get_pos()
        self.check_limit((p - ref) / (ms / 1000.0), P.Param.FMAXVEL, f"{name} step of {ms} ms", "rad/s")
        return p, ms

    def move_step(self, pos: float, time_s: float, *, extended: bool = False):
        """Constant-velocity motion to ``pos`` [rad] in ``time_s`` [s] (``PCube_moveStep``;
        the time goes on the wire in whole ms, 1..65535); see :meth:`check_step`."""
        self._refuse_if_halted()
        return self._move(P.Mode.FSTEP, *self.check_step(pos, time_s), extended)

    def move_vel(self, vel: float, *, extended: bool = False):
        """Constant-velocity motion at ``vel`` [rad/s] (``PCube_moveVel``), within FMAXVEL."""
        v = _finite(vel, "vel")
        self.check_limit(v, P.Param.FMAXVEL, "velocity", "rad/s")
        return self._move(P.Mode.FVEL, v, None, extended)

    def move_cur(self, current: float, *, extended: bool = False):
        """Constant-current motion at ``current`` [A] (``PCube_moveCur``), within FMAXCUR."""
        c = _finite(current, "current")
        self.check_limit(c, P.Param.FMAXCUR, "current", "A")
        return self._move(P.Mode.FCUR, c, None, extended)

    # -- watchdog
    def set_watchdog(self, enabled: bool) -> None:
        """Set or clear the CONFIG watchdog bit (read-modify-write)."""
        cfg = int(self.get_param(P.Param.CONFIG))
        cfg = cfg | P.CONFIG_WATCHDOG if enabled else cfg & ~P.CONFIG_WATCHDOG
        self.set_param(P.Param.CONFIG, cfg)


def step_ms(time_s: float) -> int:
    """``time_s`` [s] as the u16 millisecond count of an FSTEP (1..65535)."""
    t = _check_positive(time_s, "time_s")
    ms = int(round(t * 1000.0))
    if not 1 <= ms <= 0xFFFF:
        raise SafetyError("time_s", f"{t} s is not 1..65535 ms")
    return ms


def scan(bus: can.BusABC, ids: Iterable[int] = P.MODULE_IDS, *, timeout: float = 0.02,
         link: Link | None = None) -> dict[int, int]:
    """Find modules: read VERSION on each id; returns ``{id: version}`` of those that answer.

    Raises:
        DuplicateModuleError: an id answered twice (two modules with that id).
    """
    link = link if link is not None else Link(bus, timeout)
    found = {}
    for i in ids:
        try:
            found[int(i)] = link.request(P.GetParam(int(i), P.Param.VERSION), timeout).value
        except CANTimeoutError:
            continue
    link.drain(timeout)  # a second answer to the last request
    return found


class PowerCubeArm:
    """Several PowerCube modules on one bus, addressed together (joint order = ``module_ids``).

    Args:
        bus: Any python-can bus.
        module_ids: Module ids in joint order, e.g. ``(1, 2, 3, 4, 5, 6)``.
        arm: Joint limits for the local target check (Table I for the thesis arm);
            used when there are six modules. ``None`` disables the local check.
        timeout: Time to wait for each ACK [s].
        owns_bus: Shut the bus down in :meth:`close` (set by :meth:`from_config`).

    Vector methods take and return arrays in joint order (rad, rad/s, A, s).
    """

    def __init__(self, bus: can.BusABC, module_ids: Sequence[int], *, arm: Arm | None,
                 timeout: float = DEFAULT_TIMEOUT, owns_bus: bool = False):
        ids = check_module_ids(module_ids)
        self.bus = bus
        self.link = Link(bus, timeout)
        lims, vels = [None] * len(ids), [None] * len(ids)
        if arm is not None and len(ids) == 6:
            lims, vels = list(zip(arm.lower, arm.upper, strict=True)), list(arm.velocity)
        self.modules = [PowerCubeModule(bus, i, limits=lim, max_vel=v, link=self.link)
                        for i, lim, v in zip(ids, lims, vels, strict=True)]
        self.module_ids = tuple(ids)
        self.arm = arm
        self._owns_bus = owns_bus
        self._watchdog = None

    @classmethod
    def from_config(cls, config: BusConfig, *, arm: Arm | None) -> PowerCubeArm:
        """Open the bus ``config`` names (:meth:`hardware.bus.BusConfig.open`, ``PCube_openDevice``'s first
        half) and an arm of its modules on it, with its ACK timeout; :meth:`close` shuts the bus. Simulated
        modules the config describes are not attached here (:func:`hardware.sim.connect` does that)."""
        bus = config.open()
        try:
            return cls(bus, config.module_ids, arm=arm, timeout=config.ack_timeout, owns_bus=True)
        except BaseException:
            bus.shutdown()
            raise

    @classmethod
    def from_interface(cls, module_ids: Sequence[int] = (1, 2, 3, 4, 5, 6), *, interface: str,
                       channel: str | int | None, bitrate: int | None = None, port: int | None = None,
                       timeout: float | None = None, arm: Arm | None) -> PowerCubeArm:
        """:meth:`from_config` of ``BusConfig(interface, channel, bitrate, port, module_ids, timeout)``
        (validated there: :class:`~iik.errors.InvalidInputError` naming the argument)."""
        config = BusConfig(interface, channel, bitrate, port, tuple(module_ids), timeout)
        return cls.from_config(config, arm=arm)

    def __repr__(self) -> str:
        return f"PowerCubeArm(module_ids={self.module_ids})"

    def __len__(self) -> int:
        return len(self.modules)

    def __enter__(self) -> PowerCubeArm:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def open(self) -> list[P.State]:
        """Check every module answers (VERSION), exactly once (a second answer is a
        :class:`DuplicateModuleError`), and return their states."""
        for m in self.modules:
            m.version()
        self.link.drain(OPEN_LISTEN)
        return self.states()

    def speed_limits(self) -> np.ndarray:
        """Each module's speed limit [rad/s]: its FMAXVEL, at most the joint's Sec 3.2 limit."""
        return np.array([m.module_limit(P.Param.FMAXVEL) for m in self.modules])

    def close(self) -> None:
        """Disable the watchdog and, if this arm opened the bus, shut the bus down."""
        self.stop_watchdog(disable=True)
        if self._owns_bus:
            self.bus.shutdown()
            self._owns_bus = False

    # -- reading
    def get_pos(self) -> np.ndarray:
        return np.array([m.get_pos() for m in self.modules])

    def get_vel(self) -> np.ndarray:
        return np.array([m.get_vel() for m in self.modules])

    def get_cur(self) -> np.ndarray:
        return np.array([m.get_cur() for m in self.modules])

    def states(self) -> list[P.State]:
        return [m.state() for m in self.modules]

    def scan(self, ids: Iterable[int] = P.MODULE_IDS, timeout: float = 0.02) -> dict[int, int]:
        return scan(self.bus, ids, timeout=timeout, link=self.link)

    @property
    def halted(self) -> bool:
        """True if any module is known to be halted (latched)."""
        return any(m.halted for m in self.modules)

    # -- settings
    def _per_joint(self, values, name: str) -> list[float]:
        arr = np.broadcast_to(np.asarray(values, dtype=float), (len(self.modules),)) \
            if np.ndim(values) == 0 else np.asarray(values, dtype=float)
        if arr.shape != (len(self.modules),):
            raise SafetyError(name, f"expected {len(self.modules)} values, got shape {arr.shape}")
        if not np.all(np.isfinite(arr)):
            raise SafetyError(name, "contains NaN or inf")
        return [float(v) for v in arr]

    def set_max_cur(self, current) -> None:
        for m, c in zip(self.modules, self._per_joint(current, "current"), strict=True):
            m.set_max_cur(c)

    # -- commands
    def home(self) -> None:
        """Home every module, one command each (see :meth:`home_all` for the broadcast)."""
        for m in self.modules:
            m.home()

    def home_all(self) -> None:
        """Broadcast HOME (``PCube_homeAll``); no reply. See :meth:`wait_homed`."""
        if self.halted:
            raise ModuleHalted(next(m.id for m in self.modules if m.halted))
        self.link.send(P.Broadcast(P.Cmd.HOME))

    def wait_homed(self, timeout: float = 30.0) -> list[P.State]:
        return [m.wait_homed(timeout) for m in self.modules]

    def halt(self) -> None:
        """Broadcast HALT (one frame reaches every module at once) and latch it locally."""
        for m in self.modules:
            m.halted = True
        self.link.send(P.Broadcast(P.Cmd.HALT))

    def reset(self) -> None:
        """RESET every module (acknowledged one by one); clears the latch."""
        for m in self.modules:
            m.reset()

    def start_move(self) -> None:
        """Broadcast STARTMOVE: buffered motions of all modules start together."""
        self.link.send(P.Broadcast(P.Cmd.STARTMOVE))

    def _check_targets(self, qs: list[float]) -> None:
        """Every joint target is checked before any module is commanded."""
        for i, (m, p) in enumerate(zip(self.modules, qs, strict=True)):
            m.check_target(p, f"joint q{i + 1}")

    def move_ramp(self, q, vel, acc) -> None:
        """Ramp every joint (``PCube_moveRamp``); every joint is checked before any is commanded."""
        qs, vs, as_ = (self._per_joint(q, "q"), self._per_joint(vel, "vel"), self._per_joint(acc, "acc"))
        self._check_targets(qs)
        for i, (m, p, v, a) in enumerate(zip(self.modules, qs, vs, as_, strict=True)):
            m.check_ramp(p, v, a, f"joint q{i + 1}")
        for m, p, v, a in zip(self.modules, qs, vs, as_, strict=True):
            m.move_ramp(p, v, a)

    def move_step(self, q, time_s: float, *, extended: bool = False):
        """FSTEP every joint to ``q`` [rad] in ``time_s`` [s]. Every joint is checked first
        (:meth:`PowerCubeModule.check_step`: limits, whole ms, speed).

        With ``extended`` returns the (n,) actual positions and the short states."""
        qs = self._per_joint(q, "q")
        self._check_targets(qs)
        for i, (m, p) in enumerate(zip(self.modules, qs, strict=True)):
            m.check_step(p, time_s, f"joint q{i + 1}")
        out = [m.move_step(p, time_s, extended=extended) for m, p in zip(self.modules, qs, strict=True)]
        if extended:
            return np.array([o[0] for o in out]), [o[1] for o in out]
        return None

    def move_vel(self, vel) -> None:
        """Constant velocity [rad/s] on every joint, each within its FMAXVEL (all checked first)."""
        self._move_within(vel, "vel", P.Param.FMAXVEL, "velocity", "rad/s", PowerCubeModule.move_vel)

    def move_cur(self, current) -> None:
        """Constant current [A] on every joint, each within its FMAXCUR (all checked first)."""
        self._move_within(current, "current", P.Param.FMAXCUR, "current", "A", PowerCubeModule.move_cur)

    def _move_within(self, value, argument: str, param: P.Param, what: str, unit: str, move) -> None:
        """Check every joint's ``value`` against its module's limit ``param``, then ``move(module, value)``
        each module (nothing is commanded unless every joint passes)."""
        values = self._per_joint(value, argument)
        for m, v in zip(self.modules, values, strict=True):
            m.check_limit(v, param, what, unit)
        for m, v in zip(self.modules, values, strict=True):
            move(m, v)

    # -- watchdog
    def start_watchdog(self, period: float = WATCHDOG_PERIOD) -> None:
        """Enable the watchdog: set the CONFIG bit on every module, then broadcast
        WATCHDOG (0x07) every ``period`` s. If the refresh stops, the modules stop."""
        _check_positive(period, "period")
        if self._watchdog is not None:
            return
        frame = P.encode(P.Broadcast(P.Cmd.WATCHDOG))
        self.link.send(P.Broadcast(P.Cmd.WATCHDOG))
        self.link.own(frame)  # python-can repeats it: this host's, on an interface that loops frames back
        try:
            self._watchdog = self.bus.send_periodic(frame, period)
        except can.CanError as exc:
            raise BusError(f"cannot start the watchdog refresh: {exc}") from exc
        for m in self.modules:
            m.set_watchdog(True)

    def stop_watchdog(self, *, disable: bool = True) -> None:
        """Stop the periodic refresh. With ``disable`` the CONFIG bit is cleared first
        (best effort); without, the modules' watchdog trips and they stop."""
        if self._watchdog is None:
            return
        if disable:
            for m in self.modules:
                try:
                    m.set_watchdog(False)
                except (CANTimeoutError, BusError, ProtocolError):
                    pass
        if self._watchdog is not None:
            self._watchdog.stop()
            self._watchdog = None
