"""The time budget and progress reports of a plan (iik.planning.budget)."""

import math

import pytest

import iik.planning.budget as budget_module
from iik.errors import IIKError
from iik.planning import Budget, PlanningError, PlanningTimeout


class Clock:
    """A stand-in for the ``time`` module whose ``perf_counter`` moves only when told."""

    def __init__(self):
        self.now = 100.0

    def perf_counter(self) -> float:
        return self.now


@pytest.fixture
def clock(monkeypatch):
    c = Clock()
    monkeypatch.setattr(budget_module, "time", c)
    return c


def test_ticks_report_at_most_once_per_period_and_stop_at_the_deadline(clock):
    said = []
    b = Budget(10.0, said.append, period=1.0)
    b.stage("IK along the path")
    for i in range(30):  # 0.25 s per iteration: a report every 4th, the deadline after 40
        clock.now += 0.25
        b.tick("IK", i, 30)
    assert said[0] == "IK along the path"
    assert said[1:] == [f"IK: {i}/30 ({(i + 1) * 0.25:.1f} s)" for i in range(3, 30, 4)]
    clock.now += 2.6
    with pytest.raises(PlanningTimeout) as exc:
        b.tick("IK", 30, 40)
    e = exc.value
    assert (e.stage, e.timeout) == ("IK along the path (IK: 30/40)", 10.0)
    assert e.elapsed == pytest.approx(10.1)
    assert "timed out after 10.1 s (budget 10 s) during IK along the path" in str(e)


def test_a_stage_past_the_deadline_raises_and_remaining_counts_down(clock):
    b = Budget(2.0)
    clock.now += 1.5
    assert b.remaining == pytest.approx(0.5)
    b.stage("fine")
    clock.now += 1.0
    assert b.remaining == 0.0
    with pytest.raises(PlanningTimeout, match="during late"):
        b.stage("late")


def test_without_a_timeout_nothing_ever_raises(clock):
    b = Budget()
    clock.now += 1e9
    b.tick("x", 1, 2)
    assert b.timeout == math.inf


def test_the_timeout_error_is_typed():
    assert issubclass(PlanningTimeout, PlanningError) and issubclass(PlanningTimeout, IIKError)
    assert issubclass(PlanningTimeout, TimeoutError)
