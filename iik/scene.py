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

from dataclasses import dataclass

import numpy as np

from .errors import InvalidInputError
from .validation import as_points

__all__ = [
    "PLATFORM_HEIGHT",
    "TABLE_HEIGHT",
    "AxisBox",
    "Floor",
    "Scene",
    "THESIS_SCENE",
]

#: Sec 4.2.1: height of the platform top above the floor [m].
PLATFORM_HEIGHT = 0.45
#: Sec 4.2.1: height of a standard dining table above the floor [m].
TABLE_HEIGHT = 0.80


@dataclass(frozen=True)
class AxisBox:
    """An axis-aligned box in the base frame, from corner ``lower`` to corner ``upper`` [m]."""

    name: str
    lower: tuple[float, float, float]
    upper: tuple[float, float, float]

    def __post_init__(self) -> None:
        lo, hi = np.asarray(self.lower, float), np.asarray(self.upper, float)
        if lo.shape != (3,) or hi.shape != (3,) or not np.all(np.isfinite([lo, hi])):
            raise InvalidInputError(self.name, "box corners must be 3 finite numbers each")
        if not np.all(lo < hi):
            raise InvalidInputError(self.name, f"lower corner {self.lower} is not below upper {self.upper}")

    @property
    def center(self) -> np.ndarray:
        """Centre [m], shape (3,)."""
        return (np.asarray(self.lower) + np.asarray(self.upper)) / 2

    @property
    def size(self) -> np.ndarray:
        """Edge lengths along x, y, z [m], shape (3,)."""
        return np.asarray(self.upper) - np.asarray(self.lower)

    def contains(self, p, margin: float = 0.0):
        """Is each point ``p`` [m] ((3,) or (n, 3)) inside the box grown by ``margin`` [m]?"""
        pb, batched = as_points(p, "p")
        inside = np.all((pb >= np.asarray(self.lower) - margin)
                        & (pb <= np.asarray(self.upper) + margin), axis=1)
        return inside if batched else bool(inside[0])

    def distance(self, p):
        """Euclidean distance [m] from each point to the box (0 inside), (n,) or scalar."""
        pb, batched = as_points(p, "p")
        d = np.maximum(np.maximum(np.asarray(self.lower) - pb, pb - np.asarray(self.upper)), 0.0)
        out = np.linalg.norm(d, axis=1)
        return out if batched else float(out[0])


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
    """The fixed surroundings of the arm: the mobile platform it stands on and the floor."""

    platform: AxisBox
    floor: Floor

    def z_at_height(self, height: float) -> float:
        """Base-frame z [m] of a horizontal surface ``height`` m above the floor."""
        if not np.isfinite(height):
            raise InvalidInputError("height", "must be finite")
        return float(self.floor.z + height)


#: The scene of Sec 4.2.1 with the assumed platform footprint (module docstring).
THESIS_SCENE = Scene(
    platform=AxisBox("platform", lower=(-0.55, -0.25, -PLATFORM_HEIGHT), upper=(0.10, 0.25, 0.0)),
    floor=Floor(z=-PLATFORM_HEIGHT),  # arm base on the platform top (decision above)
)
