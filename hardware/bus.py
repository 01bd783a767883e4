"""Where the PowerCube modules are: one validated bus configuration, in python-can's terms.

:class:`BusConfig` names a python-can bus (``interface``, ``channel``, ``bitrate``, ``port``), the
module ids in joint order and the ACK timeout. It is validated once, when built: every bad value is an
:class:`iik.errors.InvalidInputError` naming the argument. The driver
(:meth:`hardware.PowerCubeArm.from_config`), the simulated arm (:meth:`hardware.sim.SimulatedArm.attach`,
:func:`hardware.sim.serve`, ``iik sim-arm``) and the runner (:func:`hardware.run`, ``iik run``) all
take one, and the driver's constructors check ids and timeouts with the same functions.

The simulated arm is just another bus: a :class:`SimConfig` on the config attaches simulated modules to
the bus in this process. ``BusConfig.simulated()`` is python-can's virtual twin: a private ``virtual``
channel with the simulated modules on one bus object and the host on another.
"""

from __future__ import annotations

import math
import operator
import uuid
from dataclasses import dataclass, field, replace

import can

from iik.errors import InvalidInputError
from iik.validation import bounded_number

from . import protocol as P
from .clock import REAL_TIME, Clock
from .errors import BusError

__all__ = ["BusConfig", "SimConfig", "open_bus", "check_module_ids", "check_module_id", "check_timeout",
           "SIM_TIMEOUT", "BUS_TIMEOUT", "MAX_TIMEOUT", "MAX_LAG"]

#: ACK timeout [s] with simulated modules in this process: generous, since their thread shares one
#: interpreter (and a loaded machine) with the host; they never go silent unless a fault is injected.
SIM_TIMEOUT = 2.0
#: ACK timeout [s] on a real bus (or a simulator in another process).
BUS_TIMEOUT = 0.1
#: Longest ACK timeout accepted [s] (a reply takes milliseconds; more only hides a dead bus).
MAX_TIMEOUT = 10.0
#: Longest tracking lag of simulated modules [s].
MAX_LAG = 1.0


def _integer(value, argument: str, allowed, what: str) -> int:
    """``value`` as an int if it is one (not a bool) and in ``allowed``; else InvalidInputError."""
    try:
        number = None if isinstance(value, bool) else operator.index(value)
    except TypeError:
        number = None
    if number is None or number not in allowed:
        raise InvalidInputError(argument, f"must be {what}, got {value!r}")
    return number


def check_module_id(value, argument: str = "module_id") -> int:
    """A module id (an int in 1..31) as an int; else InvalidInputError naming ``argument``."""
    return _integer(value, argument, P.MODULE_IDS, "a module id, an int in 1..31")


def check_module_ids(values, argument: str = "module_ids") -> tuple[int, ...]:
    """Module ids in joint order (at least one, distinct, each an int in 1..31) as a tuple; else
    InvalidInputError naming ``argument``."""
    try:
        ids = tuple(check_module_id(v, argument) for v in values)
    except (TypeError, InvalidInputError):
        ids = ()
    if not ids or len(set(ids)) != len(ids):
        shown = list(values) if isinstance(values, (list, tuple, range)) else values
        raise InvalidInputError(argument, f"need distinct module ids in 1..31, got {shown!r}")
    return ids


def check_timeout(value, argument: str = "timeout") -> float:
    """An ACK timeout in (0, :data:`MAX_TIMEOUT`] s as a float; else InvalidInputError."""
    return bounded_number(value, argument, 0.0, MAX_TIMEOUT, unit=" s", open_lo=True)


@dataclass(frozen=True)
class SimConfig:
    """Simulated PowerCube modules (:class:`hardware.sim.SimulatedArm`) attached to a bus in this process.

    Attributes:
        lag: Tracking lag of the measured signals behind the set-point, [0, 1] s.
        initial: Initial joint positions [rad], one per module (inside the arm's limits, checked when
            the modules are attached); None: all zero.
        homed: The modules start with HOME_OK set.
        clock: The modules' time (:mod:`hardware.clock`): :data:`~hardware.clock.REAL_TIME`, or a
            :class:`~hardware.clock.VirtualClock`, which :func:`hardware.run` shares with the executor.
    """

    lag: float = 0.02
    initial: tuple[float, ...] | None = None
    homed: bool = True
    clock: Clock = field(default=REAL_TIME, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "lag", bounded_number(self.lag, "lag", 0.0, MAX_LAG, unit=" s"))
        if self.initial is not None:
            try:
                q = tuple(float(v) for v in self.initial)
            except (TypeError, ValueError):
                q = (math.nan,)
            if not q or not all(math.isfinite(v) for v in q):
                raise InvalidInputError("initial", f"need finite positions [rad], one per module, got "
                                                   f"{self.initial!r}")
            object.__setattr__(self, "initial", q)
        if not isinstance(self.homed, bool):
            raise InvalidInputError("homed", f"must be True or False, got {self.homed!r}")
        if not isinstance(self.clock, Clock):
            raise InvalidInputError("clock", "needs now() and sleep(seconds), got "
                                             f"{type(self.clock).__name__}")


@dataclass(frozen=True)
class BusConfig:
    """A python-can bus and the PowerCube modules on it, validated when built.

    Attributes:
        interface: The python-can interface (``"virtual"``, ``"udp_multicast"``, ``"socketcan"``,
            ``"pcan"``, ``"kvaser"``...).
        channel: The bus channel (``"can0"``, ``"239.74.163.2"``...); None: the interface's default, or
            with simulated modules on ``virtual`` a private channel (:meth:`private`).
        bitrate: Bit rate [bit/s] where the interface needs one: a PowerCube rate (125k, 250k, 500k, 1M).
        port: UDP port (``udp_multicast`` only), 1..65535.
        module_ids: The module ids in joint order (distinct, 1..31).
        timeout: ACK timeout (0, 10] s; None: :data:`SIM_TIMEOUT` with simulated modules in this process,
            :data:`BUS_TIMEOUT` otherwise (:attr:`ack_timeout`).
        sim: Simulated modules attached to this bus in this process (:class:`SimConfig`), or None: the
            modules are elsewhere (real ones, or ``iik sim-arm`` in another process).
    """

    interface: str
    channel: str | int | None = None
    bitrate: int | None = None
    port: int | None = None
    module_ids: tuple[int, ...] = (1, 2, 3, 4, 5, 6)
    timeout: float | None = None
    sim: SimConfig | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.interface, str) or not self.interface.strip():
            raise InvalidInputError("interface", f"must name a python-can interface, got {self.interface!r}")
        if self.channel is not None and (isinstance(self.channel, bool)
                                         or not isinstance(self.channel, (str, int))):
            raise InvalidInputError("channel", f"must be a str or an int, got {self.channel!r}")
        object.__setattr__(self, "module_ids", check_module_ids(self.module_ids))
        if self.timeout is not None:
            object.__setattr__(self, "timeout", check_timeout(self.timeout))
        if self.bitrate is not None:
            rates = ", ".join(f"{b}" for b in P.BAUD_CODES)
            _integer(self.bitrate, "bitrate", P.BAUD_CODES,
                     f"a PowerCube bit rate, one of {rates} bit/s (docs/POWERCUBE.md)")
        if self.port is not None:
            _integer(self.port, "port", range(1, 65536), "a UDP port in 1..65535")
        if self.sim is not None:
            if not isinstance(self.sim, SimConfig):
                raise InvalidInputError("sim", f"expected a SimConfig, got {type(self.sim).__name__}")
            n = len(self.module_ids)
            if self.sim.initial is not None and len(self.sim.initial) != n:
                raise InvalidInputError("initial", f"need {n} finite positions [rad], one per module, got "
                                                   f"{len(self.sim.initial)}")

    @classmethod
    def simulated(cls, sim: SimConfig | None = None, **kwargs) -> BusConfig:
        """Simulated modules (``sim``, default :class:`SimConfig`) on a private ``virtual`` channel, the
        host on its twin; ``kwargs``: the other fields (``module_ids``, ``timeout``)."""
        return cls("virtual", sim=SimConfig() if sim is None else sim, **kwargs)

    @property
    def ack_timeout(self) -> float:
        """The ACK timeout used [s] (:attr:`timeout`, or its default)."""
        if self.timeout is not None:
            return self.timeout
        return SIM_TIMEOUT if self.sim is not None else BUS_TIMEOUT

    @property
    def where(self) -> str:
        """Where the modules are, for messages."""
        if self.sim is not None and self.interface == "virtual":
            return "simulated arm (in-process, virtual bus)"
        bus = f"{self.interface}:{self.channel}"
        return f"simulated arm (in-process) on {bus}" if self.sim is not None else bus

    def private(self) -> BusConfig:
        """This config, on a fresh private channel if it has simulated modules on ``virtual`` and names
        no channel (so that nothing else on this process's virtual buses hears them)."""
        if self.sim is None or self.interface != "virtual" or self.channel is not None:
            return self
        return replace(self, channel=f"iik-sim-{uuid.uuid4().hex}")

    def open(self) -> can.BusABC:
        """A new python-can bus object on this bus (:func:`open_bus`); the caller shuts it down."""
        return open_bus(self.interface, self.channel, bitrate=self.bitrate, port=self.port)


def open_bus(interface: str, channel, *, bitrate: int | None = None, port: int | None = None,
             **kwargs) -> can.BusABC:
    """Open a python-can bus (``PCube_openDevice``'s first half).

    ``bitrate`` [bit/s] and ``port`` (``udp_multicast``) are passed only when given.

    Raises:
        BusError: the interface is unknown or could not be opened (python-can's
            ``CanError``, ``OSError``, ``ValueError`` or a missing backend).
    """
    if bitrate is not None:
        kwargs["bitrate"] = int(bitrate)
    if port is not None:
        kwargs["port"] = int(port)
    try:
        return can.Bus(interface=interface, channel=channel, **kwargs)
    except (can.CanError, OSError, ValueError, ImportError) as exc:
        raise BusError(f"cannot open {interface}:{channel}: {exc}") from exc
