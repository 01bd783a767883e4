"""Benchmark: iik.in_workspace (vectorised) and iik.dexterity (per point).

Run: ``python benchmarks/bench_workspace.py [n]``. Prints medians over several
repetitions and ratios against baselines measured in the same run:

* ``in_workspace`` on an (n, 3) batch vs the same test called point by point
  (the naive loop); target >= 1e6 points/s for the batch;
* ``dexterity`` per point vs one ``iik.solve`` (complete IK) per point (the cost
  of asking the IK whether one orientation works); target <= 50 us per point.
"""

from __future__ import annotations

import sys

import numpy as np

import iik
from iik import THESIS_ARM
from verification.testing.timing import median_seconds


def main(n: int = 1_000_000) -> None:
    rng = np.random.default_rng(0)
    P = rng.uniform([-1.0, -1.0, -0.6], [1.0, 1.0, 1.2], size=(n, 3))
    m = min(n, 2000)
    t_batch = median_seconds(lambda: iik.in_workspace(P, THESIS_ARM)) / n
    t_loop = median_seconds(lambda: [iik.in_workspace(p, THESIS_ARM) for p in P[:m]], reps=3) / m
    print(f"in_workspace, batch of {n}: {t_batch * 1e9:8.1f} ns/point = {1 / t_batch / 1e6:6.2f} M points/s")
    print(f"in_workspace, per-point loop (baseline): {t_loop * 1e9:8.1f} ns/point; "
          f"batch speed-up x{t_loop / t_batch:,.0f}")

    q = rng.uniform(iik.THESIS_ARM.q_min, iik.THESIS_ARM.q_max, size=(m, 6))
    T = iik.fk(q, THESIS_ARM)
    pts = T[:, :3, 3]
    k = min(m, 1000)
    t_dex = median_seconds(lambda: [iik.dexterity(p, THESIS_ARM) for p in pts[:k]]) / k
    betas = []
    for p in pts[:k]:
        r = iik.dexterity(p, THESIS_ARM)
        betas.append(None if r.beta_range is None else 0.5 * (r.beta_range[0] + r.beta_range[1]))
    t_dex_b = median_seconds(lambda: [iik.dexterity(p, THESIS_ARM, beta=b)
                                      for p, b in zip(pts[:k], betas, strict=True)
                               if b is not None]) / max(1, sum(b is not None for b in betas))
    kk = min(k, 300)
    t_ik = median_seconds(lambda: [iik.solve(t, THESIS_ARM) for t in T[:kk]], reps=3) / kk
    print(f"dexterity(p): {t_dex * 1e6:8.2f} us/point (beta range)")
    print(f"dexterity(p, beta): {t_dex_b * 1e6:8.2f} us/point (beta range + alpha range)")
    print(f"iik.solve per pose (baseline: one IK feasibility query): {t_ik * 1e6:8.2f} us/pose; "
          f"dexterity is x{t_ik / t_dex_b:,.1f} faster than one IK call")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 1_000_000)
