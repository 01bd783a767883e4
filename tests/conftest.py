"""Hypothesis profiles: ``ci`` (derandomised, used when CI is set), ``dev``
(default) and ``thorough`` (long runs: HYPOTHESIS_PROFILE=thorough); the ``udp_bus``
fixture for tests that run ``iik`` processes on udp_multicast."""

import os
import time

import pytest
from hypothesis import HealthCheck, settings

settings.register_profile(
    "ci", derandomize=True, max_examples=60, deadline=None,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.register_profile("dev", max_examples=60, deadline=None)
settings.register_profile(
    "thorough", max_examples=5000, deadline=None,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.load_profile(
    os.environ.get("HYPOTHESIS_PROFILE") or ("ci" if os.environ.get("CI") else "dev")
)


# --------------------------------------------------------------------------- real-time margins
def timeout_from_baseline(request, *, margin: float, floor: float, ceiling: float = 10.0,
                          n: int = 10) -> float:
    """A timeout [s] for a test that must wait in real time, derived from a baseline measured now, under
    whatever load the machine has: ``margin`` times the slowest of ``n`` calls of ``request`` (a round
    trip that succeeds), at least ``floor`` and at most ``ceiling``. The first call is not counted (it
    may pay for imports and discovery)."""
    request()
    worst = 0.0
    for _ in range(n):
        t0 = time.monotonic()
        request()
        worst = max(worst, time.monotonic() - t0)
    return min(max(floor, margin * worst), ceiling)


@pytest.fixture
def baseline_timeout():
    """:func:`timeout_from_baseline`, for tests whose waits are real time (a scan waits out every absent
    id; a watchdog is refreshed by python-can's own thread)."""
    return timeout_from_baseline


# --------------------------------------------------------------------------- processes on udp_multicast
class UdpBus:
    """A private udp_multicast bus (its own port) for ``iik`` processes: ``start_sim()`` launches
    an ``iik sim-arm`` and waits until it serves; ``process(*argv)`` runs ``python -m iik.cli``.
    Every process is stopped when the test ends."""

    group = "239.74.163.2"

    def __init__(self, port: int):
        self.port = port
        self.procs = []

    @property
    def args(self) -> list[str]:
        """The ``--interface/--channel/--port`` options of this bus."""
        return ["--interface", "udp_multicast", "--channel", self.group, "--port", str(self.port)]

    def process(self, *argv: str):
        import subprocess
        import sys

        proc = subprocess.Popen([sys.executable, "-m", "iik.cli", *argv], stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, text=True, env=dict(os.environ, PYTHONUNBUFFERED="1"))
        self.procs.append(proc)
        return proc

    def start_sim(self, *extra: str):
        proc = self.process("sim-arm", *self.args, "--lag", "0.01", "--duration", "120", *extra)
        line = proc.stdout.readline()
        assert "sim-arm ready" in line, (line, proc.stderr.read() if proc.poll() is not None else "")
        return proc

    def unavailable(self) -> str | None:
        """Why udp_multicast cannot be used here (None if it can): the loopback must deliver."""
        import time

        try:
            import can

            a, b = (can.Bus(interface="udp_multicast", channel=self.group, port=self.port) for _ in range(2))
            try:
                a.send(can.Message(arbitration_id=0x7FF, data=[1], is_extended_id=False))
                t0 = time.monotonic()
                while time.monotonic() - t0 < 1.0:
                    f = b.recv(0.2)
                    if f is not None and f.arbitration_id == 0x7FF:
                        return None
                return "multicast loopback delivers nothing"
            finally:
                a.shutdown()
                b.shutdown()
        except (OSError, ImportError) as exc:
            return f"udp_multicast unavailable: {exc}"

    def request_timeout(self, floor: float = 5.0, margin: float = 25.0, arm=None) -> str:
        """A CAN request timeout [s] for ``iik run`` on this bus (as ``--timeout`` text), derived from a
        baseline measured now, under whatever load the machine has: ``margin`` times the slowest of
        ten round trips to the running ``sim-arm`` (GETPOS of every module), at least ``floor`` and at
        most the longest timeout accepted (:data:`hardware.bus.MAX_TIMEOUT`). ``arm``: the arm the
        ``sim-arm`` serves (default the thesis arm's). (The load can rise after the baseline: with
        six processes on two cores a reply once took more than the 1 s floor of then, and the run
        stopped at its first request. The timeout only detects a hang here.)"""
        from hardware import PowerCubeArm
        from hardware.bus import MAX_TIMEOUT
        from iik import THESIS_ARM

        with PowerCubeArm.from_interface(interface="udp_multicast", channel=self.group, port=self.port,
                                         timeout=MAX_TIMEOUT, arm=arm or THESIS_ARM) as modules:
            timeout = timeout_from_baseline(modules.get_pos, margin=margin, floor=floor, ceiling=MAX_TIMEOUT)
        return f"{timeout:.3f}"

    def close(self) -> None:
        import subprocess

        for proc in self.procs:
            if proc.poll() is None:
                proc.terminate()
                try:
                    proc.wait(timeout=10)
                except subprocess.TimeoutExpired:
                    proc.kill()
                    proc.wait()


@pytest.fixture
def udp_bus():
    """A :class:`UdpBus` on a random port (skips the test where multicast does not loop back)."""
    import random

    bus = UdpBus(random.randint(20000, 60000))
    reason = bus.unavailable()
    if reason:
        pytest.skip(reason)
    yield bus
    bus.close()
