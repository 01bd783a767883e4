"""The configuration of one IK solution nearest a previous configuration by the effort index
(Eq 54), inside the joint limits.

A row of an :class:`~iik.ik.result.IKResult` can stand for more than one joint vector:

* **Windings.** Angles are returned wrapped to (-pi, pi], but a joint whose range is wider than
  that (the CRX-10iA's J3 runs from -71 to 251 deg, its J6 over +-225 deg) reaches the same pose
  at ``q_i + 2 pi m``. Eq 54 is a sum over the joints and the limits are a box, so the nearest
  winding inside the limits is chosen joint by joint (:func:`windings`): exact.
* **Collinear continua** (:class:`~iik.ik.result.Continuum` kind ``"collinear"``): the members are
  ``theta_free = t``, ``theta_coupled = c + s t`` (+ 2 pi m). For each winding m, Eq 54 along
  the continuum is convex and piecewise linear in t, and the members inside the limits form an
  interval of t; its minimum is at a kink (t at the previous free angle, or the coupled angle at
  its previous value) or at an end of the interval: :func:`nearest` evaluates exactly those
  points. Exact.
* **The other continua** (``"theta1"``, ``"theta2"``, ``"numerical"``): the members are sampled
  along the free joint by continuation (:func:`iik.ik.members.along`, at most
  :data:`~iik.ik.members.STEP` apart); the best sample is refined by golden section within one
  STEP on each side, and the member at the previous value of the free joint is tried exactly, so a
  previous configuration that lies on the continuum is returned as itself (effort ~0). Between
  samples this is a local search: a minimum narrower than STEP can be missed by up to the
  effort's change over one STEP.

Units: rad. Limits: ``arm.within_limits(q, tol=limit_tol)`` (a negative ``limit_tol`` is a
margin inside the stops, as the planner uses).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..arm import LIMIT_TOL, Arm
from ..joint_path import effort_index
from ..validation import as_joints
from . import members as _members
from .result import Continuum, IKResult

__all__ = ["Candidates", "windings", "nearest", "GOLDEN_STEPS"]

#: Golden-section iterations when refining a sampled continuum (2 STEP * 0.618^n ~ 5e-10 rad).
GOLDEN_STEPS = 40
_TWO_PI = 2.0 * math.pi
_EDGE = 1e-12  # clipped ends are moved this far inside, against rounding [rad]


def _bounds(arm, limit_tol: float) -> tuple[np.ndarray, np.ndarray]:
    return arm.q_min - limit_tol, arm.q_max + limit_tol


def windings(q, previous, arm, limit_tol: float) -> np.ndarray:
    """Each row of ``q`` (n, 6) [rad] with every joint moved by the multiple of 2 pi that puts it
    nearest ``previous`` (6,) inside the limits; NaN for a joint that has no winding inside."""
    q = np.atleast_2d(np.asarray(q, dtype=float))
    lo, hi = _bounds(arm, limit_tol)
    m_lo = np.ceil((lo - q) / _TWO_PI)
    m_hi = np.floor((hi - q) / _TWO_PI)
    m = np.clip(np.round((np.asarray(previous, float) - q) / _TWO_PI), m_lo, m_hi)
    out = q + _TWO_PI * m
    out[m_lo > m_hi] = np.nan
    return out


def _best(qs: np.ndarray, previous: np.ndarray) -> tuple[np.ndarray | None, float]:
    ok = ~np.any(np.isnan(qs), axis=1)
    if not np.any(ok):
        return None, math.inf
    E = np.atleast_1d(effort_index(previous, qs[ok]))  # Eq 54
    k = int(np.argmin(E))
    return qs[ok][k].copy(), float(E[k])


def _collinear(c: Continuum, previous: np.ndarray, arm, limit_tol: float):
    """Exact: the candidates of the module docstring, over the windings of the coupled joint."""
    j, k, s = c.free_joint - 1, c.coupled_joint - 1, float(c.sign)
    base = windings(c.representative, previous, arm, limit_tol)[0]  # joints j, k are set below
    if np.isnan(np.delete(base, [j, k])).any():
        return None, math.inf
    lo, hi = _bounds(arm, limit_tol)
    a0 = c.representative[k] - s * c.representative[j]  # coupled = a0 + s * free (+ 2 pi m)
    cands = []
    for m in range(-3, 4):
        a = a0 + _TWO_PI * m
        t_k = sorted(((lo[k] - a) / s, (hi[k] - a) / s))
        L, U = max(lo[j], t_k[0]) + _EDGE, min(hi[j], t_k[1]) - _EDGE
        if L > U:
            continue
        for t in (previous[j], (previous[k] - a) / s, L, U):
            t = min(max(t, L), U)
            q = base.copy()
            q[j], q[k] = t, a + s * t
            cands.append(q)
    if not cands:
        return None, math.inf
    qs = np.array(cands)
    qs[~arm.within_limits(qs, tol=limit_tol)] = np.nan
    return _best(qs, previous)


def _member(c: Continuum, t: float, previous, arm, limit_tol: float) -> tuple[np.ndarray | None, float]:
    q, r = _members.follow(c, [t])
    if not (r[0, 0] <= c.tolerance[0] and r[0, 1] <= c.tolerance[1]):
        return None, math.inf
    return _best(windings(q, previous, arm, limit_tol), previous)


def _sampled(c: Continuum, previous: np.ndarray, arm, limit_tol: float, samples):
    """Along a sampled continuum: the best sample, refined (module docstring)."""
    thetas, qs = samples
    W = windings(qs, previous, arm, limit_tol)
    ok = ~np.isnan(W).any(axis=1)
    if not np.any(ok):
        return None, math.inf
    E = np.full(len(W), math.inf)
    E[ok] = effort_index(previous, W[ok])  # Eq 54 at every sample inside the limits
    k = int(np.argmin(E))
    j = c.free_joint - 1
    tries = [(W[k].copy(), float(E[k]))]
    p = float(np.clip(previous[j], arm.q_min[j], arm.q_max[j]))
    tries.append(_member(c, p, previous, arm, limit_tol))  # staying put, if p is a member
    a = max(float(arm.q_min[j]), thetas[k] - _members.STEP)  # one step on each side: beyond the
    b = min(float(arm.q_max[j]), thetas[k] + _members.STEP)  # last sample too (a tube's end)
    f = lambda t: _member(c, t, previous, arm, limit_tol)  # noqa: E731
    g = (math.sqrt(5.0) - 1.0) / 2.0
    x1, x2 = b - g * (b - a), a + g * (b - a)
    f1, f2 = f(x1), f(x2)
    for _ in range(GOLDEN_STEPS if b > a else 0):
        if f1[1] <= f2[1]:
            b, x2, f2 = x2, x1, f1
            x1 = b - g * (b - a)
            f1 = f(x1)
        else:
            a, x1, f1 = x1, x2, f2
            x2 = a + g * (b - a)
            f2 = f(x2)
    tries += [f1, f2]
    return min(tries, key=lambda qe: qe[1])


def nearest(row, continua, previous, arm, *, limit_tol: float, samples=None):
    """The configuration (6,) [rad] of one solution nearest ``previous`` (6,) by Eq 54 inside the
    limits, and its effort [rad]; ``(None, inf)`` if none is inside.

    Args:
        row: The solution's row (6,) [rad] (a continuum's representative).
        continua: Its :class:`~iik.ik.result.Continuum` objects (empty for an isolated solution).
        arm: The arm whose limits apply.
        limit_tol: Tolerance of the limits [rad] (negative: a margin inside the stops).
        samples: For a sampled continuum, its :func:`iik.ik.members.along` (else computed).
    """
    previous = np.asarray(previous, dtype=float)
    best = _best(windings(row, previous, arm, limit_tol), previous)
    for c in continua:
        if c.kind == "collinear":
            found = _collinear(c, previous, arm, limit_tol)
        else:
            found = _sampled(c, previous, arm, limit_tol, samples or _members.along(c))
        best = min(best, found, key=lambda qe: qe[1])
    return best


@dataclass(frozen=True)
class Candidates:
    """The solutions of one pose that a selection may pick from: every row with a configuration
    inside the arm's limits, its windings (q_i + 2 pi m) and its continuum's members considered
    (:mod:`iik.ik.nearest`).

    Attributes:
        q: (k, 6) the rows [rad] as the IK returned them (a continuum's representative).
        continua: Per row, its :class:`~iik.ik.result.Continuum` objects (empty if isolated).
        rows: Per row, its index in the :class:`IKResult` (or array) it came from.
        arm: The arm whose limits apply.
        limit_tol: Tolerance of the limits [rad] (negative: a margin inside the stops).
    """

    q: np.ndarray
    continua: tuple
    rows: tuple[int, ...]
    arm: Arm
    limit_tol: float = LIMIT_TOL
    _samples: dict = field(default_factory=dict, compare=False, repr=False)

    @classmethod
    def of(cls, result_or_q, *, arm: Arm, limit_tol: float = LIMIT_TOL) -> Candidates:
        """The candidates of an :class:`IKResult` or of an array (k, 6) of solutions [rad]."""
        if isinstance(result_or_q, IKResult):
            q, cont = np.asarray(result_or_q.q, float).reshape(-1, 6), result_or_q.continua
        else:
            raw = np.asarray(result_or_q) if not isinstance(result_or_q, np.ndarray) else result_or_q
            q = np.zeros((0, 6)) if raw.size == 0 else as_joints(raw, "solutions")[0]
            cont = ((),) * len(q)
        every = cls(q, tuple(cont), tuple(range(len(q))), arm, limit_tol)
        plain = ~np.isnan(windings(q, q, arm, limit_tol)).any(axis=1) if len(q) else np.zeros(0, bool)
        keep = [i for i in range(len(q)) if plain[i] or every._feasible(i)]
        return cls(q[keep], tuple(cont[i] for i in keep), tuple(keep), arm, limit_tol,
                   {keep.index(i): v for i, v in every._samples.items() if i in keep})

    def __len__(self) -> int:
        return len(self.q)

    def _feasible(self, i: int) -> bool:
        """Has row i a configuration inside the limits (the row's windings first: cheap)?"""
        if not np.isnan(windings(self.q[i], self.q[i], self.arm, self.limit_tol)).any():
            return True
        return bool(self.continua[i]) and self._nearest(i, self.q[i])[0] is not None

    def _nearest(self, i: int, previous):
        sampled = [c for c in self.continua[i] if c.kind != "collinear"]
        if sampled and i not in self._samples:
            self._samples[i] = _members.along(sampled[0])
        return nearest(self.q[i], self.continua[i], previous, self.arm, limit_tol=self.limit_tol,
                       samples=self._samples.get(i))

    def configurations(self) -> np.ndarray:
        """Per row, its configuration inside the limits nearest the row itself (k, 6) [rad]: the
        row, another winding of it, or a member of its continuum."""
        return np.array([self._nearest(i, self.q[i])[0] for i in range(len(self))]).reshape(-1, 6)

    def nearest(self, previous_q) -> tuple[np.ndarray, np.ndarray]:
        """Per row, the configuration nearest ``previous_q`` (6,) [rad] by Eq 54 inside the limits
        (k, 6) [rad] and its effort (k,) [rad]: the row itself, another winding of it, or the
        nearest member of its continuum."""
        prev = as_joints(previous_q, "previous_q")[0][0]
        Q = windings(self.q, prev, self.arm, self.limit_tol)  # isolated rows: all at once
        E = np.full(len(self), math.inf)
        ok = ~np.isnan(Q).any(axis=1)
        if np.any(ok):
            E[ok] = effort_index(prev, Q[ok])  # Eq 54
        for i in (i for i in range(len(self)) if self.continua[i]):
            q, E[i] = self._nearest(i, prev)
            Q[i] = np.nan if q is None else q
        return Q.reshape(-1, 6), E
