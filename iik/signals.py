"""Every way of stopping a command takes one path: SIGTERM and SIGHUP become :class:`StopSignal`.

Ctrl-C raises ``KeyboardInterrupt`` in the main thread; the code it interrupts cleans up
(the hardware executor broadcasts HALT and closes its run log, an output being written
is discarded, :mod:`iik.files`). A service manager's SIGTERM or a closed terminal's
SIGHUP would instead kill the process (python's default), leaving the arm moving, the
log without its last records or a temporary output behind. :func:`stop_on_signals`
turns both into :class:`StopSignal`, a ``KeyboardInterrupt``, for the duration of a
``with`` block, so they take the same path. The first signal raises; further ones while
the block is being stopped are ignored, so the cleanup is not interrupted. Outside the
main thread (where Python cannot install handlers) it does nothing.

:func:`signals_deferred` holds Ctrl-C, SIGTERM and SIGHUP for a few statements that must
not be separated (two renames that replace a folder) and delivers the first one after.
"""

from __future__ import annotations

import contextlib
import signal
import threading
from collections.abc import Iterator

__all__ = ["STOP_SIGNALS", "StopSignal", "stop_on_signals", "signals_deferred"]

#: Signals handled like Ctrl-C during a run (SIGHUP where the platform has it).
STOP_SIGNALS = tuple(s for s in (getattr(signal, "SIGTERM", None), getattr(signal, "SIGHUP", None))
                     if s is not None)


class StopSignal(KeyboardInterrupt):
    """SIGTERM or SIGHUP arrived inside :func:`stop_on_signals`; handled like Ctrl-C (for a run:
    HALT broadcast, fault and end records, log flushed; for an output: the temporary discarded).

    Attributes:
        signum: The signal number (``signal.SIGTERM``...).
    """

    def __init__(self, signum: int):
        self.signum = int(signum)
        super().__init__(f"stopped by {signal.Signals(self.signum).name}")


def _main_thread() -> bool:
    return threading.current_thread() is threading.main_thread()


@contextlib.contextmanager
def stop_on_signals(signals=STOP_SIGNALS) -> Iterator[None]:
    """Raise :class:`StopSignal` in the main thread when one of ``signals`` arrives
    inside the block; the previous handlers are restored on exit. Re-entrant."""
    if not _main_thread():
        yield
        return
    raised = []

    def handler(signum, frame) -> None:
        if not raised:  # the first one stops the run; later ones must not cut the cleanup short
            raised.append(signum)
            raise StopSignal(signum)

    previous = {s: signal.signal(s, handler) for s in signals}
    try:
        yield
    finally:
        for s, h in previous.items():
            signal.signal(s, h)


@contextlib.contextmanager
def signals_deferred() -> Iterator[None]:
    """Hold Ctrl-C and :data:`STOP_SIGNALS` inside the block; the first one that arrived is
    raised again (to the handler that was in place) when it ends. Main thread only (elsewhere
    signals are not delivered to Python code anyway)."""
    if not _main_thread():
        yield
        return
    held: list[int] = []
    previous = {s: signal.signal(s, lambda signum, frame: held.append(signum))
                for s in (signal.SIGINT, *STOP_SIGNALS)}
    try:
        yield
    finally:
        for s, h in previous.items():
            signal.signal(s, h)
        if held:
            signal.raise_signal(held[0])
