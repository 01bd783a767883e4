"""Robots nobody here wrote, from ``example-robot-data``: their URDF files, and the FK of a model
generated from a published DH table next to the reference model's (used by :mod:`.ur5`, :mod:`.panda`)."""

from __future__ import annotations

import importlib.metadata
from pathlib import Path

import numpy as np
import pinocchio as pin

__all__ = ["example_robot_urdf", "fk_pair"]


def example_robot_urdf(relative: str) -> Path:
    """Path of the URDF ``robots/<relative>`` installed by ``example-robot-data`` (it has no Python
    module to ask). Raises ``FileNotFoundError`` if the distribution lacks it."""
    for f in importlib.metadata.files("example-robot-data") or ():
        if str(f).endswith(f"robots/{relative}"):
            return Path(f.locate())
    raise FileNotFoundError(f"{Path(relative).name} not found in the example-robot-data distribution")


def fk_pair(models, qs: np.ndarray, extra: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """Poses (n, 4, 4) of the generated and the reference frame at joints ``qs`` (n, dof).

    ``models`` is ``(generated model, its frame id, reference model, its frame id)``; the reference
    has ``extra`` further joints (e.g. fingers), held at 0."""
    gen, fg, ref, fr = models
    dg, dr = gen.createData(), ref.createData()
    Tg, Tr = np.empty((len(qs), 4, 4)), np.empty((len(qs), 4, 4))
    rest = np.zeros(extra)
    for k, q in enumerate(qs):
        pin.framesForwardKinematics(gen, dg, q)
        pin.framesForwardKinematics(ref, dr, np.concatenate([q, rest]))
        Tg[k], Tr[k] = dg.oMf[fg].homogeneous, dr.oMf[fr].homogeneous
    return Tg, Tr
