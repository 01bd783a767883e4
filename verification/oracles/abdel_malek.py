"""Normal-acceleration boundary test of Abdel-Malek [10] as written in Appendix E (Eq 57-68).

Everything is computed with Pinocchio on the shipped URDF: ``G(q)`` is the
tool-frame position (Eq 34), ``G_q`` the linear rows of the frame Jacobian in
``LOCAL_WORLD_ALIGNED`` (columns of joints 1-5), and second derivatives are
central differences of those Jacobians (step 1e-6 rad). Units are SI (m, rad);
the thesis prints mm, so :meth:`NormalAcceleration.in_mm` rescales
(H*, Q*, eigenvalues, sigma, K-bar scale with length; B with 1/length).

Steps (per point ``q0`` on a singular set with free joints ``u``):

* Eq 58: ``q_i = (qU + qL)/2 + (qU - qL)/2 sin(lambda_i)``, so
  ``q_s = diag((qU - qL)/2 cos(lambda))`` and ``[q_i]_ss = -(qU - qL)/2 sin(lambda_i)``.
* Eq 59: ``N0`` spans the left null space of ``G_q q_s`` (3x5, rank 2 on a
  singular set). Its sign is arbitrary; it is chosen to match a reference
  direction when one is given.
* Eq 61: ``H* = q_s^T [N0.G]_qq q_s + sum_i (N0.G_qi) [q_i]_ss``.
* Eq 63: ``B = [E f_u]^-1 E`` with ``f_u`` the 3x2 Jacobian of the surface
  w.r.t. its free joints and ``E`` the first pair of independent rows.
* Eq 65: ``Q* = H* - q_s^T G_q^T B^T [N0.f]_uu B G_q q_s``.
* Eq 66-67: ``sigma_i = N0.G_qi dq_i``, ``dq_i = +1`` at a lower limit, -1 at an upper.
* Eq 68: ``K_i = G_qi^T B^T [N0.G]_uu B G_qi - [N0.G]_qiqi``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pinocchio as pin

import iik
from iik import THESIS_ARM

__all__ = ["NormalAcceleration", "normal_acceleration", "position_and_jacobian", "hessian", "eq58_rates",
           "eq59_normal", "eq61_h_star", "eq63_b", "eq65_q_star", "eq67_dq", "eq68_kbar"]

_H = 1e-6


def _model():
    from iik.planning.robot_model import thesis_model

    tm = thesis_model(THESIS_ARM)
    return tm.model, tm.tool_frame_id


def position_and_jacobian(q5: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Pinocchio: tool position G [m] (3,) and G_q [m/rad] (3, 5) at joints 1-5 ``q5``."""
    model, fid = _model()
    data = model.createData()
    q = np.zeros(model.nq)
    q[:5] = q5
    pin.forwardKinematics(model, data, q)
    pin.updateFramePlacements(model, data)
    J = pin.computeFrameJacobian(model, data, q, fid, pin.LOCAL_WORLD_ALIGNED)
    return data.oMf[fid].translation.copy(), J[:3, :5].copy()


def hessian(q5: np.ndarray) -> np.ndarray:
    """Second derivatives d2G/dq_i dq_j [m/rad^2], shape (3, 5, 5), by central differences."""
    Hs = np.empty((3, 5, 5))
    for i in range(5):
        e = np.zeros(5)
        e[i] = _H
        Jp = position_and_jacobian(q5 + e)[1]
        Jm = position_and_jacobian(q5 - e)[1]
        Hs[:, i, :] = (Jp - Jm) / (2 * _H)
    return 0.5 * (Hs + Hs.transpose(0, 2, 1))


@dataclass(frozen=True)
class NormalAcceleration:
    """Appendix E quantities at one point (SI units: m, rad)."""

    q0: np.ndarray  # (5,) rad
    lam0: np.ndarray  # (5,) Eq 58 parameters
    point: np.ndarray  # (3,) m
    free: tuple[int, int]  # 1-based free joints u
    N0: np.ndarray  # (3,)
    H: np.ndarray  # (5, 5) m
    E_rows: tuple[int, int]
    B: np.ndarray  # (2, 3) 1/m (rad per m)
    Q: np.ndarray  # (5, 5) m
    eig: np.ndarray  # (5,) m, ascending
    at_limit: tuple[tuple[int, str], ...]  # (joint, "lower"/"upper")
    sigma: dict = field(default_factory=dict)  # joint -> sigma [m]
    kbar: dict = field(default_factory=dict)  # joint -> K-bar [m]

    def in_mm(self) -> dict:
        """The thesis's display units (mm)."""
        return {
            "N0": self.N0,
            "H": self.H * 1e3,
            "B": self.B * 1e-3,
            "Q": self.Q * 1e3,
            "eig": self.eig * 1e3,
            "sigma": {k: v * 1e3 for k, v in self.sigma.items()},
            "kbar": {k: v * 1e3 for k, v in self.kbar.items()},
        }

    @property
    def verdict(self) -> str:
        """Abdel-Malek's reading: which side of N0 the motion may go.

        ``"+N0"`` / ``"-N0"``: one side only (a boundary); ``"both"``: not a boundary.
        Eigenvalues within 1e-9 m of zero are ignored; with joints at limits the
        signs of sigma join the signs of the non-zero eigenvalues.
        """
        ev = self.eig[np.abs(self.eig) > 1e-9]
        signs = set(np.sign(ev).astype(int).tolist())
        signs |= {int(np.sign(s)) for s in self.sigma.values() if abs(s) > 1e-12}
        if signs == {1}:
            return "+N0"
        if signs == {-1}:
            return "-N0"
        return "both"


def eq58_rates(q0: np.ndarray, arm: iik.Arm = iik.THESIS_ARM) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Eq 58 at ``q0`` (5,) [rad]: ``(lambda0, q_s, [q]_ss)``: the parameters and the diagonals of dq/dlambda
    and d2q/dlambda2."""
    lo, hi = arm.q_min[:5], arm.q_max[:5]
    mid, half = (hi + lo) / 2, (hi - lo) / 2
    lam = np.arcsin(np.clip((np.asarray(q0, float) - mid) / half, -1.0, 1.0))
    return lam, half * np.cos(lam), -half * np.sin(lam)


def eq59_normal(Gq: np.ndarray, qs: np.ndarray) -> np.ndarray:
    """Eq 59: the left null vector of G_q q_s (3 x 5) (sign arbitrary)."""
    U, _, _ = np.linalg.svd(Gq * qs[None, :])
    return U[:, 2]


def eq61_h_star(N0: np.ndarray, Hq: np.ndarray, Gq: np.ndarray, qs: np.ndarray,
    qss: np.ndarray) -> np.ndarray:
    """Eq 61: H* = q_s^T [N0.G]_qq q_s + sum_i (N0.G_qi) [q_i]_ss (5 x 5)."""
    NG_qq = np.einsum("k,kij->ij", N0, Hq)
    return qs[:, None] * NG_qq * qs[None, :] + np.diag((N0 @ Gq) * qss)


def eq63_b(f_u: np.ndarray, rows: tuple[int, int]) -> np.ndarray:
    """Eq 63: B = [E f_u]^-1 E with E picking ``rows`` (2 x 3)."""
    E = np.zeros((2, 3))
    E[0, rows[0]] = E[1, rows[1]] = 1.0
    return np.linalg.solve(E @ f_u, E)


def eq65_q_star(H: np.ndarray, B: np.ndarray, Gq: np.ndarray, qs: np.ndarray,
    Nf_uu: np.ndarray) -> np.ndarray:
    """Eq 65: Q* = H* - q_s^T G_q^T B^T [N0.f]_uu B G_q q_s (5 x 5)."""
    M = B @ (Gq * qs[None, :])
    return H - M.T @ Nf_uu @ M


def eq67_dq(q0: np.ndarray, arm: iik.Arm = iik.THESIS_ARM, tol: float = 1e-9) -> dict[int, float]:
    """Eq 67: ``{joint: dq}`` for the joints (1-based) at a limit: +1 at a lower limit, -1 at an upper one."""
    out = {}
    for i in range(5):
        if abs(q0[i] - arm.q_min[i]) <= tol:
            out[i + 1] = 1.0
        elif abs(q0[i] - arm.q_max[i]) <= tol:
            out[i + 1] = -1.0
    return out


def eq68_kbar(g: np.ndarray, B: np.ndarray, Nf_uu: np.ndarray, NG_ii: float) -> float:
    """Eq 68: K-bar = G_qi^T B^T [N0.G]_uu B G_qi - [N0.G]_qiqi for the column ``g`` = G_qi."""
    return float(g @ B.T @ Nf_uu @ B @ g - NG_ii)


def normal_acceleration(q0, free: tuple[int, int], arm: iik.Arm = iik.THESIS_ARM,
                        normal_hint=None, limit_tol: float = 1e-9,
                        prefer_rows: tuple[int, int] | None = None) -> NormalAcceleration:
    """Evaluate Eq 57-68 at joints ``q0`` (5,) [rad] on a set with free joints ``free`` (1-based).

    ``normal_hint`` picks the sign of N0; ``prefer_rows`` (0-based row pair)
    is tried first for E in Eq 63 (any independent pair gives the same Q*,
    because the columns of ``G_q q_s`` lie in the span of ``f_u``).
    """
    q0 = np.asarray(q0, dtype=float)[:5]
    lam, qs, qss = eq58_rates(q0, arm)  # Eq 58
    G, Gq = position_and_jacobian(q0)
    N0 = eq59_normal(Gq, qs)  # Eq 59
    if normal_hint is not None and np.dot(N0, normal_hint) < 0:
        N0 = -N0
    Hq = hessian(q0)  # (3, 5, 5)
    NG_qq = np.einsum("k,kij->ij", N0, Hq)  # [N0.G]_qq
    NG_q = N0 @ Gq  # d(N0.G)/dq_i
    H = eq61_h_star(N0, Hq, Gq, qs, qss)  # Eq 61
    u = [j - 1 for j in free]
    f_u = Gq[:, u]  # 3x2 surface Jacobian w.r.t. the free joints
    E_rows = None
    order = ((0, 1), (0, 2), (1, 2))
    if prefer_rows is not None:
        order = (tuple(prefer_rows),) + order
    for rows in order:  # Eq 63: first independent pair of rows
        if abs(np.linalg.det(f_u[list(rows)])) > 1e-9 * max(1.0, np.abs(f_u).max() ** 2):
            E_rows = rows
            break
    if E_rows is None:
        raise iik.InvalidInputError("q0", "the surface Jacobian f_u has rank < 2 at this point")
    B = eq63_b(f_u, E_rows)  # Eq 63
    Nf_uu = NG_qq[np.ix_(u, u)]  # [N0.f]_uu
    Q = eq65_q_star(H, B, Gq, qs, Nf_uu)  # Eq 65
    eig = np.sort(np.linalg.eigvalsh(0.5 * (Q + Q.T)))
    at_limit, sigma, kbar = [], {}, {}
    for j, dq in eq67_dq(q0, arm, limit_tol).items():  # Eq 67
        at_limit.append((j, "lower" if dq > 0 else "upper"))
        sigma[j] = float(NG_q[j - 1] * dq)  # Eq 66
        kbar[j] = eq68_kbar(Gq[:, j - 1], B, Nf_uu, NG_qq[j - 1, j - 1])  # Eq 68
    return NormalAcceleration(q0, lam, G, tuple(free), N0, H, E_rows, B, Q, eig, tuple(at_limit), sigma, kbar)
