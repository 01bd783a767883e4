"""Options shared by several commands (this module is no command: it has no ``NAME``)."""

from __future__ import annotations

__all__ = ["add_pose_arguments"]


def add_pose_arguments(p, *, required: bool) -> None:
    """``--xyz`` (tool position [m]) and ``--zxz`` (Eq 42 Euler angles, rad or deg with ``--deg``)."""
    p.add_argument("--xyz", nargs=3, type=float, required=required, default=None, metavar=("X", "Y", "Z"),
                   help="tool position in the base frame [m]")
    p.add_argument("--zxz", nargs=3, type=float, required=required, default=None, metavar=("A", "B", "G"),
                   help="Eq 42 Euler angles alpha beta gamma [rad, or deg with --deg]")
