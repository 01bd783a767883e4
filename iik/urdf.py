"""URDF text from a DH table: the thesis arm (and any other revolute chain) as a robot model.

:func:`urdf_from_dh` turns a :class:`~iik.dh.DHTable` (modified or standard
convention, with its limits) into URDF XML text. It performs no file I/O; the
committed ``urdf/thesis_arm.urdf`` is written by ``iik urdf`` from
:func:`thesis_urdf` and a test fails if the two differ.

Mapping of DH rows to URDF (angles rad, lengths m)
--------------------------------------------------
Links are ``base_link, link1..linkN`` and joints ``joint1..jointN`` (revolute
about their local z axis); a fixed joint ``tool_joint`` attaches the link ``tool``.

* **Modified (Craig)**, ``T_i = RotX(alpha_{i-1}) TransX(a_{i-1}) RotZ(q_i + offset_i) TransZ(d_i)``.
  Because ``RotZ`` and ``TransZ`` commute, ``T_i = [RotX TransX RotZ(offset) TransZ(d)] RotZ(q_i)``:
  the bracket is the fixed origin of ``joint_i`` in ``link_{i-1}``, and the frame of
  ``link_i`` *is* DH frame i. ``tool`` = frame N composed with ``tool``.
* **Standard**, ``T_i = RotZ(q_i + offset_i) TransZ(d_i) TransX(a_i) RotX(alpha_i)`` =
  ``RotZ(q_i) C_i`` with ``C_i = RotZ(offset_i) TransZ(d_i) TransX(a_i) RotX(alpha_i)``.
  ``joint_1`` sits at the base (origin ``base``), ``joint_i`` has origin ``C_{i-1}`` in
  ``link_{i-1}``, so the frame of ``link_i`` is DH frame i-1 turned by ``q_i``; the
  ``tool`` origin is ``C_N`` composed with ``tool``. In both conventions the ``tool``
  frame equals ``dh_chain(table, q) @ tool``.

Numbers are written with ``repr`` (17 significant digits), so Pinocchio reads the
limits back bit for bit and the model reproduces the DH product to ~1e-16 m.

Joint limits: ``lower/upper`` of the table (Table I for the thesis arm), ``velocity``
of the table (:attr:`iik.arm.Arm.velocity`), ``effort`` as given (the thesis arm
uses :attr:`iik.arm.Arm.effort`, 239 N m on every joint: the weaker PowerCube module
kind of Sec 3.2, because the text does not say which joint is which kind).

Collision geometry of the thesis arm (:func:`thesis_geometry`)
--------------------------------------------------------------
The thesis gives no drawings or module sizes (Fig 7 is missing from the text), so
the shapes below are **assumptions** sized like Schunk/Amtec PowerCube modules. They are
laid out along the stretched home pose (q = 0, Fig 8) between the joint points
``J1`` (on the joint-1 axis), ``J2``, ``J34`` (frames 3 and 4 coincide), ``J5`` and the
tool point ``E`` (origin of frame 6, the Eq 4 point), and follow the arm's lengths.
All sizes are in :data:`POWERCUBE` (one place to change):

======== ================================================ =============================
link     shapes                                           size [m]
======== ================================================ =============================
base     joint-1 module (PR110), box on the mount plane   0.11 x 0.11, up to 0.13
link1    column up the joint-1 axis + joint-2 module      0.11 square section
         (PR110, a cube centred on J2)
link2    joint-3 module (PR90 cube) next to the joint-2   cube 0.09
         module (the joint-3 axis is the upper-arm axis)
link3    tube from the joint-3 module to J34 + joint-4    tube d = 0.08; cube 0.09
         module (PR90 cube centred on J34)
link4    tube J34 -> J5 + joint-5 module (PR70 cube)      tube d = 0.07; cube 0.07
link5    tube J5 -> joint-6 module (PR70 cube) before     tube d = 0.07; cube 0.07
         the gripper
link6    gripper (palm box + two finger boxes) ending     palm 0.08 x 0.08 x 0.06;
         at the tool point E                              fingers 0.015 x 0.02 x 0.04
======== ================================================ =============================

Collision geometry of any other arm (:func:`link_geometry`)
----------------------------------------------------------
An arm that is neither of the thesis's form nor read from a URDF with shapes gets cylinders of
radius :func:`link_radius` (3 % of its reach, at least 1 cm) along the polyline of each link's DH
chain: from the link's frame origin along the common normal ``a`` and then along the next joint
axis by ``d`` to the next joint's frame (the tool frame after link 6). They are an assumption,
not a drawing of the arm; :mod:`iik.planning.robot_model` says which body an arm gets.

Shapes of non-adjacent links are separated by at least ``POWERCUBE.gap`` at home;
adjacent links touch or overlap by construction (they share a joint module), so
collision checking must skip the pairs of :func:`adjacent_pairs` (an SRDF
``disable_collisions`` list, also written as a comment into the URDF).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from xml.sax.saxutils import quoteattr

import numpy as np

from .arm import Arm
from .dh import DHTable, dh_chain
from .errors import InvalidInputError

__all__ = [
    "BoxShape",
    "CylinderShape",
    "PowerCubeSizes",
    "POWERCUBE",
    "urdf_from_dh",
    "thesis_urdf",
    "thesis_geometry",
    "link_geometry",
    "link_radius",
    "generated_urdf",
    "arm_urdf",
    "link_names",
    "joint_names",
    "adjacent_pairs",
    "urdf_link_frames",
    "TOOL_FRAME",
    "MAX_URDF_BYTES",
]

#: Largest URDF file the project reads [bytes] (the generated thesis arm is about 10 kB).
MAX_URDF_BYTES = 10_000_000

#: Name of the fixed frame at the end effector (origin of DH frame N, composed with ``tool``).
TOOL_FRAME = "tool"


@dataclass(frozen=True)
class BoxShape:
    """A box of edge lengths ``size`` [m], centred at ``xyz`` [m] with URDF ``rpy`` [rad] in its link."""

    size: tuple[float, float, float]
    xyz: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rpy: tuple[float, float, float] = (0.0, 0.0, 0.0)


@dataclass(frozen=True)
class CylinderShape:
    """A cylinder (axis = its local z) of ``radius`` and ``length`` [m], centred at ``xyz``."""

    radius: float
    length: float
    xyz: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rpy: tuple[float, float, float] = (0.0, 0.0, 0.0)


Shape = BoxShape | CylinderShape


@dataclass(frozen=True)
class PowerCubeSizes:
    """Assumed collision sizes of the PowerCube modules [m] (see the module docstring)."""

    large: float = 0.11  # PR110 square module (joints 1, 2)
    medium: float = 0.09  # PR90 square module (joints 3, 4)
    small: float = 0.07  # PR70 module (joints 5, 6)
    base_height: float = 0.13  # joint-1 module on the mounting plane
    tube_upper: float = 0.08  # diameter of the tube J2 -> J34
    tube_lower: float = 0.07  # diameter of the tubes J34 -> J5 -> wrist
    palm: tuple[float, float, float] = (0.08, 0.08, 0.06)  # gripper palm (w, w, length)
    finger: tuple[float, float, float] = (0.015, 0.02, 0.04)  # each finger (w, w, length)
    finger_spread: float = 0.03  # lateral offset of each finger from the tool axis
    gap: float = 0.005  # clearance kept between non-adjacent links at home


#: The sizes used for :data:`iik.THESIS_ARM` (assumptions; the thesis gives none).
POWERCUBE = PowerCubeSizes()


def link_names(n: int) -> list[str]:
    """``["base_link", "link1", ..., "link<n>"]``."""
    return ["base_link"] + [f"link{i}" for i in range(1, n + 1)]


def joint_names(n: int) -> list[str]:
    """``["joint1", ..., "joint<n>"]``."""
    return [f"joint{i}" for i in range(1, n + 1)]


def adjacent_pairs(n: int = 6) -> tuple[tuple[str, str], ...]:
    """Link pairs joined by a joint (SRDF ``disable_collisions``, reason "Adjacent").

    Their shapes touch by construction (a joint module belongs to one side and the
    tube of the other starts on it), so collision checks must skip them.
    """
    names = link_names(n)
    return tuple((names[i], names[i + 1]) for i in range(n))


# ----------------------------------------------------------------------------- helpers


def _rotx(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1.0]])


def _rotz(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def _trans(x: float = 0.0, y: float = 0.0, z: float = 0.0) -> np.ndarray:
    T = np.eye(4)
    T[:3, 3] = (x, y, z)
    return T


def _rpy_matrix(rpy) -> np.ndarray:
    """URDF convention: ``R = Rz(yaw) Ry(pitch) Rx(roll)``."""
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = (math.cos(r), math.sin(r), math.cos(p), math.sin(p),
                              math.cos(y), math.sin(y))
    return np.array([
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ])


def _rpy(R: np.ndarray) -> tuple[float, float, float]:
    """URDF roll-pitch-yaw of a rotation matrix (handles gimbal lock at pitch = +-90 deg)."""
    cp = math.hypot(R[0, 0], R[1, 0])
    if cp > 1e-9:
        roll = math.atan2(R[2, 1], R[2, 2])
        pitch = math.atan2(-R[2, 0], cp)
        yaw = math.atan2(R[1, 0], R[0, 0])
    else:  # pitch = +-pi/2: only roll -+ yaw is defined; take yaw = 0
        pitch = math.copysign(math.pi / 2, -R[2, 0])
        yaw = 0.0
        roll = math.atan2(-R[1, 2], R[1, 1])
    return roll, pitch, yaw


def _num(x: float) -> str:
    x = float(x)
    if abs(x) < 1e-15:  # cos(pi/2)-sized noise
        x = 0.0
    return repr(x + 0.0)  # + 0.0 turns -0.0 into 0.0


def _vec(v, ndigits: int | None = None) -> str:
    return " ".join(_num(x if ndigits is None else round(float(x), ndigits)) for x in v)


def _origin(T: np.ndarray) -> str:
    return f'<origin xyz="{_vec(T[:3, 3])}" rpy="{_vec(_rpy(T[:3, :3]))}"/>'


def _checked_table(table) -> DHTable:
    if not isinstance(table, DHTable):
        raise InvalidInputError("table", f"expected an iik.dh.DHTable, got {type(table).__name__}")
    try:  # re-run DHTable's validation: catches tables altered after construction
        return DHTable(rows=tuple(table.rows), convention=table.convention,
                       lower=tuple(float(v) for v in table.lower),
                       upper=tuple(float(v) for v in table.upper),
                       velocity=tuple(float(v) for v in table.velocity))
    except InvalidInputError:
        raise
    except (TypeError, ValueError, AttributeError) as exc:
        raise InvalidInputError("table", f"is inconsistent ({exc})") from None


def _checked_transform(T, name: str) -> np.ndarray:
    if T is None:
        return np.eye(4)
    from .validation import as_poses

    Ts, batched = as_poses(T, name, orthonormal_tol=1e-9)
    if batched:
        raise InvalidInputError(name, "expected one 4x4 transform, got a batch")
    return Ts[0]


def _checked_positive(values, n: int, name: str) -> tuple[float, ...]:
    from .validation import as_float_array

    arr = as_float_array(values, name)
    if arr.shape != (n,):
        raise InvalidInputError(name, f"expected {n} values (one per joint), got shape {arr.shape}")
    if np.any(arr <= 0):
        raise InvalidInputError(name, "values must be positive")
    return tuple(float(v) for v in arr)


def _shape_xml(shape: Shape, link: str, k: int) -> str:
    if isinstance(shape, BoxShape):
        size = np.asarray(shape.size, dtype=float)
        if size.shape != (3,) or not np.all(np.isfinite(size)) or np.any(size <= 0):
            raise InvalidInputError(f"links[{link!r}][{k}]", "box size must be 3 positive numbers")
        geom = f'<box size="{_vec(size, 12)}"/>'
    elif isinstance(shape, CylinderShape):
        if not (np.isfinite(shape.radius) and np.isfinite(shape.length)
                and shape.radius > 0 and shape.length > 0):
            raise InvalidInputError(f"links[{link!r}][{k}]", "cylinder radius and length must be positive")
        geom = (f'<cylinder radius="{_num(round(shape.radius, 12))}" '
                f'length="{_num(round(shape.length, 12))}"/>')
    else:
        raise InvalidInputError(f"links[{link!r}][{k}]",
                                f"expected BoxShape or CylinderShape, got {type(shape).__name__}")
    for attr in ("xyz", "rpy"):
        v = np.asarray(getattr(shape, attr), dtype=float)
        if v.shape != (3,) or not np.all(np.isfinite(v)):
            raise InvalidInputError(f"links[{link!r}][{k}].{attr}", "must be 3 finite numbers")
    return (f'    <collision name="{link}_{k}">\n'
            f'      <origin xyz="{_vec(shape.xyz, 12)}" rpy="{_vec(shape.rpy)}"/>\n'
            f"      <geometry>{geom}</geometry>\n"
            f"    </collision>\n")


# ----------------------------------------------------------------------------- generator


def _fixed_parts(table: DHTable, base: np.ndarray, tool: np.ndarray) -> list[np.ndarray]:
    """Origins of joint1..jointN and of the tool joint, each in its parent link."""
    n = table.dof
    if table.convention == "modified":
        origins = [_rotx(r.alpha) @ _trans(x=r.a) @ _rotz(r.offset) @ _trans(z=r.d) for r in table.rows]
        origins[0] = base @ origins[0]
        return origins + [tool]
    C = [_rotz(r.offset) @ _trans(z=r.d) @ _trans(x=r.a) @ _rotx(r.alpha) for r in table.rows]
    return [base] + [C[i - 1] for i in range(1, n)] + [C[n - 1] @ tool]


def urdf_link_frames(table: DHTable, q, *, base=None) -> np.ndarray:
    """Frames of the URDF links ``link1..linkN`` in ``base_link`` at ``q`` [rad] -> (N, 4, 4).

    For a modified table these are the DH frames 1..N; for a standard table frame
    i-1 turned by ``q_i`` (see the module docstring). Used to place collision shapes.
    """
    table = _checked_table(table)
    base_T = _checked_transform(base, "base")
    if table.convention == "modified":
        return base_T @ dh_chain(table, q, all_frames=True)
    from .validation import as_joints

    qb, batched = as_joints(q, "q", table.dof)
    if batched:
        raise InvalidInputError("q", "expected one joint vector")
    prev = np.concatenate([np.eye(4)[None], dh_chain(table, qb[0], all_frames=True)[:-1]])
    turned = np.stack([prev[i] @ _rotz(float(qb[0, i])) for i in range(table.dof)])
    return base_T @ turned


def urdf_from_dh(
    table: DHTable,
    *,
    name: str,
    links: Mapping[str, Sequence[Shape]] | None = None,
    tool=None,
    base=None,
    effort: Sequence[float] | None = None,
    adjacent: Sequence[tuple[str, str]] | None = None,
) -> str:
    """URDF XML text of the revolute chain ``table``.

    Args:
        table: DH rows (modified or standard) with joint limits [rad] and speeds [rad/s].
        name: Robot name.
        links: Collision shapes per link name (``"base_link"``, ``"link1"``, ...), each
            given in that link's frame (see :func:`urdf_link_frames`). Links not named
            get no geometry.
        tool: 4x4 transform [m] from DH frame N to the ``tool`` frame (default identity).
        base: 4x4 transform [m] from ``base_link`` to DH frame 0 (default identity).
        effort: Joint torque limits [N m], one per joint (default 1.0 each: URDF requires a
            value; kinematics ignores it).
        adjacent: Link pairs listed as "disable collisions" in a comment (default
            :func:`adjacent_pairs`).

    Returns:
        The URDF document as a string (no file is written).

    Raises:
        InvalidInputError: inconsistent table (limit/speed counts, order, non-finite
            values), bad ``effort``, ``tool`` or ``base`` not a proper rigid transform,
            unknown link names or malformed shapes.
    """
    table = _checked_table(table)
    n = table.dof
    if not isinstance(name, str) or not name.strip():
        raise InvalidInputError("name", "must be a non-empty string")
    tool_T = _checked_transform(tool, "tool")
    base_T = _checked_transform(base, "base")
    eff = _checked_positive([1.0] * n if effort is None else effort, n, "effort")
    names = link_names(n)
    links = dict(links or {})
    unknown = sorted(set(links) - set(names))
    if unknown:
        raise InvalidInputError("links", f"unknown link name(s) {unknown}; expected some of {names}")
    pairs = adjacent_pairs(n) if adjacent is None else tuple(tuple(p) for p in adjacent)
    for p in pairs:
        if len(p) != 2 or not set(p) <= set(names):
            raise InvalidInputError("adjacent", f"pair {p!r} does not name two links of {names}")

    origins = _fixed_parts(table, base_T, tool_T)
    out = ['<?xml version="1.0"?>',
           "<!-- Generated by iik.urdf.urdf_from_dh; do not edit by hand. -->",
           f"<!-- DH convention: {table.convention}. Units: m, rad, rad/s, N m. -->",
           "<!-- Disable collisions between adjacent links (SRDF-like):"]
    out += [f'     <disable_collisions link1="{a}" link2="{b}" reason="Adjacent"/>' for a, b in pairs]
    out += ["-->", f"<robot name={quoteattr(name)}>"]
    for k, link in enumerate(names):
        shapes = links.get(link, ())
        body = "".join(_shape_xml(s, link, j) for j, s in enumerate(shapes))
        out.append(f'  <link name="{link}">\n{body}  </link>' if body else f'  <link name="{link}"/>')
        if k == 0:
            continue
        i = k - 1
        out.append(
            f'  <joint name="joint{k}" type="revolute">\n'
            f'    <parent link="{names[k - 1]}"/>\n'
            f'    <child link="{link}"/>\n'
            f"    {_origin(origins[i])}\n"
            f'    <axis xyz="0 0 1"/>\n'
            f'    <limit lower="{_num(table.lower[i])}" upper="{_num(table.upper[i])}" '
            f'velocity="{_num(table.velocity[i])}" effort="{_num(eff[i])}"/>\n'
            f"  </joint>"
        )
    out.append(f'  <link name="{TOOL_FRAME}"/>')
    out.append(
        f'  <joint name="{TOOL_FRAME}_joint" type="fixed">\n'
        f'    <parent link="{names[-1]}"/>\n'
        f'    <child link="{TOOL_FRAME}"/>\n'
        f"    {_origin(origins[-1])}\n"
        f"  </joint>"
    )
    out.append("</robot>")
    return "\n".join(out) + "\n"


# ----------------------------------------------------------------------------- thesis arm


def _place(F_link: np.ndarray, center_world, R_world=None) -> tuple[tuple, tuple]:
    """xyz, rpy in a link of frame ``F_link`` for a shape at ``center_world`` with axes ``R_world``."""
    R_world = np.eye(3) if R_world is None else R_world
    R = F_link[:3, :3].T
    xyz = R @ (np.asarray(center_world, float) - F_link[:3, 3])
    return tuple(float(v) for v in xyz), _rpy(R @ R_world)


def _box_along_x(F, x0, x1, y, z, wy, wz):
    """BoxShape spanning world x in [x0, x1] at (y, z), cross-section wy x wz, at the home pose."""
    xyz, rpy = _place(F, ((x0 + x1) / 2, y, z))
    return BoxShape(size=(x1 - x0, wy, wz), xyz=xyz, rpy=rpy)


def _tube_along_x(F, x0, x1, z, d):
    """CylinderShape along world x in [x0, x1] at height z, diameter d, at home."""
    R_world = np.array([[0, 0, 1.0], [0, 1.0, 0], [-1.0, 0, 0]])  # local z -> world x
    xyz, rpy = _place(F, ((x0 + x1) / 2, 0.0, z), R_world)
    return CylinderShape(radius=d / 2, length=x1 - x0, xyz=xyz, rpy=rpy)


def thesis_geometry(arm: Arm, sizes: PowerCubeSizes = POWERCUBE) -> dict[str, tuple[Shape, ...]]:
    """Collision shapes of ``arm`` per link, laid out along the home pose (module docstring).

    Raises:
        InvalidInputError: if the arm is too short for the modules (shapes would overlap
            or have non-positive length).
    """
    table = arm.dh_table()
    F = urdf_link_frames(table, np.zeros(table.dof))  # home pose, links 1..6
    J2, J34, J5, E = (F[i, :3, 3] for i in (1, 2, 4, 5))
    h = J2[2]  # every joint point lies at this height, along +x, at home
    if not np.allclose([J34[1:], J5[1:], E[1:]], [[0, h]] * 3, atol=1e-12) or not (
        0 < J2[0] < J34[0] < J5[0] < E[0]
    ):
        raise InvalidInputError("arm", "home pose is not the stretched +x pose of Table II")
    s, g = sizes, sizes.gap
    L, M, S = s.large, s.medium, s.small
    palm_w1, palm_w2, palm_len = s.palm
    fw1, fw2, flen = s.finger
    x_palm0 = E[0] - flen - palm_len  # gripper starts here
    x_j6 = x_palm0 - S  # joint-6 module [x_j6, x_palm0]
    spans = {
        "base column": (0.0, s.base_height),
        "link1 column": (s.base_height + g, h - L / 2),
        "link3 tube": (J2[0] + L / 2 + M + g, J34[0] - M / 2),
        "link4 tube": (J34[0] + M / 2 + g, J5[0] - S / 2),
        "link5 tube": (J5[0] + S / 2 + g, x_j6),
    }
    for what, (a, b) in spans.items():
        if not b - a > 1e-3:
            raise InvalidInputError(
                "arm", f"too short for the PowerCube modules ({what} has length {b - a:.3g} m)")
    geo: dict[str, tuple[Shape, ...]] = {
        "base_link": (BoxShape(size=(L, L, s.base_height), xyz=(0.0, 0.0, s.base_height / 2)),),
        "link1": (
            _box_along_x(F[0], -L / 2, L / 2, 0, (s.base_height + g + h + L / 2) / 2, L,
                         h + L / 2 - s.base_height - g),
            _box_along_x(F[0], -L / 2, J2[0] + L / 2, 0, h, L, L),  # arm bar + joint-2 module
        ),
        "link2": (_box_along_x(F[1], J2[0] + L / 2, J2[0] + L / 2 + M, 0, h, M, M),),  # joint-3 module
        "link3": (
            _tube_along_x(F[2], *spans["link3 tube"], h, s.tube_upper),
            _box_along_x(F[2], J34[0] - M / 2, J34[0] + M / 2, 0, h, M, M),  # joint-4 module
        ),
        "link4": (
            _tube_along_x(F[3], *spans["link4 tube"], h, s.tube_lower),
            _box_along_x(F[3], J5[0] - S / 2, J5[0] + S / 2, 0, h, S, S),  # joint-5 module
        ),
        "link5": (
            _tube_along_x(F[4], *spans["link5 tube"], h, s.tube_lower),
            _box_along_x(F[4], x_j6, x_palm0, 0, h, S, S),  # joint-6 module
        ),
        "link6": (
            _box_along_x(F[5], x_palm0, E[0] - flen, 0, h, palm_w1, palm_w2),  # palm
            _box_along_x(F[5], E[0] - flen, E[0], +s.finger_spread, h, fw1, fw2),  # finger
            _box_along_x(F[5], E[0] - flen, E[0], -s.finger_spread, h, fw1, fw2),  # finger
        ),
    }
    return geo


def thesis_urdf(arm: Arm, sizes: PowerCubeSizes = POWERCUBE) -> str:
    """URDF text of ``arm`` (Table II rows, Table I limits, speeds, efforts, collision shapes).

    ``iik urdf`` writes this to ``urdf/thesis_arm.urdf``; the ``tool`` frame is DH frame 6,
    whose origin is the end-effector point of Eq 4.
    """
    return urdf_from_dh(arm.dh_table(), name="thesis_arm", links=thesis_geometry(arm, sizes),
                        effort=arm.effort)


# ----------------------------------------------------------------------------- any arm


def link_radius(arm: Arm) -> float:
    """Radius [m] of the generated link cylinders of ``arm``: 3 % of its reach, at least 0.01 m."""
    return max(0.01, 0.03 * arm.reach)


def _cylinder(a: np.ndarray, b: np.ndarray, radius: float) -> CylinderShape:
    """A cylinder of ``radius`` from point ``a`` to point ``b`` (in one link's frame) [m]."""
    d = (b - a) / np.linalg.norm(b - a)
    helper = np.array([1.0, 0.0, 0.0]) if abs(d[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    x = np.cross(helper, d)
    x /= np.linalg.norm(x)
    R = np.column_stack([x, np.cross(d, x), d])  # local z along the segment
    return CylinderShape(radius=radius, length=float(np.linalg.norm(b - a)),
                         xyz=tuple(float(v) for v in 0.5 * (a + b)), rpy=_rpy(R))


def link_geometry(arm: Arm, radius: float | None = None) -> dict[str, tuple[Shape, ...]]:
    """Cylinders along the links of ``arm``'s DH chain, per URDF link of :func:`generated_urdf`
    (module docstring); ``radius`` [m] default :func:`link_radius`."""
    r = link_radius(arm) if radius is None else float(radius)
    if not (math.isfinite(r) and r > 0):
        raise InvalidInputError("radius", f"must be a positive number of metres, got {radius!r}")
    table = arm.dh_table()
    origins = _fixed_parts(table, np.array(arm.base), np.array(arm.tool))
    names = link_names(table.dof)
    out: dict[str, tuple[Shape, ...]] = {}
    for k, link in enumerate(names):
        nxt = origins[k]  # the next joint's (or the tool's) frame in this link
        if k < table.dof:
            corner = (nxt @ _trans(z=-table.rows[k].d))[:3, 3]  # before the offset along the next axis
        else:
            corner = np.zeros(3)
        pts = [np.zeros(3), corner, nxt[:3, 3]]
        shapes = tuple(_cylinder(a, b, r) for a, b in zip(pts[:-1], pts[1:], strict=True)
                       if np.linalg.norm(b - a) > 1e-6)
        if shapes:
            out[link] = shapes
    return out


def generated_urdf(arm: Arm, radius: float | None = None) -> str:
    """URDF text of ``arm`` (its DH rows, base, tool, limits, efforts) with the cylinders of
    :func:`link_geometry` as collision shapes."""
    return urdf_from_dh(arm.dh_table(), name=_robot_name(arm), links=link_geometry(arm, radius),
                        tool=np.array(arm.tool), base=np.array(arm.base), effort=arm.effort)


def _robot_name(arm: Arm) -> str:
    return "".join(c if c.isalnum() or c in "-_" else "_" for c in arm.name).strip("_") or "arm"


def arm_urdf(arm: Arm) -> str:
    """URDF text of ``arm`` as the project generates it: :func:`thesis_urdf` (PowerCube shapes) for an
    arm of the thesis's Table II form, else :func:`generated_urdf` (cylinders along the links)."""
    try:
        arm.thesis_lengths  # noqa: B018 - raises for another form
    except InvalidInputError:
        return generated_urdf(arm)
    return thesis_urdf(arm)
