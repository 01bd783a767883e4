"""``iik plan``: plan a pick-and-place scenario and write the trajectory, per-step data and figures.

The output folder is written whole or not at all (:func:`iik.planning.write_outputs`); an
``--out`` that is a file, or a folder holding other things than a plan's files, is refused
before planning."""

from __future__ import annotations

import math
import sys
from pathlib import Path

from .arm_option import add_arm_argument, chosen_arm

NAME = "plan"
HELP = "plan a scenario (TOML): thesis planner + whole-arm Coal check + fallbacks + TOPP-RA timing"


def add_arguments(p) -> None:
    p.add_argument("scenario", help="scenario file, e.g. scenarios/j.toml, or a shipped name, e.g. j")
    add_arm_argument(p, data="the scenario's")
    p.add_argument("--out", type=Path, default=None, help="output folder (default: plan_<name>), replaced "
                   "only when every file is written")
    p.add_argument("--no-fallbacks", action="store_true",
                   help="thesis planner only (no other branches, redesigns or RRT-Connect)")
    p.add_argument("--no-figures", action="store_true", help="skip the PNG figures")
    p.add_argument("--dt", type=float, default=0.01, help="trajectory sample period [s] (default 0.01)")
    p.add_argument("--seed", type=int, default=1, help="seed of the RRT-Connect fallback")
    p.add_argument("--timeout", default="60", metavar="SECONDS",
                   help="stop planning after this many seconds with the best attempt so far (default 60)")
    p.spelling.update(file="SCENARIO")  # ScenarioError("file", ...): the scenario file as typed


def run(args) -> int:
    from iik.files import check_output
    from iik.planning import PLAN_FILES, PlanOptions, plan, write_outputs

    if args.out is not None:  # refused before planning, not after
        check_output(args.out, "out", folder=True, owns=PLAN_FILES)
    opts = PlanOptions(fallbacks=not args.no_fallbacks, rrt=not args.no_fallbacks, dt=args.dt, seed=args.seed,
                       timeout=_seconds(args.timeout, "--timeout"))

    def progress(msg: str) -> None:
        print(f"  ... {msg}", file=sys.stderr, flush=True)

    arm = chosen_arm(args, data=True)  # a bad --arm is refused before planning
    print(f"planning {args.scenario}", file=sys.stderr)
    res = plan(args.scenario, opts, arm=arm, progress=progress)
    out = args.out or Path(f"plan_{res.scenario.name}")
    files = write_outputs(res, out, figures=not args.no_figures)
    print(res.summary())
    for line in res.log:
        print(f"  - {line}")
    print("wrote: " + ", ".join(str(f) for f in files))
    return 0 if res.success else 1


def _seconds(text: str, flag: str) -> float:
    """A positive finite number of seconds, else an error naming ``flag`` (one line, exit 2)."""
    from iik.errors import InvalidInputError

    try:
        t = float(text)
    except ValueError:
        t = math.nan
    if not (math.isfinite(t) and t > 0):
        raise InvalidInputError(flag, f"expected a positive finite number of seconds, got {text!r}")
    return t
