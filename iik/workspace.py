"""Position workspace of the arm: the Cartesian test of Sec 3.4.4 and the
closest reachable point suggested to the user (App. G).

Positions are in metres in base frame 0 (see :mod:`iik.kinematics`). The
workspace is the set of tool-point positions ``fk(q)[:3, 3]`` over all joint
vectors ``q`` inside the limits of Table I (position only: every orientation
allowed; joint 6 does not move the tool point, Eq 34).

:func:`in_workspace` implements regions 1-3 of Sec 3.4.4 (Eq 36-41) with two
corrections found by ``iik verify`` (``verification/checks/workspace.py``):

* Eq 40 prints ``x4 = (l2 - l3 c2) cos 160``; joint 4 sits at
  ``(l2 + l3 c2) (cos th1, sin th1)`` (Table II), so the sign is wrong.
* Eq 39 aims link 3 at the point's elevation seen from the base axis
  (``atan2(pz - l1, sqrt(px^2 + py^2))``); the nearest joint-4 position is the
  one aimed from joint 2, ``atan2(pz - l1, u - l2)`` with ``u`` the horizontal
  coordinate of the point along the joint-1 limit direction, clipped to the
  joint-2 limits.

With both corrections the test agreed with position-reachability ground truth
on every one of 14000 test points (and accepted all of 10^6 reachable sampled
points); the numbers are in the ``iik verify`` report.

Region 1 (Eq 37-38) is used as printed.

Sec 3.4 is written for arms of the thesis's Table II form (:attr:`iik.Arm.thesis_lengths`). For any
other arm of the class (a FANUC CRX, a constructed member) :func:`closest_reachable` runs the same
bounded multi-start search over all six joints with the arm's own FK (:func:`iik.fk`), and
:func:`in_workspace` asks it: a point counts as inside when the search reaches it within
:data:`SEARCH_TOL` (a local search: a reachable point it fails to reach would be called outside;
``tests/iik/test_workspace.py`` checks it reaches FK points of random configurations of the CRX).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from scipy.optimize import least_squares
from scipy.spatial import cKDTree

from .arm import Arm
from .errors import InvalidInputError
from .ik.angles import clip_angle
from .kinematics import eq4_position, eq4_terms, fk, position_jacobian
from .validation import as_points

__all__ = ["in_workspace", "closest_reachable", "ClosestReachable", "position_lm", "tool_positions",
           "joint4_distance", "SEARCH_TOL"]

#: For an arm not of the thesis's form, :func:`in_workspace` counts a point as inside when the search of
#: :func:`closest_reachable` reaches it within this distance [m].
SEARCH_TOL = 1e-6


def _thesis_form(arm: Arm) -> bool:
    """Is ``arm`` of the thesis's Table II form (the form Sec 3.4 is written for)?"""
    try:
        arm.thesis_lengths  # noqa: B018 - raises for another form
    except InvalidInputError:
        return False
    return True


def tool_positions(q5: np.ndarray, arm: Arm) -> np.ndarray:
    """Tool-point positions [m], (n, 3), for joint angles ``q5`` (n, 5) [rad] of joints 1-5.

    Eq 34 (the position column of Eq 4; joint 6 does not move the tool point), evaluated
    by the closed forms of :mod:`iik.kinematics` on arrays. Equal to ``fk(q)[:, :3, 3]``
    (tested), without building the rotation.
    """
    c1, c2, c3, c4 = (np.cos(q5[:, i]) for i in range(4))
    s1, s2, s3, s4 = (np.sin(q5[:, i]) for i in range(4))
    c45, s45 = np.cos(q5[:, 3] + q5[:, 4]), np.sin(q5[:, 3] + q5[:, 4])
    l1, l2, l3, l4, l5 = arm.lengths
    A, B, W, V = eq4_terms(c1, s1, c2, s2, c3, s3, c4, s4, c45, s45, l4, l5)
    out = np.empty((q5.shape[0], 3))
    out[:, 0], out[:, 1], out[:, 2] = eq4_position(c1, s1, c2, s2, c3, A, B, W, V, l1, l2, l3)  # Eq 34
    return out


def _norm3(x, y, z):
    """sqrt(x^2 + y^2 + z^2) without overflow for points far out (hypot scales)."""
    return np.hypot(np.hypot(x, y), z)


def _regions(p: np.ndarray, arm: Arm):
    phi = np.arctan2(p[:, 1], p[:, 0])  # Eq 36
    r2 = phi >= arm.upper[0]  # region 2: phi >= theta1 upper limit (160 deg)
    r3 = phi <= arm.lower[0]  # region 3: phi <= theta1 lower limit (-160 deg)
    return phi, r2, r3


def joint4_distance(p: np.ndarray, th1: float, arm: Arm) -> np.ndarray:
    """rho_23 of Eq 41 [m]: distance of points ``p`` (n, 3) from joint 4 with joint 1 at ``th1``
    [rad] and joint 2 aimed at them (corrected Eq 39-40, see the module docstring)."""
    l1, l2, l3 = arm.l1, arm.l2, arm.l3
    u = p[:, 0] * np.cos(th1) + p[:, 1] * np.sin(th1)
    th2 = clip_angle(-np.arctan2(p[:, 2] - l1, u - l2), arm.lower[1], arm.upper[1])  # Eq 39 (corrected)
    c2, s2 = np.cos(th2), np.sin(th2)
    x4 = (l2 + l3 * c2) * np.cos(th1)  # Eq 40 (corrected sign)
    y4 = (l2 + l3 * c2) * np.sin(th1)  # Eq 40 (corrected sign)
    z4 = l1 - l3 * s2  # Eq 40
    return _norm3(p[:, 0] - x4, p[:, 1] - y4, p[:, 2] - z4)  # Eq 41


def in_workspace(p, arm: Arm, *, tol: float = 1e-9) -> np.ndarray | bool:
    """Is each point inside the workspace, by the (corrected) test of Sec 3.4.4?

    Args:
        p: Point(s) [m] in base frame 0, shape (3,) or (n, 3).
        arm: Arm parameters.
        tol: Points up to ``tol`` [m] beyond a boundary count as inside (round-off
            on the boundary itself).

    Returns:
        ``bool`` for one point, or a boolean array (n,).

    Raises:
        InvalidInputError: NaN/inf or a wrong shape.
    """
    pb, batched = as_points(p, "p")
    if not _thesis_form(arm):
        inside = _general_closest(pb, arm, SEARCH_TOL * 0.1)[2] <= max(tol, SEARCH_TOL)
        return inside if batched else bool(inside[0])
    l1, l2, l3, l4, l5 = arm.lengths
    phi, r2, r3 = _regions(pb, arm)
    # Region 1 (Eq 37-38): joint 2 at l2 (cos phi, sin phi, l1), reach l3 + l4 + l5.
    rho1 = _norm3(pb[:, 0] - l2 * np.cos(phi), pb[:, 1] - l2 * np.sin(phi), pb[:, 2] - l1)  # Eq 38
    inside = rho1 <= l3 + l4 + l5 + tol  # Eq 38
    for region, th1 in ((r2, arm.upper[0]), (r3, arm.lower[0])):
        if np.any(region):
            rho23 = joint4_distance(pb[region], th1, arm)
            inside[region] = rho23 <= l4 + l5 + tol  # Eq 41
    return inside if batched else bool(inside[0])


def position_lm(p: np.ndarray, q0: np.ndarray, arm: Arm, iters: int = 60,
                tol: float = 1e-10) -> tuple[np.ndarray, np.ndarray]:
    """Batched bounded Levenberg-Marquardt on ``|fk(q)[:3,3] - p|`` over joints 1-5.

    A position-only numerical IK used as ground truth and by
    :func:`closest_reachable`. Joints pushed against a limit are frozen for
    that step (active set); the other steps are projected onto the limits.

    Args:
        p: Targets [m], (n, 3).
        q0: Start configurations [rad], (n, 5), inside the limits.
        arm: Arm parameters.
        iters: Iterations.
        tol: Stop when every residual is below this [m].

    Returns:
        ``(q (n, 5) [rad], residual (n,) [m])``.
    """
    def jac(q):
        q6 = np.zeros((len(q), 6))
        q6[:, :5] = q
        return position_jacobian(q6, arm)[..., :5]

    return _bounded_lm(p, q0, arm.q_min[:5], arm.q_max[:5], lambda q: tool_positions(q, arm), jac, iters, tol)


def _bounded_lm(p, q0, lo, hi, positions, jac, iters: int, tol: float) -> tuple[np.ndarray, np.ndarray]:
    """:func:`position_lm` over the joints of ``lo``/``hi`` with ``positions(q)`` (n, 3) [m] and its
    Jacobian ``jac(q)`` (n, 3, k)."""
    q = np.clip(np.array(q0, dtype=float), lo, hi)
    r = positions(q) - p
    c = np.einsum("ni,ni->n", r, r)
    lam = np.full(len(p), 1e-3)
    eye = np.eye(len(lo))
    for _ in range(iters):
        act = c > tol * tol
        if not np.any(act):
            break
        ia = np.nonzero(act)[0]
        J = jac(q[ia])
        A = np.einsum("nij,nik->njk", J, J) + lam[ia, None, None] * eye
        g = np.einsum("nij,ni->nj", J, r[ia])
        step = -np.linalg.solve(A, g[..., None])[..., 0]
        qa = q[ia]
        blocked = ((qa <= lo + 1e-12) & (step < 0)) | ((qa >= hi - 1e-12) & (step > 0))
        rb = np.nonzero(blocked.any(axis=1))[0]
        if len(rb):  # active set: joints pushed against a limit are frozen for this step
            Jb = J[rb] * (~blocked[rb])[:, None, :]
            Ab = np.einsum("nij,nik->njk", Jb, Jb) + lam[ia[rb], None, None] * eye
            gb = np.einsum("nij,ni->nj", Jb, r[ia[rb]])
            step[rb] = -np.linalg.solve(Ab, gb[..., None])[..., 0] * (~blocked[rb])
        qn = np.clip(qa + step, lo, hi)
        rn = positions(qn) - p[ia]
        cn = np.einsum("ni,ni->n", rn, rn)
        acc = cn < c[ia]
        ib = ia[acc]
        q[ib], r[ib], c[ib] = qn[acc], rn[acc], cn[acc]
        lam[ia] = np.clip(np.where(acc, lam[ia] * 0.3, lam[ia] * 10.0), 1e-9, 1e8)
    return q, np.sqrt(c)


@dataclass(frozen=True)
class ClosestReachable:
    """Result of :func:`closest_reachable`.

    Attributes:
        point: Closest reachable tool position(s) [m], (3,) or (n, 3).
        q: A joint vector reaching it [rad], (6,) or (n, 6) (joint 6 = 0).
        distance: ``|point - p|`` [m] (0 for a reachable ``p``, up to ``tol``).
        moved: True where ``p`` was relocated (it was not reachable).
    """

    point: np.ndarray
    q: np.ndarray
    distance: np.ndarray | float
    moved: np.ndarray | bool


@lru_cache(maxsize=4)
def _sample_tree(arm: Arm, n: int = 20_000):
    """A fixed (seeded) uniform sample of joints 1-5 and a KD-tree of its tool positions."""
    q = np.random.default_rng(20120101).uniform(arm.q_min[:5], arm.q_max[:5], size=(n, 5))
    return q, cKDTree(tool_positions(q, arm))


def _seeds(pb: np.ndarray, arm: Arm, k_near: int = 8) -> np.ndarray:
    """(n, k, 5) start configurations: the Sec 3.4.4 projection, a fixed grid, and the
    ``k_near`` samples of a fixed joint sample whose tool positions are nearest to each point."""
    n = len(pb)
    phi = np.arctan2(pb[:, 1], pb[:, 0])
    th1 = np.clip(phi, arm.lower[0], arm.upper[0])
    u = pb[:, 0] * np.cos(th1) + pb[:, 1] * np.sin(th1)
    th2 = np.clip(-np.arctan2(pb[:, 2] - arm.l1, u - arm.l2), arm.lower[1], arm.upper[1])
    first = np.zeros((n, 1, 5))
    first[:, 0, 0], first[:, 0, 1] = th1, th2  # straight arm aimed at p (f(1), s(1))
    g2 = np.deg2rad([-90.0, 0.0, 60.0])
    g3 = np.deg2rad([-90.0, 0.0, 90.0])
    g4 = np.deg2rad([-60.0, 0.0, 60.0])
    grid = np.array([(a, b, c, 0.0) for a in g2 for b in g3 for c in g4])  # (27, 4)
    rest = np.empty((n, len(grid), 5))
    rest[:, :, 0] = th1[:, None]
    rest[:, :, 1:] = grid[None]
    qs, tree = _sample_tree(arm)
    _, idx = tree.query(pb, k=k_near)
    near = qs[idx.reshape(n, k_near)]
    return np.concatenate([first, rest, near], axis=1)


#: Points farther than this from the base origin [m] are searched for on their ray at this
#: distance (see :func:`closest_reachable`).
FAR = 1e7


def _near_proxy(pb: np.ndarray) -> np.ndarray:
    """Points farther than :data:`FAR` moved along their ray from the base origin to FAR."""
    r = _norm3(*pb.T)
    far = r > FAR
    if not np.any(far):
        return pb
    out = pb.copy()
    out[far] = pb[far] / r[far, None] * FAR
    return out


def closest_reachable(p, arm: Arm, *, tol: float = 1e-7) -> ClosestReachable:
    """The reachable tool position nearest to ``p`` (App. G's relocation suggestion).

    Minimises ``|fk(q)[:3,3] - p|`` over joints 1-5 inside Table I by bounded
    Levenberg-Marquardt from 36 deterministic starts (the straight arm aimed
    at ``p`` as in Sec 3.4.4, a grid, and the 8 configurations of a fixed
    20000-sample whose tool points are nearest to ``p``), so the returned point
    is reachable by construction (``q`` is returned). It is a local search with
    many starts: the global minimum is not guaranteed (``iik verify`` measures
    the gap). A point that is already reachable is returned unchanged.

    A point farther than :data:`FAR` (10^7 m) is searched for on its ray at FAR (the
    arithmetic stays finite however far it is): the nearest reachable point moves by
    less than ~R^2 / FAR (~1e-7 m, R the arm's reach) between FAR and infinity;
    ``distance`` is measured to the point as given.

    Args:
        p: Point(s) [m], (3,) or (n, 3), base frame 0.
        arm: Arm parameters.
        tol: Residual [m] under which ``p`` counts as reachable.

    For an arm not of the thesis's Table II form the search runs over all six joints with the arm's FK,
    from the 12 configurations of a fixed 20000-sample whose tool points are nearest to ``p``.

    Raises:
        InvalidInputError: NaN/inf, wrong shape, or a non-positive ``tol``.
    """
    pb, batched = as_points(p, "p")
    if not (np.isfinite(tol) and tol > 0):
        raise InvalidInputError("tol", "must be a positive finite number of metres")
    if not _thesis_form(arm):
        given = pb
        point, qbest, _ = _general_closest(_near_proxy(pb), arm, tol * 0.1)
        dist = _norm3(*(point - given).T)
        moved = dist > tol
        point = np.where(moved[:, None], point, given)
        dist = np.where(moved, dist, 0.0)
        if not batched:
            return ClosestReachable(point[0], qbest[0], float(dist[0]), bool(moved[0]))
        return ClosestReachable(point, qbest, dist, moved)
    given, pb = pb, _near_proxy(pb)
    seeds = _seeds(pb, arm)
    n, k, _ = seeds.shape
    q, res = position_lm(np.repeat(pb, k, axis=0), seeds.reshape(n * k, 5), arm, iters=80,
                         tol=tol * 0.1)
    q, res = q.reshape(n, k, 5), res.reshape(n, k)
    best = np.argmin(res, axis=1)
    qbest = np.zeros((n, 6))
    qbest[:, :5] = q[np.arange(n), best]
    point = tool_positions(qbest[:, :5], arm)
    dist = np.linalg.norm(point - pb, axis=1)
    moved = dist > tol
    for i in np.nonzero(moved)[0]:  # polish relocated points with exact bound handling
        order = np.argsort(res[i])[:2]
        for j in order:
            sol = least_squares(
                lambda x, i=i: tool_positions(x[None], arm)[0] - pb[i], q[i, j],
                jac=lambda x: position_jacobian(np.r_[x, 0.0], arm)[:, :5],
                bounds=(arm.q_min[:5], arm.q_max[:5]), method="trf", xtol=1e-12, ftol=1e-12, gtol=1e-12,
                max_nfev=200)
            d = float(np.linalg.norm(sol.fun))
            if d < dist[i]:
                dist[i], qbest[i, :5] = d, sol.x
        point[i] = tool_positions(qbest[i:i + 1, :5], arm)[0]
        dist[i] = float(np.linalg.norm(point[i] - pb[i]))
    point = np.where(moved[:, None], point, pb)
    dist = np.where(moved, _norm3(*(point - given).T), 0.0)  # (to the point as given)
    if not batched:
        return ClosestReachable(point[0], qbest[0], float(dist[0]), bool(moved[0]))
    return ClosestReachable(point, qbest, dist, moved)



@lru_cache(maxsize=4)
def _general_tree(arm: Arm, n: int = 20_000):
    """A fixed (seeded) uniform sample of all six joints and a KD-tree of its tool positions (FK)."""
    q = np.random.default_rng(20120101).uniform(arm.q_min, arm.q_max, size=(n, 6))
    return q, cKDTree(fk(q, arm)[:, :3, 3])


def _general_closest(pb: np.ndarray, arm: Arm, tol: float, k_near: int = 12):
    """(point (n, 3), q (n, 6), distance (n,)) [m, rad]: the reachable tool point nearest to each of
    ``pb`` found by bounded Levenberg-Marquardt over six joints from the ``k_near`` nearest samples."""
    n = len(pb)
    qs, tree = _general_tree(arm)
    _, idx = tree.query(pb, k=k_near)
    seeds = qs[idx.reshape(n, k_near)].reshape(n * k_near, 6)
    q, res = _bounded_lm(np.repeat(pb, k_near, axis=0), seeds, arm.q_min, arm.q_max,
                         lambda q: fk(q, arm)[:, :3, 3], lambda q: position_jacobian(q, arm), 80, tol)
    q, res = q.reshape(n, k_near, 6), res.reshape(n, k_near)
    best = np.argmin(res, axis=1)
    qbest = q[np.arange(n), best]
    point = fk(qbest, arm)[:, :3, 3]
    return point, qbest, np.linalg.norm(point - pb, axis=1)
