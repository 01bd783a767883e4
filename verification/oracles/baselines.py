"""Numerical IK baselines on Pinocchio: Newton (pseudo-inverse Jacobian) and damped least squares.

Both use the real URDF (:func:`iik.planning.robot_model.thesis_model`): Pinocchio's
forward kinematics of frame ``tool`` and its frame Jacobian in
``LOCAL_WORLD_ALIGNED`` (rows v then w, base axes). The error is
``[p* - p, log3(R* R^T)]`` (base frame). They return one solution (the one
the iteration converges to from the initial guess), as the thesis's
comparator does (Sec 4.2.1).

* :func:`newton_pinv` - ``dq = J^+ e``; stops when every joint step is below
  ``tol_step`` (the thesis: 1e-6 deg) or after ``max_iter`` iterations.
* :func:`damped_least_squares` - ``dq = J^T (J J^T + lambda^2 I)^-1 e``.
* :func:`newton_pinv_batch` - the same Newton iteration vectorised over many poses with
  NumPy (:func:`iik.fk`, :func:`iik.jacobian`, batched ``pinv``): the batch counterpart
  of the vectorised IIK, for a like-for-like cost comparison.

Units: m, rad.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin
from scipy.spatial.transform import Rotation

from iik.arm import THESIS_ARM, Arm
from iik.errors import InvalidInputError
from iik.kinematics import fk, jacobian
from iik.planning.robot_model import thesis_model
from iik.validation import as_joints, as_poses

__all__ = [
    "NumericIKResult",
    "NumericIKBatch",
    "newton_pinv",
    "newton_pinv_batch",
    "damped_least_squares",
    "THESIS_NEWTON_TOL",
]

#: Sec 4.2.1: "a similar tolerance of convergence was used (1e-6 degrees)" [rad].
THESIS_NEWTON_TOL = np.radians(1e-6)


@dataclass(frozen=True)
class NumericIKResult:
    """One numerical IK run.

    Attributes:
        q: Final joint angles (6,) [rad].
        converged: Step below tolerance and pose error below ``tol_pose``.
        iterations: Iterations used.
        position_error: |p - p*| at the end [m].
        rotation_error: Rotation angle between R and R* at the end [rad].
    """

    q: np.ndarray
    converged: bool
    iterations: int
    position_error: float
    rotation_error: float


class _Model:
    def __init__(self):
        tm = thesis_model(THESIS_ARM)
        self.model = tm.model
        self.data = tm.model.createData()
        self.fid = tm.tool_frame_id

    def error(self, q, M_target):
        pin.framesForwardKinematics(self.model, self.data, q)
        M = self.data.oMf[self.fid]
        ep = M_target.translation - M.translation
        er = pin.log3(M_target.rotation @ M.rotation.T)
        return np.concatenate([ep, er])

    def jacobian(self, q):
        pin.computeJointJacobians(self.model, self.data, q)
        return pin.getFrameJacobian(self.model, self.data, self.fid, pin.LOCAL_WORLD_ALIGNED)


_MODEL: _Model | None = None


def _model() -> _Model:
    global _MODEL
    if _MODEL is None:
        _MODEL = _Model()
    return _MODEL


def _run(T, q0, step, *, tol_step: float, tol_pose: float, max_iter: int) -> NumericIKResult:
    Tb, batched = as_poses(T, "T")
    if batched:
        raise InvalidInputError("T", f"expected one (4, 4) pose, got shape {Tb.shape}; use newton_pinv_batch")
    q = as_joints(q0, "q0")[0][0].copy()
    m = _model()
    Mt = pin.SE3(Tb[0, :3, :3], Tb[0, :3, 3])
    it = 0
    converged = False
    for it in range(1, max_iter + 1):  # noqa: B007
        e = m.error(q, Mt)
        dq = step(m.jacobian(q), e)
        q = q + dq
        if np.max(np.abs(dq)) < tol_step:
            converged = True
            break
    e = m.error(q, Mt)
    pe, re = float(np.linalg.norm(e[:3])), float(np.linalg.norm(e[3:]))
    converged = converged and pe <= tol_pose and re <= tol_pose
    return NumericIKResult(q=q, converged=converged, iterations=it, position_error=pe, rotation_error=re)


def newton_pinv(
    T, q0, *, tol_step: float = THESIS_NEWTON_TOL, tol_pose: float = 1e-6, max_iter: int = 100
) -> NumericIKResult:
    """Newton's method with the pseudo-inverse Jacobian (the thesis's comparator, Sec 4.2.1)."""
    return _run(
        T, q0, lambda J, e: np.linalg.pinv(J) @ e, tol_step=tol_step, tol_pose=tol_pose, max_iter=max_iter
    )


def damped_least_squares(
    T,
    q0,
    *,
    damping: float = 1e-3,
    tol_step: float = THESIS_NEWTON_TOL,
    tol_pose: float = 1e-6,
    max_iter: int = 200,
) -> NumericIKResult:
    """Damped least squares (Levenberg-Marquardt style) with damping ``lambda`` [m]."""
    lam2 = damping**2

    def step(J, e):
        return J.T @ np.linalg.solve(J @ J.T + lam2 * np.eye(6), e)

    return _run(T, q0, step, tol_step=tol_step, tol_pose=tol_pose, max_iter=max_iter)


@dataclass(frozen=True)
class NumericIKBatch:
    """Newton on many poses at once.

    Attributes:
        q: Final joint angles (n, 6) [rad].
        converged: (n,) step below tolerance and pose error below ``tol_pose``.
        iterations: (n,) iterations used per pose.
    """

    q: np.ndarray
    converged: np.ndarray
    iterations: np.ndarray


def newton_pinv_batch(
    T,
    q0,
    *,
    tol_step: float = THESIS_NEWTON_TOL,
    tol_pose: float = 1e-6,
    max_iter: int = 100,
    arm: Arm = THESIS_ARM,
) -> NumericIKBatch:
    """Newton with the pseudo-inverse Jacobian on poses ``T`` (n, 4, 4) from ``q0`` (n, 6), vectorised.

    Same iteration and stopping rule as :func:`newton_pinv`, with the analytic FK and Jacobian
    (:func:`iik.fk`, :func:`iik.jacobian`, equal to Pinocchio's to 1e-15, checked in ``iik verify``).
    """
    Tb, _ = as_poses(T, "T")
    q = np.array(as_joints(q0, "q0")[0], dtype=float, copy=True)
    if len(q) != len(Tb):
        raise InvalidInputError("q0", f"{len(q)} start vectors for {len(Tb)} poses")
    n = len(Tb)
    active = np.ones(n, bool)
    its = np.zeros(n, int)
    for _ in range(max_iter):
        idx = np.flatnonzero(active)
        if len(idx) == 0:
            break
        Tc = fk(q[idx], arm)
        e = np.concatenate(
            [
                Tb[idx, :3, 3] - Tc[:, :3, 3],
                Rotation.from_matrix(Tb[idx, :3, :3] @ Tc[:, :3, :3].transpose(0, 2, 1)).as_rotvec(),
            ],
            axis=1,
        )
        dq = np.einsum("nij,nj->ni", np.linalg.pinv(jacobian(q[idx], arm)), e)
        q[idx] += dq
        its[idx] += 1
        active[idx[np.max(np.abs(dq), axis=1) < tol_step]] = False
    Tf = fk(q, arm)
    pe = np.linalg.norm(Tf[:, :3, 3] - Tb[:, :3, 3], axis=1)
    re = Rotation.from_matrix(Tb[:, :3, :3] @ Tf[:, :3, :3].transpose(0, 2, 1)).magnitude()
    return NumericIKBatch(q=q, converged=~active & (pe <= tol_pose) & (re <= tol_pose), iterations=its)
