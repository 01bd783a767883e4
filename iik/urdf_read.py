"""Reading a serial revolute chain from a URDF file (standard library XML; no ROS, no Pinocchio).

Only the kinematic data are read: each joint's ``origin`` (xyz, rpy: fixed-axis roll, pitch,
yaw, i.e. ``Rz(yaw) Ry(pitch) Rx(roll)``), ``axis``, type and ``limit`` (lower, upper,
velocity, effort). Fixed joints between the base link, the revolute joints and the tip link
are folded into the neighbouring transforms. Geometry, inertia and transmissions are ignored.
Units: metres, radians, seconds, newton metres.
"""

from __future__ import annotations

import math
import os
import xml.etree.ElementTree as ET
from dataclasses import dataclass

import numpy as np

from .errors import InvalidInputError

__all__ = ["UrdfJoint", "UrdfChain", "read_urdf_chain", "MAX_URDF_BYTES"]

#: The largest URDF file read [bytes]; reading stops there.
MAX_URDF_BYTES = 8 * 1024 * 1024


@dataclass(frozen=True)
class UrdfJoint:
    """One revolute joint: its name, the fixed transform from the previous revolute joint's
    frame (or the base link) to its frame at q = 0 (4, 4), its unit axis in its own frame and
    its limits [rad, rad/s, N m]."""

    name: str
    origin: np.ndarray
    axis: np.ndarray
    lower: float
    upper: float
    velocity: float
    effort: float


@dataclass(frozen=True)
class UrdfChain:
    """The revolute chain from ``base_link`` to ``tip_link``: its joints, the fixed transform
    from the last revolute joint's frame to the tip link (4, 4), and where it came from."""

    robot: str
    base_link: str
    tip_link: str
    joints: tuple[UrdfJoint, ...]
    tip: np.ndarray
    source: str


def _rpy(r: float, p: float, y: float) -> np.ndarray:
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return np.array(
        [
            [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr],
        ]
    )


def _floats(text: str | None, n: int, what: str, where: str) -> list[float]:
    if text is None:
        return [0.0] * n
    try:
        vals = [float(x) for x in text.split()]
    except ValueError:
        raise InvalidInputError(where, f"{what} {text!r} is not {n} numbers") from None
    if len(vals) != n or not all(math.isfinite(v) for v in vals):
        raise InvalidInputError(where, f"{what} {text!r} is not {n} finite numbers")
    return vals


def _origin(el, where: str) -> np.ndarray:
    T = np.eye(4)
    o = el.find("origin")
    if o is not None:
        T[:3, 3] = _floats(o.get("xyz"), 3, "origin xyz", where)
        T[:3, :3] = _rpy(*_floats(o.get("rpy"), 3, "origin rpy", where))
    return T


def _read_text(path) -> tuple[str, str]:
    """(text, source name) of a URDF file path, or of URDF text given directly."""
    if isinstance(path, str) and path.lstrip().startswith("<"):
        return path, "<urdf text>"
    name = os.fspath(path)
    try:
        if not os.path.isfile(name):
            raise InvalidInputError(
                name, "is not a regular file" if os.path.exists(name) else "does not exist"
            )
        with open(name, "rb") as f:
            data = f.read(MAX_URDF_BYTES + 1)
    except OSError as exc:
        raise InvalidInputError(name, f"cannot be read ({exc.strerror or exc})") from None
    if len(data) > MAX_URDF_BYTES:
        raise InvalidInputError(name, f"is larger than {MAX_URDF_BYTES} bytes: not read")
    try:
        return data.decode("utf-8"), name
    except UnicodeDecodeError:
        raise InvalidInputError(name, "is not UTF-8 text") from None


def read_urdf_chain(path, base_link: str | None = None, tip_link: str | None = None) -> UrdfChain:
    """The revolute chain of a URDF file (or URDF text) from ``base_link`` (default: the root
    link) to ``tip_link`` (default: the single leaf link below the last revolute joint).

    Raises:
        InvalidInputError: the file does not parse, a link is missing, the chain branches
            without a ``tip_link``, has a prismatic or floating joint, or a malformed number.
    """
    text, source = _read_text(path)
    try:
        root = ET.fromstring(text)
    except ET.ParseError as exc:
        raise InvalidInputError(source, f"is not valid XML ({exc})") from None
    if root.tag != "robot":
        raise InvalidInputError(source, f"has root element <{root.tag}>, expected <robot>")
    links = {el.get("name") for el in root.findall("link")}
    by_child, by_parent = {}, {}
    for el in root.findall("joint"):
        name = el.get("name") or "?"
        par, chi = el.find("parent"), el.find("child")
        if par is None or chi is None:
            raise InvalidInputError(source, f"joint {name!r} has no parent or child link")
        p, c = par.get("link"), chi.get("link")
        by_child[c] = el
        by_parent.setdefault(p, []).append(el)
    roots = sorted(links - set(by_child))
    if base_link is None:
        if len(roots) != 1:
            raise InvalidInputError(source, f"has {len(roots)} root links {roots}: name base_link")
        base_link = roots[0]
    if base_link not in links:
        raise InvalidInputError("base_link", f"{base_link!r} is not a link of {source}")
    if tip_link is not None and tip_link not in links:
        raise InvalidInputError("tip_link", f"{tip_link!r} is not a link of {source}")
    chain = _path(base_link, tip_link, by_parent, by_child, source)
    return _fold(root.get("name") or "robot", base_link, chain, source)


def _path(base, tip, by_parent, by_child, source) -> list:
    """The joint elements from base to tip (tip given) or down the single branch (tip None)."""
    if tip is not None:
        out, link = [], tip
        while link != base:
            el = by_child.get(link)
            if el is None:
                raise InvalidInputError("tip_link", f"{tip!r} is not below {base!r} in {source}")
            out.append(el)
            link = el.find("parent").get("link")
        return out[::-1]
    out, link = [], base
    while by_parent.get(link):
        kids = by_parent[link]
        moving = [k for k in kids if k.get("type") != "fixed" or by_parent.get(k.find("child").get("link"))]
        if len(moving) != 1 and len(kids) != 1:
            raise InvalidInputError(source, f"link {link!r} branches into {len(kids)} joints: name tip_link")
        el = moving[0] if len(moving) == 1 else kids[0]
        out.append(el)
        link = el.find("child").get("link")
    return out


def _fold(robot, base, elements, source) -> UrdfChain:
    joints, acc = [], np.eye(4)
    for el in elements:
        name, kind = el.get("name") or "?", el.get("type")
        where = f"{source}: joint {name!r}"
        T = _origin(el, where)
        if kind == "fixed":
            acc = acc @ T
            continue
        if kind not in ("revolute", "continuous"):
            raise InvalidInputError(where, f"is of type {kind!r}: only revolute joints are supported")
        ax = np.array(
            _floats(el.find("axis").get("xyz") if el.find("axis") is not None else "1 0 0", 3, "axis", where)
        )
        nrm = float(np.linalg.norm(ax))
        if nrm == 0.0:
            raise InvalidInputError(where, "has a zero axis")
        lim = el.find("limit")
        if kind == "continuous" or lim is None:
            lo, hi = -math.pi, math.pi
        else:
            lo, hi = (
                _floats(lim.get("lower", "0"), 1, "lower limit", where)[0],
                _floats(lim.get("upper", "0"), 1, "upper limit", where)[0],
            )
        vel = _floats(lim.get("velocity"), 1, "velocity", where)[0] if lim is not None else 0.0
        eff = _floats(lim.get("effort"), 1, "effort", where)[0] if lim is not None else 0.0
        joints.append(UrdfJoint(name, acc @ T, ax / nrm, lo, hi, vel, eff))
        acc = np.eye(4)
    tip = elements[-1].find("child").get("link") if elements else base
    if len(joints) != 6:
        raise InvalidInputError(
            source, f"the chain {base!r} -> {tip!r} has {len(joints)} revolute joints, expected 6"
        )
    return UrdfChain(robot, base, tip, tuple(joints), acc, source)
