"""An IK oracle independent of the compiled kernel: dense multi-start Levenberg-Marquardt.

For a pose, ``starts`` joint vectors (uniform on the torus [-pi, pi]^6, plus optional seeds)
are driven to the pose by Levenberg-Marquardt steps on the arm's forward kinematics, all
starts at once in NumPy: the chain product of :func:`iik.dh.dh_chain` (not the kernel's
compiled chain) with its geometric Jacobian. Converged points (both residuals within the
tolerance) are clustered (wrapped max-norm distance ``cluster``); each cluster is one
solution found by the oracle. The oracle can miss a solution whose basin no start hits
(hence many starts) and can split a continuum into many clusters; it never solves the
eliminant, so agreement with the kernel is evidence.

Units: metres and radians.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from iik.arm import Arm
from iik.dh import dh_chain
from iik.ik.angles import wrap_angle

__all__ = ["OracleOptions", "OracleSolutions", "multistart_ik", "pose_residuals_np", "project", "refit"]


@dataclass(frozen=True)
class OracleOptions:
    """Options of :func:`multistart_ik`.

    Attributes:
        starts: Random starts per pose (uniform on [-pi, pi]^6).
        iterations: Levenberg-Marquardt iterations per start.
        tol: A point solves the pose if both residuals are within this [m, rad].
        cluster: Points closer than this in every joint (wrapped) are one solution [rad].
        seed: Seed of the starts.
    """

    starts: int = 256
    iterations: int = 60
    tol: float = 1e-10
    cluster: float = 1e-5
    seed: int = 0


@dataclass(frozen=True)
class OracleSolutions:
    """The solutions the oracle found for one pose.

    Attributes:
        q: (k, 6) one point per cluster (the least residual) [rad], wrapped to (-pi, pi].
        position_residual, rotation_residual: (k,) their residuals [m, rad].
        hits: (k,) how many starts converged into each cluster.
        converged: How many starts converged at all.
    """

    q: np.ndarray
    position_residual: np.ndarray
    rotation_residual: np.ndarray
    hits: np.ndarray
    converged: int


def _chain(arm: Arm, q: np.ndarray):
    """Tool poses (n, 4, 4) and geometric Jacobians (n, 6, 6) by the NumPy DH product."""
    frames = dh_chain(arm.dh_table(), q, all_frames=True)  # (n, 6, 4, 4)
    base, tool = np.array(arm.base), np.array(arm.tool)
    F = base @ frames
    T = F[:, -1] @ tool
    z = F[:, :, :3, 2]
    o = F[:, :, :3, 3]
    p = T[:, None, :3, 3]
    J = np.concatenate([np.cross(z, p - o), z], axis=2).transpose(0, 2, 1)
    return T, J


def _error(T, target):
    """(n, 6) [p* - p; vee(R* R^T - R R*^T) / 2] and the residuals (position, rotation angle)."""
    e = np.empty((len(T), 6))
    e[:, :3] = target[:3, 3] - T[:, :3, 3]
    M = target[:3, :3] @ np.transpose(T[:, :3, :3], (0, 2, 1))
    e[:, 3] = 0.5 * (M[:, 2, 1] - M[:, 1, 2])
    e[:, 4] = 0.5 * (M[:, 0, 2] - M[:, 2, 0])
    e[:, 5] = 0.5 * (M[:, 1, 0] - M[:, 0, 1])
    pres = np.linalg.norm(e[:, :3], axis=1)
    d = np.linalg.norm(T[:, :3, :3] - target[:3, :3], axis=(1, 2))
    rres = 2.0 * np.arcsin(np.minimum(d / np.sqrt(8.0), 1.0))
    return e, pres, rres


def pose_residuals_np(arm: Arm, q, T):
    """Position [m] and rotation [rad] residuals of q (n, 6) against the pose T (4, 4), by the
    oracle's NumPy chain."""
    Tq, _ = _chain(arm, np.atleast_2d(np.asarray(q, float)))
    _, pres, rres = _error(Tq, np.asarray(T, float))
    return pres, rres


def _lm(arm: Arm, q: np.ndarray, target: np.ndarray, iterations: int, tol: float):
    """Levenberg-Marquardt on every row of q (n, 6) at once; returns (q, pres, rres)."""
    lam = np.full(len(q), 1e-3)
    Tq, J = _chain(arm, q)
    e, pres, rres = _error(Tq, target)
    err = np.einsum("ni,ni->n", e, e)
    eye = np.eye(6)
    for _ in range(iterations):
        active = (pres > 0.01 * tol) | (rres > 0.01 * tol)
        if not active.any():
            break
        A = np.einsum("nri,nrj->nij", J, J)
        g = np.einsum("nri,nr->ni", J, e)
        tr = np.trace(A, axis1=1, axis2=2)[:, None, None] / 6.0
        dq = np.linalg.solve(A + (lam[:, None, None] * tr + 1e-14 * tr + 1e-300) * eye, g[..., None])[..., 0]
        qn = q + np.where(active[:, None], dq, 0.0)
        Tn, Jn = _chain(arm, qn)
        en, pn, rn = _error(Tn, target)
        errn = np.einsum("ni,ni->n", en, en)
        better = (errn <= err) & active
        q = np.where(better[:, None], qn, q)
        e = np.where(better[:, None], en, e)
        J = np.where(better[:, None, None], Jn, J)
        pres, rres, err = np.where(better, pn, pres), np.where(better, rn, rres), np.where(better, errn, err)
        lam = np.where(better, np.maximum(lam * 0.2, 1e-12), np.minimum(lam * 10.0, 1e8))
    return q, pres, rres


def project(arm: Arm, q, T, iterations: int = 8, tol: float = 1e-10) -> np.ndarray:
    """Each row of q (n, 6) moved onto the pose T by a few Levenberg-Marquardt steps (n, 6)."""
    out, _, _ = _lm(arm, np.atleast_2d(np.asarray(q, float)).copy(), np.asarray(T, float), iterations, tol)
    return out


def refit(arm: Arm, q, T, held: int, iterations: int = 30, rcond: float = 1e-12) -> np.ndarray:
    """q (6,) moved onto the pose T (4, 4) with joint ``held`` (0-based) left where it is:
    Gauss-Newton minimum-norm steps (singular values below ``rcond`` times the largest ignored),
    each halved until it lowers the error, until none does. Undamped, they reach the bottom of a
    flat valley of near-solutions (a nearly singular Jacobian) that damped steps cannot."""
    target = np.asarray(T, float)
    x = np.asarray(q, float).copy()
    Tq, J = _chain(arm, x[None])
    e = _error(Tq, target)[0][0]
    for _ in range(iterations):
        J[0, :, held] = 0.0
        step = np.linalg.lstsq(J[0], e, rcond=rcond)[0]
        for _ in range(30):
            Tn, Jn = _chain(arm, (x + step)[None])
            en = _error(Tn, target)[0][0]
            if en @ en < e @ e:
                break
            step = step / 2
        else:
            break
        x, J, e = x + step, Jn, en
    return x


def multistart_ik(T, arm: Arm, options: OracleOptions = OracleOptions(), seeds=None) -> OracleSolutions:
    """Every solution of the pose T (4, 4) that the oracle's starts reach (see the module doc)."""
    target = np.asarray(T, dtype=float)
    rng = np.random.default_rng(options.seed)
    q = rng.uniform(-np.pi, np.pi, (options.starts, 6))
    if seeds is not None and len(seeds):
        q = np.concatenate([np.atleast_2d(np.asarray(seeds, float)), q])
    q, pres, rres = _lm(arm, q, target, options.iterations, options.tol)
    ok = (pres <= options.tol) & (rres <= options.tol)
    return _clusters(wrap_angle(q[ok]), pres[ok], rres[ok], options.cluster)


def _clusters(q, pres, rres, radius) -> OracleSolutions:
    order = np.argsort(pres + rres)
    reps, hits = [], []
    for i in order:
        for k, r in enumerate(reps):
            if np.max(np.abs(wrap_angle(q[i] - q[r]))) <= radius:
                hits[k] += 1
                break
        else:
            reps.append(i)
            hits.append(1)
    idx = np.array(reps, dtype=int)
    return OracleSolutions(
        q=q[idx] if len(idx) else np.zeros((0, 6)),
        position_residual=pres[idx],
        rotation_residual=rres[idx],
        hits=np.array(hits, dtype=int),
        converged=int(len(q)),
    )
