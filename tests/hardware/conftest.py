"""Fixtures for the hardware tests: a simulated arm and a host arm on a private virtual bus.

The simulated modules of ``sim`` run on ``virtual_clock`` (:class:`hardware.clock.VirtualClock`): time
passes only when a test waits on it (``virtual_clock.sleep``), so what they measure cannot depend on the
machine's load. Replies still travel through real threads: the host's ACK timeout is generous
(:data:`REPLY_TIMEOUT`), as replies are not what these tests time.
"""

import uuid

import can
import pytest

from hardware import PowerCubeArm, SimulatedArm
from hardware.clock import VirtualClock
from iik import THESIS_ARM

#: ACK timeout [s] of host arms whose replies are not under test: a reply takes well under a millisecond
#: on an idle machine, but the simulator's thread may wait its turn on a loaded one.
REPLY_TIMEOUT = 5.0


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
def reply_timeout():
    """:data:`REPLY_TIMEOUT`, for host arms built in a test."""
    return REPLY_TIMEOUT


@pytest.fixture
def virtual_clock():
    return VirtualClock()


@pytest.fixture
def host_bus(channel):
    bus = can.Bus(interface="virtual", channel=channel)
    yield bus
    bus.shutdown()


@pytest.fixture
def sim(channel, virtual_clock):
    s = SimulatedArm.virtual(channel, (1, 2, 3, 4, 5, 6), lag=0.01, arm=THESIS_ARM, clock=virtual_clock.now)
    yield s
    s.close()
    assert not s.errors, s.errors


@pytest.fixture
def arm(sim, host_bus):
    a = PowerCubeArm(host_bus, (1, 2, 3, 4, 5, 6), timeout=REPLY_TIMEOUT, arm=THESIS_ARM)
    yield a
    a.stop_watchdog(disable=False)
