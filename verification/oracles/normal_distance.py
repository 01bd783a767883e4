"""Appendix E's quantities recomputed from what they mean: an independent route to Eq 58-68.

:mod:`verification.oracles.abdel_malek` evaluates Eq 58-68 *as written* (Pinocchio Jacobians, their
finite differences, the printed matrix formulas). Here every quantity is computed from its meaning
instead, with the tool point of Table II's chain (:func:`iik.dh.dh_chain`, not Pinocchio) and central
differences of it:

* Eq 58: ``q(s) = mid + half sin(lambda)`` is the parameterisation itself (a definition); its
  inverse gives ``s0``.
* Eq 59: ``N0`` is the unit normal of the singular surface ``f(u)`` at the point: the cross product
  of its two tangents ``df/du_1``, ``df/du_2`` (``f`` is the tool point with the fixed joints held and
  the free joints ``u`` varying).
* Eq 61: ``H*`` is the Hessian in ``s`` of ``N0 . G(q(s))`` (the normal component of the tool point).
* Eq 62-65: ``Q*`` is the Hessian in ``s`` of the normal distance of the tool from the surface,
  ``phi(s) = N0 . (G(q(s)) - f(u*(s)))``, where ``u*(s)`` solves ``E f(u*) = E G(q(s))`` (Eq 63's row
  choice ``E``): its second-order change is the normal acceleration of Eq 57 (``eta = s'^T Q* s'``).
* Eq 63: ``B G_q q_s`` is ``du*/ds``.
* Eq 66: ``sigma_i`` is the first-order normal motion ``N0 . dG/dq_i dq_i`` of the tool when joint i
  leaves its limit in the direction ``dq_i`` (Eq 67: into the range).
* Eq 68: ``-K_i`` is the second derivative of ``phi`` along joint i alone.

Units: SI (m, rad); the thesis prints mm (multiply lengths by 1e3).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

import iik
from iik.dh import dh_chain

__all__ = ["SurfacePoint", "tool_point", "parameters", "surface_point"]

_H1 = 1e-6  # [rad] central-difference step of first derivatives
_H2 = 1e-4  # [rad] central-difference step of second derivatives


def tool_point(q5: np.ndarray, arm: iik.Arm = iik.THESIS_ARM) -> np.ndarray:
    """Tool point(s) [m] of joints 1-5 ``q5`` (..., 5) by the Table II chain (joint 6 does not move it)."""
    q5 = np.asarray(q5, float)
    flat = q5.reshape(-1, 5)
    q = np.concatenate([flat, np.zeros((len(flat), 1))], axis=1)
    return dh_chain(arm.dh_table(), q)[:, :3, 3].reshape(q5.shape[:-1] + (3,))


def parameters(q0: np.ndarray, arm: iik.Arm = iik.THESIS_ARM) -> np.ndarray:
    """``s0``: Eq 58 inverted at ``q0`` (5,) [rad] (``lambda_i`` in [-pi/2, pi/2])."""
    lo, hi = arm.q_min[:5], arm.q_max[:5]
    mid, half = (hi + lo) / 2, (hi - lo) / 2
    return np.arcsin(np.clip((np.asarray(q0, float) - mid) / half, -1.0, 1.0))


def _q_of_s(s: np.ndarray, arm: iik.Arm) -> np.ndarray:
    lo, hi = arm.q_min[:5], arm.q_max[:5]
    return (hi + lo) / 2 + (hi - lo) / 2 * np.sin(s)


def _hessian(f, x0: np.ndarray, h: float = _H2) -> np.ndarray:
    """Central-difference Hessian of a vectorised scalar function ``f((m, k)) -> (m,)`` at ``x0`` (k,)."""
    k = len(x0)
    E = np.eye(k) * h
    pts = [x0]
    for i in range(k):
        pts += [x0 + E[i], x0 - E[i]]
    for i in range(k):
        for j in range(i + 1, k):
            pts += [x0 + E[i] + E[j], x0 + E[i] - E[j], x0 - E[i] + E[j], x0 - E[i] - E[j]]
    v = f(np.array(pts))
    f0 = v[0]
    H = np.zeros((k, k))
    for i in range(k):
        H[i, i] = (v[1 + 2 * i] + v[2 + 2 * i] - 2 * f0) / h**2
    idx = 1 + 2 * k
    for i in range(k):
        for j in range(i + 1, k):
            a, b, c, d = v[idx : idx + 4]
            H[i, j] = H[j, i] = (a - b - c + d) / (4 * h**2)
            idx += 4
    return H


@dataclass(frozen=True)
class SurfacePoint:
    """A point of a singular surface and what Eq 58-68 mean there (SI units).

    Attributes:
        q0: Joints 1-5 [rad]; free: the surface's free joints (1-based); s0: Eq 58 parameters.
        point: The tool point [m]; N0: the surface normal (sign as hinted).
        arm: The arm.
    """

    q0: np.ndarray
    free: tuple[int, int]
    s0: np.ndarray
    point: np.ndarray
    N0: np.ndarray
    arm: iik.Arm

    def f(self, u: np.ndarray) -> np.ndarray:
        """The surface: the tool point with the fixed joints at ``q0`` and the free ones at ``u`` (m, 2)."""
        q = np.repeat(self.q0[None], len(u), 0)
        q[:, [j - 1 for j in self.free]] = u
        return tool_point(q, self.arm)

    def _f_u(self, u: np.ndarray) -> np.ndarray:
        cols = []
        for k in range(2):
            e = np.zeros(2)
            e[k] = _H1
            cols.append((self.f(u + e) - self.f(u - e)) / (2 * _H1))
        return np.stack(cols, -1)  # (m, 3, 2)

    @property
    def rows(self) -> tuple[int, int]:
        """The pair of rows of f_u at the point with the best-conditioned 2x2 block (Eq 63's E)."""
        fu = self._f_u(self.q0[[j - 1 for j in self.free]][None])[0]
        pairs = ((0, 1), (0, 2), (1, 2))
        return max(pairs, key=lambda r: abs(np.linalg.det(fu[list(r)])))

    def _u_star(self, G: np.ndarray, rows: tuple[int, int] | None) -> np.ndarray:
        """u* with E f(u*) = E G for each tool point ``G`` (m, 3) by Newton from the point's own u."""
        r = list(self.rows if rows is None else rows)
        u = np.repeat(self.q0[[j - 1 for j in self.free]][None], len(G), 0)
        for _ in range(12):
            res = (G - self.f(u))[:, r]
            J = self._f_u(u)[:, r, :]
            u = u + np.linalg.solve(J, res[..., None])[..., 0]
        return u

    def normal_distance(self, s: np.ndarray, rows: tuple[int, int] | None = None) -> np.ndarray:
        """phi(s) = N0 . (G(q(s)) - f(u*(s))) [m] for parameter vectors ``s`` (m, 5)."""
        G = tool_point(_q_of_s(s, self.arm), self.arm)
        return (G - self.f(self._u_star(G, rows))) @ self.N0

    def h_star(self) -> np.ndarray:
        """Eq 61 by its meaning: the Hessian in s of N0 . G(q(s)) [m] (5, 5)."""
        return _hessian(lambda s: tool_point(_q_of_s(s, self.arm), self.arm) @ self.N0, self.s0)

    def q_star(self, rows: tuple[int, int] | None = None) -> np.ndarray:
        """Eq 62-65 by their meaning: the Hessian in s of the normal distance phi [m] (5, 5)."""
        return _hessian(lambda s: self.normal_distance(s, rows), self.s0)

    def du_ds(self, rows: tuple[int, int] | None = None) -> np.ndarray:
        """Eq 63 by its meaning: du*/ds (2, 5) [rad per unit of s], central differences."""
        cols = []
        for i in range(5):
            e = np.zeros(5)
            e[i] = _H1
            G = tool_point(_q_of_s(np.array([self.s0 + e, self.s0 - e]), self.arm), self.arm)
            u = self._u_star(G, rows)
            cols.append((u[0] - u[1]) / (2 * _H1))
        return np.stack(cols, -1)

    def sigma(self, joint: int, dq: float) -> float:
        """Eq 66 by its meaning: the first-order normal motion [m] when joint ``joint`` moves by ``dq``
        rad."""
        e = np.zeros(5)
        e[joint - 1] = _H1
        G = tool_point(np.array([self.q0 + e, self.q0 - e]), self.arm)
        return float((G[0] - G[1]) @ self.N0 / (2 * _H1) * dq)

    def kbar(self, joint: int, rows: tuple[int, int] | None = None) -> float:
        """Eq 68 by its meaning: minus the second derivative [m] of phi along joint ``joint`` alone."""
        return -self.offset_curvature(joint, rows)

    def offset(self, joint: int, t: float, rows: tuple[int, int] | None = None) -> float:
        """phi [m] after joint ``joint`` moves by ``t`` rad alone: the tool's signed distance from the
        surface."""
        q = self.q0.copy()
        q[joint - 1] += t
        G = tool_point(q[None], self.arm)
        return float(((G - self.f(self._u_star(G, rows))) @ self.N0)[0])

    def offset_curvature(self, joint: int, rows: tuple[int, int] | None = None) -> float:
        """d^2 phi / dq_joint^2 [m] (central differences)."""
        e = np.zeros(5)
        e[joint - 1] = _H2
        q = np.array([self.q0 + e, self.q0, self.q0 - e])
        G = tool_point(q, self.arm)
        phi = (G - self.f(self._u_star(G, rows))) @ self.N0
        return float((phi[0] - 2 * phi[1] + phi[2]) / _H2**2)


def surface_point(q0, free: tuple[int, int], *, hint=None, arm: iik.Arm = iik.THESIS_ARM) -> SurfacePoint:
    """The :class:`SurfacePoint` at joints ``q0`` (5,) [rad] on the surface whose free joints are ``free``;
    ``hint`` picks the sign of N0."""
    q0 = np.asarray(q0, float)[:5].copy()
    probe = SurfacePoint(q0, tuple(free), parameters(q0, arm), tool_point(q0, arm), np.zeros(3), arm)
    t = probe._f_u(q0[[j - 1 for j in free]][None])[0]
    n = np.cross(t[:, 0], t[:, 1])
    norm = np.linalg.norm(n)
    if norm < 1e-12:
        raise iik.InvalidInputError("q0", "the surface's tangents are parallel here (no normal)")
    n = n / norm
    if hint is not None and np.dot(n, hint) < 0:
        n = -n
    return SurfacePoint(q0, tuple(free), probe.s0, probe.point, n, arm)
