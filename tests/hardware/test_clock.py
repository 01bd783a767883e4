"""hardware.clock.FastForwardClock: waits advance the clock in full while sleeping a fraction of
them; the host's own time counts its latency share."""

import pytest

from hardware.clock import FastForwardClock
from iik.errors import InvalidInputError


def test_fast_forward_clock_shrinks_host_time():
    """With latency < 1 the host's own time (computation, round trips) barely advances the clock."""
    import time

    c = FastForwardClock(20.0, latency=0.01)
    clock, sleep = c.now, c.sleep
    c0, r0 = clock(), time.monotonic()
    sum(range(300_000))
    real = time.monotonic() - r0
    assert clock() - c0 <= 0.011 * real + 1e-4
    c1 = clock()
    sleep(0.4)
    assert 0.4 <= clock() - c1 < 0.41  # a wait still advances the clock by its full length


def test_fast_forward_clock_skips_waits_only():
    import time

    c = FastForwardClock(20.0)
    clock, sleep = c.now, c.sleep
    c0, r0 = clock(), time.monotonic()
    sleep(0.4)
    advanced, real = clock() - c0, time.monotonic() - r0
    assert advanced >= 0.4 and real < 0.2  # the clock advanced by the whole wait, real time by ~1/20
    c1, r1 = clock(), time.monotonic()
    sum(range(200_000))  # computation runs at real speed
    assert abs((clock() - c1) - (time.monotonic() - r1)) < 5e-3


@pytest.mark.parametrize(("kw", "name"), [({"factor": 0.0}, "factor"), ({"factor": float("nan")}, "factor"),
                                          ({"latency": -0.1}, "latency")])
def test_bad_arguments_are_named(kw, name):
    with pytest.raises(InvalidInputError) as e:
        FastForwardClock(**kw)
    assert e.value.argument == name
