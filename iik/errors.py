"""The project's exception hierarchy: one root, typed subclasses.

Every error raised on bad input by ``iik``, ``verification`` or ``hardware``
derives from :class:`IIKError`. Subclasses also inherit the matching built-in
(``ValueError``, ``TimeoutError``) so generic handlers keep working. Each layer
keeps its own errors module under this root (planning: :mod:`iik.planning.errors`).

Errors speak the library's terms: they name the library argument (``port``, ``allow_outside_limits``)
and carry what to do about them as data (:class:`Remedy`), never a command-line flag; the CLI
(:mod:`iik.cli`) shows the option it maps that argument to.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = [
    "Remedy",
    "IIKError",
    "InvalidInputError",
    "UnreachablePoseError",
    "DexterityError",
    "NotOrthonormalError",
    "FileError",
    "MissingExtraError",
]


@dataclass(frozen=True)
class Remedy:
    """What to do about an error, in library terms: an instruction naming the argument it concerns.

    The library's message shows the argument as ``argument`` (or ``argument=value``); the CLI shows
    the option it maps the argument to (``port`` -> ``--port``), with ``rerun`` as the whole command
    line to run again (``iik run --reset``).

    Attributes:
        action: The instruction, ``{}`` where the argument goes: ``"choose another {}"``.
        arguments: The library argument(s) it concerns (a keyword or a request's field): ``("port",)``;
            several are named as "a, b or c".
        value: The value to give it, if the instruction is to set it (``True`` for a switch).
        rerun: The instruction is to call again with the argument set.
    """

    action: str
    arguments: tuple[str, ...]
    value: object = None
    rerun: bool = False

    def __post_init__(self) -> None:
        if isinstance(self.arguments, str):
            object.__setattr__(self, "arguments", (self.arguments,))

    def text(self, spelled=None) -> str:
        """The instruction, each argument as ``spelled(argument)`` (the CLI's option) or, by default,
        as the library's ``argument`` / ``argument=value``."""
        shown = [spelled(a) if spelled else a if self.value is None else f"{a}={self.value!r}"
                 for a in self.arguments]
        named = shown[0] if len(shown) == 1 else f"{', '.join(shown[:-1])} or {shown[-1]}"
        return self.action.format(named)


class IIKError(Exception):
    """Root of every error this project raises on purpose.

    Attributes:
        remedy: What to do about it (:class:`Remedy`), or None; the message ends with it, in
            library terms (:attr:`problem` is the message without it).
    """

    remedy: Remedy | None = None

    def __str__(self) -> str:
        return self.problem if self.remedy is None else f"{self.problem}; {self.remedy.text()}"

    @property
    def problem(self) -> str:
        """The message without the remedy."""
        return super().__str__()


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
        remedy: What to do about it (:class:`Remedy`), or None.
    """

    def __init__(self, argument: str, reason: str, remedy: Remedy | None = None):
        self.argument = argument
        self.reason = reason
        self.remedy = remedy
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

    def __init__(self, argument: str, reason: str, path=None, remedy: Remedy | None = None):
        self.path = path
        super().__init__(argument, reason, remedy)


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
