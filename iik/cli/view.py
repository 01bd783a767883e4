"""``iik view``: the 3D web viewer -- a pose and all its IK solutions, interactive IK, a plan, a run log.

Serves on http://127.0.0.1:PORT until Ctrl-C (``--host`` to listen elsewhere),
or writes a page that opens from disk with ``--export DIR``. Units: m and rad,
or degrees with ``--deg``.
"""

from __future__ import annotations

import sys
from pathlib import Path

NAME = "view"
HELP = "3D web viewer: a pose (--q, --xyz/--zxz), interactive IK (no target), a plan (SCENARIO), a run log"


def add_arguments(p) -> None:
    p.add_argument("scenario", nargs="?", default=None,
                   help="scenario file, or a shipped scenario name (e.g. j): plan it and play the plan")
    p.add_argument("--q", nargs=6, type=float, default=None, metavar="Q",
                   help="a configuration [rad, deg with --deg]")
    p.add_argument("--xyz", nargs=3, type=float, default=None, metavar=("X", "Y", "Z"),
                   help="tool position [m]")
    p.add_argument("--zxz", nargs=3, type=float, default=None, metavar=("A", "B", "G"),
                   help="Eq 42 Euler angles alpha beta gamma [rad, deg with --deg]")
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


def run(args) -> int:
    import numpy as np

    from iik.errors import InvalidInputError
    from iik.planning.viewer import ExportResult, ViewOptions, ViewRequest, view

    ang = (lambda v: None if v is None else tuple(np.radians(v) if args.deg else v))
    opts = ViewOptions(host=args.host, port=args.port, export=args.export, force=args.force)
    if args.run is not None:
        if args.scenario or args.q or args.xyz or args.zxz:
            raise InvalidInputError("--run", "show a run log alone (no scenario or pose)")
        from hardware.view import view_run

        shown = view_run(args.run, opts)
    else:
        xyz = None if args.xyz is None else tuple(args.xyz)
        req = ViewRequest(scenario=args.scenario, q=ang(args.q), xyz=xyz, zxz=ang(args.zxz),
                          previous=ang(args.previous), interactive=args.interactive)
        shown = view(req, opts)
    for w in shown.warnings:
        print(f"iik view: warning: {w}", file=sys.stderr)
    print(shown.headline)
    res = shown.result
    if isinstance(res, ExportResult):
        print(f"wrote {res.path / 'index.html'} ({res.size / 1e6:.2f} MB, {res.frames} frame(s), "
              f"{res.seconds:.2f} s): open it in a browser, no server needed")
        return 0
    print(f"viewer at {res.url}  (Ctrl-C to stop)", flush=True)
    try:
        res.serve_forever()
    except KeyboardInterrupt:  # Ctrl-C before serve_forever took SIGINT over: the same clean stop
        res.stop()
    print("viewer stopped")
    return 0
