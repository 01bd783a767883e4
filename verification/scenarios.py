"""Load pick-and-place scenarios from TOML files into :class:`iik.planning.Scenario`.

File format (all keys documented in ``scenarios/README.md``)::

    name = "j"
    title = "Fig 42j: from the top of one table to another while avoiding an obstacle"
    reference = "Sec 4.2.2, Fig 42j, Figs 43-44"
    reconstruction = "What is reconstructed ..."
    frame = "floor"        # "floor": z is the height above the floor; "base": arm base frame 0
    [start]
    position = [0.45, 0.30, 0.86]   # m
    beta_deg = 0.0                  # Z-X-Z (corrected Eq 42) angles in degrees;
    alpha_deg = 0.0                 # omit alpha_deg for "any alpha" (Sec 3.6)
    gamma_deg = 0.0
    [goal]
    ...
    [planning]                      # all optional
    via_points = "auto"             # or [[x, y, z], ...] in the file's frame
    segments = ["line", "arc", "line"]
    steps_per_segment = 39
    max_step = 0.03
    orientation = "euler"           # or "slerp"
    safety_zone = 0.03
    [[obstacles]]
    name = "box"
    center = [0.5, 0.0, 0.95]
    size = [0.2, 0.3, 0.3]          # full width (x), depth (y), height (z) [m]
    kind = "obstacle"               # or "support" (a table the object stands on)

Every problem is a :class:`iik.errors.ScenarioError` naming the field: TOML
syntax errors (with line/column), missing or mistyped keys, unknown keys,
and impossible tasks (start/goal in an obstacle, the platform, below the
floor, or outside the workspace -- with the closest reachable point).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from iik.errors import IIKError, ScenarioError
from iik.planning.obstacles import Box
from iik.planning.scenario import Scenario, Waypoint, check_scenario
from iik.resources import scenarios_dir
from iik.scene import THESIS_SCENE, Scene

try:  # Python >= 3.11
    import tomllib
except ModuleNotFoundError:  # pragma: no cover - Python 3.10
    import tomli as tomllib

__all__ = ["load_scenario", "scenario_from_dict", "thesis_scenario_paths", "platform_box",
           "validate_scenario", "dexterity_notes"]

_TOP = {"name", "title", "reference", "reconstruction", "frame", "start", "goal", "planning", "obstacles"}
_WP = {"position", "alpha_deg", "beta_deg", "gamma_deg"}
_PLAN = {"via_points", "segments", "steps_per_segment", "max_step", "orientation", "safety_zone", "mode"}
_OBS = {"name", "center", "size", "kind"}


def thesis_scenario_paths() -> list[Path]:
    """The shipped scenario files, sorted (predefined paths p1..p3, then a..j)."""
    return sorted(scenarios_dir().glob("*.toml"), key=lambda p: (not p.stem.startswith("p"), p.stem))


def platform_box(scene: Scene = THESIS_SCENE) -> Box:
    """The scene's platform as a planning :class:`Box` (kind ``support``)."""
    p = scene.platform
    return Box(tuple(p.center), tuple(p.size), name="platform", kind="support")


def load_scenario(path, *, scene: Scene = THESIS_SCENE, check_workspace: bool = True) -> Scenario:
    """Read and validate one scenario file (see the module docstring)."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise ScenarioError("file", f"{path} does not exist") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise ScenarioError("file", f"cannot read {path}: {exc}") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ScenarioError("file", f"{path.name} is not valid TOML: {exc}") from None
    sc = scenario_from_dict(data, source=str(path), default_name=path.stem, scene=scene)
    validate_scenario(sc, scene=scene, check_workspace=check_workspace)
    return sc


def validate_scenario(sc: Scenario, *, scene: Scene = THESIS_SCENE, check_workspace: bool = True) -> None:
    """Geometric and workspace checks of Sec 3.6.1 (raises :class:`ScenarioError`)."""
    kw = {}
    if check_workspace:
        from iik import closest_reachable, in_workspace

        kw = {"in_workspace": in_workspace, "closest_reachable": lambda p: closest_reachable(p).point}
    check_scenario(sc, platform=platform_box(scene), floor_z=scene.floor.z, **kw)


def dexterity_notes(sc: Scenario) -> list[str]:
    """Sec 3.6 asks for beta within the dexterity range (Sec 3.5); say where start/goal are not.

    Advisory only: the Sec 3.5 model ignores the joint limits of joints 3-6 and is
    stricter than the complete IK in places (a beta it rejects can have IK solutions),
    so the planner decides by IK, not by this range.
    """
    from iik import dexterity
    from iik.errors import InvalidInputError

    notes = []
    for fld, wp in (("start", sc.start), ("goal", sc.goal)):
        try:
            dexterity(np.asarray(wp.position, float), beta=wp.beta)
        except InvalidInputError as exc:
            if getattr(exc, "argument", "") != "beta":
                raise
            notes.append(f"{fld}.beta_deg = {math.degrees(wp.beta):.1f} deg is outside the Sec 3.5 dexterity "
                         f"range ({exc.reason})")
    return notes
