"""Scenario files (TOML): load and validate into :class:`iik.planning.Scenario`, and write back.

File format (all keys documented in ``scenarios/README.md``)::

    name = "j"
    arm = "thesis"         # the arm: a shipped name (iik.arms.NAMES) or a URDF file (relative to this file)
    title = "Fig 42j: from the top of one table to another while avoiding an obstacle"
    reference = "Sec 4.2.2, Fig 42j, Figs 43-44"
    reconstruction = "What is reconstructed ..."
    frame = "floor"        # "floor": z is the height above the floor; "base": arm base frame 0
    [start]
    position = [0.45, 0.30, 0.86]   # m
    beta_deg = 0.0                  # Z-Y-Z (corrected Eq 42) angles in degrees (or beta = ... in rad);
    alpha_deg = 0.0                 # omit alpha for "any alpha" (Sec 3.6)
    gamma_deg = 0.0
    [goal]
    ...
    [planning]                      # all optional
    via_points = "auto"             # or [[x, y, z], ...] in the file's frame
    segments = ["line", "arc", "line"]
    steps_per_segment = 39
    max_step = 0.03
    orientation = "euler"           # or "slerp"
    mode = "LEI"                    # or "LJI"
    safety_zone = 0.03
    [[obstacles]]
    name = "box"
    center = [0.5, 0.0, 0.95]
    size = [0.2, 0.3, 0.3]          # full width (x), depth (y), height (z) [m]
    kind = "obstacle"               # or "support" (a table the object stands on)

A scenario is for one arm: the file's ``arm`` key names it, or the caller gives it
(``load_scenario(path, arm=...)``; a file that names another arm is refused). The loaded
:class:`Scenario` carries it (:attr:`Scenario.arm`), and the workspace checks are that arm's.

Every problem is a :class:`iik.planning.ScenarioError` naming the field: an
unreadable file (missing, not a regular file, not UTF-8, over :data:`MAX_FILE_SIZE`:
read by :func:`iik.files.read_text`, which stops there; nested too deeply), TOML syntax
errors (with line/column), missing or mistyped keys, unknown keys, values outside the
bounds of :mod:`iik.planning.scenario`, and impossible tasks (start, goal or a
requested via-point in an obstacle, the platform, below the floor, or outside the
workspace of the arm -- with the closest reachable point -- or a path of too many
step-points). Points in messages are in the file's frame, and the message says which.

:func:`scenario_to_toml` / :func:`write_scenario` write the base frame and
every field, so ``load_scenario(write_scenario(sc, path)) == sc`` exactly:
angles are written in degrees where a decimal degree value reads back to the
same radians, else in radians (``beta = ...``).
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np

from iik.arm import Arm
from iik.errors import FileError, InvalidInputError, Remedy
from iik.files import read_text, write_text
from iik.resources import scenarios_dir
from iik.scene import THESIS_SCENE, Box, Scene

from .errors import ScenarioError
from .scenario import (
    FRAMES,
    MAX_ANGLE,
    MAX_COORDINATE,
    MAX_OBSTACLES,
    Scenario,
    Waypoint,
    brief,
    check_scenario,
    finite_number,
    point3,
)

try:  # Python >= 3.11
    import tomllib
except ModuleNotFoundError:  # pragma: no cover - Python 3.10
    import tomli as tomllib

__all__ = ["load_scenario", "scenario_from_dict", "scenario_to_toml", "write_scenario", "scenario_path",
           "thesis_scenario_paths", "shipped_scenario_paths", "validate_scenario",
           "dexterity_notes", "scenario_arm",
           "MAX_FILE_SIZE"]

#: Largest scenario file [bytes] (a shipped one is about 2 kB).
MAX_FILE_SIZE = 1_000_000

_TOP = {"name", "arm", "title", "reference", "reconstruction", "frame", "start", "goal", "planning",
        "obstacles"}
_ANGLES = ("alpha", "beta", "gamma")
_WP = {"position", *_ANGLES, *(f"{a}_deg" for a in _ANGLES)}
_PLAN = {"via_points", "segments", "steps_per_segment", "max_step", "orientation", "safety_zone", "mode"}
_OBS = {"name", "center", "size", "kind"}


def shipped_scenario_paths() -> list[Path]:
    """Every shipped scenario file, sorted (predefined paths p1..p3, then the others by name)."""
    return sorted(scenarios_dir().glob("*.toml"), key=lambda p: (not p.stem.startswith("p"), p.stem))


def thesis_scenario_paths() -> list[Path]:
    """The shipped scenarios of the thesis (its arm: ``arm = "thesis"``), sorted (p1..p3, then a..j)."""
    return [p for p in shipped_scenario_paths()
            if tomllib.loads(read_text(p, "file", limit=MAX_FILE_SIZE, what="a scenario file")).get("arm")
            == "thesis"]


def scenario_path(scenario: str | Path) -> Path:
    """The file of ``scenario``: a file name (with a suffix or a folder) or a shipped scenario's name.

    Raises:
        ScenarioError: (field ``scenario``) a bare name that is neither a file nor a shipped
            scenario; the message lists the shipped names.
    """
    path = Path(scenario)
    if path.exists() or path.suffix or len(path.parts) > 1:
        return path  # a file name: load_scenario says if it is missing or not a regular file
    shipped = scenarios_dir() / f"{path.name}.toml"
    if shipped.is_file():
        return shipped
    names = ", ".join(p.stem for p in shipped_scenario_paths())
    raise ScenarioError("scenario", f"{str(scenario)!r} is neither a scenario file nor a shipped scenario "
                                    f"({names})")


def load_scenario(path, *, arm: Arm | None = None, scene: Scene = THESIS_SCENE,
                  check_workspace: bool = True) -> Scenario:
    """Read and validate one scenario file (see the module docstring) in ``scene``.

    Args:
        arm: The arm to plan for; None: the one the file names (its ``arm`` key). A file that names
            another arm (other numbers, :func:`iik.arms.same_arm`) is refused.

    Returns:
        The :class:`Scenario`, carrying its arm (:attr:`Scenario.arm`).

    Raises:
        ScenarioError: see the module docstring; (field ``arm``) the file names no arm and none is
            given, names an unknown arm or an unusable URDF, or names another arm than ``arm``.
    """
    path = Path(path)
    try:
        text = read_text(path, "file", limit=MAX_FILE_SIZE, what="a scenario file")
    except FileError as exc:
        raise ScenarioError("file", exc.reason) from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ScenarioError("file", f"{path.name} is not valid TOML: {exc}") from None
    except RecursionError:
        raise ScenarioError("file", f"{path.name} nests arrays or tables too deeply") from None
    sc = scenario_from_dict(data, source=str(path), default_name=path.stem, scene=scene,
                            relative_to=path.parent)
    sc = dataclasses.replace(sc, arm=scenario_arm(sc, arm))
    validate_scenario(sc, arm=sc.arm, scene=scene, check_workspace=check_workspace,
                      frame=data.get("frame", "base"))
    return sc


def scenario_arm(sc: Scenario, arm: Arm | None) -> Arm:
    """The arm to plan ``sc`` for: ``arm`` if given, else the scenario's own; both given, they must be
    the same arm (:func:`iik.arms.same_arm`).

    Raises:
        ScenarioError: (field ``arm``) neither is given, or they differ.
    """
    from iik.arms import same_arm

    if arm is not None and not isinstance(arm, Arm):
        raise InvalidInputError("arm", f"expected an iik.Arm, got {type(arm).__name__}")
    if sc.arm is None and arm is None:
        raise ScenarioError("arm", f"scenario {sc.name!r} names no arm and none was given: add arm = "
                                   "\"NAME\" (a shipped arm, iik.arms.NAMES) or arm = \"path/to.urdf\" to "
                                   "the file", Remedy("or give one as {}", "arm"))
    if sc.arm is not None and arm is not None and not same_arm(sc.arm, arm):
        raise ScenarioError("arm", f"scenario {sc.name!r} is for the arm {sc.arm.name!r}, not {arm.name!r} "
                                   "(its positions, reach and obstacles were laid out for it)")
    return sc.arm if arm is None else arm


def validate_scenario(sc: Scenario, *, arm: Arm, scene: Scene = THESIS_SCENE,
                      check_workspace: bool = True, frame: str = "base") -> None:
    """Geometric and workspace (of ``arm``) checks of Sec 3.6.1 (raises :class:`ScenarioError`).

    For an arm not of the thesis's Table II form the workspace test is the numerical search of
    :func:`iik.workspace.in_workspace` (Sec 3.4.4 is written for the thesis's form).

    ``frame``: the frame of the file ``sc`` came from (``"base"`` or ``"floor"``); messages
    give points in it.
    """
    kw = {}
    if check_workspace:
        from iik.workspace import closest_reachable, in_workspace

        kw = {"in_workspace": lambda p: in_workspace(p, arm),
              "closest_reachable": lambda p: closest_reachable(p, arm).point}
    check_scenario(sc, platform=scene.platform, floor_z=scene.floor.z, frame=frame, **kw)


def dexterity_notes(sc: Scenario, arm: Arm) -> list[str]:
    """Sec 3.6 asks for beta within the dexterity range (Sec 3.5); say where start/goal are not.

    Exact (:func:`iik.dexterity.alpha_intervals`, on the complete IK): a note when no alpha with
    the waypoint's beta has an IK solution within the arm's limits at its position. Advisory: the
    planner decides by IK along the whole path.
    """
    from iik.dexterity import alpha_intervals

    notes = []
    for fld, wp in (("start", sc.start), ("goal", sc.goal)):
        try:
            found = alpha_intervals(np.asarray(wp.position, float), wp.beta, arm)
        except InvalidInputError as exc:
            notes.append(f"{fld}: the dexterity at this point was not computed ({exc})")
            continue
        if not found:
            notes.append(f"{fld}.beta_deg = {math.degrees(wp.beta):.1f} deg is outside the dexterity range "
                         "(no alpha with this beta has an IK solution within the joint limits here; "
                         "iik.dexterity)")
    return notes


def _vec(v, field: str, bound: float = MAX_COORDINATE) -> np.ndarray:
    """Three numbers of the file [m] within ``+-bound`` (a list, not a string or a table)."""
    if not isinstance(v, list):
        raise ScenarioError(field, f"expected a list of 3 numbers, got {brief(v)}")
    return np.array(point3(v, field, bound))


def _angle(d: dict, table: str, name: str) -> float | None:
    """Angle ``name`` [rad] of a waypoint table, given in degrees (``<name>_deg``) or rad; None if absent."""
    if name in d and f"{name}_deg" in d:
        raise ScenarioError(f"{table}.{name}", f"given twice (as {name} [rad] and {name}_deg)")
    if f"{name}_deg" in d:
        deg = math.degrees(MAX_ANGLE)
        return math.radians(finite_number(d[f"{name}_deg"], f"{table}.{name}_deg", lo=-deg, hi=deg,
                                          unit=" deg"))
    if name in d:
        return finite_number(d[name], f"{table}.{name}", lo=-MAX_ANGLE, hi=MAX_ANGLE, unit=" rad")
    return None


def _table(d, field: str, allowed: set[str]) -> dict:
    if not isinstance(d, dict):
        raise ScenarioError(field, f"expected a table, got {type(d).__name__}")
    extra = sorted(set(d) - allowed)
    if extra:
        raise ScenarioError(f"{field}.{extra[0]}" if field else extra[0],
                            f"unknown key (allowed: {', '.join(sorted(allowed))})")
    return d


def scenario_from_dict(data: dict, *, source: str = "", default_name: str = "scenario",
                       scene: Scene = THESIS_SCENE, relative_to=None) -> Scenario:
    """Build a :class:`Scenario` from parsed TOML (no validation against the workspace).

    ``relative_to``: the folder a relative URDF path in the ``arm`` key is read from (the file's
    folder; default: the working directory)."""
    _table(data, "", _TOP)
    frame = data.get("frame", "base")
    if not isinstance(frame, str) or frame not in FRAMES:
        raise ScenarioError("frame", f"expected 'base' or 'floor', got {brief(frame)}")
    dz = scene.floor.z if frame == "floor" else 0.0  # floor frame: z = height above the floor
    for k in ("name", "title", "reference", "reconstruction"):
        if k in data and not isinstance(data[k], str):
            raise ScenarioError(k, f"expected a string, got {brief(data[k])}")
    start, goal = _waypoint(data, "start", dz), _waypoint(data, "goal", dz)
    plan = _table(data.get("planning", {}), "planning", _PLAN)
    return Scenario(name=str(data.get("name", default_name)), start=start, goal=goal,
                    title=data.get("title", ""), reference=data.get("reference", ""),
                    reconstruction=data.get("reconstruction", ""), obstacles=_obstacles(data, dz),
                    arm=_arm(data, relative_to), source=source, **_planning(plan, dz))


def _arm(data: dict, relative_to) -> Arm | None:
    """The arm the file's ``arm`` key names (None without the key)."""
    from iik.arms import resolve

    if "arm" not in data:
        return None
    text = data["arm"]
    if not isinstance(text, str) or not text:
        raise ScenarioError("arm", f"expected a shipped arm's name or a URDF file, got {brief(text)}")
    try:
        return resolve(text, relative_to=relative_to)
    except InvalidInputError as exc:  # unknown name, a URDF that does not parse or is outside the class
        raise ScenarioError("arm", f"{text!r}: {exc}") from None


def _position(v, field: str, dz: float) -> tuple[float, float, float]:
    """A point [m] of the file, in the base frame (``dz``: the file frame's z offset)."""
    p = _vec(v, field)
    p[2] += dz
    return tuple(p)


def _waypoint(data: dict, key: str, dz: float) -> Waypoint:
    if key not in data:
        raise ScenarioError(key, "missing (needs position and beta_deg)")
    d = _table(data[key], key, _WP)
    if "position" not in d:
        raise ScenarioError(f"{key}.position", "missing")
    if "beta_deg" not in d and "beta" not in d:
        raise ScenarioError(f"{key}.beta_deg", "missing")
    alpha, beta, gamma = (_angle(d, key, a) for a in _ANGLES)
    position = _position(d["position"], f"{key}.position", dz)
    try:
        return Waypoint(position, alpha, beta, 0.0 if gamma is None else gamma)
    except ScenarioError as exc:  # a bound crossed by the frame shift: name the field as in the file
        raise ScenarioError(f"{key}.{exc.field}", exc.reason) from None


def _planning(plan: dict, dz: float) -> dict:
    """The ``[planning]`` table as :class:`Scenario` keyword arguments."""
    kw = {}
    vias = plan.get("via_points", "auto")
    if isinstance(vias, list):
        kw["via_points"] = tuple(_position(v, f"planning.via_points[{i}]", dz) for i, v in enumerate(vias))
    elif vias != "auto":
        raise ScenarioError("planning.via_points", f"expected 'auto' or a list of points, got {brief(vias)}")
    segs = plan.get("segments")
    if segs is not None:
        if not isinstance(segs, list) or not all(isinstance(s, str) for s in segs):
            raise ScenarioError("planning.segments", "expected a list of 'line'/'arc'")
        kw["segments"] = tuple(segs)
    steps = plan.get("steps_per_segment")
    if steps is not None:
        if isinstance(steps, bool) or not isinstance(steps, int):
            raise ScenarioError("planning.steps_per_segment", f"expected an integer, got {brief(steps)}")
        kw["steps_per_segment"] = steps
    for key in ("max_step", "safety_zone"):
        if key in plan:
            kw[key] = finite_number(plan[key], f"planning.{key}", unit=" m")
    for key in ("orientation", "mode"):
        if key in plan:
            kw[key] = plan[key]
    return kw


def _obstacles(data: dict, dz: float) -> tuple[Box, ...]:
    obs = data.get("obstacles", [])
    if not isinstance(obs, list):
        raise ScenarioError("obstacles", "expected an array of tables ([[obstacles]])")
    if len(obs) > MAX_OBSTACLES:
        raise ScenarioError("obstacles", f"{len(obs)} boxes; at most {MAX_OBSTACLES} are allowed")
    out = []
    for i, o in enumerate(obs):
        f = f"obstacles[{i}]"
        _table(o, f, _OBS)
        for k in ("center", "size"):
            if k not in o:
                raise ScenarioError(f"{f}.{k}", "missing")
        for k in ("name", "kind"):
            if not isinstance(o.get(k, ""), str):
                raise ScenarioError(f"{f}.{k}", f"expected a string, got {brief(o[k])}")
        center = _position(o["center"], f"{f}.center", dz)
        size = tuple(_vec(o["size"], f"{f}.size", 2 * MAX_COORDINATE))
        try:
            out.append(Box(center, size, name=o.get("name", f"obstacle{i}"),
                                kind=o.get("kind", "obstacle")))
        except InvalidInputError as exc:  # the box's own checks (positive size, kind)
            raise ScenarioError(f, exc.reason) from None
    return tuple(out)


def _str(v: str, field: str) -> str:
    """A TOML basic string: quotes, backslashes and control characters escaped."""
    try:
        v.encode("utf-8")
    except UnicodeEncodeError:
        raise ScenarioError(field, f"{brief(v)} is not valid Unicode text") from None
    esc = {'"': '\\"', "\\": "\\\\"}
    return '"' + "".join(esc.get(ch) or (f"\\u{ord(ch):04X}" if ord(ch) < 0x20 or ord(ch) == 0x7F else ch)
                         for ch in v) + '"'


def _float(v, field: str) -> str:
    x = float(v)
    if not math.isfinite(x):
        raise ScenarioError(field, f"cannot write the non-finite value {x!r}")
    return repr(x)


def _point(v, field: str) -> str:
    return "[" + ", ".join(_float(x, f"{field}[{i}]") for i, x in enumerate(v)) + "]"


def _angle_line(name: str, x: float, field: str) -> str:
    """``name_deg = d`` with the shortest d that reads back to ``x`` [rad]; else ``name = x`` [rad]."""
    _float(x, field)
    d = math.degrees(x)
    near = [d]
    lo = hi = d
    for _ in range(8):
        lo, hi = math.nextafter(lo, -math.inf), math.nextafter(hi, math.inf)
        near += [lo, hi]
    exact = [c for c in near if math.radians(c) == x]
    if exact:
        return f"{name}_deg = {min((repr(c) for c in exact), key=len)}"
    return f"{name} = {repr(float(x))}"


def scenario_to_toml(sc: Scenario) -> str:
    """TOML text of ``sc`` in the base frame (loads back to an equal :class:`Scenario`).

    Raises:
        ScenarioError: A number is not finite (the field is named).
    """
    lines = [f"# Scenario {sc.name} (written by iik.planning.write_scenario). Units: m, degrees / rad.",
             f"name = {_str(sc.name, 'name')}"]
    if sc.arm is not None:
        lines.append(f"arm = {_str(_arm_reference(sc.arm), 'arm')}")
    lines += [f"title = {_str(sc.title, 'title')}",
             f"reference = {_str(sc.reference, 'reference')}",
             f"reconstruction = {_str(sc.reconstruction, 'reconstruction')}", 'frame = "base"']
    for key, wp in (("start", sc.start), ("goal", sc.goal)):
        lines += ["", f"[{key}]", f"position = {_point(wp.position, f'{key}.position')}"]
        lines += [_angle_line(a, getattr(wp, a), f"{key}.{a}") for a in _ANGLES if getattr(wp, a) is not None]
    lines += ["", "[planning]"]
    if sc.via_points is not None:
        vias = ", ".join(_point(v, f"planning.via_points[{i}]") for i, v in enumerate(sc.via_points))
        lines.append(f"via_points = [{vias}]")
    if sc.segments is not None:
        lines.append(f"segments = [{', '.join(_str(s, 'planning.segments') for s in sc.segments)}]")
    if sc.steps_per_segment is not None:
        lines.append(f"steps_per_segment = {int(sc.steps_per_segment)}")
    lines += [f"max_step = {_float(sc.max_step, 'planning.max_step')}",
              f"orientation = {_str(sc.orientation, 'planning.orientation')}",
              f"mode = {_str(sc.mode, 'planning.mode')}",
              f"safety_zone = {_float(sc.safety_zone, 'planning.safety_zone')}"]
    for i, b in enumerate(sc.obstacles):
        lines += ["", "[[obstacles]]", f"name = {_str(b.name, f'obstacles[{i}].name')}",
                  f"center = {_point(b.center, f'obstacles[{i}].center')}",
                  f"size = {_point(b.size, f'obstacles[{i}].size')}",
                  f"kind = {_str(b.kind, f'obstacles[{i}].kind')}"]
    return "\n".join(lines) + "\n"


def _arm_reference(arm: Arm) -> str:
    """What a file's ``arm`` key says for ``arm``: its shipped name, else its URDF file."""
    from iik.arms import name_of

    ref = name_of(arm) or arm.urdf
    if not ref:
        raise ScenarioError("arm", f"cannot be written: {arm.name!r} is neither a shipped arm nor read "
                                   "from a URDF file")
    return ref


def write_scenario(sc: Scenario, path) -> Path:
    """Write ``sc`` to ``path`` as TOML (:func:`scenario_to_toml`), whole or not at all
    (:func:`iik.files.write_text`); return the path."""
    path = Path(path)
    text = scenario_to_toml(sc)
    try:
        return write_text(path, "file", text)
    except FileError as exc:
        raise ScenarioError("file", exc.reason) from None
