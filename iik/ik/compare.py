"""Comparing IK answers: residuals of a configuration, and "is q among these solutions?".

Used by the tests, the benchmark and ``iik verify`` (recovery of the generating q,
agreement of the compiled kernel with the NumPy reference).
"""

from __future__ import annotations

import numpy as np

from ..arm import Arm
from ..kinematics import fk, jacobian
from ..rotations import rotation_angle
from .angles import wrap_angle as _wrap

__all__ = ["pose_residuals", "contains", "POSE_EPS", "CONTINUUM_TOL", "free_joints_of"]

#: Size of the pose perturbation (rounding of fk(q) and of the solver, ~1000 ulp) used to
#: bound how precisely a pose determines q near a singularity, see :func:`contains`.
POSE_EPS = 1e-13

#: A flagged continuum row stands for every q reaching the pose whose non-free joints
#: are within this of it [rad] (see :func:`contains`).
CONTINUUM_TOL = 1e-4

_FREE = {0: (), 1: (1, 6), 2: (3, 6), 3: (1, 3, 6), 4: (3, 6)}


def free_joints_of(flags) -> list[tuple[int, ...]]:
    """The ``free_joints`` tuples of :class:`~iik.ik.result.IKResult` for free-kind flags
    (bit 1: theta1/theta6, bit 2: theta3/theta6, 4: a numerical theta3/theta6 continuum)."""
    return [_FREE[int(f)] for f in np.ravel(flags)]


def pose_residuals(q: np.ndarray, T: np.ndarray, arm: Arm) -> tuple[np.ndarray, np.ndarray]:
    """Position [m] and rotation [rad] residuals of ``fk(q)`` against ``T`` (batched)."""
    Tq = fk(q, arm)
    return (np.linalg.norm(Tq[..., :3, 3] - T[..., :3, 3], axis=-1),
            rotation_angle(Tq[..., :3, :3], T[..., :3, :3]))


def contains(solutions: np.ndarray, q: np.ndarray, T: np.ndarray, arm: Arm, *,
             tol: float = 1e-9, tol_p: float = 1e-10, tol_r: float = 1e-10,
             free_joints=None) -> bool:
    """Is configuration ``q`` (6,) among ``solutions`` (k, 6) of pose ``T``?

    Yes if some solution is within ``tol`` rad in every joint (angles wrapped),
    or within ``POSE_EPS / sigma_min(J(q))`` (how far q moves when the pose is
    perturbed by :data:`POSE_EPS`, i.e. the accuracy the pose carries).
    Near a singularity a pose fixes q only to ~sqrt(machine eps), so a solution
    also counts if the straight joint-space segment from it to ``q`` stays
    inside the FK tolerance (``tol_p`` m, ``tol_r`` rad) at 9 interior points:
    then the two are the same solution within the accuracy the pose carries.
    With ``free_joints`` (per solution, as in :class:`~iik.ik.result.IKResult`),
    ``q`` also counts if it reaches ``T`` and matches a flagged continuum
    representative to :data:`CONTINUUM_TOL` in every joint that is not free
    (near theta4 = theta5 = 0 the isolated solutions crowd within ~1e-6 rad in
    those joints: numerically a continuum).
    """
    sol = np.asarray(solutions, float).reshape(-1, 6)
    if len(sol) == 0:
        return False
    if free_joints is not None and any(free_joints):
        pr, rr = pose_residuals(np.asarray(q, float)[None], np.asarray(T)[None], arm)
        if pr[0] <= tol_p and rr[0] <= tol_r:
            for row, fj in zip(sol, free_joints, strict=False):
                fixed = [j for j in range(6) if j + 1 not in fj]
                if fj and np.max(np.abs(_wrap(row[fixed] - q[fixed]))) <= CONTINUUM_TOL:
                    return True  # q reaches T and lies on the flagged (numerical) continuum
        # Move each continuum representative along its continuum to q's free joints.
        extra = []
        for row, fj in zip(sol, free_joints, strict=False):
            for j in (1, 3):
                if j in fj:
                    for sgn in (1.0, -1.0):
                        r2 = row.copy()
                        r2[j - 1] = q[j - 1]
                        r2[5] = _wrap(row[5] + sgn * (q[j - 1] - row[j - 1]))
                        extra.append(r2)
        if extra:
            sol = np.concatenate([sol, np.array(extra)])
    d = _wrap(sol - q)
    dist = np.max(np.abs(d), axis=1)
    # First-order sensitivity: a pose known to POSE_EPS moves q by up to POSE_EPS / sigma_min(J).
    smin = np.linalg.svd(jacobian(np.asarray(q, float), arm), compute_uv=False)[-1]
    if np.min(dist) <= max(tol, POSE_EPS / max(smin, 1e-300)):
        return True
    s = np.linspace(0.1, 0.9, 9)
    for i in np.argsort(dist)[:4]:
        if dist[i] > 1e-3:
            break
        pts = q + s[:, None] * d[i]
        pr, rr = pose_residuals(pts, np.broadcast_to(T, (len(s), 4, 4)), arm)
        if np.all(pr <= tol_p) and np.all(rr <= tol_r):
            return True
    return False
