"""Time for the simulated arm and the executor: real time, or a virtual clock that moves only when waited on.

A :class:`Clock` is anything with ``now()`` [s] and ``sleep(seconds)``. The simulated modules read
their time from one (:class:`hardware.bus.SimConfig`, :class:`hardware.sim.SimulatedArm`), and
:func:`hardware.run` gives the executor the same one, so host and modules share one timeline.

* :data:`REAL_TIME`: :func:`time.monotonic` and :func:`time.sleep` (a real bus, ``iik run``).
* :class:`FunctionClock`: a clock made of two functions.
* :class:`FastForwardClock`: real time with the waits skipped (``iik verify``'s hardware rows and the
  hardware notebook): bus round trips keep (a share of) their real length, waits take almost none.
* :class:`VirtualClock`: stands still except in ``sleep(s)``, which moves it on by ``s`` at once. Bus
  round trips then take no simulated time, so a simulated run is exact and takes only as long as its
  requests, whatever the machine's load (the tests; a run to see what a trajectory would do).
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol, runtime_checkable

from iik.errors import InvalidInputError

__all__ = ["Clock", "RealTime", "REAL_TIME", "VirtualClock", "FunctionClock", "FastForwardClock"]


@runtime_checkable
class Clock(Protocol):
    """A time source and a wait on it."""

    def now(self) -> float:
        """The time [s] (monotonic; its origin is arbitrary)."""

    def sleep(self, seconds: float) -> None:
        """Wait ``seconds`` [s] of this clock's time."""


class RealTime:
    """Real time: :func:`time.monotonic` and :func:`time.sleep`."""

    def now(self) -> float:
        return time.monotonic()

    def sleep(self, seconds: float) -> None:
        time.sleep(max(float(seconds), 0.0))

    def __repr__(self) -> str:
        return "REAL_TIME"


#: Real time, the default of every simulated arm and of a run.
REAL_TIME = RealTime()


class VirtualClock:
    """A deterministic time base for a simulated arm and the executor together: :meth:`now` [s]
    stands still except in :meth:`sleep`, which moves it on by ``seconds`` at once (and lets the
    simulator's thread run). Thread-safe.

    Args:
        start: The time it starts at [s].
    """

    def __init__(self, start: float = 1000.0):
        self._now = float(start)
        self._lock = threading.Lock()

    def now(self) -> float:
        with self._lock:
            return self._now

    def sleep(self, seconds: float) -> None:
        with self._lock:
            self._now += max(float(seconds), 0.0)
        time.sleep(0)  # let the simulator's thread run

    def __repr__(self) -> str:
        return f"VirtualClock(now={self.now():.6f})"


@dataclass(frozen=True)
class FunctionClock:
    """A :class:`Clock` made of two functions.

    Attributes:
        now: Returns the time [s]. sleep: Waits that many seconds of it (default :func:`time.sleep`).
    """

    now: Callable[[], float]
    sleep: Callable[[float], None] = time.sleep


class FastForwardClock:
    """Real time with the waits skipped: :meth:`sleep` moves :meth:`now` on by its full length [s]
    but sleeps only ``1 / factor`` of it in real time, and the host's own time (everything but those
    sleeps: computation, bus round trips) counts ``latency`` of its real length (1: real speed).

    Give ``now`` and ``sleep`` to the simulated arm and the executor together: idle waits are
    skipped, and with ``latency < 1`` the host's load barely moves the simulated timeline.

    Args:
        factor: Clock time per unit of real time slept (> 0).
        latency: Share of the host's real time the clock counts (>= 0).
    """

    def __init__(self, factor: float = 60.0, latency: float = 1.0):
        if not factor > 0.0:
            raise InvalidInputError("factor", f"must be > 0, got {factor!r}")
        if not latency >= 0.0:
            raise InvalidInputError("latency", f"must be >= 0, got {latency!r}")
        self.factor, self.latency = float(factor), float(latency)
        self._t0 = time.monotonic()
        self._skipped = 0.0  # clock time [s] added by the sleeps beyond their counted real time

    def now(self) -> float:
        return self._t0 + (time.monotonic() - self._t0) * self.latency + self._skipped

    def sleep(self, seconds: float) -> None:
        seconds = max(float(seconds), 0.0)
        self._skipped += seconds - seconds / self.factor * self.latency
        time.sleep(seconds / self.factor)

    def __repr__(self) -> str:
        return f"FastForwardClock(factor={self.factor:g}, latency={self.latency:g})"
