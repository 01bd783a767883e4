"""Fixtures for the command-line tests: simulated arms in their own processes on udp_multicast."""

import os
import random
import subprocess
import sys
import time

import pytest

GROUP = "239.74.163.2"


def multicast_unavailable(port: int) -> str | None:
    """Why udp_multicast cannot be used here (None if it can): the loopback must deliver."""
    try:
        import can

        a = can.Bus(interface="udp_multicast", channel=GROUP, port=port)
        b = can.Bus(interface="udp_multicast", channel=GROUP, port=port)
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


def iik_process(*argv: str) -> subprocess.Popen:
    """``python -m iik.cli ARGV`` with unbuffered pipes."""
    return subprocess.Popen([sys.executable, "-m", "iik.cli", *argv], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, env=dict(os.environ, PYTHONUNBUFFERED="1"))


def stop(proc: subprocess.Popen) -> None:
    if proc.poll() is None:
        proc.terminate()
        try:
            proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()


@pytest.fixture
def udp_bus():
    """``start_sim()`` launches an ``iik sim-arm`` process on a private udp_multicast port and
    waits until it serves; returns ``(port, start_sim)``. Every process is stopped afterwards."""
    port = random.randint(20000, 60000)
    reason = multicast_unavailable(port)
    if reason:
        pytest.skip(reason)
    procs = []

    def start_sim(*extra: str) -> subprocess.Popen:
        proc = iik_process("sim-arm", "--interface", "udp_multicast", "--channel", GROUP, "--port", str(port),
                           "--lag", "0.01", "--duration", "120", *extra)
        procs.append(proc)
        line = proc.stdout.readline()
        assert "sim-arm ready" in line, (line, proc.stderr.read() if proc.poll() is not None else "")
        return proc

    yield port, start_sim
    for p in procs:
        stop(p)
