"""Options shared by several commands (this module is no command: it has no ``NAME``)."""

from __future__ import annotations

import argparse
import math
import sys

__all__ = ["add_pose_arguments", "warn_degrees", "warn_millimetres", "joint_angles", "millimetres"]


#: The Euler angles option and its deprecated alias (the thesis calls Eq 42 "Z-X-Z"; it is Z-Y-Z).
EULER, EULER_DEPRECATED = "--zyz", "--zxz"
_EULER_NAMES = ("zyz", "zxz", "alpha", "beta", "gamma")  # zxz: ViewRequest's field


class _EulerAngles(argparse.Action):
    """Store ``--zyz A B G``; the deprecated ``--zxz`` warns on stderr and is named as typed in errors."""

    def __call__(self, parser, namespace, values, option_string=None):
        if option_string == EULER_DEPRECATED:
            print(f"{parser.prog}: warning: {EULER_DEPRECATED} is deprecated: the angles are Z-Y-Z (the "
                  f"corrected Eq 42, which the thesis calls Z-X-Z); use {EULER} (same angles, same pose)",
                  file=sys.stderr)
            parser.spelling.update({name: EULER_DEPRECATED for name in _EULER_NAMES},
                                   T=f"--xyz/{EULER_DEPRECATED}")
        setattr(namespace, self.dest, values)


def add_pose_arguments(p, *, required: bool) -> None:
    """``--xyz`` (tool position [m]) and ``--zyz`` (the corrected Eq 42 Euler angles, Z-Y-Z, rad or deg
    with ``--deg``; ``--zxz`` is its deprecated alias)."""
    p.add_argument("--xyz", nargs=3, type=float, required=required, default=None, metavar=("X", "Y", "Z"),
                   help="tool position in the base frame [m]")
    p.add_argument(EULER, EULER_DEPRECATED, dest="zyz", nargs=3, type=float, required=required, default=None,
                   metavar=("A", "B", "G"), action=_EulerAngles,
                   help="Euler angles alpha beta gamma of the corrected Eq 42: Z-Y-Z, Rz(A) Ry(B) Rz(G) (the "
                        "thesis calls it Z-X-Z) [rad, or deg with --deg]; --zxz is a deprecated alias")
    p.spelling.update({name: EULER for name in _EULER_NAMES}, p="--xyz", T=f"--xyz/{EULER}")  # library names


def warn_degrees(command: str, args, flags: tuple[str, ...]) -> None:
    """One stderr line per angle option (``flags``, e.g. ``("--zyz", "--previous")``) whose values
    go beyond one turn while read as radians: almost surely degrees typed without ``--deg``."""
    for flag in flags:
        values = getattr(args, flag.lstrip("-").replace("-", "_")) or ()
        if not args.deg and any(abs(v) > 2 * math.pi for v in values if math.isfinite(v)):
            typed = args._parser.spelling.get(flag.lstrip("-"), flag) if flag == EULER else flag
            print(f"iik {command}: warning: {typed} {' '.join(f'{v:g}' for v in values)} look like degrees "
                  "(beyond 2 pi); they are read as radians: add --deg", file=sys.stderr)


def warn_millimetres(command: str, xyz, reach: float) -> None:
    """One stderr line if the position ``--xyz`` [m] lies beyond the arm's ``reach`` [m] but would be
    within it read as millimetres: almost surely millimetres typed as metres."""
    if xyz is None or not all(math.isfinite(v) for v in xyz):
        return
    r = math.hypot(*xyz)
    if reach < r <= 1000 * reach:
        print(f"iik {command}: warning: --xyz {' '.join(f'{v:g}' for v in xyz)} is {r:.4g} m from the base, "
              f"farther than the arm reaches (at most {reach:.3f} m): millimetres typed as metres? (--xyz is "
              f"in m; in mm this is --xyz {' '.join(f'{v / 1000:g}' for v in xyz)})", file=sys.stderr)


def joint_angles(values, flag: str, deg: bool, arm):
    """``values`` (six joint angles, rad or deg with ``deg``) as radians inside ``arm``'s joint limits
    (Table I for the thesis arm); else an InvalidInputError naming ``flag`` and the joint, in the
    unit typed (a 999 deg or 1e300 deg "previous configuration" is no configuration of the arm)."""
    import numpy as np

    from iik.arm import LIMIT_TOL
    from iik.errors import InvalidInputError

    with np.errstate(over="ignore"):
        q = np.radians(values) if deg else np.asarray(values, float)
    unit, show = ("deg", np.degrees) if deg else ("rad", lambda v: v)
    finite = np.isfinite(q)
    outside = arm.limit_violations(np.where(finite, q, 0.0), -LIMIT_TOL)  # the arm's one limit test
    bad = sorted({*np.flatnonzero(~finite).tolist(), *(v.joint for v in outside)})
    if bad:
        j, lo, hi = bad[0], arm.lower[bad[0]], arm.upper[bad[0]]
        raise InvalidInputError(flag, f"q{j + 1} = {values[j]:g} {unit} is outside the joint limits "
                                      f"[{show(lo):.4g}, {show(hi):.4g}] {unit} ({arm.limits_name})")
    return q


def millimetres(value: float, flag: str, largest: float) -> float:
    """An option typed in mm as metres, if a finite number in (0, ``largest`` [m]]; else an
    InvalidInputError naming ``flag`` in the unit typed."""
    from iik.errors import InvalidInputError

    if not (math.isfinite(value) and 0 < value <= largest * 1e3):
        raise InvalidInputError(flag, f"must be a finite number in (0, {largest * 1e3:g}] mm, "
                                      f"got {value:g} mm")
    return value / 1e3
