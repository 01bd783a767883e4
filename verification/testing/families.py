"""Adversarial families of joint configurations for the complete IK, for any arm of the class.

Uniform random poses are not evidence of completeness: the IK loses solutions where the
eliminant has clustered or multiple roots, where the closed forms are ill-conditioned, and on
continua. Each family here builds configurations q* aimed at one such place (the pose to solve
is fk(q*)); ``docs/IK_CLASS.md`` derives where these places are. Families are defined on the
arm's *solver chain* (the canonical member of the class, read from the base or the flange), so
they apply to the thesis arm and to the FANUC CRX alike; for the thesis arm they are the ones
named in the issue (theta3 near 0 / pi, theta4 = theta5 = 0, the wrist centre on the joint-1
axis, ...).

Every family is a :class:`Family` with a ``sample(arm, rng, n) -> q (n, 6)``; :data:`FAMILIES`
lists them and :func:`family_configurations` is the Hypothesis strategy of one family.
Sizes: :data:`CI_SIZE` poses per family in the default suite, :data:`THOROUGH_SIZE` in the
``thorough`` profile.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

import iik
from iik.arm import Arm
from iik.extras import require

__all__ = [
    "Family",
    "FAMILIES",
    "family",
    "family_configurations",
    "CI_SIZE",
    "THOROUGH_SIZE",
    "det_jacobian",
    "singular_on_line",
    "solver_joints",
    "user_joints",
    "wrist_point",
]

CI_SIZE = 60
THOROUGH_SIZE = 100_000


# ----------------------------------------------------------------------------- solver-chain helpers
def user_joints(arm: Arm, qs: np.ndarray) -> np.ndarray:
    """User joint angles of solver-chain joint angles qs (..., 6) (reversed for a flange-read arm)."""
    qs = np.asarray(qs, float)
    return qs[..., ::-1].copy() if arm.solver.reversed else qs.copy()


def solver_joints(arm: Arm, q: np.ndarray) -> np.ndarray:
    """Solver-chain joint angles of user joint angles q (..., 6)."""
    return user_joints(arm, q)


def _solver_frames(arm: Arm, qs: np.ndarray) -> np.ndarray:
    """Frames (n, 7, 4, 4) of the solver chain (frame 0 .. 6) at solver joint angles qs (n, 6)."""
    qs = np.atleast_2d(qs)
    out = np.zeros((len(qs), 7, 4, 4))
    out[:, 0] = np.eye(4)
    for i, (ca, sa, a, d, off) in enumerate(arm.solver.rows):
        th = qs[:, i] + off
        ct, st = np.cos(th), np.sin(th)
        L = np.zeros((len(qs), 4, 4))
        L[:, 0, 0], L[:, 0, 1], L[:, 0, 3] = ct, -st, a
        L[:, 1, 0], L[:, 1, 1], L[:, 1, 2], L[:, 1, 3] = ca * st, ca * ct, -sa, -sa * d
        L[:, 2, 0], L[:, 2, 1], L[:, 2, 2], L[:, 2, 3] = sa * st, sa * ct, ca, ca * d
        L[:, 3, 3] = 1.0
        out[:, i + 1] = out[:, i] @ L
    return out


def wrist_point(arm: Arm, q: np.ndarray) -> np.ndarray:
    """The wrist point D (axis 5 ∩ axis 6 of the solver chain) in the solver chain's frame 0 (n, 3)."""
    return _solver_frames(arm, solver_joints(arm, np.atleast_2d(q)))[:, 6, :3, 3]


def det_jacobian(arm: Arm, q) -> np.ndarray:
    """det J(q) (n,) of the geometric Jacobian (at the tool point; the determinant does not
    depend on the reference point)."""
    return np.linalg.det(iik.jacobian(np.atleast_2d(np.asarray(q, float)), arm))


def singular_on_line(arm: Arm, q0, d, samples: int = 64) -> list[np.ndarray]:
    """Configurations with det J = 0 on the line q0 + s d, s in [-pi, pi]: every sign change of
    det J on ``samples`` points, refined by Brent's method."""
    from scipy.optimize import brentq

    s = np.linspace(-np.pi, np.pi, samples)
    Q = q0[None] + s[:, None] * d[None]
    f = det_jacobian(arm, Q)
    out = []
    for k in np.flatnonzero(np.sign(f[:-1]) * np.sign(f[1:]) < 0):
        g = lambda t: float(det_jacobian(arm, q0 + t * d)[0])  # noqa: E731
        t = brentq(g, s[k], s[k + 1], xtol=1e-15, rtol=1e-15, maxiter=200)
        out.append(q0 + t * d)
    return out


def _uniform(arm: Arm, rng, n):
    return rng.uniform(arm.q_min, arm.q_max, (n, 6))


def _log_offset(rng, n, lo=-12.0, hi=-2.0):
    """Signed offsets 10^U(lo, hi) (n,)."""
    return rng.choice([-1.0, 1.0], n) * 10.0 ** rng.uniform(lo, hi, n)


# ----------------------------------------------------------------------------- the families
def _sample_uniform(arm, rng, n):
    return _uniform(arm, rng, n)


def _continuum_angles(arm: Arm, qs: np.ndarray):
    """Solver joints 4 and 5 (n, 2) that put D on axis 3 and z6 along it (the theta3/theta6
    continuum) for the solver joints 1-3 of qs, the nearest to qs's."""
    F = _solver_frames(arm, qs)
    z3 = F[:, 3, :3, 2]
    out = np.empty((len(qs), 2))
    for i in range(len(qs)):
        ca, sa, a, d, off4 = arm.solver.rows[3]
        q = qs[i].copy()
        # frame 4 at angle 0: F3 . RotX(alpha3)
        R40 = F[i, 3, :3, :3] @ np.array([[1, 0, 0], [0, ca, -sa], [0, sa, ca]])
        w = R40.T @ z3[i]
        phi = math.atan2(w[1], w[0])
        t4 = min((phi, phi + math.pi), key=lambda t: abs(math.remainder(t - (q[3] + off4), 2 * math.pi)))
        q[3] = t4 - off4
        G = _solver_frames(arm, q[None])[0]
        ca5, sa5, a5, d5, off5 = arm.solver.rows[4]
        R50 = G[4, :3, :3] @ np.array([[1, 0, 0], [0, ca5, -sa5], [0, sa5, ca5]])
        s6 = arm.solver.rows[5][1]
        w = R50.T @ z3[i]
        phi = math.atan2(s6 * w[0], -s6 * w[1])
        t5 = min((phi, phi + math.pi), key=lambda t: abs(math.remainder(t - (q[4] + off5), 2 * math.pi)))
        out[i] = q[3], t5 - off5
    return out


def _sample_continuum(arm, rng, n):
    qs = solver_joints(arm, _uniform(arm, rng, n))
    qs[:, 3:5] = _continuum_angles(arm, qs)
    return user_joints(arm, qs)


def _sample_near_continuum(arm, rng, n):
    qs = solver_joints(arm, _uniform(arm, rng, n))
    qs[:, 3:5] = _continuum_angles(arm, qs)
    qs[:, 3] += _log_offset(rng, n, -9.0, -3.0)
    qs[:, 4] += _log_offset(rng, n, -9.0, -3.0) * rng.choice([0.0, 1.0], n)
    return user_joints(arm, qs)


def _sample_near_continuum_equal(arm, rng, n):
    """theta4 and theta4 + theta5 both tiny and equal in size (the slow zone of the old kernel:
    e.g. theta4 = 1e-7, theta5 = -1e-7 + 1e-7)."""
    qs = solver_joints(arm, _uniform(arm, rng, n))
    qs[:, 3:5] = _continuum_angles(arm, qs)
    eps = _log_offset(rng, n, -9.0, -5.0)
    qs[:, 3] += eps
    qs[:, 4] += -eps + rng.choice([-1.0, 1.0], n) * np.abs(eps) * rng.uniform(0.0, 2.0, n)
    return user_joints(arm, qs)


def _axis2_parallel_axis4(arm: Arm, qs: np.ndarray) -> np.ndarray:
    """Solver joint 3 angles (n,) where axis 4 is parallel to axis 2, nearest to qs's (for the
    thesis arm theta3 = 0 or pi)."""
    F = _solver_frames(arm, qs)
    out = np.empty(len(qs))
    ca, sa, a, d, off3 = arm.solver.rows[2]
    for i in range(len(qs)):
        z2 = F[i, 2, :3, 2]
        # z4 in frame 3 at angle t: (s4 sin t, -s4 cos t, 0) with s4 = sin(alpha3)
        R30 = F[i, 2, :3, :3] @ np.array([[1, 0, 0], [0, ca, -sa], [0, sa, ca]])
        w = R30.T @ z2
        s4 = arm.solver.rows[3][1]
        phi = math.atan2(s4 * w[0], -s4 * w[1])
        t = min((phi, phi + math.pi), key=lambda x: abs(math.remainder(x - (qs[i, 2] + off3), 2 * math.pi)))
        out[i] = t - off3
    return out


def _sample_theta3_band(arm, rng, n):
    qs = solver_joints(arm, _uniform(arm, rng, n))
    qs[:, 2] = _axis2_parallel_axis4(arm, qs) + _log_offset(rng, n, -12.0, -2.0)
    return user_joints(arm, qs)


def _sample_at_stops(arm, rng, n):
    q = _uniform(arm, rng, n)
    for i in range(n):
        k = rng.integers(1, 4)
        for j in rng.choice(6, size=k, replace=False):
            q[i, j] = arm.q_min[j] if rng.random() < 0.5 else arm.q_max[j]
    return q


def _newton(arm: Arm, q, cols, residual, iters=60):
    """Newton's method (least squares) on ``residual(q) -> (r, J_r)`` over the joints ``cols``."""
    q = q.copy()
    for _ in range(iters):
        r, Jr = residual(q)
        if np.max(np.abs(r)) <= 1e-15:
            break
        dq = np.linalg.lstsq(Jr[:, cols], -r, rcond=None)[0]
        if np.max(np.abs(dq)) > 0.5:
            dq *= 0.5 / np.max(np.abs(dq))
        q[cols] += dq
    return q


def _axis1_residual(arm: Arm):
    """Residual (x, y of D in the solver frame 0) and its Jacobian (2, 6) by differences."""

    def res(qs):
        D = wrist_point(arm, user_joints(arm, qs)[None])[0]
        J = np.empty((2, 6))
        for j in range(6):
            e = np.zeros(6)
            e[j] = 1e-7
            Dp = wrist_point(arm, user_joints(arm, qs + e)[None])[0]
            Dm = wrist_point(arm, user_joints(arm, qs - e)[None])[0]
            J[:, j] = (Dp[:2] - Dm[:2]) / 2e-7
        return D[:2], J

    return res


def _sample_wrist_on_axis1(arm, rng, n, continuum=False):
    out = []
    res = _axis1_residual(arm)
    while len(out) < n:
        qs = solver_joints(arm, _uniform(arm, rng, 1))[0]
        if continuum:
            qs[3] = _continuum_angles(arm, qs[None])[0, 0]
        cols = [1, 2] if continuum else [1, 2, 3]
        qs = _newton(arm, qs, cols, res)
        if np.max(np.abs(res(qs)[0])) <= 1e-15:
            out.append(user_joints(arm, qs))
    return np.array(out)


def _sample_wrist_on_axis1_theta4(arm, rng, n):
    return _sample_wrist_on_axis1(arm, rng, n, continuum=True)


def _sample_tool_near_base(arm, rng, n):
    out = []
    while len(out) < n:
        q = _uniform(arm, rng, 1)[0]

        def res(q):
            T = iik.fk(q, arm)
            return T[:3, 3], iik.jacobian(q, arm)[:3]

        q = _newton(arm, q, [0, 1, 2, 3, 4, 5], res)
        p = iik.fk(q, arm)[:3, 3]
        if np.linalg.norm(p) > 1e-12:
            continue  # the base origin is out of reach for this start
        eps = 10.0 ** rng.uniform(-9.0, -3.0)
        d = rng.normal(size=3)
        d *= eps / np.linalg.norm(d)
        q = _newton(
            arm, q, [0, 1, 2, 3, 4, 5], lambda x, d=d: (iik.fk(x, arm)[:3, 3] - d, iik.jacobian(x, arm)[:3])
        )
        out.append(q)
    return np.array(out)


def _sample_singular(arm, rng, n):
    out = []
    while len(out) < n:
        q0 = _uniform(arm, rng, 1)[0]
        d = rng.normal(size=6)
        d /= np.linalg.norm(d)
        pts = singular_on_line(arm, q0, d)
        if pts:
            out.append(pts[rng.integers(len(pts))])
    return np.array(out)


def _sample_off_singular(arm, rng, n):
    qs = _sample_singular(arm, rng, n)
    out = np.empty_like(qs)
    for i, q in enumerate(qs):
        g = np.empty(6)
        for j in range(6):
            e = np.zeros(6)
            e[j] = 1e-6
            g[j] = (det_jacobian(arm, q + e)[0] - det_jacobian(arm, q - e)[0]) / 2e-6
        out[i] = q + _log_offset(rng, 1, -12.0, -4.0)[0] * g / np.linalg.norm(g)
    return out


@dataclass(frozen=True)
class Family:
    """A family of configurations aimed at one weakness of an IK (see the module docstring).

    Attributes:
        name: Short name (``"near-continuum"``).
        description: What the configurations are, in the solver chain's terms and, where they
            differ, in the thesis arm's.
        sample: ``(arm, rng, n) -> q (n, 6)`` [rad] (user joint order).
    """

    name: str
    description: str
    sample: Callable[[Arm, np.random.Generator, int], np.ndarray]


FAMILIES = (
    Family("uniform", "q uniform in the joint limits (the baseline, not evidence)", _sample_uniform),
    Family("singular", "det J = 0: a root of det J on a random line in joint space", _sample_singular),
    Family(
        "off-singular",
        "det J = 0 moved by +-10^U(-12, -4) rad along the normal of the singular set",
        _sample_off_singular,
    ),
    Family(
        "theta3-band",
        "joint 3 within +-10^U(-12, -2) rad of axis 4 parallel to axis 2 (thesis: theta3 at 0 or pi)",
        _sample_theta3_band,
    ),
    Family(
        "continuum",
        "D on axis 3 and z6 along it: joints 3 and 6 collinear (thesis: theta4 = 0, theta4 + theta5 = 0)",
        _sample_continuum,
    ),
    Family(
        "near-continuum",
        "the continuum with joint 4 moved by 10^U(-9, -3) and joint 5 by the same or nothing",
        _sample_near_continuum,
    ),
    Family(
        "near-continuum-equal",
        "joint 4 and joint 4 + joint 5 both 10^U(-9, -5) from the continuum (the slow zone)",
        _sample_near_continuum_equal,
    ),
    Family("wrist-on-axis1", "the wrist point D on the joint-1 axis", _sample_wrist_on_axis1),
    Family(
        "wrist-on-axis1-theta4",
        "D on the joint-1 axis and on axis 3 (thesis: theta4 = 0): a theta1 continuum",
        _sample_wrist_on_axis1_theta4,
    ),
    Family("at-stops", "one to three joints exactly at a joint limit", _sample_at_stops),
    Family("tool-near-base", "the tool point 10^U(-9, -3) m from the base origin", _sample_tool_near_base),
)


def family(name: str) -> Family:
    """The family called ``name``."""
    for f in FAMILIES:
        if f.name == name:
            return f
    raise KeyError(f"no family {name!r}; families: {[f.name for f in FAMILIES]}")


def family_configurations(fam: Family, arm: Arm):
    """Hypothesis strategy: one configuration q* (6,) of ``fam`` for ``arm`` (seeded draws)."""
    require("test", "verification.testing.families.family_configurations")
    from hypothesis import strategies as st

    return st.integers(0, 2**32 - 1).map(lambda seed: fam.sample(arm, np.random.default_rng(seed), 1)[0])
