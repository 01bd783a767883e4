"""A pick-and-place scenario as a frozen dataclass, and its geometric checks.

Units: positions [m] in the arm's base frame 0; angles [rad] (Z-Y-Z Euler
angles of the corrected Eq 42, which the thesis calls Z-X-Z). :class:`Waypoint`
and :class:`Scenario` check every value on construction (finite numbers of the
right type, within the bounds below) and raise :class:`~iik.planning.ScenarioError`
naming the field. The file
loader (:mod:`iik.planning.scenario_io`) converts file units and frames and
then calls :func:`check_scenario` for the geometric checks: start, goal and
requested via-points outside every box, the platform and the floor, and
inside the workspace (``in_workspace`` / ``closest_reachable`` callables,
bound to the arm by the loader), and the path's step-points within
:data:`~iik.planning.MAX_STEP_POINTS`. Messages give points in the frame the
file was written in and say which (``frame``).

Bounds that keep a plan's memory and time bounded (ours; the thesis has no
such limits): coordinates within :data:`MAX_COORDINATE` of the base, at most
:data:`MAX_OBSTACLES` boxes, angles within :data:`MAX_ANGLE`, at most
:data:`MAX_STEPS_PER_SEGMENT` fixed steps per segment and
:data:`~iik.planning.MAX_STEP_POINTS` step-points per path.
"""

from __future__ import annotations

import math
import numbers
import reprlib
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from ..arm import Arm
from ..errors import InvalidInputError
from ..scene import Box
from .errors import ScenarioError
from .obstacles import SAFETY_ZONE
from .path import MAX_STEP, MAX_STEP_POINTS, segment_length, segment_steps
from .viapoints import via_point_path

__all__ = ["Waypoint", "Scenario", "check_scenario", "check_step_points", "finite_number", "point3", "brief",
           "MAX_COORDINATE", "MAX_OBSTACLES", "MAX_ANGLE", "MAX_STEPS_PER_SEGMENT", "FRAMES"]

#: Largest absolute coordinate of any point or box centre, and largest box dimension [m] (a scene bound).
MAX_COORDINATE = 100.0
#: Most boxes in one scenario.
MAX_OBSTACLES = 100
#: Largest absolute Euler angle [rad] (one full turn).
MAX_ANGLE = 2 * math.pi
#: Largest fixed number of steps per segment.
MAX_STEPS_PER_SEGMENT = 10000
#: The frames a scenario file can be written in: the arm's base frame 0, or x, y of the base
#: frame with z the height above the floor.
FRAMES = ("base", "floor")


_BRIEF = reprlib.Repr()
_BRIEF.maxlevel, _BRIEF.maxlist, _BRIEF.maxdict, _BRIEF.maxstring, _BRIEF.maxother = 3, 5, 5, 60, 60


def brief(v) -> str:
    """A short ``repr`` of a value for a message (long strings, deep or long lists cut with ``...``)."""
    return _BRIEF.repr(v)


def finite_number(v, field: str, *, lo: float = -math.inf, hi: float = math.inf, unit: str = "") -> float:
    """``v`` as a float if it is a real number in ``[lo, hi]``, else a :class:`ScenarioError` (``field``)."""
    if isinstance(v, (bool, np.bool_)) or not isinstance(v, numbers.Real):
        raise ScenarioError(field, f"expected a number, got {brief(v)}")
    x = float(v)
    if not math.isfinite(x):
        raise ScenarioError(field, f"expected a finite number, got {brief(v)}")
    if not lo <= x <= hi:
        rng = (f"at most {hi:g}" if lo == -math.inf else f"at least {lo:g}" if hi == math.inf
               else f"in [{lo:g}, {hi:g}]")
        raise ScenarioError(field, f"must be {rng}{unit}, got {brief(v)}")
    return x


def point3(v, field: str, bound: float = MAX_COORDINATE) -> tuple[float, float, float]:
    """``v`` as three finite coordinates [m] within ``+-bound``; else a :class:`ScenarioError`."""
    if isinstance(v, (str, bytes, dict)) or not hasattr(v, "__len__") or len(v) != 3:
        raise ScenarioError(field, f"expected a list of 3 numbers, got {brief(v)}")
    return tuple(finite_number(x, f"{field}[{i}]", lo=-bound, hi=bound, unit=" m") for i, x in enumerate(v))


@dataclass(frozen=True)
class Waypoint:
    """An end-effector target: tool point and Z-Y-Z orientation (corrected Eq 42).

    Attributes:
        position: Tool point (3,) [m], base frame.
        alpha, beta, gamma: Euler angles [rad] (Eq 42). ``alpha=None`` means
            "any alpha" (Sec 3.6: alpha does not tilt the tool): the planner
            uses the azimuth-facing alpha' of Eq 46, ``atan2(py, px)``.

    Raises:
        ScenarioError: A value is not a finite number (``position[i]``, ``beta``, ...)
            or outside :data:`MAX_COORDINATE` / :data:`MAX_ANGLE`.
    """

    position: tuple[float, float, float]
    alpha: float | None
    beta: float
    gamma: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "position", point3(self.position, "position"))
        for name in ("alpha", "beta", "gamma"):
            v = getattr(self, name)
            if not (name == "alpha" and v is None):
                v = finite_number(v, name, lo=-MAX_ANGLE, hi=MAX_ANGLE, unit=" rad")
                object.__setattr__(self, name, v)


@dataclass(frozen=True)
class Scenario:
    """Everything the planner needs for one task.

    Attributes:
        name: Short id (file stem), e.g. ``"j"``.
        title: The thesis caption, e.g. ``"Fig 42j: from the top of one table to another"``.
        reference: Thesis figure/section.
        reconstruction: What in the scenario is reconstructed (not printed).
        start, goal: :class:`Waypoint`.
        obstacles: Boxes (obstacles and supports), base frame.
        via_points: ``None`` = choose by Table IV (:mod:`~iik.planning.viapoints`);
            otherwise the requested (k, 3) via-points [m]: the tool passes through
            each of them (Sec 4.2.1: "must pass through such via-points"), or the plan fails.
        segments: Per-segment route ``"line"`` or ``"arc"`` (len = k + 1; needs
            explicit ``via_points``), or ``None`` = all lines.
        steps_per_segment: Fixed steps per segment (39 in Sec 4.2.1) or ``None`` (by ``max_step``).
        max_step: Largest step [m] (30 mm, Sec 4.2.1).
        orientation: ``"euler"`` (gradual Euler change, thesis) or ``"slerp"``.
        mode: ``"LEI"`` (dense Cartesian steps) or ``"LJI"`` (joint interpolation).
        safety_zone: Ellipsoid padding and required whole-arm clearance [m].
        arm: The arm the task is for (:class:`iik.Arm`; a file's ``arm =`` key names it), or None when
            the scenario names none: :func:`~iik.planning.plan` then needs one given.
        source: Where it was loaded from (for messages).

    Raises:
        ScenarioError: A field has the wrong type, a non-finite or out-of-range value
            (named as in the file, e.g. ``planning.via_points[1][2]``).
    """

    name: str
    start: Waypoint
    goal: Waypoint
    title: str = ""
    reference: str = ""
    reconstruction: str = ""
    obstacles: tuple[Box, ...] = ()
    via_points: tuple[tuple[float, float, float], ...] | None = None
    segments: tuple[str, ...] | None = None
    steps_per_segment: int | None = None
    max_step: float = MAX_STEP
    orientation: str = "euler"
    mode: str = "LEI"
    safety_zone: float = SAFETY_ZONE
    arm: Arm | None = None
    source: str = field(default="", compare=False)

    def __post_init__(self) -> None:
        self._check_texts()
        for fld in ("start", "goal"):
            if not isinstance(getattr(self, fld), Waypoint):
                raise ScenarioError(fld, f"expected a Waypoint, got {type(getattr(self, fld)).__name__}")
        self._check_obstacles()
        self._check_route()
        if self.arm is not None and not isinstance(self.arm, Arm):
            raise ScenarioError("arm", f"expected an iik.Arm or None, got {type(self.arm).__name__}")
        set_ = object.__setattr__
        set_(self, "max_step", finite_number(self.max_step, "planning.max_step", hi=0.5, unit=" m"))
        if self.max_step <= 0:
            raise ScenarioError("planning.max_step", f"must be in (0, 0.5] m, got {brief(self.max_step)}")
        set_(self, "safety_zone", finite_number(self.safety_zone, "planning.safety_zone", lo=0.0, hi=0.5,
                                                unit=" m"))
        for fld, allowed in (("orientation", ("euler", "slerp")), ("mode", ("LEI", "LJI"))):
            v = getattr(self, fld)
            if not isinstance(v, str) or v not in allowed:
                raise ScenarioError(f"planning.{fld}",
                                    f"expected {' or '.join(map(repr, allowed))}, got {brief(v)}")

    def _check_texts(self) -> None:
        for fld in ("name", "title", "reference", "reconstruction", "source"):
            if not isinstance(getattr(self, fld), str):
                raise ScenarioError(fld, f"expected a string, got {type(getattr(self, fld)).__name__}")
        n = self.name
        if not n or n in (".", "..") or len(n) > 200 or any(c in "/\\" or ord(c) < 0x20 for c in n):
            raise ScenarioError("name", f"{brief(n)} cannot name an output folder (1-200 characters, no path "
                                        "separators or control characters)")

    def _check_obstacles(self) -> None:
        if not isinstance(self.obstacles, (tuple, list)) or len(self.obstacles) > MAX_OBSTACLES:
            raise ScenarioError("obstacles", f"expected at most {MAX_OBSTACLES} boxes")
        for k, b in enumerate(self.obstacles):
            if not isinstance(b, Box):
                raise ScenarioError(f"obstacles[{k}]", f"expected a Box, got {type(b).__name__}")
            point3(b.center, f"obstacles[{k}].center")
            point3(b.size, f"obstacles[{k}].size", 2 * MAX_COORDINATE)
        object.__setattr__(self, "obstacles", tuple(self.obstacles))

    def _check_route(self) -> None:
        """Via-points, segments and steps per segment."""
        set_ = object.__setattr__
        if self.via_points is not None:
            if isinstance(self.via_points, (str, bytes, dict)) or not hasattr(self.via_points, "__len__"):
                raise ScenarioError("planning.via_points",
                                    f"expected a list of points, got {brief(self.via_points)}")
            if len(self.via_points) > MAX_STEP_POINTS - 2:  # each adds a step-point
                raise ScenarioError("planning.via_points", f"{len(self.via_points)} via-points; at most "
                                                           f"{MAX_STEP_POINTS - 2} are allowed")
            set_(self, "via_points", tuple(point3(v, f"planning.via_points[{i}]")
                                           for i, v in enumerate(self.via_points)))
        if self.segments is not None:
            if self.via_points is None:
                raise ScenarioError("planning.segments", "needs explicit planning.via_points (the Table IV "
                                                         "via-points are chosen when planning)")
            if isinstance(self.segments, (str, bytes)) or not hasattr(self.segments, "__len__"):
                raise ScenarioError("planning.segments", "expected a list of 'line'/'arc'")
            if len(self.segments) != len(self.via_points) + 1:
                raise ScenarioError(
                    "planning.segments",
                    f"needs {len(self.via_points) + 1} entries (via-points + 1), got {len(self.segments)}")
            for i, s in enumerate(self.segments):
                if not isinstance(s, str) or s not in ("line", "arc"):
                    raise ScenarioError(f"planning.segments[{i}]",
                                        f"expected 'line' or 'arc', got {brief(s)}")
            set_(self, "segments", tuple(self.segments))
        n = self.steps_per_segment
        if n is not None:
            if isinstance(n, (bool, np.bool_)) or not isinstance(n, numbers.Integral):
                raise ScenarioError("planning.steps_per_segment", f"expected an integer, got {brief(n)}")
            if not 1 <= n <= MAX_STEPS_PER_SEGMENT:
                raise ScenarioError("planning.steps_per_segment",
                                    f"must be an integer in 1..{MAX_STEPS_PER_SEGMENT}, got {brief(n)}")
            set_(self, "steps_per_segment", int(n))


def check_step_points(sc: Scenario, keys: np.ndarray | None = None,
                      routes: tuple[str, ...] | None = None) -> int:
    """Number of step-points of ``sc``'s path before repulsion; a :class:`ScenarioError` above the limit.

    Args:
        sc: The scenario.
        keys: (k + 2, 3) start, via-points and goal [m]; default: those of ``sc``
            (Table IV via-points when ``sc.via_points`` is None).
        routes: Route per segment; default ``sc.segments`` or all lines.

    Raises:
        ScenarioError: (``planning.max_step`` or ``planning.steps_per_segment``) more than
            :data:`~iik.planning.MAX_STEP_POINTS` step-points; the message gives the
            smallest ``max_step`` that fits.
    """
    if keys is None:
        vias = (via_point_path(sc.start.position, sc.goal.position)[0] if sc.via_points is None
                else sc.via_points)
        keys = np.vstack([sc.start.position, np.reshape(vias, (-1, 3)), sc.goal.position])
    routes = routes or sc.segments or ("line",) * (len(keys) - 1)
    counts = [segment_steps(a, b, route=r, max_step=sc.max_step, n_steps=sc.steps_per_segment)
              for a, b, r in zip(keys[:-1], keys[1:], routes, strict=True)]
    n = 1 + sum(counts)
    if n <= MAX_STEP_POINTS:
        return n
    if sc.steps_per_segment is not None:
        raise ScenarioError("planning.steps_per_segment",
                            f"{sc.steps_per_segment} steps on each of {len(counts)} segments give {n} "
                            f"step-points; at most {MAX_STEP_POINTS} are allowed (bounded memory and time)")
    length = sum(segment_length(a, b, route=r) for a, b, r in zip(keys[:-1], keys[1:], routes, strict=True))
    fits = length / (MAX_STEP_POINTS - 1 - len(counts))  # then every segment has <= len/max_step + 1 steps
    unit = 10.0 ** (math.floor(math.log10(max(fits, 1e-12))) - 2)  # three significant digits, rounded up
    raise ScenarioError("planning.max_step",
                        f"{sc.max_step:g} m divides the {length:.3f} m path into {n} step-points; at most "
                        f"{MAX_STEP_POINTS} are allowed (bounded memory and time): use max_step >= "
                        f"{math.ceil(fits / unit) * unit:.3g} m")


@dataclass(frozen=True)
class _Frame:
    """The frame points are shown in: the file's (``"floor"``: z above the floor at ``floor_z``)."""

    name: str = "base"
    floor_z: float = 0.0

    def to_file(self, p) -> np.ndarray:
        return np.asarray(p, float) - [0.0, 0.0, self.floor_z if self.name == "floor" else 0.0]

    def to_base(self, p) -> np.ndarray:
        return np.asarray(p, float) + [0.0, 0.0, self.floor_z if self.name == "floor" else 0.0]

    def show(self, p) -> str:
        """``"[x, y, z] m (floor frame)"`` with mm precision."""
        return "[" + ", ".join(f"{v:.3f}" for v in self.to_file(p)) + f"] m ({self.name} frame)"


@dataclass(frozen=True)
class _Placement:
    """The checks of one point of a scenario (start, goal, a via-point)."""

    obstacles: tuple[Box, ...]
    platform: Box | None
    floor_z: float | None
    in_workspace: Callable | None
    frame: _Frame

    def blocked(self, p: np.ndarray) -> str | None:
        """Why ``p`` [m] cannot be a point of the path (inside a box, the platform, below the floor)."""
        for k, box in enumerate(self.obstacles):
            if box.contains(p):
                return f"{self.frame.show(p)} lies inside {box.kind} {brief(box.name)} (obstacles[{k}])"
        if self.platform is not None and self.platform.contains(p):
            return f"{self.frame.show(p)} lies inside the mobile platform"
        if self.floor_z is not None and p[2] < self.floor_z:
            z = self.frame.to_file([0.0, 0.0, self.floor_z])[2]
            return f"{self.frame.show(p)} is below the floor (z = {z:.3f} m in the {self.frame.name} frame)"
        return None

    def reachable(self, p: np.ndarray) -> bool:
        return self.in_workspace is None or bool(np.asarray(self.in_workspace(p)).reshape(-1)[0])

    def suggest(self, p: np.ndarray, closest_reachable: Callable) -> str:
        """The closest reachable point, rounded to mm in the file's frame so that pasting it passes."""
        c = np.asarray(closest_reachable(p), float).reshape(-1)[:3]
        inward = (c - p) / max(float(np.linalg.norm(c - p)), 1e-12)
        best = c
        for k in range(11):  # step up to 10 mm inwards until the rounded point passes every check
            q = self.frame.to_base(np.round(self.frame.to_file(c + 1e-3 * k * inward), 3))
            if self.blocked(q) is None and self.reachable(q):
                best = q
                break
        away = float(np.linalg.norm(best - p))
        return (f"; closest reachable point {self.frame.show(best)} "
                + (f"({away * 1000:.0f} mm away)" if away < 1 else f"({away:.3f} m away)"))


def check_scenario(sc: Scenario, *, platform: Box | None = None, floor_z: float | None = None,
                   in_workspace: Callable | None = None, closest_reachable: Callable | None = None,
                   frame: str = "base") -> None:
    """Raise :class:`~iik.planning.ScenarioError` if the task is impossible as stated.

    Checks (Sec 3.6.1: "the initial and final points were verified to be inside
    the manipulator workspace ... also checked to be outside the mobile robot
    base and any obstacles"), for the start, the goal and every requested via-point:

    * not inside any box, the platform, or below the floor;
    * inside the workspace (if ``in_workspace`` is given), with the closest
      reachable point in the message (``closest_reachable``), rounded so that
      pasting it into the file passes these checks;
    * then the path has at most :data:`~iik.planning.MAX_STEP_POINTS` step-points
      (:func:`check_step_points`).

    Args:
        frame: The frame of the file (``"base"`` or ``"floor"``, which needs
            ``floor_z``): points in messages are given in it.
    """
    if frame not in FRAMES or (frame == "floor" and floor_z is None):
        raise InvalidInputError("frame", f"expected 'base', or 'floor' with floor_z, got {frame!r}")
    place = _Placement(sc.obstacles, platform, floor_z, in_workspace, _Frame(frame, floor_z or 0.0))
    points = [("start.position", sc.start.position), ("goal.position", sc.goal.position)]
    points += [(f"planning.via_points[{i}]", v) for i, v in enumerate(sc.via_points or ())]
    for fld, v in points:
        p = np.asarray(v, float)
        if (why := place.blocked(p)) is not None:
            raise ScenarioError(fld, why)
        if not place.reachable(p):
            hint = place.suggest(p, closest_reachable) if closest_reachable is not None else ""
            raise ScenarioError(fld, f"{place.frame.show(p)} is outside the workspace{hint}")
    check_step_points(sc)
