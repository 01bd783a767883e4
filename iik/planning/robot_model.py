"""Pinocchio models loaded from the shipped URDF (cached per process).

:func:`thesis_model` loads ``urdf/thesis_arm.urdf`` (found with
:func:`iik.resources.urdf_path`, never the working directory) into a
``pin.Model`` and its collision ``pin.GeometryModel``. The collision model has
every pair of shapes on different, non-adjacent links registered (adjacent
links share a joint module, see :func:`iik.urdf.adjacent_pairs`).

Callers must not mutate the returned objects; create their own ``Data``
(``model.createData()``, ``pin.GeometryData(collision_model)``).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import pinocchio as pin

from iik.resources import urdf_path
from iik.urdf import TOOL_FRAME, adjacent_pairs

__all__ = ["ThesisModel", "thesis_model", "load_model", "collision_link"]


@dataclass(frozen=True)
class ThesisModel:
    """The thesis arm in Pinocchio.

    Attributes:
        model: Kinematic model (6 revolute joints ``joint1..joint6``, Table I limits).
        collision_model: Collision shapes with non-adjacent link pairs registered.
        tool_frame_id: Id of frame ``tool`` (origin of DH frame 6 = Eq 4 point).
        path: The URDF that was loaded.
    """

    model: pin.Model
    collision_model: pin.GeometryModel
    tool_frame_id: int
    path: Path

    def __iter__(self):  # allows ``model, collision_model = thesis_model()``
        return iter((self.model, self.collision_model))


def collision_link(model: pin.Model, geom: pin.GeometryObject) -> str:
    """Name of the link a collision shape belongs to (its parent body frame)."""
    return model.frames[geom.parentFrame].name


def load_model(path: Path | str, *, with_collision: bool = True) -> ThesisModel:
    """Load any URDF written by :mod:`iik.urdf` (not cached)."""
    path = Path(path)
    model = pin.buildModelFromUrdf(str(path))
    geom = pin.buildGeomFromUrdf(model, str(path), pin.COLLISION) if with_collision else pin.GeometryModel()
    if with_collision:
        skip = {frozenset(p) for p in adjacent_pairs(model.nq)}
        objs = geom.geometryObjects
        for i in range(len(objs)):
            for j in range(i + 1, len(objs)):
                a, b = collision_link(model, objs[i]), collision_link(model, objs[j])
                if a != b and frozenset((a, b)) not in skip:
                    geom.addCollisionPair(pin.CollisionPair(i, j))
    return ThesisModel(model, geom, model.getFrameId(TOOL_FRAME), path)


@lru_cache(maxsize=1)
def thesis_model() -> ThesisModel:
    """The thesis arm from ``urdf/thesis_arm.urdf`` (cached)."""
    return load_model(urdf_path())
