"""Adversarial families of joint configurations for the complete IK, for any arm of the class.

Uniform random poses are not evidence of completeness: the IK loses solutions where the
eliminant has clustered or multiple roots, where the closed forms are ill-conditioned, and on
continua. Each family here builds configurations q* aimed at one such place (the pose to solve
is fk(q*)); ``docs/IK_CLASS.md`` derives where these places are. Families are defined on the
arm's *solver chain* (the canonical member of the class, read from the base or the flange,
``B`` = axis 2 ∩ axis 3, ``C`` = axis 3 ∩ axis 4, ``D`` = axis 5 ∩ axis 6), so they apply to
the thesis arm and to the FANUC CRX alike; for the thesis arm they are the ones named in
issue 17 (theta3 near 0 / pi, theta4 = theta5 = 0, the wrist centre on the joint-1 axis, ...).

The singular set det J = 0 (``docs/IK_CLASS.md`` section 4) and its pieces, as geometric
conditions on the solver chain, each solved by Newton's method from a uniform q:

* ``elbow``: D on axis 3 (thesis: sin theta4 = 0), the factor ``e = det[x4, z4, z3]``;
* ``singular``: a root of det J on a random line in joint space (the general set, mostly the
  second factor), ``singular-second``: a root of ``det J / e`` on a random line;
* ``elbow-second``: both factors;
* ``split-*``: axis 4 perpendicular to axis 2 (thesis: theta3 = +-90 deg), where the second
  factor splits into ``C on axis 1`` (thesis: l3 cos theta2 + l2 = 0) and ``axis 6 through
  B`` (thesis: l3 sin(theta4 + theta5) + l4 sin theta5 = 0), each and both.

A family that has no member for an arm (e.g. ``C on axis 1`` for the CRX, whose axes 1 and 2
are offset along axis 2) raises :class:`FamilyEmpty` after a bounded number of tries; the
tests skip it with that reason.

Every family is a :class:`Family` with a ``sample(arm, rng, n) -> q (n, 6)``; :data:`FAMILIES`
lists them and :func:`family_configurations` is the Hypothesis strategy of one family.
Units: radians and metres.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import cache

import numpy as np

import iik
from iik.arm import Arm
from iik.extras import require
from iik.ik.angles import wrap

__all__ = [
    "Family",
    "FamilyEmpty",
    "FAMILIES",
    "family",
    "family_configurations",
    "applicability",
    "det_jacobian",
    "singular_on_line",
    "solver_joints",
    "user_joints",
    "wrist_point",
]

#: Tries per configuration asked for before a family is declared empty for an arm.
TRIES = 20


class FamilyEmpty(ValueError):
    """The family has no member for this arm (none found in the bounded number of tries)."""


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


def singular_on_line(arm: Arm, q0, d, samples: int = 64, f=None) -> list[np.ndarray]:
    """Configurations where ``f`` (default det J; (n, 6) user q -> (n,)) changes sign on the
    line q0 + s d, s in [-pi, pi]: every sign change on ``samples`` points, refined by Brent
    (a sign change through a pole, where |f| is large, is not a root and is left out)."""
    from scipy.optimize import brentq

    f = f or (lambda Q: det_jacobian(arm, Q))
    s = np.linspace(-np.pi, np.pi, samples)
    vals = f(q0[None] + s[:, None] * d[None])
    out = []
    for k in np.flatnonzero(np.sign(vals[:-1]) * np.sign(vals[1:]) < 0):
        g = lambda t: float(f((q0 + t * d)[None])[0])  # noqa: E731
        t = brentq(g, s[k], s[k + 1], xtol=1e-15, rtol=1e-15, maxiter=200)
        if abs(g(t)) <= 1e-9 * np.max(np.abs(vals)):
            out.append(q0 + t * d)
    return out


# ----------------------------------------------------------------------------- geometric conditions
def _points(arm: Arm, qs):
    """Solver-chain geometry at solver joints qs (n, 6): frames and the points B, C, D."""
    F = _solver_frames(arm, qs)
    return F, F[:, 2, :3, 3], F[:, 4, :3, 3], F[:, 6, :3, 3]


def elbow_factor(arm: Arm, qs) -> np.ndarray:
    """``e = det[x4, z4, z3]`` (n,) at solver joints qs: zero exactly when D is on axis 3
    (x4 = +-z3). For the thesis arm the first factor of det J (sin theta4); not a factor for
    every arm of the class (the CRX-10iA is singular there only when folded):
    :func:`elbow_is_factor`."""
    F = _solver_frames(arm, qs)
    return np.linalg.det(np.stack([F[:, 4, :3, 0], F[:, 4, :3, 2], F[:, 3, :3, 2]], axis=2))


@cache
def elbow_is_factor(arm: Arm) -> bool:
    """Does det J vanish wherever D is on axis 3 (at 8 random such configurations)?"""
    rng = np.random.default_rng(1)
    qs = _newton(arm, solver_joints(arm, _uniform(arm, rng, 8)), _residual_elbow, np.full((8, 1), 3))
    qs = qs[np.all(np.isfinite(qs), axis=1)]
    scale = np.max(np.abs(det_jacobian(arm, _uniform(arm, rng, 64))))
    return bool(np.all(np.abs(det_jacobian(arm, user_joints(arm, qs))) <= 1e-12 * scale))


def second_factor(arm: Arm, q) -> np.ndarray:
    """det J / e at user joints q (n, 6): the second factor of det J, continued across e = 0 by
    the ratio of the derivatives along solver joint 4 (l'Hopital); det J itself where e is not
    a factor (:func:`elbow_is_factor`)."""
    q = np.atleast_2d(np.asarray(q, float))
    if not elbow_is_factor(arm):
        return det_jacobian(arm, q)
    qs = solver_joints(arm, q)
    e = elbow_factor(arm, qs)
    out = det_jacobian(arm, q) / np.where(e == 0.0, 1.0, e)
    small = np.abs(e) < 1e-3
    if small.any():
        h = np.zeros(6)
        h[3] = 1e-4
        qp, qm = qs[small] + h, qs[small] - h
        num = det_jacobian(arm, user_joints(arm, qp)) - det_jacobian(arm, user_joints(arm, qm))
        out[small] = num / (elbow_factor(arm, qp) - elbow_factor(arm, qm))
    return out


# Residuals of the geometric conditions: solver joints qs (n, 6) -> (n, k), zero on the condition.
def _residual_elbow(arm, qs):
    return elbow_factor(arm, qs)[:, None]


def _residual_split(arm, qs):
    """z4 . z2: axis 4 perpendicular to axis 2 (thesis: theta3 = +-90 deg)."""
    F = _solver_frames(arm, qs)
    return np.einsum("ni,ni->n", F[:, 4, :3, 2], F[:, 2, :3, 2])[:, None]


def _residual_c_on_axis1(arm, qs):
    """C's offset from axis 1 (x, y in frame 0): thesis l3 cos theta2 + l2 = 0 (with theta3 = 90 deg)."""
    return _points(arm, qs)[2][:, :2] / arm.reach


def _residual_axis6_through_b(arm, qs):
    """((D - B) x z6) . z4: axis 6 through B within the plane of the arm (thesis:
    l3 sin(theta4 + theta5) + l4 sin theta5 = 0)."""
    F, B, _, D = _points(arm, qs)
    return np.einsum("ni,ni->n", np.cross(D - B, F[:, 6, :3, 2]), F[:, 4, :3, 2])[:, None] / arm.reach


def _residual_second(arm, qs):
    return second_factor(arm, user_joints(arm, qs))[:, None] / arm.reach**2


def _residual_d_on_axis1(arm, qs):
    return _points(arm, qs)[3][:, :2] / arm.reach


def _newton(arm: Arm, qs, residual, cols, *per_row, iters: int = 60) -> np.ndarray:
    """Configurations qs (n, 6), row i moved over its columns ``cols[i]`` (n, k) until
    ``residual(arm, x, *rows of per_row)`` (m, r) vanishes: least-squares Newton steps on all
    rows at once, Jacobian by central differences, steps capped at 0.5 rad. Rows that do not
    converge (residual above 1e-13 after ``iters`` steps, or a non-finite step) come back NaN."""
    qs, cols = np.array(qs, float), np.asarray(cols)
    live = np.all(np.isfinite(qs), axis=1)
    for _ in range(iters):
        idx = np.flatnonzero(live)
        if not idx.size:
            break
        x, c, args = qs[idx], cols[idx], [a[idx] for a in per_row]
        r = residual(arm, x, *args)
        done = np.max(np.abs(r), axis=1) <= 1e-15
        J = np.empty(r.shape + (c.shape[1],))
        for k in range(c.shape[1]):
            h = np.zeros_like(x)
            h[np.arange(len(x)), c[:, k]] = 1e-7
            J[..., k] = (residual(arm, x + h, *args) - residual(arm, x - h, *args)) / 2e-7
        ok = ~done & np.all(np.isfinite(r), axis=1) & np.all(np.isfinite(J), axis=(1, 2))
        dq = np.full((len(x), c.shape[1]), np.nan)
        dq[ok] = -(np.linalg.pinv(J[ok]) @ r[ok][..., None])[..., 0]
        bad = ~done & ~np.all(np.isfinite(dq), axis=1)
        big = np.max(np.abs(np.where(ok[:, None], dq, 0.0)), axis=1)
        dq *= np.where(big > 0.5, 0.5 / np.maximum(big, 0.5), 1.0)[:, None]
        step = idx[ok & ~bad]
        qs[step[:, None], cols[step]] += dq[ok & ~bad]
        qs[idx[bad]] = np.nan
        live[idx[done | bad]] = False
    fin = np.flatnonzero(np.all(np.isfinite(qs), axis=1))
    if fin.size:
        r = residual(arm, qs[fin], *[a[fin] for a in per_row])
        qs[fin[~(np.max(np.abs(r), axis=1) <= 1e-13)]] = np.nan
    return qs


# ----------------------------------------------------------------------------- sampling
def _uniform(arm: Arm, rng, n):
    return rng.uniform(arm.q_min, arm.q_max, (n, 6))


def _log_offset(rng, n, lo=-12.0, hi=-2.0):
    """Signed offsets 10^U(lo, hi) (n,)."""
    return rng.choice([-1.0, 1.0], n) * 10.0 ** rng.uniform(lo, hi, n)


#: Configurations tried at once by a batched sampler.
BATCH = 1024


def _draw(arm: Arm, rng, n: int, one: Callable) -> np.ndarray:
    """n configurations from ``one(arm, rng) -> q (6,) or None``; FamilyEmpty if none comes in
    TRIES tries per configuration asked for."""
    out, tries = [], 0
    while len(out) < n:
        if tries >= TRIES * n:
            raise FamilyEmpty(f"no member found for {arm.name!r} in {tries} tries")
        tries += 1
        q = one(arm, rng)
        if q is not None:
            out.append(q)
    return np.array(out).reshape(-1, 6)


def _draw_batches(arm: Arm, rng, n: int, batch: Callable) -> np.ndarray:
    """n configurations from ``batch(arm, rng, m) -> q (<= m, 6)`` (the members among m tries);
    FamilyEmpty if they do not come in TRIES tries per configuration asked for."""
    out, got, tries = [], 0, 0
    while got < n:
        if tries >= TRIES * n:
            raise FamilyEmpty(f"no member found for {arm.name!r} in {tries} tries")
        m = min(TRIES * n - tries, BATCH, max(8, 2 * (n - got)))
        tries += m
        out.append(batch(arm, rng, m))
        got += len(out[-1])
    return np.concatenate(out)[:n]


def _columns(rng, cols, k: int, m: int) -> np.ndarray:
    """m rows of k distinct columns drawn from ``cols``, each row sorted (m, k)."""
    pick = np.argsort(rng.random((m, len(cols))), axis=1)[:, :k]
    return np.sort(np.asarray(cols)[pick], axis=1)


def _conditions(*parts):
    """A sampler: from uniform q, Newton on each (residual, candidate columns, k) in turn, over
    k columns drawn at random among the candidates (as many as the residual needs)."""

    def batch(arm, rng, m):
        qs = solver_joints(arm, _uniform(arm, rng, m))
        for residual, cols, k in parts:
            qs = _newton(arm, qs, residual, _columns(rng, cols, k, m))
        return user_joints(arm, qs[np.all(np.isfinite(qs), axis=1)])

    return lambda arm, rng, n: _draw_batches(arm, rng, n, batch)


def _sample_uniform(arm, rng, n):
    return _uniform(arm, rng, n)


def _line_sampler(f_of_arm):
    """A sampler of the sign changes of ``f_of_arm(arm)`` on random lines through uniform q."""

    def one(arm, rng):
        q0 = _uniform(arm, rng, 1)[0]
        d = rng.normal(size=6)
        pts = singular_on_line(arm, q0, d / np.linalg.norm(d), f=f_of_arm(arm))
        return pts[rng.integers(len(pts))] if pts else None

    return lambda arm, rng, n: _draw(arm, rng, n, one)


def _normal(arm: Arm, q) -> np.ndarray:
    """The unit normal (6,) of the singular set at q: the gradient of det J."""
    g = np.empty(6)
    for j in range(6):
        e = np.zeros(6)
        e[j] = 1e-6
        g[j] = (det_jacobian(arm, q + e)[0] - det_jacobian(arm, q - e)[0]) / 2e-6
    return g / np.linalg.norm(g)


def _sample_off_singular(arm, rng, n):
    """det J = 0 moved by +-10^U(-12, -4) rad along the normal of the singular set."""
    qs = _line_sampler(lambda a: None)(arm, rng, n)
    return np.array([q + _log_offset(rng, 1, -12.0, -4.0)[0] * _normal(arm, q) for q in qs])


def _continuum_angles(arm: Arm, qs: np.ndarray):
    """Solver joints 4 and 5 (n, 2) that put D on axis 3 and z6 along it (the theta3/theta6
    continuum) for the solver joints 1-3 of qs, the nearest to qs's."""
    F = _solver_frames(arm, qs)
    out = np.empty((len(qs), 2))
    for i in range(len(qs)):
        z3, q = F[i, 3, :3, 2], qs[i].copy()
        ca, sa, _, _, off4 = arm.solver.rows[3]
        R40 = F[i, 3, :3, :3] @ np.array([[1, 0, 0], [0, ca, -sa], [0, sa, ca]])
        w = R40.T @ z3
        q[3] = _nearest_mod_pi(math.atan2(w[1], w[0]), q[3] + off4) - off4
        G = _solver_frames(arm, q[None])[0]
        ca5, sa5, _, _, off5 = arm.solver.rows[4]
        R50 = G[4, :3, :3] @ np.array([[1, 0, 0], [0, ca5, -sa5], [0, sa5, ca5]])
        s6 = arm.solver.rows[5][1]
        w = R50.T @ z3
        out[i] = q[3], _nearest_mod_pi(math.atan2(s6 * w[0], -s6 * w[1]), q[4] + off5) - off5
    return out


def _nearest_mod_pi(phi, t):
    return min((phi, phi + math.pi), key=lambda x: abs(wrap(x - t)))


def _on_continuum(arm, rng, n):
    qs = solver_joints(arm, _uniform(arm, rng, n))
    qs[:, 3:5] = _continuum_angles(arm, qs)
    return qs


def _sample_continuum(arm, rng, n):
    return user_joints(arm, _on_continuum(arm, rng, n))


def _sample_near_continuum(arm, rng, n):
    qs = _on_continuum(arm, rng, n)
    qs[:, 3] += _log_offset(rng, n, -9.0, -3.0)
    qs[:, 4] += _log_offset(rng, n, -9.0, -3.0) * rng.choice([0.0, 1.0], n)
    return user_joints(arm, qs)


def _sample_near_continuum_equal(arm, rng, n):
    """theta4 and theta4 + theta5 both tiny and of one size (the slow zone of the old kernel:
    e.g. theta4 = 1e-7, theta5 = -1e-7 + 1e-7)."""
    qs = _on_continuum(arm, rng, n)
    eps = _log_offset(rng, n, -9.0, -5.0)
    qs[:, 3] += eps
    qs[:, 4] += -eps + rng.choice([-1.0, 1.0], n) * np.abs(eps) * rng.uniform(0.0, 2.0, n)
    return user_joints(arm, qs)


def _axis2_parallel_axis4(arm: Arm, qs: np.ndarray) -> np.ndarray:
    """Solver joint 3 angles (n,) where axis 4 is parallel to axis 2, nearest to qs's (for the
    thesis arm theta3 = 0 or pi)."""
    F = _solver_frames(arm, qs)
    out = np.empty(len(qs))
    ca, sa, _, _, off3 = arm.solver.rows[2]
    s4 = arm.solver.rows[3][1]
    for i in range(len(qs)):
        R30 = F[i, 2, :3, :3] @ np.array([[1, 0, 0], [0, ca, -sa], [0, sa, ca]])
        w = R30.T @ F[i, 2, :3, 2]  # z4 in frame 3 at angle t: (s4 sin t, -s4 cos t, 0)
        out[i] = _nearest_mod_pi(math.atan2(s4 * w[0], -s4 * w[1]), qs[i, 2] + off3) - off3
    return out


def _sample_theta3_band(arm, rng, n):
    qs = solver_joints(arm, _uniform(arm, rng, n))
    qs[:, 2] = _axis2_parallel_axis4(arm, qs) + _log_offset(rng, n, -12.0, -2.0)
    return user_joints(arm, qs)


def _sample_near_wrist_on_axis1_theta4(arm, rng, n):
    """wrist-on-axis1-theta4 with solver joint 2 moved by +-10^U(-9, -3) rad: D off the joint-1
    axis by about that times its distance from axis 2, still on axis 3."""
    qs = solver_joints(arm, family("wrist-on-axis1-theta4").sample(arm, rng, n))
    qs[:, 1] += _log_offset(rng, n, -9.0, -3.0)
    return user_joints(arm, qs)


def _sample_at_stops(arm, rng, n):
    q = _uniform(arm, rng, n)
    for i in range(n):
        for j in rng.choice(6, size=rng.integers(1, 4), replace=False):
            q[i, j] = arm.q_min[j] if rng.random() < 0.5 else arm.q_max[j]
    return q


def _tool_near_base(arm, rng, m):
    """Of m tries, those q with the tool point at 0 (probability 1/5) or 10^U(-9, -3) m from
    the base origin (user joints)."""

    def res(a, x, target):
        return (iik.fk(x, a)[:, :3, 3] - target) / a.reach

    every = np.tile(np.arange(6), (m, 1))
    at0 = _newton(arm, _uniform(arm, rng, m), res, every, np.zeros((m, 3)))
    d = rng.normal(size=(m, 3))
    d *= (10.0 ** rng.uniform(-9.0, -3.0, m) / np.linalg.norm(d, axis=1))[:, None]
    d[rng.random(m) < 0.2] = 0.0
    q = _newton(arm, at0, res, every, d)
    return q[np.all(np.isfinite(q), axis=1)]


def _sample_tool_near_base(arm, rng, n):
    return _draw_batches(arm, rng, n, _tool_near_base)


@dataclass(frozen=True)
class Family:
    """A family of configurations aimed at one weakness of an IK (see the module docstring).

    Attributes:
        name: Short name (``"near-continuum"``).
        description: What the configurations are, in the solver chain's terms and, where they
            differ, in the thesis arm's.
        sample: ``(arm, rng, n) -> q (n, 6)`` [rad] (user joint order); raises
            :class:`FamilyEmpty` if the family has no member for the arm.
    """

    name: str
    description: str
    sample: Callable[[Arm, np.random.Generator, int], np.ndarray]


_ELBOW = (_residual_elbow, [3], 1)
_SPLIT = (_residual_split, [2], 1)

FAMILIES = (
    Family("uniform", "q uniform in the joint limits (the baseline, not evidence)", _sample_uniform),
    Family("singular", "det J = 0: a root of det J on a random line in joint space",
           _line_sampler(lambda a: None)),
    Family("singular-second", "the second factor of det J: a root of det J / e on a random line",
           _line_sampler(lambda a: lambda Q: second_factor(a, Q))),
    Family("elbow", "D on axis 3 (thesis: theta4 = 0 or pi, the first factor of det J)", _conditions(_ELBOW)),
    Family("elbow-second", "D on axis 3 and det J / e = 0 (thesis: both factors)",
           _conditions(_ELBOW, (_residual_second, [0, 1, 2, 4, 5], 1))),
    Family("split-c-on-axis1", "axis 4 _|_ axis 2 and C on axis 1 (thesis: theta3 = +-90 deg, "
           "l3 cos theta2 + l2 = 0)", _conditions(_SPLIT, (_residual_c_on_axis1, [0, 1], 2))),
    Family("split-axis6-through-b", "axis 4 _|_ axis 2 and axis 6 through B (thesis: theta3 = +-90 "
           "deg, l3 sin(theta4 + theta5) + l4 sin theta5 = 0)",
           _conditions(_SPLIT, (_residual_axis6_through_b, [3, 4], 1))),
    Family("split-both", "axis 4 _|_ axis 2, C on axis 1 and axis 6 through B (the intersection)",
           _conditions(_SPLIT, (_residual_c_on_axis1, [0, 1], 2), (_residual_axis6_through_b, [3, 4], 1))),
    Family("off-singular", "det J = 0 moved by +-10^U(-12, -4) rad along the normal of the singular set",
           _sample_off_singular),
    Family("theta3-band", "joint 3 within +-10^U(-12, -2) rad of axis 4 parallel to axis 2 "
           "(thesis: theta3 at 0 or pi)", _sample_theta3_band),
    Family("continuum", "D on axis 3 and z6 along it: joints 3 and 6 collinear "
           "(thesis: theta4 = 0, theta4 + theta5 = 0)", _sample_continuum),
    Family("near-continuum", "the continuum with joint 4 moved by 10^U(-9, -3) and joint 5 by the "
           "same or nothing", _sample_near_continuum),
    Family("near-continuum-equal", "joint 4 and joint 4 + joint 5 both 10^U(-9, -5) from the "
           "continuum (the slow zone)", _sample_near_continuum_equal),
    Family("wrist-on-axis1", "the wrist point D on the joint-1 axis",
           _conditions((_residual_d_on_axis1, [1, 2, 3], 3))),
    Family("wrist-on-axis1-theta4", "D on the joint-1 axis and on axis 3 (thesis: theta4 = 0): a "
           "theta1 continuum", _conditions(_ELBOW, (_residual_d_on_axis1, [1, 2], 2))),
    Family("at-stops", "one to three joints exactly at a joint limit", _sample_at_stops),
    Family("tool-near-base", "the tool point 0 (one in five) or 10^U(-9, -3) m from the base origin",
           _sample_tool_near_base),
    Family("near-wrist-on-axis1-theta4", "wrist-on-axis1-theta4 with joint 2 moved by +-10^U(-9, -3) "
           "rad: D just off the joint-1 axis, beside the theta1 continuum",
           _sample_near_wrist_on_axis1_theta4),
)


def family(name: str) -> Family:
    """The family called ``name``."""
    for f in FAMILIES:
        if f.name == name:
            return f
    raise KeyError(f"no family {name!r}; families: {[f.name for f in FAMILIES]}")


@cache
def _applicability(name: str, arm: Arm) -> str | None:
    try:
        family(name).sample(arm, np.random.default_rng(0), 1)
    except FamilyEmpty as exc:
        return f"family {name!r} is empty for this arm: {exc}"
    return None


def applicability(fam: Family, arm: Arm) -> str | None:
    """None if ``fam`` has members for ``arm``, else why not (cached per family and arm)."""
    return _applicability(fam.name, arm)


def family_configurations(fam: Family, arm: Arm):
    """Hypothesis strategy: one configuration q* (6,) of ``fam`` for ``arm`` (seeded draws)."""
    require("test", "verification.testing.families.family_configurations")
    from hypothesis import strategies as st

    return st.integers(0, 2**32 - 1).map(lambda seed: fam.sample(arm, np.random.default_rng(seed), 1)[0])
