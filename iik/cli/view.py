"""``iik view``: the 3D web viewer -- a pose and all its IK solutions, interactive IK, a plan, a run log.

Serves on http://127.0.0.1:PORT until Ctrl-C (``--host`` to listen elsewhere),
or writes a page that opens from disk with ``--export DIR``. Units: m and rad,
or degrees with ``--deg``.
"""

from __future__ import annotations

import sys
from pathlib import Path

from .arm_option import add_arm_argument, chosen_arm
from .options import add_pose_arguments, joint_angles, warn_degrees, warn_millimetres

NAME = "view"
HELP = "3D web viewer: a pose (--q, --xyz/--zyz), interactive IK (no target), a plan (SCENARIO), a run log"
EPILOG = ("A --q outside the joint limits (Table I) is bad input: one-line error, exit 2, nothing shown or "
          "written; with --allow-outside-limits it is shown, the links its offending joints move in red, "
          "with a one-line warning on stderr, exit 0. Exit status: 0 shown; 1 shown, but the plan failed or "
          "timed out (as iik plan); 2 bad input (nothing shown or written).")


def add_arguments(p) -> None:
    p.epilog = EPILOG
    p.add_argument("scenario", nargs="?", default=None,
                   help="scenario file or shipped name (e.g. j): plan it, play the plan, list its attempts; "
                        "a plan that fails or times out is shown with its reason and best attempt")
    add_arm_argument(p, data="the scenario's or run log's")
    p.add_argument("--timeout", type=float, default=None, metavar="SECONDS",
                   help="with SCENARIO: stop planning after this many seconds (default 60)")
    p.add_argument("--no-fallbacks", action="store_true",
                   help="with SCENARIO: thesis planner only (no other branches, redesigns or RRT-Connect)")
    p.add_argument("--q", nargs=6, type=float, default=None, metavar="Q",
                   help="a configuration [rad, deg with --deg]")
    p.add_argument("--allow-outside-limits", action="store_true",
                   help="show a --q outside Table I (those links red, a warning) instead of refusing it")
    add_pose_arguments(p, required=False)
    p.add_argument("--deg", action="store_true", help="angles in degrees")
    p.add_argument("--previous", nargs=6, type=float, default=None, metavar="Q",
                   help="reference configuration of the Eq 54 effort index (default: --q, else q = 0)")
    p.add_argument("--interactive", action="store_true", help="add a draggable gizmo for the tool pose")
    p.add_argument("--run", type=Path, default=None, metavar="LOG",
                   help="a log of iik run (runs/NAME-DATE-TIME.jsonl): commanded and measured arms")
    p.add_argument("--port", type=int, default=8080, help="TCP port (default 8080)")
    p.add_argument("--host", default="127.0.0.1",
                   help="interface to listen on (default 127.0.0.1: this machine only)")
    p.add_argument("--export", type=Path, default=None, metavar="DIR",
                   help="write a self-contained page DIR/index.html instead of serving")
    p.add_argument("--force", action="store_true", help="with --export: replace a non-empty DIR")
    p.spelling.update(planning="--timeout/--no-fallbacks")  # ViewRequest.planning: what these options set


def _request(args, arm):
    """The :class:`~iik.planning.viewer.ViewRequest` of the command line (angles to rad)."""
    import numpy as np

    from iik.planning import PlanOptions
    from iik.planning.viewer import ViewRequest

    ang = (lambda v: None if v is None else tuple(np.radians(v) if args.deg else v))
    plan = ({} if args.timeout is None else {"timeout": args.timeout}) | (
        {"fallbacks": False, "rrt": False} if args.no_fallbacks else {})
    previous = None if args.previous is None else tuple(joint_angles(args.previous, "--previous", args.deg,
                                                                     arm or chosen_arm(args)))
    return ViewRequest(arm=arm, scenario=args.scenario, planning=PlanOptions(**plan) if plan else None,
                       q=ang(args.q),
                       xyz=None if args.xyz is None else tuple(args.xyz), zxz=ang(args.zyz),
                       previous=previous, interactive=args.interactive,
                       allow_outside_limits=args.allow_outside_limits)


def run(args) -> int:
    from iik.extras import require

    require("viewer", "iik view")  # first: importing iik.planning would name only its own extra
    from iik.errors import InvalidInputError
    from iik.kinematics import reach_bound
    from iik.planning.viewer import ExportResult, ViewOptions, view

    arm = chosen_arm(args, data=args.scenario is not None or args.run is not None)  # None: the data's own
    warn_degrees(NAME, args, ("--q", "--zyz", "--previous"))
    warn_millimetres(NAME, args.xyz, reach_bound(arm or chosen_arm(args)))
    opts = ViewOptions(host=args.host, port=args.port, export=args.export, force=args.force)
    if args.run is not None:
        if args.scenario or args.q or args.xyz or args.zyz:
            raise InvalidInputError("--run", "show a run log alone (no scenario or pose)")
        from hardware.view import view_run

        shown = view_run(args.run, opts, arm=arm)
    else:
        shown = view(_request(args, arm), opts)
    for w in shown.warnings:
        print(f"iik view: warning: {w}", file=sys.stderr)
    print(shown.headline)
    for line in shown.details:
        print(f"  - {line}")
    res = shown.result
    if isinstance(res, ExportResult):
        print(f"wrote {res.path / 'index.html'} ({res.size / 1e6:.2f} MB, {res.frames} frame(s), "
              f"{res.seconds:.2f} s): open it in a browser, no server needed")
    else:
        try:
            print(f"viewer at {res.url}  (Ctrl-C to stop)", flush=True)
            res.serve_forever()
        except KeyboardInterrupt:  # Ctrl-C before serve_forever took SIGINT over: the same clean stop
            res.stop()
        print("viewer stopped")
    return 0 if shown.ok else 1
