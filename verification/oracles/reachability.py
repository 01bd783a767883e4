"""Ground truth for position reachability: dense joint sampling plus numerical IK.

A point ``p`` [m] is *reachable* if some ``q`` inside Table I puts the tool
point there (every orientation allowed). :class:`ReachabilityOracle` decides
it in two steps:

1. ``n`` joint vectors are drawn uniformly inside the limits and pushed through
   the position column of Eq 4 (:func:`iik.workspace.tool_positions`, equal to
   ``iik.fk(q)[:, :3, 3]`` to 1e-15 m, tested) in batches; the tool positions go
   into a KD-tree.
2. For each query point, the ``k`` (3) nearest sampled configurations seed a
   bounded Levenberg-Marquardt position IK over joints 1-5
   (:func:`iik.workspace.position_lm`, 60 iterations). A residual below ``tol`` (1e-6 m)
   means reachable. Points farther than ``radius`` from every sample are
   declared unreachable without IK (the largest nearest-sample distance of a
   reachable point is reported so this cut can be audited). Every
   "unreachable" verdict with a residual under 20 mm is retried from more
   seeds with more iterations.

The oracle does not use any workspace formula of the thesis.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

import iik
from iik.workspace import position_lm, tool_positions

__all__ = ["ReachabilityOracle", "Classification", "oracle_for"]


@dataclass(frozen=True)
class Classification:
    """Result of :meth:`ReachabilityOracle.classify` (arrays of length n)."""

    reachable: np.ndarray  # bool
    residual: np.ndarray  # best IK residual [m] (inf where no IK was run)
    nearest: np.ndarray  # distance to the nearest sampled tool position [m]
    q: np.ndarray  # (n, 5) best joint vector found [rad]


class ReachabilityOracle:
    """Dense-sampling + IK reachability oracle for an :class:`iik.Arm`."""

    def __init__(self, arm: iik.Arm = iik.THESIS_ARM, n_samples: int = 1_000_000,
                 rng: np.random.Generator | None = None, batch: int = 250_000):
        rng = rng or np.random.default_rng(0)
        self.arm = arm
        q = rng.uniform(arm.q_min, arm.q_max, size=(n_samples, 6))
        q[:, 5] = 0.0
        pts = np.empty((n_samples, 3))
        for i in range(0, n_samples, batch):  # vectorised Eq 4 position column in batches
            pts[i:i + batch] = tool_positions(q[i:i + batch, :5], arm)
        self.q = q[:, :5]
        self.points = pts
        self.tree = cKDTree(pts)

    def classify(self, p, *, k: int = 3, radius: float = 0.08, tol: float = 1e-6,
                 iters: int = 60, thorough: bool = True, retry_below: float = 0.02) -> Classification:
        """Classify points ``p`` (n, 3) [m]; ``thorough`` retries every unreachable verdict
        whose residual is below ``retry_below`` [m] from k more seeds with 2x the iterations."""
        p = np.atleast_2d(np.asarray(p, dtype=float))
        n = len(p)
        d, idx = self.tree.query(p, k=k)
        d, idx = d.reshape(n, k), idx.reshape(n, k)
        reach = np.zeros(n, bool)
        resid = np.full(n, np.inf)
        qbest = self.q[idx[:, 0]].copy()
        cand = d[:, 0] < radius
        for j in range(k):
            sel = np.nonzero(cand & ~reach)[0]
            if len(sel) == 0:
                break
            qs, rr = position_lm(p[sel], self.q[idx[sel, j]], self.arm, iters=iters, tol=tol * 1e-2)
            better = rr < resid[sel]
            resid[sel[better]] = rr[better]
            qbest[sel[better]] = qs[better]
            reach[sel] = resid[sel] < tol
        if thorough:  # second opinion for every candidate declared unreachable
            sel = np.nonzero(cand & ~reach & (resid < retry_below))[0]
            if len(sel):
                kk = min(2 * k, len(self.q))
                _, idx2 = self.tree.query(p[sel], k=kk)
                for j in range(k, kk):
                    s2 = sel[~reach[sel]]
                    if len(s2) == 0:
                        break
                    rows = np.searchsorted(sel, s2)
                    qs, rr = position_lm(p[s2], self.q[idx2[rows, j]], self.arm, iters=2 * iters,
                                         tol=tol * 1e-2)
                    better = rr < resid[s2]
                    resid[s2[better]] = rr[better]
                    qbest[s2[better]] = qs[better]
                    reach[s2] = resid[s2] < tol
        return Classification(reach, resid, d[:, 0], qbest)


def oracle_for(ctx, arm: iik.Arm = iik.THESIS_ARM) -> ReachabilityOracle:
    """The oracle cached in ``ctx.cache`` (10^6 samples, 10^5 in quick mode)."""
    key = ("reachability_oracle", id(arm), ctx.quick)
    if key not in ctx.cache:
        ctx.cache[key] = ReachabilityOracle(arm, ctx.n(1_000_000, 100_000), ctx.rng("reachability"))
    return ctx.cache[key]
