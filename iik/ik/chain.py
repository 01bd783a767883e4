"""The compiled chain of any six-joint revolute arm: forward kinematics and the geometric
Jacobian from a modified-DH table with fixed base and tool transforms.

A DH row is ``(cos alpha, sin alpha, a, d, offset)`` (Craig's modified convention, the
convention of the thesis's Table II): link i is ``RotX(alpha) TransX(a) RotZ(q_i + offset)
TransZ(d)``. The cosines and sines of the twists are stored, not the angles, so that a twist
of exactly 90 deg has ``cos alpha = 0`` exactly. A pose is kept as 12 scalars
``(r00, r01, r02, r10, r11, r12, r20, r21, r22, px, py, pz)`` [m].

Frames: the user's base frame; the tool frame is the last link frame times the tool
transform. Everything here is scalar code compiled by Numba into the kernel's entry points
(:mod:`iik.ik.kernel`).
"""

from __future__ import annotations

import math

import numba

__all__ = [
    "IDENTITY",
    "compose_link",
    "turn",
    "compose_fixed",
    "load_fixed",
    "chain_pose",
    "pose_into",
    "jacobian_into",
    "rotation_angle_12",
    "position_error_12",
    "pose_error_vector",
]

_njit = numba.njit(error_model="numpy")

IDENTITY = (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0)
_SQRT8 = math.sqrt(8.0)


@_njit
def compose_link(r, ca, sa, a, d, ct, st):
    """``r`` times one modified-DH link with twist (ca, sa), length a, offset d and joint angle
    (ct, st) = (cos, sin) of theta: ``RotX(alpha) TransX(a) RotZ(theta) TransZ(d)``."""
    r00, r01, r02, r10, r11, r12, r20, r21, r22, px, py, pz = r
    ty, tz = -sa * d, ca * d  # RotX(alpha) (a, 0, 0) + RotX(alpha) RotZ(theta) (0, 0, d)
    px += r00 * a + r01 * ty + r02 * tz
    py += r10 * a + r11 * ty + r12 * tz
    pz += r20 * a + r21 * ty + r22 * tz
    # RotX(alpha) RotZ(theta) = [[ct, -st, 0], [ca st, ca ct, -sa], [sa st, sa ct, ca]]
    m10, m11, m20, m21 = ca * st, ca * ct, sa * st, sa * ct
    return (
        r00 * ct + r01 * m10 + r02 * m20,
        -r00 * st + r01 * m11 + r02 * m21,
        -r01 * sa + r02 * ca,
        r10 * ct + r11 * m10 + r12 * m20,
        -r10 * st + r11 * m11 + r12 * m21,
        -r11 * sa + r12 * ca,
        r20 * ct + r21 * m10 + r22 * m20,
        -r20 * st + r21 * m11 + r22 * m21,
        -r21 * sa + r22 * ca,
        px,
        py,
        pz,
    )


@_njit
def turn(r, ct, st):
    """``r`` times ``RotZ(theta)`` (ct, st: cos and sin of theta): a link frame at angle 0
    turned to its joint angle (RotZ commutes with the link's TransZ)."""
    r00, r01, r02, r10, r11, r12, r20, r21, r22, px, py, pz = r
    return (
        r00 * ct + r01 * st,
        -r00 * st + r01 * ct,
        r02,
        r10 * ct + r11 * st,
        -r10 * st + r11 * ct,
        r12,
        r20 * ct + r21 * st,
        -r20 * st + r21 * ct,
        r22,
        px,
        py,
        pz,
    )


@_njit
def compose_fixed(r, f):
    """``r`` times the fixed transform ``f`` (both 12-tuples)."""
    r00, r01, r02, r10, r11, r12, r20, r21, r22, px, py, pz = r
    f00, f01, f02, f10, f11, f12, f20, f21, f22, fx, fy, fz = f
    return (
        r00 * f00 + r01 * f10 + r02 * f20,
        r00 * f01 + r01 * f11 + r02 * f21,
        r00 * f02 + r01 * f12 + r02 * f22,
        r10 * f00 + r11 * f10 + r12 * f20,
        r10 * f01 + r11 * f11 + r12 * f21,
        r10 * f02 + r11 * f12 + r12 * f22,
        r20 * f00 + r21 * f10 + r22 * f20,
        r20 * f01 + r21 * f11 + r22 * f21,
        r20 * f02 + r21 * f12 + r22 * f22,
        px + r00 * fx + r01 * fy + r02 * fz,
        py + r10 * fx + r11 * fy + r12 * fz,
        pz + r20 * fx + r21 * fy + r22 * fz,
    )


@_njit
def load_fixed(v, o):
    """The fixed transform stored at ``v[o:o + 12]`` (3 x 4 row-major) as a 12-tuple."""
    return (
        v[o],
        v[o + 1],
        v[o + 2],
        v[o + 4],
        v[o + 5],
        v[o + 6],
        v[o + 8],
        v[o + 9],
        v[o + 10],
        v[o + 3],
        v[o + 7],
        v[o + 11],
    )


@_njit
def chain_pose(q, v, dh, base, tool):
    """Pose (12-tuple) of the tool for joint angles q (6,) [rad] of the chain whose DH rows
    start at ``v[dh]`` and whose base and tool transforms are at ``v[base]``, ``v[tool]``."""
    r = load_fixed(v, base)
    for i in range(6):
        o = dh + 5 * i
        th = q[i] + v[o + 4]
        r = compose_link(r, v[o], v[o + 1], v[o + 2], v[o + 3], math.cos(th), math.sin(th))
    return compose_fixed(r, load_fixed(v, tool))


@_njit
def pose_into(r, T) -> None:
    """Write the 12-tuple pose ``r`` into the homogeneous matrix T (4, 4)."""
    T[0, 0], T[0, 1], T[0, 2], T[0, 3] = r[0], r[1], r[2], r[9]
    T[1, 0], T[1, 1], T[1, 2], T[1, 3] = r[3], r[4], r[5], r[10]
    T[2, 0], T[2, 1], T[2, 2], T[2, 3] = r[6], r[7], r[8], r[11]
    T[3, 0], T[3, 1], T[3, 2], T[3, 3] = 0.0, 0.0, 0.0, 1.0


@_njit
def jacobian_into(q, v, dh, base, tool, J) -> None:
    """Geometric Jacobian J (6, 6) of the chain at the tool point: rows ``[v; w]`` in base-frame
    axes [m/rad; 1]; column i = ``[z_i x (p_tool - o_i); z_i]`` (z_i, o_i: axis and origin of
    link frame i)."""
    r = load_fixed(v, base)
    for i in range(6):
        o = dh + 5 * i
        th = q[i] + v[o + 4]
        r = compose_link(r, v[o], v[o + 1], v[o + 2], v[o + 3], math.cos(th), math.sin(th))
        J[0, i], J[1, i], J[2, i] = r[9], r[10], r[11]  # origin of frame i (replaced below)
        J[3, i], J[4, i], J[5, i] = r[2], r[5], r[8]  # its z axis: joint i's axis
    e = compose_fixed(r, load_fixed(v, tool))
    for i in range(6):
        dx, dy, dz = e[9] - J[0, i], e[10] - J[1, i], e[11] - J[2, i]
        zx, zy, zz = J[3, i], J[4, i], J[5, i]
        J[0, i] = zy * dz - zz * dy
        J[1, i] = zz * dx - zx * dz
        J[2, i] = zx * dy - zy * dx


@_njit
def rotation_angle_12(r, R):
    """Angle between the rotation of the 12-tuple ``r`` and R (3, 3) [rad]: the formula of
    :func:`iik.rotations.rotation_angle`, ``2 asin(|R1 - R2|_F / sqrt 8)``."""
    d = 0.0
    for i in range(3):
        for j in range(3):
            d += (r[3 * i + j] - R[i, j]) ** 2
    return 2.0 * math.asin(min(math.sqrt(d) / _SQRT8, 1.0))


@_njit
def position_error_12(r, T):
    """|p(r) - p(T)| [m]."""
    return math.sqrt((r[9] - T[0, 3]) ** 2 + (r[10] - T[1, 3]) ** 2 + (r[11] - T[2, 3]) ** 2)


@_njit
def pose_error_vector(r, R, T, e) -> None:
    """e (6,) = ``[p* - p; vee(Re - Re^T) / 2]`` with ``Re = R* R(r)^T``: the vector Newton's
    method drives to zero (target rotation R (3, 3), target position T[:3, 3])."""
    e[0], e[1], e[2] = T[0, 3] - r[9], T[1, 3] - r[10], T[2, 3] - r[11]
    re01 = R[0, 0] * r[3] + R[0, 1] * r[4] + R[0, 2] * r[5]
    re02 = R[0, 0] * r[6] + R[0, 1] * r[7] + R[0, 2] * r[8]
    re10 = R[1, 0] * r[0] + R[1, 1] * r[1] + R[1, 2] * r[2]
    re12 = R[1, 0] * r[6] + R[1, 1] * r[7] + R[1, 2] * r[8]
    re20 = R[2, 0] * r[0] + R[2, 1] * r[1] + R[2, 2] * r[2]
    re21 = R[2, 0] * r[3] + R[2, 1] * r[4] + R[2, 2] * r[5]
    e[3], e[4], e[5] = 0.5 * (re21 - re12), 0.5 * (re02 - re20), 0.5 * (re10 - re01)
