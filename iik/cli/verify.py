"""``iik verify``: run every registered thesis check and write the report
(:func:`verification.verify`).

The report folder is replaced only when the new report is complete (an interrupt leaves the
previous one); ``--only TEXT`` that matches no check, an ``--out`` that is a file (or a folder
holding other things) and a negative ``--seed`` are one-line errors, exit 2, nothing written.
A run with ``--only`` is titled PARTIAL on its first line."""

from __future__ import annotations

import sys
from pathlib import Path

NAME = "verify"
HELP = "run every registered thesis check and write reports/verification.md"


def add_arguments(p) -> None:
    p.add_argument("--out", type=Path, default=Path("reports"),
                   help="report folder (default: ./reports), replaced only when the new report is complete")
    p.add_argument("--quick", action="store_true", help="small sample sizes (for smoke tests)")
    p.add_argument("--seed", type=int, default=20120101, help="seed for all random samples (an integer >= 0)")
    p.add_argument("--only", nargs="+", default=None, metavar="TEXT",
                   help="run only checks whose name or section contains TEXT (each TEXT must match one); "
                        "the report is titled PARTIAL")
    p.spelling.update(select="--only", out_dir="--out")  # the library's names as typed
    p.add_argument("--self-test", action="store_true",
                   help="prove every verdict can fail: rerun each check with a known-good and a "
                        "perturbed form (writes no report; exit 1 if a check cannot flip)")


def progress(i, n, chk, res) -> None:
    """One stderr line per check: its name, then its verdicts and time."""
    if res is None:
        print(f"[{i + 1:>2}/{n}] {chk.section}: {chk.name.rsplit('.', 1)[-1]} ...",
              end="", flush=True, file=sys.stderr)
    else:
        status = "FAILED" if res.error else ", ".join(sorted({r.verdict.value for r in res.rows}))
        print(f" {status} ({res.seconds:.1f} s)", file=sys.stderr, flush=True)


def run(args) -> int:
    from verification import self_test, verify

    if args.self_test:
        return self_test(quick=args.quick, seed=args.seed, select=args.only)

    done = verify(args.out, quick=args.quick, seed=args.seed, select=args.only, progress=progress)
    print(done.summary())
    print(f"report: {done.report}  ({done.seconds:.1f} s)")
    return 1 if done.failed else 0
