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
from iik.planning.obstacles import Obstacle
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


def platform_box(scene: Scene = THESIS_SCENE) -> Obstacle:
    """The scene's platform as a planning :class:`Obstacle` (kind ``support``)."""
    p = scene.platform
    return Obstacle(tuple(p.center), tuple(p.size), name="platform", kind="support")


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


def _num(v, field: str) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise ScenarioError(field, f"expected a finite number, got {v!r}")
    return float(v)


def _vec(v, field: str, n: int = 3) -> np.ndarray:
    if not isinstance(v, list) or len(v) != n:
        raise ScenarioError(field, f"expected a list of {n} numbers, got {v!r}")
    return np.array([_num(x, f"{field}[{i}]") for i, x in enumerate(v)])


def _table(d, field: str, allowed: set[str]) -> dict:
    if not isinstance(d, dict):
        raise ScenarioError(field, f"expected a table, got {type(d).__name__}")
    extra = sorted(set(d) - allowed)
    if extra:
        raise ScenarioError(f"{field}.{extra[0]}" if field else extra[0],
                            f"unknown key (allowed: {', '.join(sorted(allowed))})")
    return d


def scenario_from_dict(data: dict, *, source: str = "", default_name: str = "scenario",
                       scene: Scene = THESIS_SCENE) -> Scenario:
    """Build a :class:`Scenario` from parsed TOML (no validation against the workspace)."""
    _table(data, "", _TOP)
    frame = data.get("frame", "base")
    if frame not in ("base", "floor"):
        raise ScenarioError("frame", f"expected 'base' or 'floor', got {frame!r}")
    dz = scene.floor.z if frame == "floor" else 0.0  # floor frame: z = height above the floor

    def pos(v, field):
        p = _vec(v, field)
        p[2] += dz
        return p

    def wp(key):
        if key not in data:
            raise ScenarioError(key, "missing (needs position and beta_deg)")
        d = _table(data[key], key, _WP)
        if "position" not in d:
            raise ScenarioError(f"{key}.position", "missing")
        if "beta_deg" not in d:
            raise ScenarioError(f"{key}.beta_deg", "missing")
        a = d.get("alpha_deg")
        return Waypoint(tuple(pos(d["position"], f"{key}.position")),
                        None if a is None else math.radians(_num(a, f"{key}.alpha_deg")),
                        math.radians(_num(d["beta_deg"], f"{key}.beta_deg")),
                        math.radians(_num(d.get("gamma_deg", 0.0), f"{key}.gamma_deg")))

    for k in ("name", "title", "reference", "reconstruction"):
        if k in data and not isinstance(data[k], str):
            raise ScenarioError(k, "expected a string")
    start, goal = wp("start"), wp("goal")
    plan = _table(data.get("planning", {}), "planning", _PLAN)
    vias = plan.get("via_points", "auto")
    if vias == "auto":
        vias = None
    elif isinstance(vias, list):
        vias = tuple(tuple(pos(v, f"planning.via_points[{i}]")) for i, v in enumerate(vias))
    else:
        raise ScenarioError("planning.via_points", f"expected 'auto' or a list of points, got {vias!r}")
    segs = plan.get("segments")
    if segs is not None:
        if not isinstance(segs, list) or not all(isinstance(s, str) for s in segs):
            raise ScenarioError("planning.segments", "expected a list of 'line'/'arc'")
        segs = tuple(segs)
    steps = plan.get("steps_per_segment")
    if steps is not None and (isinstance(steps, bool) or not isinstance(steps, int)):
        raise ScenarioError("planning.steps_per_segment", f"expected an integer, got {steps!r}")
    obstacles = []
    obs = data.get("obstacles", [])
    if not isinstance(obs, list):
        raise ScenarioError("obstacles", "expected an array of tables ([[obstacles]])")
    for i, o in enumerate(obs):
        f = f"obstacles[{i}]"
        _table(o, f, _OBS)
        for k in ("center", "size"):
            if k not in o:
                raise ScenarioError(f"{f}.{k}", "missing")
        try:
            obstacles.append(Obstacle(tuple(pos(o["center"], f"{f}.center")),
                                      tuple(_vec(o["size"], f"{f}.size")),
                                      name=str(o.get("name", f"obstacle{i}")),
                                      kind=str(o.get("kind", "obstacle"))))
        except ScenarioError:
            raise
        except IIKError as exc:
            raise ScenarioError(f, getattr(exc, "reason", str(exc))) from None
    kw = {}
    for key in ("max_step", "safety_zone"):
        if key in plan:
            kw[key] = float(_num(plan[key], f"planning.{key}"))
    for key in ("orientation", "mode"):
        if key in plan:
            kw[key] = plan[key]
    return Scenario(name=str(data.get("name", default_name)), start=start, goal=goal,
                    title=data.get("title", ""), reference=data.get("reference", ""),
                    reconstruction=data.get("reconstruction", ""), obstacles=tuple(obstacles),
                    via_points=vias, segments=segs, steps_per_segment=steps, source=source, **kw)
