"""The time budget of one plan and its progress reports.

A :class:`Budget` holds a deadline and the ``progress`` callback of
:func:`~iik.planning.plan`. Stages announce themselves with :meth:`Budget.stage`;
long loops (IK along the path, whole-arm Coal checks, the orientation search)
call :meth:`Budget.tick` every iteration, which reports ``"<what>: done/total"``
at most once per :attr:`Budget.period` seconds (so a slow stage is visibly
moving, a stuck one is not) and raises :class:`~iik.planning.PlanningTimeout`
once the deadline has passed. The check is cooperative: it bounds the overrun
by the longest step between two ticks (one IK chunk, one Coal query, one
TOPP-RA call). Units: s.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable

from .errors import PlanningTimeout

__all__ = ["Budget"]


def _quiet(msg: str) -> None:
    """A ``progress`` callback that says nothing."""


class Budget:
    """A deadline (``timeout`` seconds from now) and a progress callback.

    Args:
        timeout: Seconds from construction until :meth:`tick` raises (``math.inf``: never).
        progress: Called with a short message per stage and, within long loops,
            at most every ``period`` seconds.
        period: Seconds between progress reports inside a loop.
    """

    def __init__(self, timeout: float = math.inf, progress: Callable[[str], None] | None = None,
                 period: float = 1.0):
        self.timeout = float(timeout)
        self.say = progress or _quiet
        self.period = float(period)
        self.start = time.perf_counter()
        self._last = self.start
        self.current = "start"

    def exclude(self, seconds: float) -> None:
        """Leave ``seconds`` of work out of the budget (the deadline moves by as much): a one-time
        compile of the IK kernel (:func:`iik.ik.compile_clock`) is not planning."""
        self.start += float(seconds)

    @property
    def elapsed(self) -> float:
        """Seconds since the budget started."""
        return time.perf_counter() - self.start

    @property
    def remaining(self) -> float:
        """Seconds left (0 when past the deadline)."""
        return max(0.0, self.timeout - self.elapsed)

    def stage(self, msg: str) -> None:
        """Announce a stage (``progress(msg)``), then :meth:`check` the deadline."""
        self.current = msg
        self.say(msg)
        self._last = time.perf_counter()
        self.check(msg)

    def tick(self, what: str, done: int, total: int) -> None:
        """One iteration of a long loop: report now and then, raise past the deadline."""
        now = time.perf_counter()
        if now - self._last >= self.period:
            self._last = now
            self.say(f"{what}: {done}/{total} ({now - self.start:.1f} s)")
        if now - self.start > self.timeout:
            raise PlanningTimeout(f"{self.current} ({what}: {done}/{total})", now - self.start, self.timeout)

    def check(self, what: str) -> None:
        """Raise :class:`~iik.planning.PlanningTimeout` if the deadline has passed."""
        if self.elapsed > self.timeout:
            raise PlanningTimeout(what, self.elapsed, self.timeout)
