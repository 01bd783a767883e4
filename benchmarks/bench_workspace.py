"""Benchmark: iik.in_workspace (vectorised) and the exact iik.dexterity (per point).

Run: ``python benchmarks/bench_workspace.py [n]``. Prints medians over several
repetitions and ratios against baselines measured in the same run:

* ``in_workspace`` on an (n, 3) batch vs the same test called point by point
  (the naive loop); target >= 1e6 points/s for the batch;
* the exact ``dexterity`` per point (IK feasibility on a grid of orientations, interval ends
  root-found) vs one ``iik.solve`` (complete IK) per pose: how many IK calls one answer costs.
"""

from __future__ import annotations

import sys

import numpy as np

import iik
from iik import THESIS_ARM
from iik.dexterity import alpha_intervals
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
    arm = THESIS_ARM
    k = min(m, 10)  # exact dexterity runs the IK on a grid of orientations: seconds, not microseconds
    t_dex = median_seconds(lambda: [iik.dexterity(p, arm) for p in pts[:k]], reps=1) / k
    t_alpha = median_seconds(lambda: [alpha_intervals(p, 1.5, arm) for p in pts[:k]], reps=1) / k
    kk = min(m, 300)
    t_ik = median_seconds(lambda: [iik.solve(t, arm) for t in T[:kk]], reps=3) / kk
    print(f"dexterity(p, arm): {t_dex * 1e3:8.1f} ms/point (exact beta intervals, default 2 deg grid)")
    print(f"alpha_intervals(p, beta, arm): {t_alpha * 1e3:8.1f} ms/point (exact alpha intervals at one beta)")
    print(f"iik.solve per pose (baseline: one IK feasibility query): {t_ik * 1e6:8.2f} us/pose; "
          f"dexterity(p) costs {t_dex / t_ik:,.0f} IK calls")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 1_000_000)
