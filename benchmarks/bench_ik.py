"""IK benchmark per adversarial family, with the certificate counters, and the recovery table.

    python benchmarks/bench_ik.py                                 # thesis arm, 2000 poses per family
    python benchmarks/bench_ik.py --arm crx10ia --n 500           # another shipped arm, quick
    python benchmarks/bench_ik.py --recovery 2000 --arm crx10ia   # plus the recovery table
    python benchmarks/bench_ik.py --profile                       # where a single call's time goes

The implementation is :mod:`verification.testing.ik_benchmark`.
"""

import sys

from verification.testing.ik_benchmark import main

if __name__ == "__main__":
    sys.exit(main())
