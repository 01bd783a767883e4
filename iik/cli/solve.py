"""``iik solve``: all inverse-kinematics solutions of one pose.

The pose is a position [m] and the Euler angles of the corrected Eq 42, Z-Y-Z (``--zyz``;
``--zxz`` is its deprecated alias: the thesis calls Eq 42 Z-X-Z, see :mod:`iik.rotations`)
in rad, or in degrees with ``--deg``. Prints every solution with its FK residuals, the
joint-limit flag and the Eq 54 effort index to ``--previous`` (a configuration inside
Table I, read in degrees with ``--deg`` like the angles). A position beyond the arm's
reach that would be within it in millimetres gets a warning. Exit 0 if a solution was
found, 1 if none (unreachable, or none inside Table I).
"""

from __future__ import annotations

import json

import numpy as np

from .arm_option import add_arm_argument, chosen_arm
from .options import add_pose_arguments, joint_angles, warn_degrees, warn_millimetres

NAME = "solve"
HELP = "all IK solutions of a pose given as --xyz X Y Z --zyz ALPHA BETA GAMMA (exit 1 if none)"


def add_arguments(p) -> None:
    add_pose_arguments(p, required=True)
    add_arm_argument(p)
    p.add_argument("--deg", action="store_true", help="angles in and out in degrees")
    p.add_argument("--previous", nargs=6, type=float, default=None, metavar="Q",
                   help="previous joint angles, inside Table I (for the Eq 54 effort index)")
    p.add_argument("--method", choices=("complete", "thesis"), default="complete",
                   help="complete: the compiled elimination, every solution (default); thesis: the IIK of "
                        "Sec 3.3 as printed (theta1 grid + bisection, errata corrected), which can miss some")
    p.add_argument("--all", action="store_true", help="also list solutions outside the joint limits")
    p.add_argument("--json", action="store_true", help="machine-readable output")
    p.spelling.update(q_prev="--previous", previous_q="--previous")  # the library's names as typed


def run(args) -> int:
    import iik
    from iik.ik import select_index
    from iik.kinematics import reach_bound

    arm = chosen_arm(args)
    warn_degrees(NAME, args, ("--zyz", "--previous"))
    warn_millimetres(NAME, args.xyz, reach_bound(arm))
    conv_in = np.radians if args.deg else np.asarray
    prev = None if args.previous is None else joint_angles(args.previous, "--previous", args.deg, arm)
    with np.errstate(all="ignore"):  # absurd inputs (--xyz 1e308) are unreachable, not warnings
        T = iik.pose_from_euler(np.array(args.xyz), *conv_in(args.zyz))
        with iik.ik.compile_notice():  # one line on stderr if the kernel compiles (not when it loads)
            res = iik.solve(T, arm, method=args.method, within_limits=not args.all)
        efforts = iik.effort_index(prev, res.q) if (prev is not None and res.count) else None
    best = None
    if prev is not None and np.any(res.within_limits):  # Eq 54: least effort inside the limits
        best = int(np.flatnonzero(res.within_limits)[select_index(res, prev, arm=arm)[0]])
    conv = np.degrees if args.deg else (lambda x: x)
    if args.json:
        out = res.to_dict(degrees=args.deg)
        out["arm"] = arm.name
        out["pose"] = {"xyz_m": list(args.xyz), "zyz": list(args.zyz),
                       "zxz": list(args.zyz),  # deprecated duplicate of "zyz" (the old, wrong name)
                       "angle_unit": "deg" if args.deg else "rad"}
        if efforts is not None:
            for s, e in zip(out["solutions"], np.atleast_1d(efforts), strict=True):
                s["effort_index"] = float(conv(e))
            out["selected"] = best
        print(json.dumps(out, indent=2))
        return 0 if res.count else 1
    unit = "deg" if args.deg else "rad"
    if res.count == 0:
        print(f"no solution: {res.reason}")
        return 1
    print(f"{res.count} solution(s) ({args.method}, arm {arm.name}), joint angles in {unit}:")
    for i in range(res.count):
        q = " ".join(f"{v:9.4f}" for v in conv(res.q[i]))
        extra = ""
        if efforts is not None:
            extra = f"  E={float(conv(np.atleast_1d(efforts)[i])):.4f} {unit}"
            extra += "  <- selected" if i == best else ""
        free = f"  free joints {res.free_joints[i]}" if res.free_joints[i] else ""
        lim = "in limits" if res.within_limits[i] else "OUT of limits"
        print(f"[{i:2d}] {q}   |dp|={res.position_residual[i]:.1e} m  "
              f"|dR|={res.rotation_residual[i]:.1e} rad  {lim}{extra}{free}")
    return 0
