"""The kinematic class the complete IK solves, and how close an arm is to it.

The class (derivation: ``docs/IK_CLASS.md``): six revolute joints whose axes, read in one
direction along the chain, are ``1 . 2 ∩ 3 ⊥∩ 4 ∥ 5 ⊥∩ 6`` with the two intersection points
C = 3∩4 and D = 5∩6 *level* (D - C perpendicular to the parallel axes 4 and 5):

* axes 2 and 3 intersect (any angle but parallel);
* axes 3 and 4 intersect at a right angle;
* axes 4 and 5 are parallel and distinct;
* the common normal of axes 4 and 5 through C reaches axis 5 at D (zero offset along them);
* axes 5 and 6 intersect at a right angle;
* axes 1 and 2, and every offset along an axis not named here, are free.

The thesis arm (Table II) is a member read from the base; FANUC's CRX series is a member
read from the flange (its J6 . J5 ∩ J4 ⊥∩ J3 ∥ J2 ⊥∩ J1). An arm is tested in both
directions; the first member direction gives the **solver chain**: a modified-DH table in
canonical form (axis 1 along z0 through the origin, D the origin of frame 6) with fixed base
and tool transforms, such that ``X = base . links(q) . tool`` where X is the tool pose (read
from the base) or its inverse (read from the flange, the joint order reversed).

Tolerances are relative to the arm's size (lengths) and absolute for angles; a member's
near-zero lengths and near-right angles are snapped to exact values (so cos 90 deg = 0).
Outside the class, :class:`NotInClassError` carries a near-miss report for both directions:
each condition, how far it is from holding (mm, degrees).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .errors import InvalidInputError

__all__ = [
    "Condition",
    "ClassReport",
    "SolverChain",
    "NotInClassError",
    "LENGTH_TOL",
    "ANGLE_TOL",
    "axis_lines",
    "chain_from_lines",
    "solver_chain",
    "transform_of_rows",
]

#: Lengths below this fraction of the arm's size count as zero (and are snapped to it).
LENGTH_TOL = 1e-9
#: Angles within this of a multiple of 90 deg count as that multiple [rad] (and are snapped).
ANGLE_TOL = 1e-9
_NEARLY_PARALLEL = math.sin(math.pi / 4)  # |z_i x z_j| below it: a pair meant parallel is measured as such


@dataclass(frozen=True)
class Condition:
    """One condition of the class, measured on an arm read in one direction.

    Attributes:
        text: What must hold, e.g. ``"axes 3 and 4 intersect at a right angle"``.
        deviation: How far it is from holding: a distance [m] or an angle [rad].
        unit: ``"m"`` or ``"rad"`` (displayed as mm or degrees).
        tolerance: The largest deviation that still counts as holding (same unit).
    """

    text: str
    deviation: float
    unit: str
    tolerance: float

    @property
    def holds(self) -> bool:
        return bool(self.deviation <= self.tolerance)

    def describe(self) -> str:
        if self.unit == "m":
            amount = f"{self.deviation * 1e3:.6g} mm (tolerance {self.tolerance * 1e3:.3g} mm)"
        else:
            amount = (
                f"{math.degrees(self.deviation):.6g} deg (tolerance {math.degrees(self.tolerance):.3g} deg)"
            )
        return f"{'holds' if self.holds else 'FAILS'}: {self.text}, off by {amount}"


@dataclass(frozen=True)
class ClassReport:
    """Every condition of the class for the chain read in one direction.

    Attributes:
        direction: ``"base to flange"`` or ``"flange to base"``.
        conditions: The conditions, in the order of the chain.
    """

    direction: str
    conditions: tuple[Condition, ...]

    @property
    def member(self) -> bool:
        return all(c.holds for c in self.conditions)

    def describe(self) -> str:
        head = f"read {self.direction}: {'a member of the class' if self.member else 'not a member'}"
        return "\n".join([head] + ["  " + c.describe() for c in self.conditions])


@dataclass(frozen=True)
class SolverChain:
    """The canonical member of the class the closed forms work in (see the module docstring).

    Attributes:
        reversed: True when the chain is read from the flange (solver joint k is joint 7 - k).
        rows: Six ``(cos alpha, sin alpha, a, d, offset)`` modified-DH rows [1, 1, m, m, rad].
        base, tool: The fixed transforms (4, 4) with ``X = base . links . tool``.
        report: The class report of the direction used; ``other``: of the other direction.
    """

    reversed: bool
    rows: tuple[tuple[float, float, float, float, float], ...]
    base: np.ndarray
    tool: np.ndarray
    report: ClassReport
    other: ClassReport


def _distance(report: ClassReport) -> tuple[int, float, float]:
    """How far a reading is from the class, for choosing the closer one: the failed conditions,
    then the largest failed angle [rad], then the sum of the failed lengths [m]."""
    failed = [c for c in report.conditions if not c.holds]
    angles = [c.deviation for c in failed if c.unit == "rad"]
    return len(failed), max(angles, default=0.0), sum(c.deviation for c in failed if c.unit == "m")


class NotInClassError(InvalidInputError):
    """The arm is not a member of the class the complete IK solves.

    Attributes:
        reports: The near-miss reports, read from the base and read from the flange.
    """

    def __init__(self, argument: str, reports: tuple[ClassReport, ...], detail: str = ""):
        self.reports = reports
        best = min(reports, key=_distance)
        failed = [c.describe() for c in best.conditions if not c.holds]
        lines = "; ".join(failed)
        super().__init__(
            argument,
            (detail + "; " if detail else "")
            + f"not of the arm class 1 . 2 ∩ 3 ⊥∩ 4 ∥ 5 ⊥∩ 6 (closest when read {best.direction}: "
            + lines
            + ")\n"
            + "\n".join(r.describe() for r in reports),
        )


# ----------------------------------------------------------------------------- geometry
def transform_of_rows(rows, q) -> np.ndarray:
    """``links(q)`` (4, 4) of modified-DH rows ``(ca, sa, a, d, offset)`` at joint angles q [rad]."""
    T = np.eye(4)
    for (ca, sa, a, d, off), qi in zip(rows, q, strict=True):
        ct, st = math.cos(qi + off), math.sin(qi + off)
        Li = np.array(
            [
                [ct, -st, 0.0, a],
                [ca * st, ca * ct, -sa, -sa * d],
                [sa * st, sa * ct, ca, ca * d],
                [0.0, 0.0, 0.0, 1.0],
            ]
        )
        T = T @ Li
    return T


def axis_lines(rows, base, tool, q=None):
    """Joint axis lines of a chain at q (default 0): points (6, 3) and unit directions (6, 3) in
    the base frame [m], and the tool frame (4, 4)."""
    q = np.zeros(6) if q is None else np.asarray(q, float)
    T = np.asarray(base, float).copy()
    pts, dirs = [], []
    for (ca, sa, a, d, off), qi in zip(rows, q, strict=True):
        ct, st = math.cos(qi + off), math.sin(qi + off)
        T = T @ np.array(
            [
                [ct, -st, 0.0, a],
                [ca * st, ca * ct, -sa, -sa * d],
                [sa * st, sa * ct, ca, ca * d],
                [0.0, 0.0, 0.0, 1.0],
            ]
        )
        pts.append(T[:3, 3].copy())
        dirs.append(T[:3, 2].copy())
    return np.array(pts), np.array(dirs), T @ np.asarray(tool, float)


def _snap_angle(x: float, tol: float) -> float:
    k = round(x / (math.pi / 2))
    return k * (math.pi / 2) if abs(x - k * (math.pi / 2)) <= tol else x


def _cos_sin(x: float) -> tuple[float, float]:
    """cos, sin with multiples of 90 deg exact."""
    k = round(x / (math.pi / 2))
    if abs(x - k * (math.pi / 2)) == 0.0:
        return ((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))[k % 4]
    return math.cos(x), math.sin(x)


def _foot(p, z, x):
    """Parameter of the point of line (p, z) nearest to x."""
    return float((x - p) @ z)


def chain_from_lines(
    pts, dirs, start, end, size: float, ltol: float = LENGTH_TOL, atol: float = ANGLE_TOL, parallel=()
):
    """A canonical modified-DH chain through the axis lines (pts, dirs) at q = 0.

    Frame i has z along axis i and its origin where the common normal to axis i+1 meets it
    (for parallel axes: where the previous normal meets axis i, so that offset is 0); frame 0
    is frame 1 at q = 0; frame 6 shares frame 5's x axis, its origin on axis 6. Returns
    ``(rows, base, tool, raw)``: rows ``(alpha, a, d, offset)`` snapped, ``base = start^-1 .
    frame 0``, ``tool = frame 6^-1 . end``, and ``raw`` the unsnapped rows (for the report).

    ``parallel``: indices i of the axis pairs (i+1, i+2) the class wants parallel. A pair of those
    that is only nearly parallel (under 45 deg) is measured as if parallel (the normal through the
    previous foot, made perpendicular to axis i+1; its raw alpha is the whole angle between the
    axes): the common
    normal of two nearly parallel skew lines lies far outside the arm (hundreds of metres for
    0.1 deg), so its length and offset would measure nothing about the arm.
    """
    lt = ltol * size
    n = len(pts)
    origins, xs = [], []
    prev = np.asarray(pts[0], float)
    feet2 = []
    near = set()  # pairs measured as if parallel though they are not
    for i in range(n - 1):
        p1, z1, p2, z2 = pts[i], dirs[i], pts[i + 1], dirs[i + 1]
        c = np.cross(z1, z2)
        s = float(np.linalg.norm(c))
        if s <= atol or (i in parallel and s < _NEARLY_PARALLEL):  # the normal through the previous foot
            o1 = p1 + _foot(p1, z1, prev) * z1
            o2 = p2 + _foot(p2, z2, o1) * z2
            w = o2 - o1
            if s > atol:
                near.add(i)
                w = w - (w @ z1) * z1
            dist = float(np.linalg.norm(w))
            if dist <= lt:
                raise InvalidInputError("arm", f"joint axes {i + 1} and {i + 2} coincide")
            x = w / dist
        else:
            nrm = c / s
            # p1 + t1 z1 + k nrm = p2 + t2 z2
            A = np.array([z1, -z2, nrm]).T
            t1, t2, _k = np.linalg.solve(A, p2 - p1)
            o1, o2 = p1 + t1 * z1, p2 + t2 * z2
            w = o2 - o1
            dist = float(np.linalg.norm(w))
            x = nrm if dist <= lt else w / dist
        origins.append(o1)
        xs.append(x)
        feet2.append(o2)
        prev = o2
    origins.append(feet2[-1])
    xs.append(xs[-1])
    frames = []
    for o, x, z in zip(origins, xs, dirs, strict=True):
        F = np.eye(4)
        F[:3, 0], F[:3, 1], F[:3, 2], F[:3, 3] = x, np.cross(z, x), z, o
        frames.append(F)
    raw = [(0.0, 0.0, 0.0, 0.0)]
    for i in range(n - 1):
        Fi, Fj = frames[i], frames[i + 1]
        xi, zi, zj, xj = Fi[:3, 0], Fi[:3, 2], Fj[:3, 2], Fj[:3, 0]
        alpha = math.atan2(float(np.cross(zi, zj) @ xi), float(zi @ zj))
        if i in near:
            alpha = math.copysign(math.atan2(float(np.linalg.norm(np.cross(zi, zj))), float(zi @ zj)), alpha)
        a = float((feet2[i] - origins[i]) @ xi)
        d = float((origins[i + 1] - feet2[i]) @ zj)
        off = math.atan2(float(np.cross(xi, xj) @ zj), float(xi @ xj))
        raw.append((alpha, a, d, off))
    rows = tuple(
        (
            _snap_angle(al, atol),
            0.0 if abs(a) <= lt else a,
            0.0 if abs(d) <= lt else d,
            _snap_angle(off, atol),
        )
        for al, a, d, off in raw
    )
    base = np.linalg.inv(np.asarray(start, float)) @ frames[0]
    tool = np.linalg.inv(frames[-1]) @ np.asarray(end, float)
    return rows, base, tool, tuple(raw)


def _conditions(raw, size: float, ltol: float, atol: float) -> tuple[Condition, ...]:
    """The class conditions of a canonical chain's unsnapped rows ``(alpha, a, d, offset)``."""
    lt = ltol * size
    _, a2, _, _ = raw[2]
    al2 = raw[2][0]
    al3, a3 = raw[3][0], raw[3][1]
    al4, a4, d5 = raw[4][0], raw[4][1], raw[4][2]
    al5, a5 = raw[5][0], raw[5][1]
    right = lambda al: abs(abs(al) - math.pi / 2)  # noqa: E731
    par = lambda al: min(abs(al), abs(abs(al) - math.pi))  # noqa: E731
    return (
        Condition("axes 2 and 3 intersect", abs(a2), "m", lt),
        Condition("axes 2 and 3 are not parallel", max(0.0, atol * 10 - par(al2)), "rad", 0.0),
        Condition("axes 3 and 4 intersect", abs(a3), "m", lt),
        Condition("axes 3 and 4 are perpendicular", right(al3), "rad", atol),
        Condition("axes 4 and 5 are parallel", par(al4), "rad", atol),
        Condition("axes 4 and 5 are distinct", max(0.0, 10 * lt - abs(a4)), "m", 0.0),
        Condition("the points 3∩4 and 5∩6 are level along axes 4 and 5", abs(d5), "m", lt),
        Condition("axes 5 and 6 intersect", abs(a5), "m", lt),
        Condition("axes 5 and 6 are perpendicular", right(al5), "rad", atol),
    )


def _reversed_lines(pts, dirs):
    return pts[::-1].copy(), -dirs[::-1].copy()


def solver_chain(
    rows, base, tool, argument: str = "arm", ltol: float = LENGTH_TOL, atol: float = ANGLE_TOL
) -> SolverChain:
    """The solver chain of the arm with modified-DH rows ``(alpha, a, d, offset)``, base and tool,
    or :class:`NotInClassError` (naming ``argument``) with the near-miss reports."""
    crows = [(*_cos_sin(al), a, d, off) for al, a, d, off in rows]
    pts, dirs, flange = axis_lines(crows, base, tool)
    size = max(
        1e-12,
        float(sum(abs(r[1]) + abs(r[2]) for r in rows) + np.linalg.norm(np.asarray(tool, float)[:3, 3])),
    )
    found = []
    for rev in (False, True):
        if rev:
            p, d = _reversed_lines(pts, dirs)
            start, end = flange, np.asarray(np.eye(4))
        else:
            p, d = pts, dirs
            start, end = np.eye(4), flange
        # (base-frame coordinates: the solver pose is X = start^-1 ... end)
        r, b, t, raw = chain_from_lines(p, d, start, end, size, ltol, atol, parallel=(3,))
        rep = ClassReport("from the flange" if rev else "from the base", _conditions(raw, size, ltol, atol))
        found.append((rev, r, b, t, rep))
    for k, (rev, r, b, t, rep) in enumerate(found):
        if rep.member:
            other = found[1 - k][4]
            return SolverChain(
                rev, tuple((*_cos_sin(al), a, dd, off) for al, a, dd, off in r), b, t, rep, other
            )
    raise NotInClassError(argument, (found[0][4], found[1][4]))
