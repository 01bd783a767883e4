"""Fixtures for the hardware tests: a simulated arm and a host arm on a private virtual bus."""

import uuid

import can
import pytest

from hardware import PowerCubeArm, SimulatedArm


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
    s = SimulatedArm.virtual(channel, (1, 2, 3, 4, 5, 6), lag=0.01)
    yield s
    s.close()
    assert not s.errors, s.errors


@pytest.fixture
def arm(sim, host_bus):
    a = PowerCubeArm(host_bus, (1, 2, 3, 4, 5, 6), timeout=0.2)
    yield a
    a.stop_watchdog(disable=False)
