"""Fixtures for the hardware tests: a simulated arm and a host arm on a private virtual bus."""

import threading
import time
import uuid

import can
import pytest

from hardware import PowerCubeArm, SimulatedArm
from iik import THESIS_ARM


def unique_channel(prefix: str = "t") -> str:
    return f"{prefix}-{uuid.uuid4().hex}"


@pytest.fixture
def new_channel():
    """A function returning a fresh unique virtual channel name."""
    return unique_channel


@pytest.fixture
def channel():
    return unique_channel()


@pytest.fixture
def host_bus(channel):
    bus = can.Bus(interface="virtual", channel=channel)
    yield bus
    bus.shutdown()


@pytest.fixture
def sim(channel):
    s = SimulatedArm.virtual(channel, (1, 2, 3, 4, 5, 6), lag=0.01, arm=THESIS_ARM)
    yield s
    s.close()
    assert not s.errors, s.errors


@pytest.fixture
def arm(sim, host_bus):
    a = PowerCubeArm(host_bus, (1, 2, 3, 4, 5, 6), timeout=0.2, arm=THESIS_ARM)
    yield a
    a.stop_watchdog(disable=False)


class VirtualClock:
    """A deterministic time base for the simulator and the executor together: ``clock()``
    [s] stands still except in ``sleep(s)``, which advances it by ``s`` at once.

    Bus round trips then take no simulated time, so host and modules share one exact
    timeline whatever the machine's load (the executor's waits are the only time that passes).
    """

    def __init__(self, start: float = 1000.0):
        self.now = float(start)
        self._lock = threading.Lock()

    def clock(self) -> float:
        with self._lock:
            return self.now

    def sleep(self, seconds: float) -> None:
        with self._lock:
            self.now += max(float(seconds), 0.0)
        time.sleep(0)  # let the simulator's thread run


@pytest.fixture
def virtual_clock():
    return VirtualClock()
