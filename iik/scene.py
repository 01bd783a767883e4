"""The fixed scene around the arm: the mobile platform and the floor (the one place they are described).

Frame: the arm's base frame 0 of Table II (z up along joint 1, origin on the joint-1
axis at the mounting plane, x along the stretched home pose of Fig 8). Units: m.

Decisions (the thesis gives only the heights):

* Sec 4.2.1: the platform top is **0.45 m** above the floor and a dining table is
  0.80 m high (:data:`PLATFORM_HEIGHT`, :data:`TABLE_HEIGHT`).
* The arm's base (the joint-1 module) stands **on the platform top**, so the mounting
  plane z = 0 is the platform top and **the floor is the plane z = -0.45 m**; a table top
  is at z = 0.80 - 0.45 = +0.35 m (:meth:`Scene.z_at_height`).
* The platform size is not given. It is modelled as an axis-aligned box
  **0.65 m long (x in [-0.55, 0.10]) x 0.50 m wide (y in [-0.25, 0.25]) x 0.45 m high
  (z in [-0.45, 0])**: the arm sits 0.10 m behind the front edge, and the platform
  extends behind it (Sec 3.6.3 calls it "too large to be treated as a regular
  obstacle" and routes paths around it through the via-points of Table III, which lie
  at |y| = 0.5 m, outside this footprint).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from .errors import InvalidInputError
from .validation import as_float_array, as_points

__all__ = [
    "PLATFORM_HEIGHT",
    "TABLE_HEIGHT",
    "KINDS",
    "Box",
    "AxisBox",  # deprecated: Box.from_corners
    "Floor",
    "Scene",
    "THESIS_SCENE",
]

#: Sec 4.2.1: height of the platform top above the floor [m].
PLATFORM_HEIGHT = 0.45
#: Sec 4.2.1: height of a standard dining table above the floor [m].
TABLE_HEIGHT = 0.80
#: What a box is to the planner (:attr:`Box.kind`).
KINDS = ("obstacle", "support")


@dataclass(frozen=True)
class Box:
    """An axis-aligned box in the base frame: the platform, a scenario's obstacle or support (Sec 3.6.2).

    The one box type of the project (:data:`THESIS_SCENE`'s platform, :mod:`iik.planning`'s
    scenario boxes, the viewer's and the run log's).

    Attributes:
        center: Centre (3,) [m], base frame.
        size: Full dimensions (width along x, depth along y, height along z) [m], each positive.
        name: Label for reports.
        kind: ``"obstacle"`` (repels the path, Sec 3.6.2) or ``"support"`` (a table, a shelf or
            the platform something stands on: collision-checked for the whole arm but not
            enclosed in an ellipsoid, since start/goal lie on it).
    """

    center: tuple[float, float, float]
    size: tuple[float, float, float]
    name: str = "box"
    kind: str = "obstacle"

    def __post_init__(self) -> None:
        if not isinstance(self.name, str):
            raise InvalidInputError("name", f"expected a string, got {type(self.name).__name__}")
        c = as_float_array(self.center, f"{self.name}.center").reshape(-1)
        s = as_float_array(self.size, f"{self.name}.size").reshape(-1)
        if c.shape != (3,):
            raise InvalidInputError(f"{self.name}.center", "expected three coordinates [m]")
        if s.shape != (3,) or np.any(s <= 0):
            raise InvalidInputError(f"{self.name}.size", "expected three positive dimensions [m]")
        if self.kind not in KINDS:
            raise InvalidInputError(f"{self.name}.kind", "expected 'obstacle' or 'support'")
        object.__setattr__(self, "center", tuple(float(v) for v in c))
        object.__setattr__(self, "size", tuple(float(v) for v in s))

    @classmethod
    def from_corners(cls, name: str, lower, upper, kind: str = "obstacle") -> Box:
        """The box from corner ``lower`` to corner ``upper`` [m] (each below the other on every axis)."""
        lo = as_float_array(lower, f"{name}.lower").reshape(-1)
        hi = as_float_array(upper, f"{name}.upper").reshape(-1)
        if lo.shape != (3,) or hi.shape != (3,):
            raise InvalidInputError(name, "box corners must be 3 finite numbers each")
        return cls(tuple((lo + hi) / 2), tuple(hi - lo), name=name, kind=kind)

    @property
    def half(self) -> np.ndarray:
        """Half dimensions [m], shape (3,)."""
        return 0.5 * np.asarray(self.size)

    @property
    def lower(self) -> np.ndarray:
        """The corner of least x, y, z [m], shape (3,)."""
        return np.asarray(self.center) - self.half

    @property
    def upper(self) -> np.ndarray:
        """The corner of greatest x, y, z [m], shape (3,)."""
        return np.asarray(self.center) + self.half

    @property
    def corners(self) -> np.ndarray:
        """The eight corners (8, 3) [m]."""
        signs = np.array([[i, j, k] for i in (-1, 1) for j in (-1, 1) for k in (-1, 1)], float)
        return np.asarray(self.center) + signs * self.half

    def contains(self, p, margin: float = 0.0):
        """Is each point ``p`` [m] ((3,) or (n, 3)) inside the box grown by ``margin`` [m]?
        A bool for one point, (n,) bools for n."""
        pb, batched = as_points(p, "p")
        inside = np.all(np.abs(pb - np.asarray(self.center)) <= self.half + margin, axis=1)
        return inside if batched else bool(inside[0])

    def distance(self, p):
        """Euclidean distance [m] from each point ``p`` ((3,) or (n, 3)) to the box (0 inside):
        a float for one point, (n,) for n."""
        pb, batched = as_points(p, "p")
        d = np.linalg.norm(np.maximum(np.abs(pb - np.asarray(self.center)) - self.half, 0.0), axis=1)
        return d if batched else float(d[0])


def AxisBox(name: str, lower, upper) -> Box:  # noqa: N802 (the old class name)
    """Deprecated: :meth:`Box.from_corners` (the scene's box is now the project's one :class:`Box`)."""
    warnings.warn("iik.scene.AxisBox is deprecated: use iik.scene.Box.from_corners(name, lower, upper)",
                  DeprecationWarning, stacklevel=2)
    return Box.from_corners(name, lower, upper)


@dataclass(frozen=True)
class Floor:
    """The floor: the horizontal plane ``z = z`` [m] of the base frame; free space is above it."""

    z: float

    def height_of(self, p):
        """Height above the floor [m] of each point ``p`` ((3,) or (n, 3))."""
        pb, batched = as_points(p, "p")
        h = pb[:, 2] - self.z
        return h if batched else float(h[0])


@dataclass(frozen=True)
class Scene:
    """The fixed surroundings of the arm: the mobile platform it stands on (a support box), the floor."""

    platform: Box
    floor: Floor

    def z_at_height(self, height: float) -> float:
        """Base-frame z [m] of a horizontal surface ``height`` m above the floor."""
        if not np.isfinite(height):
            raise InvalidInputError("height", "must be finite")
        return float(self.floor.z + height)


#: The scene of Sec 4.2.1 with the assumed platform footprint (module docstring).
THESIS_SCENE = Scene(
    platform=Box.from_corners("platform", lower=(-0.55, -0.25, -PLATFORM_HEIGHT), upper=(0.10, 0.25, 0.0),
                              kind="support"),
    floor=Floor(z=-PLATFORM_HEIGHT),  # arm base on the platform top (decision above)
)
