"""``iik run``: plan, validate and execute a trajectory on a PowerCube arm (simulated by default).

Sources of the trajectory (one of):

* ``SCENARIO`` (a TOML file, or the name of a shipped scenario such as ``j``): planned
  by ``iik.planning.pipeline.plan_scenario`` (the thesis planner of Sec 3.6 with
  ``iik.solve`` at every step-point, whole-arm Coal clearance, fallbacks);
* ``--trajectory FILE.csv`` with columns ``t,q1..q6`` [s, rad]; the planned poses are
  then FK of the file's joints, so the FK check cannot catch a wrong IK there;
* ``--demo``: a straight line between two poses, 30 mm step-points (Sec 4.2.1), IK
  by ``iik.solve`` and the least-effort solution (Eq 54) at each step.

Without ``--interface`` the arm is simulated in-process (``hardware.sim.SimulatedArm``
on a private ``virtual`` bus). ``--interface udp_multicast`` talks to a separate
``iik sim-arm``; ``--interface socketcan --channel can0 --bitrate 500000`` (or any
python-can interface) drives real modules.

Writes ``OUT/<name>.jsonl`` (the run log) and three PNG figures, prints the
end-effector error summary (Sec 4.3).
"""

from __future__ import annotations

import contextlib
import math
import sys
from pathlib import Path

NAME = "run"
HELP = "plan, validate and execute a trajectory on the (simulated by default) PowerCube arm"


def add_arguments(p) -> None:
    p.add_argument("scenario", nargs="?", default=None,
                   help="scenario TOML file, or the name of a shipped scenario (e.g. j)")
    p.add_argument("--trajectory", type=Path, default=None, metavar="CSV",
                   help="joint trajectory file with columns t,q1..q6 [s, rad]")
    p.add_argument("--demo", action="store_true", help="a built-in straight-line demo trajectory")
    p.add_argument("--interface", default=None,
                   help="python-can interface (default: an in-process simulated arm)")
    p.add_argument("--channel", default=None, help="bus channel (e.g. can0, 239.74.163.2)")
    p.add_argument("--bitrate", type=int, default=None, help="bit rate [bit/s], e.g. 500000")
    p.add_argument("--port", type=int, default=None, help="UDP port (udp_multicast only)")
    p.add_argument("--modules", type=int, nargs=6, default=[1, 2, 3, 4, 5, 6], metavar="ID",
                   help="the six module ids in joint order (default: 1..6)")
    p.add_argument("--timeout", type=float, default=None,
                   help="ACK timeout [s] (default: 0.1 on a real bus, 0.5 for the in-process simulation, "
                        "whose threads share one interpreter)")
    p.add_argument("--early", type=float, default=0.95,
                   help="send the next step after this fraction of the previous one (Sec 4.3: 0.95)")
    p.add_argument("--update", choices=("thesis", "buffered"), default="thesis",
                   help="thesis: the next step replaces the current one at 95 %% (Sec 4.3); buffered: it "
                        "waits in the modules' step buffer, so no step is cut")
    p.add_argument("--speed", type=float, default=0.5,
                   help="fraction of the joint speed limits used to time the steps")
    p.add_argument("--margin-deg", type=float, default=0.5, help="margin inside Table I [deg]")
    p.add_argument("--lag", type=float, default=0.02, help="simulated tracking lag [s]")
    p.add_argument("--sim-start", choices=("home", "plan"), default="home",
                   help="simulated arm starts at q = 0 (home) or at the trajectory start")
    p.add_argument("--watchdog", action="store_true",
                   help="enable the modules' watchdog during the run (they stop if this process dies)")
    p.add_argument("--reset", action="store_true", help="RESET every module before the run")
    p.add_argument("--home", action="store_true", help="HOME modules whose HOME_OK is clear")
    p.add_argument("--out", type=Path, default=Path("runs"), help="output folder (default: ./runs)")
    p.add_argument("--no-figures", action="store_true", help="skip the PNG figures")


# ----------------------------------------------------------------------------- main
def run(args) -> int:
    import can

    from hardware import PowerCubeArm, analyse, execute, read_run_log, validate
    from hardware.analysis import plot_run, summary_text
    from hardware.errors import BusError
    from hardware.executor import ExecutionOptions, ValidationOptions
    from hardware.sim import simulated_arm
    from hardware.sources import csv_trajectory, demo_trajectory, scenario_trajectory
    from iik.errors import InvalidInputError

    chosen = [x for x in (args.scenario, args.trajectory, args.demo or None) if x is not None]
    if len(chosen) != 1:
        raise InvalidInputError("run", "give exactly one of SCENARIO, --trajectory FILE or --demo")
    free = None
    if args.demo:
        name, times, q, poses = demo_trajectory(args.speed)
    elif args.trajectory is not None:
        name, times, q, poses = csv_trajectory(args.trajectory)
    else:
        name, times, q, poses, free = scenario_trajectory(args.scenario, args.speed)
    traj = validate(times, q, poses, options=ValidationOptions(margin=math.radians(args.margin_deg)),
                    orientation_free=free)
    print(f"{name}: {len(traj)} step-points, {traj.times[-1]:.2f} s planned, validated "
          f"(Table I - {args.margin_deg} deg, speed limits, FK vs planned poses)", file=sys.stderr)

    sim = None
    stack = contextlib.ExitStack()
    if args.interface is None:
        initial = traj.q[0] if args.sim_start == "plan" else None
        sim, arm = stack.enter_context(simulated_arm(args.modules, lag=args.lag, initial=initial,
                                                     timeout=args.timeout or 0.5))
        where = "simulated arm (in-process, virtual bus)"
    else:
        kw = {"port": args.port} if args.port is not None else {}
        arm = PowerCubeArm.from_interface(args.modules, interface=args.interface,
                                          channel=args.channel, bitrate=args.bitrate,
                                          timeout=args.timeout or 0.1, **kw)
        where = f"{args.interface}:{args.channel}"
    args.out.mkdir(parents=True, exist_ok=True)
    log_path = args.out / f"{name}.jsonl"
    try:
        with arm:
            arm.open()
            if args.reset:
                arm.reset()
            if args.home:
                from hardware.protocol import State

                for m, s in zip(arm.modules, arm.states(), strict=True):
                    if not s & State.HOME_OK:
                        m.home()
                arm.wait_homed()

            tty = sys.stderr.isatty()

            def progress(k, n):
                if tty:
                    print(f"\r  executing on {where}: step {k}/{n}", end="", file=sys.stderr, flush=True)
                elif k == 1 or k == n or k % max(1, n // 10) == 0:
                    print(f"  executing on {where}: step {k}/{n}", file=sys.stderr, flush=True)

            try:
                opts = ExecutionOptions(early=args.early, update=args.update, watchdog=args.watchdog)
                result = execute(arm, traj, log_path, options=opts, progress=progress)
            finally:
                if tty:
                    print(file=sys.stderr)
    except can.CanError as exc:
        raise BusError(str(exc)) from exc
    finally:
        stack.close()
    analysis = analyse(read_run_log(result.log_path))
    print(summary_text(analysis, name))
    if sim is not None:
        rests = sum(len(m.stops) for m in sim.modules.values())
        changes = len(sim.modules) * max(len(traj) - 2, 0)
        print(f"  simulated joints came to rest between two steps {rests} times (of {changes} step "
              f"changes; update {args.update}, early {args.early})")
    print(f"run log: {result.log_path} ({result.commands} commands, {result.samples} samples, "
          f"{result.duration:.2f} s)")
    if not args.no_figures:
        for p in plot_run(analysis, args.out, name):
            print(f"figure: {p}")
    return 0
