"""Typed errors of the viewer, rooted in :class:`iik.errors.IIKError`.

Each also derives from the matching built-in, so generic handlers keep working.
"""

from __future__ import annotations

from pathlib import Path

from iik.errors import IIKError

__all__ = ["ViewerError", "PortInUseError", "ExportError"]


class ViewerError(IIKError):
    """Root of the errors raised by :mod:`iik.planning.viewer`."""


class PortInUseError(ViewerError, OSError):
    """The viewer cannot listen on the requested address.

    Attributes:
        host: The interface asked for.
        port: The TCP port asked for.
    """

    def __init__(self, host: str, port: int, detail: str = ""):
        self.host = host
        self.port = port
        super().__init__(f"port {port} on {host} is in use or not available"
                         + (f" ({detail})" if detail else "") + "; choose another with --port")


class ExportError(ViewerError, OSError):
    """An offline export cannot be written (nothing is left half-written).

    Attributes:
        path: The export folder as given.
        reason: Why.
    """

    def __init__(self, path: Path | str, reason: str):
        self.path = Path(path)
        self.reason = reason
        super().__init__(f"{path}: {reason}")
