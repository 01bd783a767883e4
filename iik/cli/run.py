"""``iik run``: plan, validate and execute a trajectory on a PowerCube arm (simulated by default).

The source becomes :class:`hardware.StepTargets` (:mod:`hardware.sources`), the options a
:class:`hardware.RunOptions` and a :class:`hardware.BusConfig`, and :func:`hardware.runner.run` does the
work. The last stdout line is the status on every path (:func:`hardware.runner.failure_status` when the
run raised). Exit 0: the run went to the end inside its safety zone; 1: outside it; 2: an error (nothing
moved, or HALT after a fault); 128 + N: stopped by signal N (HALT sent). README: "PowerCube arm (CAN)".
"""

from __future__ import annotations

import argparse
import math
import sys
from dataclasses import replace
from pathlib import Path

from .arm_option import add_arm_argument, chosen_arm
from .bus_option import add_bus_arguments, bus_config
from .options import millimetres

NAME = "run"
HELP = "plan, validate and execute a trajectory on the (simulated by default) PowerCube arm"


def add_arguments(p) -> None:
    p.add_argument("scenario", nargs="?", help="scenario TOML file, or a shipped scenario's name (e.g. j)")
    p.add_argument("--trajectory", type=Path, metavar="CSV",
                   help="joint trajectory file with columns t,q1..q6 [s, rad], e.g. iik plan's steps.csv")
    p.add_argument("--demo", action="store_true", help="a built-in straight-line demo trajectory")
    add_arm_argument(p, data="the scenario's")
    add_bus_arguments(p, interface=None, channel=None, joints=6)
    p.add_argument("--timeout", type=float, help="ACK timeout (0, 10] s (default: 0.1 on a bus, 2 simulated)")
    p.add_argument("--early", type=float, default=0.95,
                   help="send the next step after this fraction of the previous one (Sec 4.3: 0.95)")
    p.add_argument("--update", choices=("thesis", "buffered"), default="thesis", help="thesis: the next "
                   "step replaces the current one at 95 %% (Sec 4.3); buffered: it waits in the modules' "
                   "step buffer, so no step is cut")
    p.add_argument("--speed", type=float, default=1.0, help="run at this fraction (0, 1] of the "
                   "planned or written speed: every step lasts 1/SPEED as long (default 1)")
    p.add_argument("--margin-deg", type=float, help="margin inside Table I [deg] (default 0.5)")
    p.add_argument("--zone-mm", type=float, help="largest end-effector error of an ok run (0, 1000] mm "
                   "(default: the scenario's safety zone; 10 mm, Sec 4.3.1, for a file or demo)")
    p.add_argument("--lag", type=float, default=0.02, help="simulated tracking lag [0, 1] s")
    p.add_argument("--sim-start", choices=("home", "plan"), default="home",
                   help="simulated arm starts at q = 0 (home) or at the trajectory start")
    p.add_argument("--watchdog", action=argparse.BooleanOptionalAction, help="the modules' watchdog: a "
                   "broadcast every 40 ms, they stop if it stays away (default: on for a bus interface, off "
                   "for the in-process simulation)")
    p.add_argument("--reset", action="store_true", help="RESET every module before the run (after a HALT)")
    p.add_argument("--home", action="store_true", help="HOME modules whose HOME_OK is clear")
    p.add_argument("--out", type=Path, default=Path("runs"), help="folder of the run log and figures "
                   "(default ./runs; a new NAME-DATE-TIME.jsonl each run), or a FILE.jsonl to write")
    p.add_argument("--no-figures", action="store_true", help="skip the PNG figures")


def run(args) -> int:
    from hardware.runner import failure_status

    try:
        report = _run(args)
    except BaseException as exc:  # the status line on stdout on every path; the error follows on stderr
        print(failure_status(exc), flush=True)
        raise
    print(report.summary())
    return 0 if report.ok else 1


def _targets(args):  # -> hardware.StepTargets of the one source given
    from hardware import sources
    from iik.errors import InvalidInputError, Remedy
    if sum((args.scenario is not None, args.trajectory is not None, args.demo)) != 1:
        raise InvalidInputError("run", "no trajectory or more than one",
                                Remedy("give exactly one of {}", ("scenario", "trajectory", "demo")))
    sources.check_speed(args.speed)  # before a scenario is planned
    arm = chosen_arm(args, data=args.scenario is not None)
    if args.scenario is not None:
        return sources.scenario_trajectory(args.scenario, args.speed, arm=arm)
    found = sources.demo_trajectory(arm) if args.demo else sources.csv_trajectory(args.trajectory, arm)
    return found.slowed(args.speed)


def _run(args):  # -> hardware.RunReport; every option is checked before anything is planned or read
    from hardware import ExecutionOptions, RunOptions, SimConfig, ValidationOptions, run
    from hardware.runner import MAX_ZONE

    margin = {"margin": math.radians(args.margin_deg)} if args.margin_deg is not None else {}
    watchdog = args.interface is not None if args.watchdog is None else args.watchdog  # on for a bus
    execution = ExecutionOptions(early=args.early, update=args.update, watchdog=watchdog)
    zone = millimetres(args.zone_mm, "--zone-mm", MAX_ZONE) if args.zone_mm is not None else None
    options = RunOptions(ValidationOptions(**margin), execution, zone, args.reset, args.home,
                         not args.no_figures)
    sim = SimConfig(lag=args.lag) if args.interface is None else None  # modules simulated in-process
    bus, targets = bus_config(args, timeout=args.timeout, sim=sim), _targets(args)
    if sim is not None and args.sim_start == "plan":
        bus = replace(bus, sim=replace(sim, initial=tuple(targets.q[0])))
    tty, shown = sys.stderr.isatty(), []

    def progress(k: int, n: int) -> None:
        shown.append(k)
        line = f"  executing on {bus.where}: step {k}/{n}"
        if tty or k == 1 or k == n or k % max(1, n // 10) == 0:
            print("\r" + line if tty else line, end="" if tty else "\n", file=sys.stderr, flush=True)

    try:
        return run(targets, bus, options, args.out, notify=lambda text: print(text, file=sys.stderr),
                   progress=progress)
    finally:
        if tty and shown:
            print(file=sys.stderr)
