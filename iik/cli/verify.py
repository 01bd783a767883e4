"""``iik verify``: run every registered thesis check and write the report."""

from __future__ import annotations

import sys
import time
from pathlib import Path

NAME = "verify"
HELP = "run every registered thesis check and write reports/verification.md"


def add_arguments(p) -> None:
    p.add_argument("--out", type=Path, default=Path("reports"),
                   help="report folder (default: ./reports)")
    p.add_argument("--quick", action="store_true", help="small sample sizes (for smoke tests)")
    p.add_argument("--seed", type=int, default=20120101, help="seed for all random samples")
    p.add_argument("--only", nargs="*", default=None, metavar="TEXT",
                   help="run only checks whose name or section contains TEXT")


def run(args) -> int:
    from verification import Context, run_checks, summary, write_report


    ctx = Context(out_dir=args.out, seed=args.seed, quick=args.quick)
    t0 = time.perf_counter()

    def progress(i, n, chk, res):
        if res is None:
            print(f"[{i + 1:>2}/{n}] {chk.section}: {chk.name.rsplit('.', 1)[-1]} ...",
                  end="", flush=True, file=sys.stderr)
        else:
            status = "FAILED" if res.error else ", ".join(sorted({r.verdict.value for r in res.rows}))
            print(f" {status} ({res.seconds:.1f} s)", file=sys.stderr, flush=True)

    results = run_checks(ctx, select=args.only, progress=progress)
    path = write_report(results, args.out / "verification.md")
    print(summary(results))
    print(f"report: {path}  ({time.perf_counter() - t0:.1f} s)")
    return 1 if any(r.error for r in results) else 0
