"""Pinocchio as the kinematic oracle: tool poses and Jacobians of the shipped URDF.

The model is :func:`iik.planning.robot_model.thesis_model` (the real
``urdf/thesis_arm.urdf`` loaded by Pinocchio); nothing here uses Eq 4.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from iik import THESIS_ARM
from iik.planning.robot_model import thesis_model

__all__ = ["thesis_model", "tool_frame_id", "tool_poses", "tool_jacobians", "joint_placements"]


def tool_frame_id() -> int:
    """Frame id of ``tool`` in :func:`thesis_model`."""
    return thesis_model(THESIS_ARM).tool_frame_id


def tool_poses(qs: np.ndarray) -> np.ndarray:
    """Pinocchio pose of frame ``tool`` for each q in ``qs`` (n, 6) [rad]: (n, 4, 4) [m]."""
    tm = thesis_model(THESIS_ARM)
    data = tm.model.createData()
    out = np.empty((len(qs), 4, 4))
    for k, q in enumerate(qs):
        pin.framesForwardKinematics(tm.model, data, q)
        out[k] = data.oMf[tm.tool_frame_id].homogeneous
    return out


def tool_jacobians(qs: np.ndarray) -> np.ndarray:
    """Pinocchio frame Jacobian of ``tool`` in LOCAL_WORLD_ALIGNED for each q in ``qs`` (n, 6):
    (n, 6, 6), rows [v; w] in base-frame axes."""
    tm = thesis_model(THESIS_ARM)
    data = tm.model.createData()
    out = np.empty((len(qs), 6, 6))
    for k, q in enumerate(qs):
        out[k] = pin.computeFrameJacobian(tm.model, data, q, tm.tool_frame_id, pin.LOCAL_WORLD_ALIGNED)
    return out


def joint_placements(qs: np.ndarray) -> np.ndarray:
    """Pinocchio placements ``oMi`` of the joint frames 0..6 for each q in ``qs`` (n, 6):
    (n, 7, 4, 4) [m]. Joint frame i of the URDF is DH frame i of Table II (frame 0 the base)."""
    tm = thesis_model(THESIS_ARM)
    data = tm.model.createData()
    out = np.empty((len(qs), tm.model.njoints, 4, 4))
    for k, q in enumerate(qs):
        pin.forwardKinematics(tm.model, data, q)
        for i in range(tm.model.njoints):
            out[k, i] = data.oMi[i].homogeneous
    return out
