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

:func:`get` takes a shipped name; :func:`resolve` a name or a URDF path (what the CLI's ``--arm``
and a scenario file's ``arm =`` key take). An arm travels with the data it belongs to: a scenario
names it, a plan carries it, a run log records it (:func:`to_record`: the numbers, the shipped name or
the URDF file and its SHA-256) and is read back with it (:func:`from_record`). Units: m, rad.
"""

from __future__ import annotations

import hashlib
import math
import os
from functools import cache
from pathlib import Path

import numpy as np

from .arm import THESIS_ARM, Arm
from .dh import DHRow, DHTable
from .errors import InvalidInputError

__all__ = ["NAMES", "get", "resolve", "UnknownArmError", "constructed_table", "CONSTRUCTED", "name_of",
           "same_arm", "to_record", "from_record", "RECORD_TOL"]

#: Two arms whose every number (DH rows, base, tool, limits) agrees within this are the same arm
#: (:func:`same_arm`) [m, rad, rad/s, rad/s^2, N m].
RECORD_TOL = 1e-12

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


def resolve(name_or_path, *, relative_to=None) -> Arm:
    """A shipped arm by name, or the arm of a URDF file (:meth:`iik.Arm.from_urdf`).

    Args:
        name_or_path: An :class:`~iik.Arm` (returned as is), a shipped name (:data:`NAMES`) or the
            path of a URDF file.
        relative_to: The folder a relative path is read from (a scenario file's folder); default:
            the working directory.

    Raises:
        UnknownArmError: neither a shipped name nor a URDF file (the message lists the names).
        InvalidInputError: the URDF file does not parse or its chain is unusable (names the file).
        NotInClassError: the URDF's arm is outside the class (with the near-miss report).
    """
    if isinstance(name_or_path, Arm):
        return name_or_path
    text = os.fspath(name_or_path) if isinstance(name_or_path, os.PathLike) else name_or_path
    if not isinstance(text, str) or not text:
        raise UnknownArmError("arm", f"expected a shipped arm's name ({', '.join(NAMES)}) or a URDF file, "
                                     f"got {name_or_path!r}")
    if text in NAMES:
        return get(text)
    path = Path(text)
    if relative_to is not None and not path.is_absolute():
        path = Path(relative_to) / path
    if text.endswith(".urdf") or path.is_file():
        return Arm.from_urdf(path)
    return get(text)


def name_of(arm: Arm) -> str | None:
    """The shipped name of ``arm`` (:data:`NAMES`) if it is one of them (equal in every field), else None."""
    return next((n for n in NAMES if _shipped(n) == arm), None)


def _numbers(arm: Arm) -> dict:
    rows = [[r.alpha, r.a, r.d, r.offset] for r in arm.dh.rows]
    return {"dh": rows, "lower": list(arm.lower), "upper": list(arm.upper), "velocity": list(arm.velocity),
            "acceleration": list(arm.acceleration), "effort": list(arm.effort),
            "base": [list(r) for r in arm.base], "tool": [list(r) for r in arm.tool]}


def same_arm(a: Arm, b: Arm) -> bool:
    """Do ``a`` and ``b`` have the same chain and limits (every number within :data:`RECORD_TOL`)?
    Names, sources and files may differ."""
    na, nb = _numbers(a), _numbers(b)
    return all(np.allclose(na[k], nb[k], rtol=0.0, atol=RECORD_TOL) for k in na)


def _sha256(path: str) -> str:
    try:
        with open(path, "rb") as f:
            return hashlib.sha256(f.read()).hexdigest()
    except OSError:
        return ""


def to_record(arm: Arm) -> dict:
    """``arm`` as JSON-ready data (a run log's header): its name, its shipped name (``registry``, or
    None), its source, its URDF file and the file's SHA-256 (or ""), and every number of the chain
    (modified-DH rows alpha, a, d, offset [rad, m]; base and tool (4, 4) [m]; limits [rad, rad/s,
    rad/s^2, N m]), so :func:`from_record` rebuilds the same arm without the registry or the file."""
    return {"name": arm.name, "registry": name_of(arm), "source": arm.source, "urdf": arm.urdf,
            "urdf_sha256": _sha256(arm.urdf) if arm.urdf else "", "joint_names": list(arm.joint_names),
            **_numbers(arm)}


def from_record(record, argument: str = "arm") -> Arm:
    """The arm of a :func:`to_record` record: the shipped arm it names, or the arm of its URDF file if
    that file is unchanged (same SHA-256), when either has the recorded numbers; otherwise the arm
    rebuilt from the numbers (with no URDF file: its body is then generated, :mod:`iik.planning.robot_model`).
    A plain string (the arm's display name, as logs of format version 1 recorded it) names the shipped
    arm of that display name.

    Raises:
        InvalidInputError: (``argument``) not a record, a number missing or malformed, or a name that
            no shipped arm has.
    """
    if isinstance(record, str):
        found = next((n for n in NAMES if _shipped(n).name == record or n == record), None)
        if found is None:
            raise InvalidInputError(argument, f"{record!r} is not the name of a shipped arm "
                                              f"({', '.join(NAMES)}) and has no numbers to rebuild it from")
        return get(found)
    try:
        rebuilt = _rebuilt(record)
    except (KeyError, TypeError, ValueError) as exc:
        raise InvalidInputError(argument, f"is not an arm record ({type(exc).__name__}: {exc})") from None
    named = record.get("registry")
    if named in NAMES and same_arm(get(named), rebuilt):
        return get(named)
    urdf = record.get("urdf") or ""
    if urdf and record.get("urdf_sha256") and _sha256(urdf) == record["urdf_sha256"]:
        try:
            from_file = Arm.from_urdf(urdf, name=rebuilt.name)
        except InvalidInputError:
            from_file = None
        if from_file is not None and same_arm(from_file, rebuilt):
            return from_file
    return rebuilt


def _rebuilt(record: dict) -> Arm:
    """The arm of a record's numbers (no URDF file)."""
    rows = tuple(DHRow(alpha=float(al), a=float(a), d=float(d), offset=float(o))
                 for al, a, d, o in record["dh"])
    table = DHTable(rows=rows, convention="modified", lower=tuple(map(float, record["lower"])),
                    upper=tuple(map(float, record["upper"])), velocity=tuple(map(float, record["velocity"])))
    return Arm(dh=table, base=np.array(record["base"], float), tool=np.array(record["tool"], float),
               acceleration=tuple(map(float, record["acceleration"])),
               effort=tuple(map(float, record["effort"])),
               name=str(record["name"]), joint_names=tuple(map(str, record["joint_names"])),
               source=str(record.get("source", "")) + " (rebuilt from a record)")
