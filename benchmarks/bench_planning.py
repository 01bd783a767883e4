"""Benchmark: one thesis scenario end to end (plan, IK, whole-arm Coal check).

Scenario ``j`` (Fig 42j). Three variants measured in the same run:

* ``full``     -- ``iik.planning.plan`` without timing: thesis path, IK branches, certified
                  continuous whole-arm check (the target is <= 200 ms median);
* ``discrete`` -- the same with the whole-arm check at the step-points only (baseline
                  without the continuous check between steps);
* ``thesis``   -- the thesis planner alone (step-points + IK, no collision check).

Run: ``python benchmarks/bench_planning.py [--runs N]``
"""

from __future__ import annotations

import argparse

from iik import THESIS_ARM
from iik.planning import (
    PlanOptions,
    SceneCollision,
    build_path,
    load_scenario,
    plan,
    scenario_path,
    track_branches,
)
from iik.scene import THESIS_SCENE
from verification.testing.timing import median_seconds


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=15)
    ap.add_argument("--scenario", default="j")
    args = ap.parse_args()
    sc = load_scenario(scenario_path(args.scenario))

    def full():
        r = plan(sc, PlanOptions(timing=False))
        assert r.success, r.reason

    def discrete():
        # same pipeline steps, but clearance at the step-points only (no motion check)
        cp = build_path(sc, scene=THESIS_SCENE)
        br = track_branches(cp, adapt_orientation=False, arm=THESIS_ARM).branches
        chk = SceneCollision(sc.obstacles, arm=THESIS_ARM)
        for b in br:
            pc = chk.path_clearance(b.q, -float("inf"))  # bound already met: no bisection samples
            if b.complete and pc.step.min() >= sc.safety_zone and pc.self_min > 0:
                return

    def thesis():
        cp = build_path(sc, scene=THESIS_SCENE)
        track_branches(cp, adapt_orientation=False, arm=THESIS_ARM)

    t_full, t_disc, t_thesis = (median_seconds(f, args.runs, warmup=True) for f in (full, discrete, thesis))
    print(f"scenario {args.scenario}: median over {args.runs} runs")
    print(f"  full (plan + IK + certified continuous whole-arm check): {t_full * 1e3:8.1f} ms"
          "  (target <= 200 ms)")
    print(f"  baseline: step-points-only check                      : {t_disc * 1e3:8.1f} ms  "
          f"(full / baseline = {t_full / t_disc:.2f})")
    print(f"  baseline: thesis planner + IK, no collision check      : {t_thesis * 1e3:8.1f} ms  "
          f"(full / thesis = {t_full / t_thesis:.2f})")


if __name__ == "__main__":
    main()
