"""The project's exception hierarchy: one root, typed subclasses.

Every error raised on bad input by ``iik``, ``verification`` or ``hardware``
derives from :class:`IIKError`. Subclasses also inherit the matching built-in
(``ValueError``, ``TimeoutError``) so generic handlers keep working. Each layer
keeps its own errors module under this root (planning: :mod:`iik.planning.errors`).
"""

from __future__ import annotations

import math

__all__ = [
    "IIKError",
    "InvalidInputError",
    "UnreachablePoseError",
    "DexterityError",
    "NotOrthonormalError",
    "FileError",
    "MissingExtraError",
]


class IIKError(Exception):
    """Root of every error this project raises on purpose."""


class MissingExtraError(IIKError, ImportError):
    """A part of the project is imported without the extra that installs its libraries
    (``pyproject.toml``'s optional dependencies; :mod:`iik.extras`).

    Attributes:
        package: The package that needs the extra (``"iik.planning"``).
        extra: The extra to install (``"planning"``).
        missing: The top-level modules of the extra that are not installed.
    """

    def __init__(self, package: str, extra: str, missing: tuple[str, ...]):
        self.package, self.extra, self.missing = package, extra, missing
        super().__init__(f"{package} needs the {extra!r} extra (missing: {', '.join(missing)}): "
                         f"pip install 'iik[{extra}]' (in a checkout: pip install '.[{extra}]')",
                         name=missing[0] if missing else None)


class InvalidInputError(IIKError, ValueError):
    """An argument has the wrong type, shape, or a non-finite or inconsistent value.

    Attributes:
        argument: Name of the offending argument.
        reason: Human-readable reason.
    """

    def __init__(self, argument: str, reason: str):
        self.argument = argument
        self.reason = reason
        super().__init__(f"{argument}: {reason}")


class FileError(InvalidInputError, OSError):
    """A file or folder an argument names cannot be read or written as asked (:mod:`iik.files`):
    missing, not a regular file (a device, a FIFO, a folder), over its size limit, not UTF-8,
    or an output that would replace something else.

    Attributes:
        argument: The argument naming the file (e.g. ``"trajectory"``, ``"out"``).
        reason: Why, naming the path.
        path: The path as given.
    """

    def __init__(self, argument: str, reason: str, path=None):
        self.path = path
        super().__init__(argument, reason)


class UnreachablePoseError(IIKError, ValueError):
    """A requested pose or point cannot be reached by the arm."""


class DexterityError(InvalidInputError):
    """A requested ``beta`` is outside every admissible interval at that point (:func:`iik.dexterity`).

    Attributes:
        beta_intervals: The admissible beta intervals ``((lo, hi), ...)`` [rad] (Eq 42 convention).
    """

    def __init__(self, beta: float, beta_intervals):
        self.beta_intervals = tuple(beta_intervals)
        shown = ", ".join(f"[{lo:.6g}, {hi:.6g}]" for lo, hi in self.beta_intervals) or "none"
        shown_deg = ", ".join(f"[{math.degrees(lo):.3f}, {math.degrees(hi):.3f}]"
                              for lo, hi in self.beta_intervals) or "none"
        super().__init__(
            "beta",
            f"{beta:.6g} rad ({math.degrees(beta):.3f} deg) is outside the admissible beta at this point: "
            f"{shown} rad ({shown_deg} deg; exact, from the IK)",
        )


class NotOrthonormalError(InvalidInputError):
    """A rotation block is too far from a rotation to be one.

    Attributes:
        deviation: max |R^T R - I| of the offending rotation.
        tolerance: The tolerance it exceeds.
        index: Index of the offending pose in a batch, or None.
    """

    def __init__(self, argument: str, reason: str, deviation: float, tolerance: float,
                 index: int | None = None):
        self.deviation = deviation
        self.tolerance = tolerance
        self.index = index
        super().__init__(argument, reason)
