"""Members and feasible intervals of the continua that are not linear (:class:`~iik.ik.result.Continuum`
of kind ``"theta1"`` and ``"numerical"``).

A member with the free joint at theta is found by continuation from the representative: the
free joint is stepped towards theta (steps of at most :data:`STEP` rad), and at each step the
other joints are refit by Levenberg-Marquardt with the free joint held (the compiled
:func:`iik.ik.kernel.continuum_members`). The feasible interval is where the members reach the
pose within the tolerance and lie inside the joint limits, found by marching from the
representative in both directions and bisecting the first failure (to :data:`RESOLUTION` rad).

Units: radians.
"""

from __future__ import annotations

import math

import numpy as np

from .angles import angle_distance, into_limits

__all__ = [
    "follow",
    "feasible_interval",
    "on_continuum",
    "theta1_branches",
    "inside_member",
    "along",
    "STEP",
    "RESOLUTION",
]

#: Largest continuation step of the free joint [rad].
STEP = 0.05
#: Resolution of the ends of a feasible interval [rad].
RESOLUTION = 1e-6
_JUMP = 0.5  # a member more than this from the previous one [rad]: the continuation lost the curve


def _kernel():
    from . import kernel

    return kernel


def _march(c, thetas: np.ndarray):
    """Members (n, 6) and residuals (n, 2) along the free-joint values ``thetas`` (in order,
    starting next to the representative)."""
    k = _kernel()
    j = c.free_joint - 1
    cols = np.array([i for i in range(6) if i != j], dtype=np.int64)
    coupled = -1 if c.coupled_joint is None else c.coupled_joint - 1
    out_q = np.empty((len(thetas), 6))
    out_r = np.empty((len(thetas), 2))
    opt = np.array([c.tolerance[0], c.tolerance[1], 1e-5, 1e-4, 1e-7])
    data = k.arm_data(c.arm).vector
    ok = k.continuum_members(
        np.ascontiguousarray(c.pose, dtype=float),
        data,
        opt,
        np.array(c.representative, dtype=float),
        cols,
        j,
        coupled,
        float(c.sign),
        np.ascontiguousarray(thetas, dtype=float),
        k.scratch(),
        out_q,
        out_r,
    )
    if not ok:  # pragma: no cover (the pose passed the IK's check)
        raise ValueError("the continuum's pose does not pass the pose check")
    return out_q, out_r


def _path(start: float, end: float) -> np.ndarray:
    n = max(1, math.ceil(abs(end - start) / STEP))
    return start + (end - start) * np.arange(1, n + 1) / n


def _march_closed(c, thetas: np.ndarray):
    """theta1 and theta2 continua: the exact closed-form configurations at each value (theta2:
    solver joint 1 held at the representative's), the one nearest the previous member taken
    (continuation without a polish: the members are exact)."""
    k = _kernel()
    n = len(thetas)
    out_q, out_r = np.empty((n, 16, 6)), np.empty((n, 16, 2))
    counts = np.zeros(n, dtype=np.int64)
    opt = np.array([c.tolerance[0], c.tolerance[1], 1e-5, 1e-3, 1e-7])
    thetas = np.ascontiguousarray(thetas, dtype=float)
    if c.kind == "theta2":  # (solver joint 1 is user joint 1, or 6 for an arm read from the flange)
        j1 = 5 if c.arm.solver.reversed else 0
        joint1, joint2 = np.full(n, float(c.representative[j1])), thetas
    else:
        joint1, joint2 = thetas, np.full(n, np.nan)
    ok = k.closed_forms_at(
        np.ascontiguousarray(c.pose, dtype=float),
        k.arm_data(c.arm).vector,
        opt,
        joint1,
        joint2,
        k.scratch(),
        out_q,
        out_r,
        counts,
    )
    if not ok:  # pragma: no cover (the pose passed the IK's check)
        raise ValueError("the continuum's pose does not pass the pose check")
    prev = np.array(c.representative, dtype=float)
    qs, rs = np.empty((n, 6)), np.full((n, 2), np.inf)
    # a member that misses the pose is taken only when none reaches it (10 rad more than any distance)
    penalty = np.where((out_r[..., 0] <= c.tolerance[0]) & (out_r[..., 1] <= c.tolerance[1]), 0.0, 10.0)
    for i in range(n):
        m = counts[i]
        if m == 0:
            qs[i] = prev
            continue
        b = int((angle_distance(out_q[i, :m], prev) + penalty[i, :m]).argmin())
        qs[i], rs[i], prev = out_q[i, b], out_r[i, b], out_q[i, b]
    return qs, rs


def _marcher(c):
    """How c's members are followed: by closed forms (theta1, theta2 continua) or by refits."""
    return _march_closed if c.kind in ("theta1", "theta2") else _march


def follow(c, thetas) -> tuple[np.ndarray, np.ndarray]:
    """Members (n, 6) of continuum ``c`` at the free-joint values ``thetas`` [rad] and their
    residuals (n, 2) [m, rad], each by continuation from the representative."""
    j = c.free_joint - 1
    start = float(c.representative[j])
    march = _marcher(c)
    qs, rs = [], []
    for th in np.atleast_1d(np.asarray(thetas, dtype=float)):
        path = _path(start, float(th))
        q, r = march(c, path)
        qs.append(q[-1])
        rs.append(r[-1])
    return np.array(qs), np.array(rs)


def _inside(arm, q):
    """q (6,) turned into the limits where a turn by 2 pi brings a joint in, and whether it is in."""
    from ..arm import LIMIT_TOL

    out, ok = into_limits(q, arm.q_min, arm.q_max, LIMIT_TOL)
    return out, bool(ok)


def _good(c, q, r, prev) -> bool:
    inside = _inside(c.arm, q)[1]
    tp, tr = c.tolerance
    near = float(angle_distance(q, prev)) <= _JUMP
    return inside and r[0] <= tp and r[1] <= tr and near


def _edge(c, start: float, limit: float) -> float:
    """How far from the representative the feasible members reach towards ``limit``."""
    if abs(limit - start) <= RESOLUTION:
        return start
    path = _path(start, limit)
    q, r = _marcher(c)(c, path)
    prev = np.array(c.representative, dtype=float)
    last = start
    for i, th in enumerate(path):
        if not _good(c, q[i], r[i], prev):
            lo, hi = last, th  # bisect between the last good value and the first bad one
            q_lo = prev
            while abs(hi - lo) > RESOLUTION:
                mid = 0.5 * (lo + hi)
                qm, rm = _marcher(c)(c, _path(start, mid))
                if _good(
                    c, qm[-1], rm[-1], q_lo if abs(mid - lo) <= STEP else qm[-2] if len(qm) > 1 else q_lo
                ):
                    lo, q_lo = mid, qm[-1]
                else:
                    hi = mid
            return lo
        prev, last = q[i], th
    return limit


def along(c) -> tuple[np.ndarray, np.ndarray]:
    """Members of continuum ``c`` across its free joint's limits, by continuation from the
    representative in both directions (steps of at most :data:`STEP` rad): the free-joint values
    (n,) [rad] in increasing order and the members (n, 6) [rad] that reach the pose within the
    tolerance. A member that misses it is left out and the march goes on (a numerical tube can
    be thinner than the tolerance in places); a direction ends where the members jump (more than
    0.5 rad from the last one kept: the curve is lost). The other joints' limits are not applied
    (their windings are the caller's, :mod:`iik.ik.nearest`)."""
    j = c.free_joint - 1
    start = float(c.representative[j])
    march = _march_closed if c.kind == "theta1" else _march
    thetas, members = [start], [np.array(c.representative, dtype=float)]
    tp, tr = c.tolerance
    for limit in (float(c.arm.q_min[j]), float(c.arm.q_max[j])):
        if abs(limit - start) <= RESOLUTION:
            continue
        path = _path(start, limit)
        q, r = march(c, path)
        prev = members[0]
        for i, th in enumerate(path):
            if float(angle_distance(q[i], prev)) > _JUMP:
                break
            if r[i, 0] <= tp and r[i, 1] <= tr:
                thetas.append(float(th))
                members.append(q[i])
                prev = q[i]
    order = np.argsort(thetas, kind="stable")
    return np.array(thetas)[order], np.array(members)[order]


def feasible_interval(c) -> tuple[float, float]:
    """The feasible interval of continuum ``c``'s free joint (the piece containing the
    representative), or (nan, nan) if the representative itself is not feasible."""
    j = c.free_joint - 1
    start = float(c.representative[j])
    if not _inside(c.arm, c.representative)[1]:
        return (math.nan, math.nan)
    lo, hi = float(c.arm.q_min[j]), float(c.arm.q_max[j])
    return (_edge(c, start, lo), _edge(c, start, hi))


def on_continuum(c, q, tol: float = 1e-7) -> bool:
    """Is the configuration q (6,) a member of continuum c (its member at q's free joint)?"""
    m, r = follow(c, [float(q[c.free_joint - 1])])
    return bool(
        angle_distance(m[0], q) <= tol
        and r[0, 0] <= c.tolerance[0]
        and r[0, 1] <= c.tolerance[1]
    )


def _continues(c) -> bool:
    """Do c's members continue on both sides of the representative (a curve, not a point)?"""
    j = c.free_joint - 1
    x = float(c.representative[j])
    for th in (x - STEP, x + STEP):
        m, r = follow(c, [th])
        jump = float(angle_distance(m[0], c.representative))
        if not (r[0, 0] <= c.tolerance[0] and r[0, 1] <= c.tolerance[1] and jump <= 2.0):
            return False
    return True


def theta1_branches(continua) -> list[int | None]:
    """For the candidate rows of a degenerate pose (one theta1 :class:`Continuum` each, in the
    result's order): the index of the row whose branch each row lies on (itself for the first
    of a branch), or None for a row that is an isolated solution (no curve through it)."""
    out: list[int | None] = []
    for i, c in enumerate(continua):
        owner = next(
            (k for k in range(i) if out[k] == k and on_continuum(continua[k], c.representative)), None
        )
        out.append(owner if owner is not None else (i if _continues(c) else None))
    return out


def inside_member(c):
    """A member of continuum c inside the joint limits, nearest the representative along the free
    joint (members every :data:`STEP` rad or closer, followed once towards each of the free joint's
    limits), or None if none is found."""
    arm = c.arm
    rep, ok = _inside(arm, np.array(c.representative, dtype=float))
    if ok:
        return rep
    j = c.free_joint - 1
    start = float(c.representative[j])
    found = []  # (distance along the free joint, member) of the first inside member each way
    for end in (arm.q_min[j], arm.q_max[j]):
        path = _path(start, float(end))
        qs, rs = _marcher(c)(c, path)
        for th, q, r in zip(path, qs, rs, strict=True):
            m, ok = _inside(arm, q)
            if ok and r[0] <= c.tolerance[0] and r[1] <= c.tolerance[1]:
                found.append((abs(th - start), m))
                break
    return min(found, key=lambda f: f[0])[1] if found else None
