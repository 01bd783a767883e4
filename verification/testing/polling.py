"""Waiting in tests for something another thread or process does (a simulated module, a browser)."""

from __future__ import annotations

import time

__all__ = ["wait_until"]


def wait_until(pred, timeout: float, interval: float) -> bool:
    """Call ``pred()`` every ``interval`` s until it is true (-> True) or ``timeout`` s have passed
    (-> False)."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if pred():
            return True
        time.sleep(interval)
    return False
