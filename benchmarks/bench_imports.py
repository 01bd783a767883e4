"""Benchmark: what importing each entry point costs in a fresh interpreter.

Run: ``python benchmarks/bench_imports.py [reps] [--path SRC]``. For ``iik``, ``iik.ik``,
``hardware.protocol``, ``iik.planning`` and ``verification``: the median wall time of the import
over ``reps`` fresh processes, the number of modules it loads and which heavy libraries among
them, against the baseline ``import numpy`` measured in the same run. ``--path SRC`` measures
the source tree ``SRC`` instead of the installed one (e.g. an older commit, for a before/after).
"""

from __future__ import annotations

import argparse
import statistics

from verification.testing.imports import import_cost

ENTRY_POINTS = ("iik", "iik.ik", "hardware.protocol", "iik.planning", "verification")
HEAVY = ("numba", "scipy", "pinocchio", "coal", "ompl", "toppra", "matplotlib", "viser", "trimesh", "can",
         "ruckig", "hypothesis")


def main(reps: int = 5, path: str | None = None) -> None:
    base = statistics.median(import_cost("numpy", path=path).seconds for _ in range(reps))
    print(f"baseline: import numpy {base:.3f} s (median of {reps} fresh processes)")
    print(f"{'entry point':<20} {'median s':>9} {'x numpy':>8} {'modules':>8}  heavy libraries loaded")
    for module in ENTRY_POINTS:
        costs = [import_cost(module, path=path) for _ in range(reps)]
        t = statistics.median(c.seconds for c in costs)
        heavy = [h for h in HEAVY if costs[-1].loads(h)]
        print(f"{module:<20} {t:9.3f} {t / base:8.1f} {len(costs[-1].modules):8d}  {', '.join(heavy) or '-'}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("reps", nargs="?", type=int, default=5)
    parser.add_argument("--path", help="measure this source tree instead of the installed one")
    args = parser.parse_args()
    main(args.reps, args.path)
