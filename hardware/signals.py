"""Every way of stopping a run halts the arm: SIGTERM and SIGHUP become :class:`StopSignal`.

Ctrl-C raises ``KeyboardInterrupt`` in the main thread, which the executor answers
with a HALT broadcast, a fault and an end record and a flushed log. A service
manager's SIGTERM or a closed terminal's SIGHUP would instead kill the process
(python's default), leaving the arm moving and the log without its last records.
:func:`stop_on_signals` turns both into :class:`~hardware.errors.StopSignal`, a
``KeyboardInterrupt``, for the duration of a ``with`` block, so they take the same path.
The first signal raises; further ones while the run is being stopped are ignored,
so the HALT and the records are not interrupted. Outside the main thread (where
Python cannot install handlers) it does nothing.
"""

from __future__ import annotations

import contextlib
import signal
import threading
from collections.abc import Iterator

from .errors import StopSignal

__all__ = ["STOP_SIGNALS", "stop_on_signals"]

#: Signals handled like Ctrl-C during a run (SIGHUP where the platform has it).
STOP_SIGNALS = tuple(s for s in (getattr(signal, "SIGTERM", None), getattr(signal, "SIGHUP", None))
                     if s is not None)


@contextlib.contextmanager
def stop_on_signals(signals=STOP_SIGNALS) -> Iterator[None]:
    """Raise :class:`StopSignal` in the main thread when one of ``signals`` arrives
    inside the block; the previous handlers are restored on exit. Re-entrant."""
    if threading.current_thread() is not threading.main_thread():
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
