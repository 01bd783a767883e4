"""Forward kinematics and Jacobians of an arm (:class:`~iik.arm.Arm`), and Eq 4 as printed.

All functions take joint angles ``q`` [rad] of shape (6,) or (n, 6) and an
:class:`~iik.arm.Arm`. Positions are in metres in the arm's base frame (for the thesis arm
the base frame 0 of Table II: z up along joint 1, origin on the joint-1 axis at the
mounting plane, i.e. ``l1`` below joint 2). The tool point is the origin of the tool frame
(for the thesis arm the end-effector point ``p`` of Eq 4, the origin of frame 6).

:func:`fk` and :func:`jacobian` run the compiled modified-DH chain (:mod:`iik.ik.chain`) for
one ``q`` and for a batch (a batch is bit-for-bit a loop of single calls).

The thesis's closed forms of Eq 4 and App. C are kept as printed (with the errata fixed) for
the thesis arm (:func:`eq4_terms`, :func:`eq4_position`, :func:`eq4_wrist_axes`,
:func:`eq4_rotation`, :func:`app_c_position_jacobian`): plain arithmetic on cosines and
sines that works on floats and arrays; ``iik verify`` checks them against :func:`fk` and
Pinocchio.
"""

from __future__ import annotations

import numpy as np

from .arm import Arm
from .dh import dh_chain
from .validation import as_joints

__all__ = ["fk", "fk_chain", "reach_bound", "position_jacobian", "jacobian", "joint_frames", "eq4_terms",
           "eq4_position", "eq4_wrist_axes", "eq4_rotation", "app_c_position_jacobian"]


# ----------------------------------------------------------------------------- closed forms
def eq4_terms(c1, s1, c2, s2, c3, s3, c4, s4, c45, s45, l4, l5):
    """The recurring terms of Eq 4 (also of Eq 34 and App. C): ``(A, B, W, V)``.

    ``A = s1 s3 + c1 s2 c3``, ``B = c1 s3 - s1 s2 c3`` (dimensionless) and
    ``W = l5 s45 + l4 s4``, ``V = l5 c45 + l4 c4`` [m], with ``c45 = cos(theta4 + theta5)``.
    """
    A = s1 * s3 + c1 * s2 * c3  # Eq 4 recurring term
    B = c1 * s3 - s1 * s2 * c3  # Eq 4 recurring term
    W = l5 * s45 + l4 * s4  # Eq 4 recurring term [m]
    V = l5 * c45 + l4 * c4  # Eq 4 recurring term [m]
    return A, B, W, V


def eq4_position(c1, s1, c2, s2, c3, A, B, W, V, l1, l2, l3):
    """Tool point ``(px, py, pz)`` [m] of Eq 4 (= Eq 34) from the terms of :func:`eq4_terms`."""
    px = l2 * c1 + l3 * c1 * c2 + W * A + V * c1 * c2  # Eq 4 px (Eq 34a)
    py = l2 * s1 + l3 * s1 * c2 - W * B + V * s1 * c2  # Eq 4 py (Eq 34b)
    pz = W * c2 * c3 - V * s2 - l3 * s2 + l1  # Eq 4 pz (Eq 34c)
    return px, py, pz


def eq4_wrist_axes(c1, s1, c2, s2, c3, s3, c45, s45, A, B):
    """The theta6-free part of the Eq 4 rotation: ``(X1, X2, X3, Y1, Y2, Y3, Z1, Z2, Z3)``.

    ``X`` is the x axis of frame 6 at theta6 = 0, ``-Y`` its y axis and ``Z`` the
    tool axis z6 (all in base frame 0); :func:`eq4_rotation` turns X and Y by theta6.
    """
    X1 = c45 * A - s45 * c1 * c2  # Eq 4 r11 at theta6 = 0
    X2 = -(c45 * B + s45 * s1 * c2)  # Eq 4 r21 at theta6 = 0
    X3 = s45 * s2 + c45 * c2 * c3  # Eq 4 r31 at theta6 = 0
    Y1 = s1 * c3 - c1 * s2 * s3  # -(Eq 4 r12 at theta6 = 0)
    Y2 = -(c1 * c3 + s1 * s2 * s3)  # -(Eq 4 r22 at theta6 = 0)
    Y3 = -c2 * s3  # -(Eq 4 r32 at theta6 = 0)
    Z1 = -s45 * A - c45 * c1 * c2  # Eq 4 r13
    Z2 = s45 * B - c45 * s1 * c2  # Eq 4 r23
    Z3 = c45 * s2 - s45 * c2 * c3  # Eq 4 r33
    return X1, X2, X3, Y1, Y2, Y3, Z1, Z2, Z3


def eq4_rotation(c6, s6, X1, X2, X3, Y1, Y2, Y3):
    """Columns 1 and 2 of the Eq 4 rotation: ``(r11, r21, r31, r12, r22, r32)``."""
    r11 = c6 * X1 - s6 * Y1  # Eq 4 r11
    r21 = c6 * X2 - s6 * Y2  # Eq 4 r21
    r31 = c6 * X3 - s6 * Y3  # Eq 4 r31
    r12 = -s6 * X1 - c6 * Y1  # Eq 4 r12
    r22 = -s6 * X2 - c6 * Y2  # Eq 4 r22
    r32 = -s6 * X3 - c6 * Y3  # Eq 4 r32
    return r11, r21, r31, r12, r22, r32


def app_c_position_jacobian(c1, s1, c2, s2, c3, s3, c4, s4, c45, s45, A, B, W, V, l2, l3, l4, l5):
    """Appendix C: the 15 entries of ``d(px, py, pz) / d(theta1..theta5)``, row-major (3 x 5) [m/rad]."""
    j11 = -l2 * s1 - l3 * s1 * c2 + W * B - V * s1 * c2  # App C df1/dth1
    j12 = -l3 * c1 * s2 + W * c1 * c2 * c3 - V * c1 * s2  # App C df1/dth2
    j13 = W * (s1 * c3 - c1 * s2 * s3)  # App C df1/dth3
    j14 = V * A - W * c1 * c2  # App C df1/dth4
    j15 = l5 * c45 * A - l5 * c1 * c2 * s45  # App C df1/dth5
    j21 = l2 * c1 + l3 * c1 * c2 + W * A + V * c1 * c2  # App C df2/dth1
    j22 = -l3 * s1 * s2 + W * s1 * c2 * c3 - V * s1 * s2  # App C df2/dth2
    j23 = -W * (c1 * c3 + s1 * s2 * s3)  # App C df2/dth3
    j24 = -V * B - W * s1 * c2  # App C df2/dth4
    j25 = -l5 * c45 * B - l5 * s1 * c2 * s45  # App C df2/dth5
    j31 = 0.0 * c1  # App C df3/dth1 = 0
    j32 = -l5 * (s45 * s2 * c3 + c45 * c2) - l4 * (s2 * c3 * s4 + c4 * c2) - l3 * c2  # App C df3/dth2
    j33 = -l5 * s45 * c2 * s3 - l4 * c2 * s3 * s4  # App C df3/dth3
    j34 = l5 * (c45 * c2 * c3 + s45 * s2) + l4 * (c2 * c3 * c4 + s4 * s2)  # App C df3/dth4
    j35 = l5 * (c45 * c2 * c3 + s45 * s2)  # App C df3/dth5
    return (j11, j12, j13, j14, j15, j21, j22, j23, j24, j25, j31, j32, j33, j34, j35)


# ----------------------------------------------------------------------------- public API
_KERNEL = None


def _kernel():
    """The compiled kernel module (imported on first use: ``import iik`` stays light)."""
    global _KERNEL
    if _KERNEL is None:
        from .ik import kernel

        _KERNEL = kernel
    return _KERNEL


_F64 = np.dtype(np.float64)


def _apply(q, compiled, data, shape: tuple[int, ...]) -> np.ndarray:
    """Run a compiled ``(Q (n, 6), data, out (n, *shape)) -> all finite`` on q (6,) or (n, 6).

    One contiguous float64 q skips the general validation (the kernel checks finiteness).
    """
    if type(q) is np.ndarray and q.dtype is _F64 and q.shape == (6,) and q.flags.c_contiguous:
        out = np.empty((1, *shape))
        if compiled(q.reshape(1, 6), data, out):
            return out[0]
    qb, batched = as_joints(q, "q")  # the typed errors
    out = np.empty((qb.shape[0], *shape))
    if not compiled(np.ascontiguousarray(qb), data, out):  # pragma: no cover (as_joints checked)
        raise AssertionError("kernel and as_joints disagree on finiteness")
    return out if batched else out[0]


def fk(q, arm: Arm) -> np.ndarray:
    """Tool pose ``base . links(q) . tool`` of the arm (Eq 4 for the thesis arm).

    Args:
        q: Joint angles [rad], shape (6,) or (n, 6) (for the thesis arm measured from the home
            pose of Fig 8: q = 0, arm stretched along +x).
        arm: The arm.

    Returns:
        Homogeneous transform(s) (4, 4) or (n, 4, 4): rotation of the tool frame (frame 6 of
        Table II for the thesis arm) and position of its origin [m], in the arm's base frame.
    """
    k = _kernel()
    return _apply(q, k.fk_many, k.arm_data(arm).vector, (4, 4))


def fk_chain(q, arm: Arm) -> np.ndarray:
    """Tool pose by the NumPy modified-DH product (:func:`iik.dh.dh_chain`) with the base and
    tool transforms: independent of the compiled :func:`fk` (checked against each other and
    against Pinocchio)."""
    T = dh_chain(arm.dh_table(), q)
    return np.array(arm.base) @ T @ np.array(arm.tool)


def joint_frames(q, arm: Arm) -> np.ndarray:
    """Link frames ``base . 0_T_i``, i = 1..6, shape (6, 4, 4) or (n, 6, 4, 4) [m]."""
    return np.array(arm.base) @ dh_chain(arm.dh_table(), q, all_frames=True)


def position_jacobian(q, arm: Arm) -> np.ndarray:
    """The position rows of :func:`jacobian`: ``d(px, py, pz) / d(q1..q6)`` [m/rad], shape
    (3, 6) or (n, 3, 6) (Appendix C for the thesis arm, whose joint 6 column is zero)."""
    return jacobian(q, arm)[..., :3, :]


def jacobian(q, arm: Arm) -> np.ndarray:
    """Full 6x6 geometric Jacobian at the tool point.

    Rows 0-2 are the linear velocity [m/s per rad/s], rows 3-5 the angular velocity
    [rad/s per rad/s], all expressed in the axes of the arm's base frame (Pinocchio's
    ``LOCAL_WORLD_ALIGNED``). Column i is ``[z_i x (p - o_i); z_i]`` with ``z_i``, ``o_i`` the
    axis and origin of joint i. Shape (6, 6) or (n, 6, 6).
    """
    k = _kernel()
    return _apply(q, k.jacobian_many, k.arm_data(arm).vector, (6, 6))


def reach_bound(arm: Arm) -> float:
    """An upper bound on the distance of the tool point from the base origin [m]
    (:attr:`iik.arm.Arm.reach`): a pose farther than this is out of reach."""
    return arm.reach
