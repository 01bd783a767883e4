"""The ``--arm`` option every command takes (this module is no command: it has no ``NAME``).

The CLI is the only place that picks a default arm (:data:`DEFAULT_ARM`): below it the arm is an
argument or travels with the data (a scenario's ``arm`` key, a plan, a run log's header).
"""

from __future__ import annotations

__all__ = ["add_arm_argument", "chosen_arm", "DEFAULT_ARM"]

#: The arm a command uses when neither ``--arm`` nor its input (a scenario, a run log) names one.
DEFAULT_ARM = "thesis"


def add_arm_argument(p, *, data: str = "") -> None:
    """``--arm NAME|URDF``: a shipped arm (``iik.arms.NAMES``) or a URDF file. ``data`` names the input
    that may carry its own arm (e.g. "the scenario's"): then that arm is the default, else thesis."""
    from iik.arms import NAMES

    default = f"{data} arm, else {DEFAULT_ARM}" if data else DEFAULT_ARM
    p.add_argument("--arm", default=None, metavar="NAME|URDF",
                   help=f"the arm: a shipped one ({', '.join(NAMES)}) or a URDF file (default: {default})")


def chosen_arm(args, *, data: bool = False):
    """The arm of ``--arm`` (:func:`iik.arms.resolve`); without it None when ``data`` (the input names its
    own arm: a scenario, a run log), else :data:`DEFAULT_ARM`. An unknown name or an unusable URDF is
    the library's typed error, which the CLI prints as one line (exit 2)."""
    from iik.arms import resolve

    if args.arm is None:
        return None if data else resolve(DEFAULT_ARM)
    return resolve(args.arm)
