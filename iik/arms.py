"""The shipped arms: one registry, by name, of every arm the project carries.

* ``"thesis"``: the PowerCube arm of the thesis (Table I, Table II; :data:`iik.arm.THESIS_ARM`).
* ``"crx10ia"``, ``"crx10ia_l"``: FANUC CRX-10iA and CRX-10iA/L, from FANUC's public ROS 2
  description package (``urdf/README.md`` cites the source, commit and licence); members of the
  class read from the flange.
* ``"offset_base"``, ``"offset_flange"``: two arms of the class built here with offsets the
  thesis arm does not have (axes 1 and 2 at 60 deg with an offset along axis 2, axes 2 and 3
  at 75 deg, a level offset along axes 4 and 5, a tool offset; and a CRX-like arm read from the
  flange whose last two axes are skew at 70 deg). Their URDFs (``urdf/offset_*.urdf``) are
  generated from the DH tables here by :func:`iik.urdf.urdf_from_dh`.

:func:`get` takes a name or a URDF path (what the CLI's ``--arm`` takes). Units: m, rad.
"""

from __future__ import annotations

import math
from functools import cache
from pathlib import Path

from .arm import THESIS_ARM, Arm
from .dh import DHRow, DHTable
from .errors import InvalidInputError

__all__ = ["NAMES", "get", "resolve", "UnknownArmError", "constructed_table", "CONSTRUCTED"]

_D = math.pi / 180.0
#: The shipped arms' names.
NAMES = ("thesis", "crx10ia", "crx10ia_l", "offset_base", "offset_flange")
_URDF = {"crx10ia": "crx10ia.urdf", "crx10ia_l": "crx10ia_l.urdf"}

#: The constructed arms: modified-DH rows (alpha [deg], a [m], d [m], offset [deg]), limits [deg].
CONSTRUCTED = {
    "offset_base": (
        ((0.0, 0.0, 0.35, 0.0), (-60.0, 0.15, 0.08, -90.0), (75.0, 0.0, 0.40, 0.0), (90.0, 0.0, 0.05, 0.0),
         (0.0, 0.30, -0.05, 90.0), (-90.0, 0.0, 0.0, 0.0)),
        ((-170.0, 170.0), (-110.0, 110.0), (-150.0, 150.0),
         (-170.0, 170.0), (-120.0, 120.0), (-180.0, 180.0)),
    ),
    "offset_flange": (
        ((0.0, 0.0, 0.30, 0.0), (90.0, 0.0, 0.0, 90.0), (0.0, 0.50, 0.0, 0.0), (90.0, 0.0, 0.45, 0.0),
         (-90.0, 0.0, 0.12, 0.0), (70.0, 0.06, 0.10, 0.0)),
        ((-180.0, 180.0), (-170.0, 170.0), (-160.0, 160.0),
         (-190.0, 190.0), (-170.0, 170.0), (-200.0, 200.0)),
    ),
}


class UnknownArmError(InvalidInputError):
    """An arm name that is not a shipped arm nor a URDF file (the message lists the names)."""


def constructed_table(name: str) -> DHTable:
    """The modified-DH table of a constructed arm (rows and Table-I-like limits; 2 rad/s)."""
    rows, lims = CONSTRUCTED[name]
    return DHTable(rows=tuple(DHRow(alpha=a * _D, a=aa, d=d, offset=o * _D) for a, aa, d, o in rows),
                   convention="modified", lower=tuple(lo * _D for lo, _ in lims),
                   upper=tuple(hi * _D for _, hi in lims), velocity=(2.0,) * 6)


@cache
def _shipped(name: str) -> Arm:
    if name == "thesis":
        return THESIS_ARM
    if name in _URDF:
        from .resources import urdf_path

        return Arm.from_urdf(urdf_path(_URDF[name]), name=name)
    tool = ((1.0, 0.0, 0.0, 0.0), (0.0, 1.0, 0.0, 0.0), (0.0, 0.0, 1.0, 0.12), (0.0, 0.0, 0.0, 1.0))
    return Arm(dh=constructed_table(name), tool=tool, name=name, source="iik.arms.CONSTRUCTED",
               assumptions=("A constructed member of the class (not a real arm).",))


def get(name: str) -> Arm:
    """The shipped arm called ``name`` (:data:`NAMES`).

    Raises:
        UnknownArmError: not a shipped name (the message lists them).
    """
    if name not in NAMES:
        raise UnknownArmError("arm", f"{name!r} is not a shipped arm; shipped: {', '.join(NAMES)} "
                                     "(or give the path of a URDF file)")
    return _shipped(name)


def resolve(name_or_path) -> Arm:
    """A shipped arm by name, or the arm of a URDF file (:meth:`iik.Arm.from_urdf`)."""
    if isinstance(name_or_path, Arm):
        return name_or_path
    text = str(name_or_path)
    if text in NAMES:
        return get(text)
    if text.endswith(".urdf") or Path(text).is_file():
        return Arm.from_urdf(text)
    return get(text)
