"""Is a configuration among an IK answer, and does the answer cover what the oracle finds?

A configuration q that reaches the pose counts as found by an :class:`~iik.IKResult` when

* a row is within :data:`SAME` rad of it in every joint (angles wrapped); or
* a row is *connected* to it: within :data:`NEAR` rad, by a straight joint-space segment whose
  points all reach the pose within the tolerances (near a singularity the configurations
  within the tolerance form a thin valley; the pose does not tell its points apart); or
* q lies on a continuum row: the member at q's value of the free joint is the same or
  connected (collinear continua: the exact member; the others: followed by continuation); or
* a *bent path* within the tolerances leads from q to a point found so (:func:`_bent_path`; one
  joint stepped, the others refit: each joint in turn, the one that differs most first), from a
  row within :data:`BLOB` rad of q: where a continuum meets another singular set, or at a
  multiple root, the configurations within the tolerance form a flat, curved blob whose far
  points no straight segment reaches.

:func:`coverage` compares an answer with the oracle (:mod:`verification.oracles.multistart`):
oracle solutions the answer does not contain (missed), and rows of the answer that do not reach
the pose by the oracle's independent forward kinematics (wrong).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from iik.arm import Arm
from iik.ik.angles import wrap_angle as _wrap
from verification.oracles.multistart import OracleSolutions, pose_residuals_np, project, refit

__all__ = ["SAME", "NEAR", "BLOB", "AGREE", "contains", "Coverage", "coverage", "Agreement", "agreement"]

#: Rows within this of q [rad] are q.
SAME = 1e-7
#: Rows within this [rad] joined to q by a segment within the tolerance are q.
NEAR = 1e-2
#: Rows within this [rad] joined to q by a bent path within the tolerance are q: at a multiple
#: root on the singular set the configurations within the tolerance form a blob that spans
#: 0.027 rad of joint 3 (thesis arm, elbow-second: the eliminant has a triple root there).
BLOB = 0.1
#: Two IK answers agree when each row of one is within this of a row of the other [rad] (or
#: connected to it, or on one of its continua): issue 17's "same solution sets within 1e-9".
AGREE = 1e-9
_SEGMENT = np.linspace(0.0, 1.0, 17)[1:-1]


def _connected(a, b, T, arm: Arm, tol) -> bool:
    """Are a and b joined by a path within the tolerance? The points of the straight segment,
    each moved onto the pose by a few damped least-squares steps (a curved valley), must reach
    the pose and stay within the segment's length of where they started."""
    d = _wrap(b - a)
    size = float(np.max(np.abs(d)))
    if size > NEAR:
        return False
    pts = a + _SEGMENT[:, None] * d
    pres, rres = pose_residuals_np(arm, pts, T)
    if np.all(pres <= tol[0]) and np.all(rres <= tol[1]):
        return True
    moved = project(arm, pts, T, iterations=30)  # (a curved valley at a singularity converges slowly)
    pres, rres = pose_residuals_np(arm, moved, T)
    shift = np.max(np.abs(_wrap(moved - pts)), axis=1)
    return bool(np.all(pres <= tol[0]) and np.all(rres <= tol[1]) and np.all(shift <= size))


def _same_or_connected(rows, q, T, arm, tol, same=SAME) -> bool:
    if len(rows) == 0:
        return False
    dist = np.max(np.abs(_wrap(np.asarray(rows) - q)), axis=1)
    if np.min(dist) <= same:
        return True
    return any(_connected(rows[i], q, T, arm, tol) for i in np.argsort(dist)[:3] if dist[i] <= NEAR)


def contains(result, q, T, arm: Arm, tol=(1e-10, 1e-10), same: float = SAME) -> bool:
    """Does the IK answer ``result`` contain the configuration q (6,) of pose T (see the module;
    ``same``: the distance [rad] within which a row is q)?"""
    q = np.asarray(q, dtype=float)
    members = _members(result, q)
    if _directly(result, members, q, T, arm, tol, same):
        return True
    near = np.vstack([np.asarray(result.q).reshape(-1, 6)] + [m[None] for m in members])
    dist = np.max(np.abs(_wrap(near - q)), axis=1)
    for i in np.argsort(dist)[:3]:
        if dist[i] > BLOB:
            continue
        for held in np.argsort(-np.abs(_wrap(near[i] - q))):  # the joint that differs most first
            end = _bent_path(near[i], q, T, arm, tol, int(held))
            if end is not None and _directly(result, _members(result, end), end, T, arm, tol, same):
                return True
    return False


def _members(result, q) -> list:
    """The member of each continuum of the answer at q's value of its free joint (6,) each."""
    return [c.member(float(q[c.free_joint - 1])) for row in result.continua for c in row]


def _directly(result, members, q, T, arm: Arm, tol, same) -> bool:
    """q the same as or connected to a row, or to one of the continuum ``members`` at q."""
    if _same_or_connected(result.q, q, T, arm, tol, same):
        return True
    return any(_same_or_connected(m[None], q, T, arm, tol, same) for m in members)


_STEPS = np.linspace(0.0, 1.0, 17)[1:]


def _bent_path(a, q, T, arm: Arm, tol, held: int):
    """The end of a path from q toward a (6,): joint ``held`` stepped from q's value to a's in
    16 steps, the others refit at each step from the previous point
    (:func:`~verification.oracles.multistart.refit`), up to its first jump (a step that moves
    any joint by more than a quarter of the distance while the two points are not connected,
    :func:`_connected`: the refit jumped to another solution; a step that slid along a tube
    within the tolerance is connected); None unless the path has a step before any jump and every
    point of it reaches the pose within the tolerances. Beside a near-continuum tube the joint
    that differs most (joint 6, coupled to joint 3 along the tube) can fail where joint 1
    succeeds: contains tries each. Where the tube's members pass a second singular set (joint 3
    at +-90 degrees) the valley is a sheet, and the refit slides along the tube by more than
    NEAR at the step after reaching it: the point before that jump is the path's end."""
    d = _wrap(a - q)
    size = float(np.max(np.abs(d)))
    x, pts = np.asarray(q, float), []
    for s in _STEPS:
        y = x.copy()
        y[held] = q[held] + s * d[held]
        y = refit(arm, y, T, held)
        if np.max(np.abs(_wrap(y - x))) > size / 4 and not _connected(x, y, T, arm, tol):
            break
        pts.append(y)
        x = y
    if not pts:
        return None
    pres, rres = pose_residuals_np(arm, np.array(pts), T)
    return x if np.all(pres <= tol[0]) and np.all(rres <= tol[1]) else None


@dataclass(frozen=True)
class Coverage:
    """An IK answer against the oracle on one pose.

    Attributes:
        missed: Oracle solutions (k, 6) the answer does not contain.
        wrong: Rows (indices) of the answer that miss the pose by the oracle's forward kinematics.
        oracle_solutions: How many clusters the oracle found.
    """

    missed: np.ndarray
    wrong: tuple[int, ...]
    oracle_solutions: int


def coverage(result, oracle: OracleSolutions, T, arm: Arm, tol=(1e-10, 1e-10)) -> Coverage:
    """Which oracle solutions the answer misses, and which of its rows are wrong."""
    missed = [o for o in oracle.q if not contains(result, o, T, arm, tol)]
    wrong = ()
    if len(result.q):
        pres, rres = pose_residuals_np(arm, result.q, T)
        wrong = tuple(int(i) for i in np.flatnonzero((pres > tol[0]) | (rres > tol[1])))
    return Coverage(np.array(missed).reshape(-1, 6), wrong, len(oracle.q))


@dataclass(frozen=True)
class Agreement:
    """Two IK answers of one pose compared as sets (:func:`agreement`).

    Attributes:
        only_a: Rows (indices) of the first answer the second does not contain.
        only_b: Rows (indices) of the second answer the first does not contain.
    """

    only_a: tuple[int, ...]
    only_b: tuple[int, ...]

    @property
    def same(self) -> bool:
        """Do the two answers hold the same solutions?"""
        return not self.only_a and not self.only_b


def agreement(a, b, T, arm: Arm, tol=(1e-10, 1e-10), same: float = AGREE) -> Agreement:
    """Compare two IK answers of pose T as sets: every row of each is within ``same`` [rad] of
    a row of the other, connected to one within the tolerance, or on one of its continua (and
    a continuum row of one is a member of the other's continuum or one of its rows)."""
    only_a = tuple(i for i, q in enumerate(a.q) if not contains(b, q, T, arm, tol, same))
    only_b = tuple(i for i, q in enumerate(b.q) if not contains(a, q, T, arm, tol, same))
    return Agreement(only_a, only_b)
