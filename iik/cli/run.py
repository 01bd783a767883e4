"""``iik run``: plan, validate and execute a trajectory on a PowerCube arm (simulated by default).

Sources of the trajectory (one of): ``SCENARIO`` (a TOML file, or the name of a shipped
scenario such as ``j``), planned and timed exactly as ``iik plan`` writes it; ``--trajectory
FILE.csv`` with columns ``t,q1..q6`` [s, rad] (``iik plan``'s ``steps.csv`` or ``trajectory.csv``
as written); ``--demo``, a straight line with 30 mm step-points (Sec 4.2.1). Without
``--interface`` the arm is simulated in-process; ``--interface udp_multicast`` talks to a
separate ``iik sim-arm``; ``--interface socketcan --channel can0 --bitrate 500000`` (or any
python-can interface) drives real modules, with their watchdog on (``--no-watchdog``). Arm: the
scenario's or ``--arm`` (default thesis for a trajectory file or the demo). Writes a new run log
``OUT/<name>-<date>-<time>.jsonl`` (or the ``--out FILE.jsonl``) and three PNG figures, prints
the end-effector error summary (Sec 4.3); its last stdout line is the status on every path
(:func:`hardware.runner.failure_status` when the run raised). Exit 0: the run went to the end
inside its safety zone; 1: it went to the end but its error left the zone; 2: an error (nothing
moved, or HALT after a fault); 128 + N: stopped by signal N (HALT sent). The work is
:func:`hardware.runner.run`.
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

from .arm_option import add_arm_argument, chosen_arm
from .options import millimetres

NAME = "run"
HELP = "plan, validate and execute a trajectory on the (simulated by default) PowerCube arm"


def add_arguments(p) -> None:
    p.add_argument("scenario", nargs="?", default=None,
                   help="scenario TOML file, or the name of a shipped scenario (e.g. j)")
    p.add_argument("--trajectory", type=Path, default=None, metavar="CSV",
                   help="joint trajectory file with columns t,q1..q6 [s, rad], e.g. iik plan's steps.csv")
    p.add_argument("--demo", action="store_true", help="a built-in straight-line demo trajectory")
    add_arm_argument(p, data="the scenario's")
    p.add_argument("--interface", default=None, help="python-can interface (default: simulated arm)")
    p.add_argument("--channel", default=None, help="bus channel (e.g. can0, 239.74.163.2)")
    p.add_argument("--bitrate", type=int, default=None,
                   help="bit rate [bit/s]: 125000, 250000, 500000 or 1000000")
    p.add_argument("--port", type=int, default=None, help="UDP port (udp_multicast only)")
    p.add_argument("--modules", type=int, nargs=6, default=[1, 2, 3, 4, 5, 6], metavar="ID",
                   help="the six module ids in joint order (default: 1..6)")
    p.add_argument("--timeout", type=float, default=None, help="ACK timeout (0, 10] s (default: 0.1 on "
                   "a bus, 2 for the in-process simulation, whose threads share one interpreter)")
    p.add_argument("--early", type=float, default=0.95,
                   help="send the next step after this fraction of the previous one (Sec 4.3: 0.95)")
    p.add_argument("--update", choices=("thesis", "buffered"), default="thesis",
                   help="thesis: the next step replaces the current one at 95 %% (Sec 4.3); buffered: it "
                        "waits in the modules' step buffer, so no step is cut")
    p.add_argument("--speed", type=float, default=1.0, help="run at this fraction (0, 1] of the "
                   "planned or written speed: every step lasts 1/SPEED as long (default 1)")
    p.add_argument("--margin-deg", type=float, default=None, help="margin inside Table I [deg] (default 0.5)")
    p.add_argument("--zone-mm", type=float, default=None, help="largest end-effector error of an ok run "
                   "(0, 1000] mm (default: the scenario's safety zone; 10 mm, Sec 4.3.1, for a file or demo)")
    p.add_argument("--lag", type=float, default=0.02, help="simulated tracking lag [0, 1] s")
    p.add_argument("--sim-start", choices=("home", "plan"), default="home",
                   help="simulated arm starts at q = 0 (home) or at the trajectory start")
    p.add_argument("--watchdog", action=argparse.BooleanOptionalAction, default=None,
                   help="the modules' watchdog: a broadcast every 40 ms, they stop if it stays away "
                        "(default: on for a bus interface, off for the in-process simulation)")
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


def _run(args):  # -> hardware.runner.RunReport
    from hardware.runner import MAX_ZONE, RunRequest
    from hardware.runner import run as run_request

    given = {"arm": chosen_arm(args, data=args.scenario is not None)}  # the library's defaults unless typed
    given |= {"margin": math.radians(args.margin_deg)} if args.margin_deg is not None else {}
    given |= {"zone": millimetres(args.zone_mm, "--zone-mm", MAX_ZONE)} if args.zone_mm is not None else {}
    request = RunRequest(
        scenario=args.scenario, trajectory=args.trajectory, demo=args.demo, interface=args.interface,
        channel=args.channel, bitrate=args.bitrate, port=args.port, modules=tuple(args.modules),
        timeout=args.timeout, early=args.early, update=args.update, speed=args.speed, lag=args.lag,
        sim_start=args.sim_start, watchdog=args.watchdog, reset=args.reset, home=args.home, out=args.out,
        figures=not args.no_figures, **given)
    tty, shown = sys.stderr.isatty(), []

    def progress(k: int, n: int) -> None:
        shown.append(k)
        line = f"  executing on {request.where}: step {k}/{n}"
        if tty:
            print("\r" + line, end="", file=sys.stderr, flush=True)
        elif k == 1 or k == n or k % max(1, n // 10) == 0:
            print(line, file=sys.stderr, flush=True)

    try:
        return run_request(request, notify=lambda text: print(text, file=sys.stderr), progress=progress)
    finally:
        if tty and shown:
            print(file=sys.stderr)
