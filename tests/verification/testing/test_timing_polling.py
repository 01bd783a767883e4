"""verification.testing.timing and .polling: the benchmarks' timer and the tests' poller."""

from __future__ import annotations

from verification.testing.polling import wait_until
from verification.testing.timing import median_seconds


def test_median_seconds_times_every_call_and_warms_up_once():
    calls = []
    t = median_seconds(lambda: calls.append(1), 3, calls=4, warmup=True)
    assert len(calls) == 1 + 3 * 4
    assert 0.0 <= t < 0.1


def test_wait_until_returns_once_true_or_false_after_the_timeout():
    polls = []
    assert wait_until(lambda: polls.append(1) or len(polls) >= 3, 5.0, 0.001)
    assert len(polls) == 3
    assert not wait_until(lambda: False, 0.02, 0.005)
