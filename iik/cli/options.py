"""Options shared by several commands (this module is no command: it has no ``NAME``)."""

from __future__ import annotations

import math
import sys

__all__ = ["add_pose_arguments", "warn_degrees"]


def add_pose_arguments(p, *, required: bool) -> None:
    """``--xyz`` (tool position [m]) and ``--zxz`` (Eq 42 Euler angles, rad or deg with ``--deg``)."""
    p.add_argument("--xyz", nargs=3, type=float, required=required, default=None, metavar=("X", "Y", "Z"),
                   help="tool position in the base frame [m]")
    p.add_argument("--zxz", nargs=3, type=float, required=required, default=None, metavar=("A", "B", "G"),
                   help="Eq 42 Euler angles alpha beta gamma [rad, or deg with --deg]")
    p.spelling.update(p="--xyz", T="--xyz/--zxz", alpha="--zxz", beta="--zxz", gamma="--zxz")  # library names


def warn_degrees(command: str, args, flags: tuple[str, ...]) -> None:
    """One stderr line per angle option (``flags``, e.g. ``("--zxz", "--previous")``) whose values
    go beyond one turn while read as radians: almost surely degrees typed without ``--deg``."""
    for flag in flags:
        values = getattr(args, flag.lstrip("-").replace("-", "_")) or ()
        if not args.deg and any(abs(v) > 2 * math.pi for v in values if math.isfinite(v)):
            print(f"iik {command}: warning: {flag} {' '.join(f'{v:g}' for v in values)} look like degrees "
                  "(beyond 2 pi); they are read as radians: add --deg", file=sys.stderr)
