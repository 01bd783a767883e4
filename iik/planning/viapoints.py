"""Via-points of Table III, the crossing pattern of Table IV and a region classifier.

Table III gives four via-points (mm, base frame); Table IV says which of them
a path needs between the seven workspace regions A..G of Fig 29. Fig 29 itself
is missing from the text, so the region layout is *inferred* (documented here):

* Table IV is mirror-symmetric under A<->G, B<->F, C<->E, D<->D with
  1<->4, 2<->3, and Table III's via-points are mirror images under y -> -y
  (1 = [-400, 500, 200] <-> 4 = [-400, -500, 200], 2 <-> 3). So the regions
  are symmetric about the x-z plane, with D in the middle (in front, +x) and
  A, G behind the arm on either side of the joint-1 cut (theta1 = +-160 deg,
  Sec 3.6.3: "the plane that connects regions A and G").
* Via-point 1 is needed to leave A for any region and via-point 4 to enter G,
  so their azimuths (atan2(500, -400) = +-128.66 deg) bound A and G.
* Between them the five regions B..F are equal azimuth sectors of
  (2 * 128.66) / 5 = 51.46 deg: B [77.2, 128.7), C [25.7, 77.2),
  D [-25.7, 25.7), E [-77.2, -25.7), F [-128.7, -77.2). Via-points 2 and 3
  (+-51.34 deg) then sit in C and E, where B->D and D->F need them.

The classifier uses only the azimuth ``atan2(y, x)`` of a point; the text
gives no radial or height boundaries. Points on the z axis are put in D.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import InvalidInputError
from ..validation import as_points

__all__ = [
    "VIA_POINTS",
    "TABLE_IV",
    "TABLE_IV_PRINTED",
    "REGIONS",
    "region_bounds",
    "region_of",
    "via_points_for",
    "via_point_path",
]

#: Table III, converted from mm to m (base frame).
VIA_POINTS: dict[int, tuple[float, float, float]] = {
    1: (-0.400, 0.500, 0.200),
    2: (0.400, 0.500, 0.000),
    3: (0.400, -0.500, 0.000),
    4: (-0.400, -0.500, 0.200),
}

#: Table IV as printed (upper triangle): via-points needed to cross from one region to another;
#: the note under Table IV makes it symmetric (:data:`TABLE_IV`).
TABLE_IV_PRINTED = {
    ("A", "B"): (1,), ("A", "C"): (1,), ("A", "D"): (1, 2), ("A", "E"): (1, 2),
    ("A", "F"): (1, 2, 3), ("A", "G"): (1, 2, 3, 4),
    ("B", "C"): (), ("B", "D"): (2,), ("B", "E"): (2,), ("B", "F"): (2, 3), ("B", "G"): (2, 3, 4),
    ("C", "D"): (), ("C", "E"): (), ("C", "F"): (3,), ("C", "G"): (3, 4),
    ("D", "E"): (), ("D", "F"): (3,), ("D", "G"): (3, 4),
    ("E", "F"): (), ("E", "G"): (4,),
    ("F", "G"): (4,),
}

REGIONS = ("A", "B", "C", "D", "E", "F", "G")


def _table_iv() -> dict[tuple[str, str], tuple[int, ...]]:
    t = {}
    for (a, b), v in TABLE_IV_PRINTED.items():
        t[(a, b)] = v
        t[(b, a)] = tuple(reversed(v))  # note under Table IV: same via-points, reverse order
    for r in REGIONS:
        t[(r, r)] = ()
    return t


#: Table IV as a full (ordered) lookup: (departure, destination) -> via-point numbers in travel order.
TABLE_IV: dict[tuple[str, str], tuple[int, ...]] = _table_iv()

_EDGE = math.atan2(VIA_POINTS[1][1], VIA_POINTS[1][0])  # +128.66 deg: A/B boundary (via-point 1)
_W = 2 * _EDGE / 5  # width of the five middle sectors


def region_bounds() -> dict[str, tuple[float, float]]:
    """Azimuth interval ``[lo, hi)`` [rad] of each region (A and G wrap through +-pi)."""
    b = {"A": (_EDGE, math.pi), "G": (-math.pi, -_EDGE)}
    for k, r in enumerate("BCDEF"):
        hi = _EDGE - k * _W
        b[r] = (hi - _W, hi)
    return b


def region_of(points) -> np.ndarray | str:
    """Region letter(s) A..G of point(s) (3,) or (n, 3) [m] by azimuth (inferred Fig 29)."""
    p, batched = as_points(points, "points")
    phi = np.arctan2(p[:, 1], p[:, 0])
    phi = np.where(np.hypot(p[:, 0], p[:, 1]) < 1e-9, 0.0, phi)
    k = np.floor((_EDGE - phi) / _W).astype(int) + 1  # 1..5 -> B..F
    k = np.where(phi >= _EDGE, 0, np.where(phi < -_EDGE, 6, np.clip(k, 1, 5)))
    out = np.array(REGIONS)[k]
    return out if batched else str(out[0])


def via_points_for(start_region: str, goal_region: str) -> tuple[int, ...]:
    """Table IV: via-point numbers, in travel order, from one region to another."""
    key = (str(start_region).upper(), str(goal_region).upper())
    if key not in TABLE_IV:
        raise InvalidInputError("region", f"unknown region pair {key}; regions are A..G")
    return TABLE_IV[key]


def via_point_path(start, goal) -> tuple[np.ndarray, tuple[int, ...]]:
    """Via-points (k, 3) [m] and their Table III numbers for a path from ``start`` to ``goal``."""
    nums = via_points_for(region_of(start), region_of(goal))
    pts = np.array([VIA_POINTS[i] for i in nums], float).reshape(-1, 3)
    return pts, nums
