"""The Franka Panda as a second outside check of :mod:`iik.urdf`, in the *modified* convention.

Franka Emika publish the Panda's kinematics as a Craig (modified) DH table, the convention
of the thesis's Table II: a = [0, 0, 0, 0.0825, -0.0825, 0, 0.088] m,
d = [0.333, 0, 0.316, 0, 0.384, 0, 0] m, alpha = [0, -pi/2, pi/2, pi/2, -pi/2, pi/2, pi/2],
and a flange 0.107 m along z of frame 7. :func:`panda_fk_pair` compares the URDF built from
that table (limits and speeds copied from the reference model) with ``panda.urdf`` of
``example-robot-data`` (frame ``panda_link8``, the flange). The base and tool transforms
solved by :func:`verification.oracles.ur5.solve_base_tool` are the identity (frozen as such).
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

import numpy as np
import pinocchio as pin

from iik.dh import DHRow, DHTable
from iik.urdf import TOOL_FRAME, urdf_from_dh

from .example_robots import example_robot_urdf, fk_pair

__all__ = ["PANDA_A", "PANDA_D", "PANDA_ALPHA", "PANDA_FLANGE", "panda_reference_path",
           "panda_models", "panda_fk_pair"]

PANDA_A = (0.0, 0.0, 0.0, 0.0825, -0.0825, 0.0, 0.088)
PANDA_D = (0.333, 0.0, 0.316, 0.0, 0.384, 0.0, 0.0)
PANDA_ALPHA = (0.0, -np.pi / 2, np.pi / 2, np.pi / 2, -np.pi / 2, np.pi / 2, np.pi / 2)
#: Flange offset along z7 [m].
PANDA_FLANGE = 0.107
REFERENCE_FRAME = "panda_link8"


def panda_reference_path() -> Path:
    """``panda.urdf`` installed by ``example-robot-data``."""
    return example_robot_urdf("panda_description/urdf/panda.urdf")


@lru_cache(maxsize=4)
def panda_models(generator=urdf_from_dh):
    """``(generated model, tool frame id, reference model, panda_link8 frame id)``; the
    generated model is built by ``generator``."""
    ref = pin.buildModelFromUrdf(str(panda_reference_path()))
    rows = tuple(DHRow(alpha=al, a=a, d=d) for al, a, d in zip(PANDA_ALPHA, PANDA_A, PANDA_D, strict=True))
    table = DHTable(rows=rows, convention="modified", lower=tuple(ref.lowerPositionLimit[:7]),
                    upper=tuple(ref.upperPositionLimit[:7]), velocity=tuple(ref.velocityLimit[:7]))
    tool = np.eye(4)
    tool[2, 3] = PANDA_FLANGE
    gen = pin.buildModelFromXML(generator(table, name="panda_from_dh", tool=tool))
    return gen, gen.getFrameId(TOOL_FRAME), ref, ref.getFrameId(REFERENCE_FRAME)


def panda_fk_pair(qs: np.ndarray, generator=urdf_from_dh) -> tuple[np.ndarray, np.ndarray]:
    """Poses (n, 4, 4) of the generated ``tool`` and the reference flange at arm joints ``qs`` (n, 7)
    (the generated model built by ``generator``, :func:`iik.urdf.urdf_from_dh` by default)."""
    models = panda_models(generator)
    return fk_pair(models, qs, extra=models[2].nq - 7)  # the fingers held at 0
