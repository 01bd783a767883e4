"""The ``iik`` command line: the one place that wires iik, verification and hardware.

Each subcommand is a module in this package defining ``NAME``, ``HELP``,
``add_arguments(parser)`` and ``run(args) -> int``; it parses, calls one library function
and prints (``parser.spelling`` maps a library argument to the option as typed, e.g.
``p`` -> ``--xyz``; :mod:`iik.cli.messages` shows errors with it). Modules are discovered
automatically; heavy packages (pinocchio, coal, python-can, verification, hardware) are imported
lazily inside ``run``.

Every expected failure (an ``IIKError``, a bad argument, an unwritable file) ends the
command with one line on stderr naming the option as typed, and exit code 2, never a
traceback. Ctrl-C, SIGTERM and SIGHUP (where a command handles them, e.g. ``iik run``)
end it with one line and exit code 128 + the signal number.
"""

from __future__ import annotations

import argparse
import importlib
import pkgutil
import signal
import sys

from ..errors import IIKError
from .messages import as_typed, remedies

__all__ = ["main", "build_parser"]


class UsageError(IIKError):
    """A command line that does not parse (instead of argparse's exit)."""


class _Parser(argparse.ArgumentParser):
    """argparse, raising :class:`UsageError` and remembering each option's spelling."""

    def __init__(self, *args, **kwargs):
        self.spelling: dict[str, str] = {}  # dest or library argument -> the option as typed
        super().__init__(*args, **kwargs)

    def add_argument(self, *args, **kwargs):
        action = super().add_argument(*args, **kwargs)
        strings = action.option_strings
        self.spelling[action.dest] = strings[-1] if strings else action.dest.upper()
        return action

    def error(self, message: str):
        raise UsageError(f"{self.prog}: error: {message} (see {self.prog} --help)")


def _command_modules():
    for info in sorted(pkgutil.iter_modules(__path__), key=lambda m: m.name):
        if info.name.startswith("_"):
            continue
        mod = importlib.import_module(f"{__name__}.{info.name}")
        if hasattr(mod, "NAME") and hasattr(mod, "run"):
            yield mod


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="iik",
        description="Verified kinematics, planning and PowerCube control for the "
        "six-joint arm of Mondragon Sanchez (2012). Units: m, rad, s unless --deg.",
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    for mod in _command_modules():
        p = sub.add_parser(mod.NAME, help=mod.HELP, description=mod.HELP)
        mod.add_arguments(p)
        p.set_defaults(_run=mod.run, _parser=p)
    return parser


def main(argv: list[str] | None = None) -> int:
    try:
        args, extra = build_parser().parse_known_args(argv)
        if extra:  # reported by the command's parser, so the message names the command
            args._parser.error(f"unrecognized arguments: {' '.join(extra)}")
    except UsageError as exc:
        print(exc, file=sys.stderr)
        return 2
    try:
        return int(args._run(args) or 0)
    except IIKError as exc:
        print(f"iik {args.command}: error: {as_typed(exc, args._parser)}", file=sys.stderr)
        return 2
    except OSError as exc:  # an output file or folder that cannot be written
        print(f"iik {args.command}: error: {type(exc).__name__}: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt as exc:  # Ctrl-C, or SIGTERM/SIGHUP as iik.signals.StopSignal
        signum = getattr(exc, "signum", signal.SIGINT)
        notes = "".join(f"; {n}" for n in [*getattr(exc, "__notes__", ()), *remedies(exc, args._parser)])
        print(f"iik {args.command}: interrupted by {signal.Signals(signum).name}{notes}", file=sys.stderr,
              flush=True)
        return 128 + int(signum)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
