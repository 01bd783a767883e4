"""Benchmark: what importing each entry point costs in a fresh interpreter.

Run: ``python benchmarks/bench_imports.py [reps] [--path SRC]``. For ``iik``, ``iik.ik``,
``hardware.protocol``, ``iik.planning`` and ``verification``, and for the first name a user of
each takes (where lazy imports move the cost): the median wall time over ``reps`` fresh
processes, the number of modules loaded and which heavy libraries among them, against the
baseline ``import numpy`` measured in the same run. ``--path SRC`` measures the source tree
``SRC`` instead of the installed one (e.g. an older commit, for a before/after).
"""

from __future__ import annotations

import argparse
import statistics

from verification.testing.imports import import_cost

STATEMENTS = ("import iik", "import iik.ik", "import hardware.protocol", "import iik.planning",
              "import verification", "from iik import solve", "from iik.planning import plan",
              "from hardware import run", "from verification import verify")
HEAVY = ("numba", "scipy", "pinocchio", "coal", "ompl", "toppra", "matplotlib", "viser", "trimesh", "can",
         "ruckig", "hypothesis")


def main(reps: int = 5, path: str | None = None) -> None:
    base = statistics.median(import_cost("import numpy", path=path).seconds for _ in range(reps))
    print(f"baseline: import numpy {base:.3f} s (median of {reps} fresh processes)")
    print(f"{'statement':<32} {'median s':>9} {'x numpy':>8} {'modules':>8}  heavy libraries loaded")
    for statement in STATEMENTS:
        costs = [import_cost(statement, path=path) for _ in range(reps)]
        t = statistics.median(c.seconds for c in costs)
        heavy = ", ".join(h for h in HEAVY if costs[-1].loads(h)) or "-"
        print(f"{statement:<32} {t:9.3f} {t / base:8.1f} {len(costs[-1].modules):8d}  {heavy}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("reps", nargs="?", type=int, default=5)
    parser.add_argument("--path", help="measure this source tree instead of the installed one")
    args = parser.parse_args()
    main(args.reps, args.path)
