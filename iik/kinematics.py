"""Forward kinematics and Jacobians of the thesis arm.

All functions take joint angles ``q`` [rad] of shape (6,) or (n, 6) and an
optional :class:`~iik.arm.Arm` (default :data:`~iik.arm.THESIS_ARM`).
Positions are in metres in the base frame 0 of Table II (z up along joint 1,
origin on the joint-1 axis at the mounting plane, i.e. ``l1`` below joint 2).
The tool point is the origin of frame 6 (the end-effector point ``p`` of Eq 4).
"""

from __future__ import annotations

import numpy as np

from .arm import THESIS_ARM, Arm
from .dh import dh_chain
from .validation import as_joints

__all__ = ["fk", "fk_chain", "position_jacobian", "jacobian", "joint_frames"]


def _trig(qb: np.ndarray):
    c, s = np.cos(qb).T, np.sin(qb).T
    c45, s45 = np.cos(qb[:, 3] + qb[:, 4]), np.sin(qb[:, 3] + qb[:, 4])
    return c, s, c45, s45


def fk(q, arm: Arm = THESIS_ARM) -> np.ndarray:
    """End-effector pose ``0_6 T`` by the closed form of Eq 4.

    Args:
        q: Joint angles [rad], shape (6,) or (n, 6), measured from the home
            pose of Fig 8 (q = 0, arm stretched along +x).
        arm: Arm parameters.

    Returns:
        Homogeneous transform(s) (4, 4) or (n, 4, 4): rotation of frame 6 and
        position of its origin [m], both in base frame 0.
    """
    qb, batched = as_joints(q, "q")
    (c1, c2, c3, c4, _c5, c6), (s1, s2, s3, s4, _s5, s6), c45, s45 = _trig(qb)
    l1, l2, l3, l4, l5 = arm.lengths
    A = s1 * s3 + c1 * s2 * c3  # recurring term of Eq 4
    B = c1 * s3 - s1 * s2 * c3  # recurring term of Eq 4
    W = l5 * s45 + l4 * s4
    V = l5 * c45 + l4 * c4
    T = np.zeros((qb.shape[0], 4, 4))
    T[:, 0, 0] = c6 * (c45 * A - s45 * c1 * c2) - s6 * (s1 * c3 - c1 * s2 * s3)  # Eq 4 r11
    T[:, 1, 0] = s6 * (c1 * c3 + s1 * s2 * s3) - c6 * (c45 * B + s45 * s1 * c2)  # Eq 4 r21
    T[:, 2, 0] = c6 * (s45 * s2 + c45 * c2 * c3) + c2 * s3 * s6  # Eq 4 r31
    T[:, 0, 1] = -s6 * (c45 * A - s45 * c1 * c2) - c6 * (c3 * s1 - c1 * s2 * s3)  # Eq 4 r12
    T[:, 1, 1] = s6 * (c45 * B + s45 * s1 * c2) + c6 * (c1 * c3 + s1 * s2 * s3)  # Eq 4 r22
    T[:, 2, 1] = c2 * s3 * c6 - s6 * (s45 * s2 + c45 * c2 * c3)  # Eq 4 r32
    T[:, 0, 2] = -s45 * A - c45 * c1 * c2  # Eq 4 r13
    T[:, 1, 2] = s45 * B - c45 * s1 * c2  # Eq 4 r23
    T[:, 2, 2] = c45 * s2 - s45 * c2 * c3  # Eq 4 r33
    T[:, 0, 3] = l2 * c1 + l3 * c1 * c2 + W * A + V * c1 * c2  # Eq 4 px
    T[:, 1, 3] = l2 * s1 + l3 * s1 * c2 - W * B + V * s1 * c2  # Eq 4 py
    T[:, 2, 3] = l5 * (s45 * c2 * c3 - c45 * s2) + l4 * (c2 * c3 * s4 - c4 * s2) - l3 * s2 + l1  # Eq 4 pz
    T[:, 3, 3] = 1.0
    return T if batched else T[0]


def fk_chain(q, arm: Arm = THESIS_ARM) -> np.ndarray:
    """End-effector pose by the generic modified-DH product of Table II.

    Independent of :func:`fk` (which uses the printed closed form); the two
    are checked against each other and against Pinocchio by ``iik verify``.
    """
    return dh_chain(arm.dh_table(), q)


def joint_frames(q, arm: Arm = THESIS_ARM) -> np.ndarray:
    """Frames ``0_T_i``, i = 1..6, shape (6, 4, 4) or (n, 6, 4, 4) [m]."""
    return dh_chain(arm.dh_table(), q, all_frames=True)


def position_jacobian(q, arm: Arm = THESIS_ARM) -> np.ndarray:
    """Appendix C: the 3x5 Jacobian ``d(px, py, pz) / d(theta1..theta5)`` [m/rad].

    Rows are x, y, z of the tool point in the base frame; columns are joints
    1..5 (joint 6 does not move the tool point, Eq 34). Shape (3, 5) or (n, 3, 5).
    """
    qb, batched = as_joints(q, "q")
    (c1, c2, c3, c4, _c5, _c6), (s1, s2, s3, s4, _s5, _s6), c45, s45 = _trig(qb)
    _l1, l2, l3, l4, l5 = arm.lengths
    A = s1 * s3 + c1 * s2 * c3
    B = c1 * s3 - s1 * s2 * c3
    W = l5 * s45 + l4 * s4
    V = l5 * c45 + l4 * c4
    J = np.zeros((qb.shape[0], 3, 5))
    J[:, 0, 0] = -l2 * s1 - l3 * s1 * c2 + W * B - V * s1 * c2  # App C df1/dth1
    J[:, 0, 1] = -l3 * c1 * s2 + W * c1 * c2 * c3 - V * c1 * s2  # App C df1/dth2
    J[:, 0, 2] = W * (s1 * c3 - c1 * s2 * s3)  # App C df1/dth3
    J[:, 0, 3] = V * A - W * c1 * c2  # App C df1/dth4
    J[:, 0, 4] = l5 * c45 * A - l5 * c1 * c2 * s45  # App C df1/dth5
    J[:, 1, 0] = l2 * c1 + l3 * c1 * c2 + W * A + V * c1 * c2  # App C df2/dth1
    J[:, 1, 1] = -l3 * s1 * s2 + W * s1 * c2 * c3 - V * s1 * s2  # App C df2/dth2
    J[:, 1, 2] = -W * (c1 * c3 + s1 * s2 * s3)  # App C df2/dth3
    J[:, 1, 3] = -V * B - W * s1 * c2  # App C df2/dth4
    J[:, 1, 4] = -l5 * c45 * B - l5 * s1 * c2 * s45  # App C df2/dth5
    # App C df3/dth1 = 0
    J[:, 2, 1] = -l5 * (s45 * s2 * c3 + c45 * c2) - l4 * (s2 * c3 * s4 + c4 * c2) - l3 * c2  # App C df3/dth2
    J[:, 2, 2] = -l5 * s45 * c2 * s3 - l4 * c2 * s3 * s4  # App C df3/dth3
    J[:, 2, 3] = l5 * (c45 * c2 * c3 + s45 * s2) + l4 * (c2 * c3 * c4 + s4 * s2)  # App C df3/dth4
    J[:, 2, 4] = l5 * (c45 * c2 * c3 + s45 * s2)  # App C df3/dth5
    return J if batched else J[0]


def jacobian(q, arm: Arm = THESIS_ARM) -> np.ndarray:
    """Full 6x6 geometric Jacobian at the tool point (origin of frame 6).

    Rows 0-2 are the linear velocity [m/s per rad/s], rows 3-5 the angular
    velocity [rad/s per rad/s], all expressed in the axes of base frame 0
    (Pinocchio's ``LOCAL_WORLD_ALIGNED``). Column i is ``[z_i x (p - o_i); z_i]``
    with ``z_i``, ``o_i`` the axis and origin of joint frame i (modified DH).
    Shape (6, 6) or (n, 6, 6).
    """
    qb, batched = as_joints(q, "q")
    frames = dh_chain(arm.dh_table(), qb, all_frames=True)  # (n, 6, 4, 4)
    z = frames[:, :, :3, 2]
    o = frames[:, :, :3, 3]
    p = frames[:, -1, :3, 3]
    J = np.empty((qb.shape[0], 6, 6))
    J[:, :3, :] = np.cross(z, p[:, None, :] - o).transpose(0, 2, 1)
    J[:, 3:, :] = z.transpose(0, 2, 1)
    return J if batched else J[0]
