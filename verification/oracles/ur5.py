"""The UR5 as an outside check of the URDF generator (:mod:`iik.urdf`).

The UR5 is built from its published *standard* DH table (Universal Robots:
d1 = 0.089159, a2 = -0.425, a3 = -0.39225, d4 = 0.10915, d5 = 0.09465, d6 = 0.0823 m,
alpha = [pi/2, 0, 0, pi/2, -pi/2, 0]) with :func:`iik.urdf.urdf_from_dh`, and compared
with ``ur5_robot.urdf`` of the ``example-robot-data`` package (written by others, from
ROS-Industrial's ``ur_description``).

The two models use different base and tool frames. With ``T_dh(q)`` the pose of the
generated ``tool`` frame and ``T_urdf(q)`` that of ``tool0`` in ``base_link`` of the
published URDF, :func:`solve_base_tool` finds the fixed transforms in
``T_urdf(q) = B T_dh(q) E`` (a hand-eye problem ``A X = X B``, solved in closed
form). The solution is frozen here as documented constants:

* :data:`UR5_BASE` = ``RotZ(pi)``: ``base_link`` of ur_description faces the other way
  from the DH base frame (its ``base`` frame is ``base_link`` turned by -pi).
* :data:`UR5_TOOL` = identity: ``tool0`` *is* DH frame 6 (the flange frame).

The joint zero positions agree (no joint offsets needed).
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

import numpy as np
import pinocchio as pin
from scipy.spatial.transform import Rotation

from iik.dh import DHRow, DHTable
from iik.urdf import TOOL_FRAME, urdf_from_dh

from .example_robots import example_robot_urdf, fk_pair

__all__ = [
    "UR5_D", "UR5_A", "UR5_ALPHA", "UR5_BASE", "UR5_TOOL",
    "ur5_dh_table", "ur5_generated_urdf", "ur5_reference_path", "ur5_models",
    "solve_base_tool", "ur5_fk_pair",
]

#: Published UR5 standard DH parameters [m, rad].
UR5_D = (0.089159, 0.0, 0.0, 0.10915, 0.09465, 0.0823)
UR5_A = (0.0, -0.425, -0.39225, 0.0, 0.0, 0.0)
UR5_ALPHA = (np.pi / 2, 0.0, 0.0, np.pi / 2, -np.pi / 2, 0.0)
#: Frozen base transform (solved by :func:`solve_base_tool`, see module docstring).
UR5_BASE = np.array([[-1.0, 0, 0, 0], [0, -1.0, 0, 0], [0, 0, 1.0, 0], [0, 0, 0, 1.0]])
#: Frozen tool transform: identity (``tool0`` = DH frame 6).
UR5_TOOL = np.eye(4)
#: Frame of the published URDF compared with the generated ``tool`` frame.
REFERENCE_FRAME = "tool0"


def ur5_dh_table() -> DHTable:
    """The UR5 standard DH table with +-2 pi limits and 3.15 rad/s speeds."""
    rows = tuple(DHRow(alpha=al, a=a, d=d) for al, a, d in zip(UR5_ALPHA, UR5_A, UR5_D, strict=True))
    return DHTable(rows=rows, convention="standard", lower=(-2 * np.pi,) * 6,
                   upper=(2 * np.pi,) * 6, velocity=(3.15,) * 6)


def ur5_generated_urdf(generator=urdf_from_dh) -> str:
    """URDF text of the UR5 from its DH table (no collision geometry), by ``generator``
    (:func:`iik.urdf.urdf_from_dh` unless a check substitutes another)."""
    return generator(ur5_dh_table(), name="ur5_from_dh", effort=(150.0,) * 3 + (28.0,) * 3)


def ur5_reference_path() -> Path:
    """Path of ``ur5_robot.urdf`` installed by ``example-robot-data``."""
    return example_robot_urdf("ur_description/urdf/ur5_robot.urdf")


@lru_cache(maxsize=4)
def ur5_models(generator=urdf_from_dh):
    """``(generated model, its tool frame id, reference model, its tool0 frame id)``."""
    gen = pin.buildModelFromXML(ur5_generated_urdf(generator))
    ref = pin.buildModelFromUrdf(str(ur5_reference_path()))
    return gen, gen.getFrameId(TOOL_FRAME), ref, ref.getFrameId(REFERENCE_FRAME)


def ur5_fk_pair(qs: np.ndarray, generator=urdf_from_dh) -> tuple[np.ndarray, np.ndarray]:
    """Poses (n, 4, 4) of the generated ``tool`` and the reference ``tool0`` at ``qs`` (n, 6)."""
    return fk_pair(ur5_models(generator), qs)


def solve_base_tool(T_dh: np.ndarray, T_ref: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Fixed ``B``, ``E`` with ``T_ref[k] = B @ T_dh[k] @ E`` (least squares, closed form).

    With ``A_k = T_ref[0]^-1 T_ref[k]`` and ``C_k = T_dh[0]^-1 T_dh[k]``,
    ``X = E^-1`` solves ``A_k X = X C_k``: its rotation aligns the rotation vectors of
    ``C_k`` to those of ``A_k`` (Kabsch), its translation solves
    ``(R_A - I) t = R_X t_C - t_A`` in least squares; then ``B = T_ref[0] X T_dh[0]^-1``.
    Needs >= 3 poses with non-parallel relative rotation axes.
    """
    inv = np.linalg.inv
    A = np.array([inv(T_ref[0]) @ T for T in T_ref[1:]])
    C = np.array([inv(T_dh[0]) @ T for T in T_dh[1:]])
    a = Rotation.from_matrix(A[:, :3, :3]).as_rotvec()
    c = Rotation.from_matrix(C[:, :3, :3]).as_rotvec()
    Rx, _ = Rotation.align_vectors(a, c)  # a_k ~ R_X c_k
    R_X = Rx.as_matrix()
    M = np.concatenate([A[k, :3, :3] - np.eye(3) for k in range(len(A))])
    rhs = np.concatenate([R_X @ C[k, :3, 3] - A[k, :3, 3] for k in range(len(A))])
    t_X = np.linalg.lstsq(M, rhs, rcond=None)[0]
    X = np.eye(4)
    X[:3, :3], X[:3, 3] = R_X, t_X
    return T_ref[0] @ X @ inv(T_dh[0]), inv(X)
