"""A one-time compile of the IK kernel is left out of a plan's budget (issue 20, item 12: a first
plan after an install timed out on a loaded machine while Numba compiled)."""

from __future__ import annotations

import numba

from iik.ik import compile_clock
from iik.planning import Budget


def test_compile_clock_reports_each_outermost_compile_and_nothing_when_cached():
    seen: list[float] = []

    def inner(x):
        return x * 2.0

    jitted_inner = numba.njit(inner)

    def outer(x):
        return jitted_inner(x) + 1.0

    jitted = numba.njit(outer)
    with compile_clock(seen.append):
        assert jitted(1.0) == 3.0  # compiles outer, and inner inside it: one report
    assert len(seen) == 1 and seen[0] > 0.0
    with compile_clock(seen.append):
        assert jitted(2.0) == 5.0  # already compiled: nothing
    assert len(seen) == 1


def test_excluded_seconds_move_the_deadline():
    b = Budget(timeout=10.0)
    before = b.remaining
    b.exclude(5.0)
    assert b.remaining > before + 4.9  # the 5 s are not charged
    assert b.elapsed < -4.9
