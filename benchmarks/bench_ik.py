"""IK benchmark: complete vs thesis IIK vs Newton on one fixed set of reachable poses.

    python benchmarks/bench_ik.py                      # 10 000 poses
    python benchmarks/bench_ik.py --n 500              # quick
    python benchmarks/bench_ik.py --recovery 100000    # plus the near-singular recovery sweep

The implementation is :mod:`verification.testing.ik_benchmark` (shared with ``iik verify``).
"""

import sys

from verification.testing.ik_benchmark import main

if __name__ == "__main__":
    sys.exit(main())
