"""``iik run``: plan, validate and execute a trajectory on a PowerCube arm (simulated by default).

Sources of the trajectory (one of):

* ``SCENARIO`` (a TOML file, or the name of a shipped scenario such as ``j``): planned
  by ``verification.pipeline.plan_scenario`` (the thesis planner of Sec 3.6 with
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
import time
import uuid
from pathlib import Path

import numpy as np

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


# ----------------------------------------------------------------------------- sources
def demo_trajectory(speed: float = 0.5):
    """(name, times, q, poses): a 30 mm-step straight line between two poses, IK per step."""
    from scipy.spatial.transform import Rotation, Slerp

    import iik
    from hardware.executor import time_steps

    qa = np.array([0.5, 0.1, 0.0, 0.4, 1.0, 0.0])  # away from the wrist singularity (q5 = 0)
    qb = np.array([0.0, 0.4, 0.0, 0.4, 1.0, 0.0])
    Ta, Tb = iik.fk(qa), iik.fk(qb)
    dist = float(np.linalg.norm(Tb[:3, 3] - Ta[:3, 3]))
    n = max(2, math.ceil(dist / 0.030)) + 1  # <= 30 mm per step (Sec 4.2.1)
    s = np.linspace(0.0, 1.0, n)
    slerp = Slerp([0.0, 1.0], Rotation.from_matrix(np.stack([Ta[:3, :3], Tb[:3, :3]])))
    poses = np.tile(np.eye(4), (n, 1, 1))
    poses[:, :3, :3] = slerp(s).as_matrix()
    poses[:, :3, 3] = (1 - s)[:, None] * Ta[:3, 3] + s[:, None] * Tb[:3, 3]
    q = np.empty((n, 6))
    prev = qa
    for k, T in enumerate(poses):
        q[k] = prev = iik.select(iik.solve(T), prev)  # Eq 54: least effort from the previous
    return "demo", time_steps(q, speed_fraction=speed), q, poses


def csv_trajectory(path: Path):
    """(name, times, q, poses) from a CSV with columns t,q1..q6; poses = FK(q)."""
    import iik
    from iik.errors import InvalidInputError

    try:
        data = np.genfromtxt(path, delimiter=",", names=True, dtype=float)
    except (OSError, ValueError) as exc:
        raise InvalidInputError("trajectory", f"cannot read {path}: {exc}") from None
    cols = ["t", "q1", "q2", "q3", "q4", "q5", "q6"]
    if data.dtype.names is None or any(c not in data.dtype.names for c in cols):
        raise InvalidInputError("trajectory", f"{path} needs the header columns {','.join(cols)}")
    data = np.atleast_1d(data)
    t = np.asarray(data["t"], dtype=float)
    q = np.stack([np.asarray(data[c], dtype=float) for c in cols[1:]], axis=1)
    if not np.all(np.isfinite(q)) or not np.all(np.isfinite(t)):
        raise InvalidInputError("trajectory", f"{path} contains empty or non-numeric cells")
    return path.stem, t, q, iik.fk(q)


def scenario_trajectory(name: str, speed: float = 0.5):
    """(name, times, q, poses, orientation_free) for a scenario, planned by
    :func:`verification.pipeline.plan_scenario` (thesis planner, Sec 3.6, with its
    fallbacks and the whole-arm Coal check).

    The planned poses are those of the thesis Cartesian path; where the planner
    changed alpha/beta (Sec 3.6) only the position is checked. For an RRT-Connect
    fallback path there is no Cartesian plan and the poses are FK of the joints.
    """
    from hardware.executor import time_steps
    from iik.errors import ScenarioError
    from iik.kinematics import fk
    from iik.planning import poses_of
    from iik.resources import scenarios_dir
    from verification.pipeline import PlanningFailed, PlanOptions, plan_scenario

    path = Path(name)
    if not path.is_file():
        shipped = scenarios_dir() / f"{name}.toml"
        if path.suffix or len(path.parts) > 1 or not shipped.is_file():
            names = ", ".join(sorted(f.stem for f in scenarios_dir().glob("*.toml")))
            raise ScenarioError("scenario", f"{name!r} is neither a scenario file nor a shipped "
                                f"scenario ({names})")
        path = shipped
    res = plan_scenario(path, options=PlanOptions(timing=False))
    if not res.success:
        raise PlanningFailed(res)
    q = np.asarray(res.q, dtype=float)
    cart = res.cartesian
    free = np.zeros(len(q), dtype=bool)
    if cart is not None and len(cart.points) == len(q):
        poses = poses_of(np.asarray(cart.points), np.asarray(cart.euler))
        free[list(res.beta_changed_steps) + list(res.alpha_changed_steps)
             + list(res.gamma_changed_steps)] = True
    else:
        print(f"{res.scenario.name}: planned by {res.method}; no Cartesian plan, poses are FK of the "
              "joints", file=sys.stderr)
        poses = fk(q)
    print(f"{res.scenario.name}: planned via {res.method} ({len(q)} step-points, min whole-arm clearance "
          f"{res.min_clearance * 1e3:.1f} mm)", file=sys.stderr)
    return res.scenario.name, time_steps(q, speed_fraction=speed), q, poses, free


# ----------------------------------------------------------------------------- simulated arm
@contextlib.contextmanager
def simulated_arm(module_ids=(1, 2, 3, 4, 5, 6), *, lag: float = 0.02, initial=None,
                  timeout: float = 0.5, clock=time.monotonic):
    """Yield ``(sim, arm)``: an in-process :class:`hardware.sim.SimulatedArm` on a private
    ``virtual`` channel and a :class:`hardware.PowerCubeArm` talking to it.

    Host and simulated modules are threads of this process, so the interpreter's
    switch interval is shortened meanwhile (request round trips stay short) and
    restored on exit; both the arm's bus and the simulator are closed on exit.
    ``clock`` is the simulator's time source [s] (pass the same one to ``execute``).
    """
    import can

    from hardware import PowerCubeArm, SimulatedArm

    channel = f"iik-run-{uuid.uuid4().hex}"
    switch = sys.getswitchinterval()
    sys.setswitchinterval(0.0005)
    try:
        with SimulatedArm.virtual(channel, module_ids, lag=lag, initial=initial, clock=clock) as sim, \
                PowerCubeArm(can.Bus(interface="virtual", channel=channel), module_ids, timeout=timeout,
                             owns_bus=True) as arm:
            yield sim, arm
    finally:
        sys.setswitchinterval(switch)


# ----------------------------------------------------------------------------- main
def run(args) -> int:
    import can

    from hardware import PowerCubeArm, analyse, execute, read_run_log, validate
    from hardware.analysis import plot_run, summary_text
    from hardware.errors import BusError
    from hardware.executor import ExecutionOptions, ValidationOptions
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
