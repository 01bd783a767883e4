"""How the CLI shows an error (this module is no command: it has no ``NAME``).

Errors below the CLI name the library's argument (``margin``) and carry their remedy in library terms
(:class:`iik.errors.Remedy`); the CLI shows each argument as the option it is typed as
(``parser.spelling``: ``--margin-deg``), and a remedy that says to call again as the command line to run.
"""

from __future__ import annotations

from ..errors import IIKError

__all__ = ["as_typed", "remedies"]


def _option(parser, argument: str | None) -> str | None:
    """The option a library argument is typed as (``--margin-deg`` for ``margin``), or None."""
    return next((typed for dest, typed in parser.spelling.items() if argument and (
        dest == argument or dest.startswith(f"{argument}_"))), None)


def remedies(exc: BaseException, parser) -> list[str]:
    """The exception's remedy (:class:`~iik.errors.Remedy`) with the options as typed: ``--port``,
    or the command line to run again (``iik run --reset``); an argument no option sets keeps its
    library name."""
    remedy = getattr(exc, "remedy", None)
    if remedy is None:
        return []

    def spelled(argument: str) -> str:
        typed = _option(parser, argument)
        if typed is None:
            return argument if remedy.value is None else f"{argument}={remedy.value!r}"
        return f"{parser.prog} {typed}" if remedy.rerun else typed

    return [remedy.text(spelled)]


def as_typed(exc: BaseException, parser) -> str:
    """``Type: message``, naming the option as typed (``--margin-deg`` for ``margin``), with
    the exception's notes (e.g. where the run log is) and its remedy after it on the same line."""
    name, reason = getattr(exc, "argument", None), getattr(exc, "reason", None)
    shown = _option(parser, name) if reason else None
    problem = exc.problem if isinstance(exc, IIKError) else str(exc)
    text = f"{type(exc).__name__}: " + (f"{shown}: {reason}" if shown else problem)
    return "; ".join([text, *getattr(exc, "__notes__", ()), *remedies(exc, parser)])
