"""Pinocchio models of an arm and its body: joints, collision shapes, the tool frame (cached per arm).

:func:`arm_model` gives the ``pin.Model`` and the collision ``pin.GeometryModel`` of any
:class:`~iik.arm.Arm`, the body the collision checks (:mod:`iik.planning.collision`) and the viewer
draw. The shapes come from, in this order:

1. ``"urdf"``: the arm's own URDF file (:attr:`iik.Arm.urdf`, e.g. ``urdf/crx10ia.urdf``) when it
   has collision shapes, exactly the six revolute joints of the arm and the same kinematics (the
   joint axes of the file agree with the arm's at two configurations within 1e-9 m / rad) -- for the
   thesis arm this is the shipped ``urdf/thesis_arm.urdf`` (found with
   :func:`iik.resources.urdf_path`, never the working directory);
2. ``"powercube"``: for another arm of the thesis's Table II form (e.g. a scaled thesis arm), the
   PowerCube shapes of :func:`iik.urdf.thesis_urdf` laid out along its links;
3. ``"generated"``: otherwise cylinders along the links of the arm's DH chain
   (:func:`iik.urdf.link_geometry`, radius :func:`iik.urdf.link_radius`).

Every model has a frame ``tool`` at the arm's tool frame (:func:`iik.fk`). Collision pairs are
every pair of shapes on different links except links joined by a joint (they share its housing);
for generated shapes also the pairs already in contact at q = 0 (links around a joint where two
axes meet: an SRDF's "Default" pairs). ``ArmModel.geometry`` says which source was used.

Callers must not mutate the returned objects; create their own ``Data``
(``model.createData()``, ``pin.GeometryData(collision_model)``).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np
import pinocchio as pin

from iik.arm import Arm
from iik.errors import InvalidInputError
from iik.files import read_text
from iik.kinematics import fk
from iik.resources import urdf_path
from iik.urdf import MAX_URDF_BYTES, TOOL_FRAME, generated_urdf, thesis_urdf

__all__ = ["ArmModel", "ThesisModel", "arm_model", "thesis_model", "load_model", "collision_link",
           "link_of_joint", "GEOMETRIES"]

#: Where an :class:`ArmModel`'s shapes come from (module docstring).
GEOMETRIES = ("urdf", "powercube", "generated")
#: Tolerance of the check that a URDF file's joints are the arm's [m, rad].
_SAME_AXES = 1e-9


@dataclass(frozen=True)
class ArmModel:
    """An arm in Pinocchio.

    Attributes:
        model: Kinematic model (the arm's six revolute joints, its limits).
        collision_model: Collision shapes with the pairs to check registered (module docstring).
        tool_frame_id: Id of frame ``tool`` (the arm's tool frame, :func:`iik.fk`).
        path: The URDF file that was loaded (None for a model built from generated text).
        geometry: Where the shapes come from, one of :data:`GEOMETRIES`.
    """

    model: pin.Model
    collision_model: pin.GeometryModel
    tool_frame_id: int
    path: Path | None
    geometry: str = "urdf"

    def __iter__(self):  # allows ``model, collision_model = arm_model(arm)``
        return iter((self.model, self.collision_model))


#: The former name of :class:`ArmModel`.
ThesisModel = ArmModel


def collision_link(model: pin.Model, geom: pin.GeometryObject) -> str:
    """Name of the link a collision shape belongs to (its parent body frame)."""
    return model.frames[geom.parentFrame].name


def link_of_joint(tm: ArmModel, j: int) -> str:
    """Name of the link moved by joint ``j`` (0-based) that carries shapes: the first shape's link
    among those attached to the joint (``link{j+1}`` for the thesis arm), else the joint's name."""
    for g in tm.collision_model.geometryObjects:
        if g.parentJoint == j + 1:
            return collision_link(tm.model, g)
    return tm.model.names[j + 1]


def load_model(path: Path | str, *, with_collision: bool = True) -> ArmModel:
    """Load any URDF file written by :mod:`iik.urdf` (not cached; read by :func:`iik.files.read_text`,
    at most :data:`iik.urdf.MAX_URDF_BYTES`: its shapes are primitives, no mesh files).

    Raises:
        FileError: (argument ``path``) missing, not a regular file, too large or not UTF-8.
    """
    path = Path(path)
    text = read_text(path, "path", limit=MAX_URDF_BYTES, what="a URDF file")
    return dataclasses.replace(_build(text, with_collision), path=path)


def _pairs(model: pin.Model, geom: pin.GeometryModel, skip=frozenset()) -> None:
    """Register every pair of shapes on different, non-adjacent links (and not in ``skip``)."""
    objs = geom.geometryObjects
    for i in range(len(objs)):
        for j in range(i + 1, len(objs)):
            a, b = objs[i].parentJoint, objs[j].parentJoint
            la, lb = collision_link(model, objs[i]), collision_link(model, objs[j])
            adjacent = a == b or model.parents[a] == b or model.parents[b] == a
            if la != lb and not adjacent and frozenset((la, lb)) not in skip:
                geom.addCollisionPair(pin.CollisionPair(i, j))


def _build(urdf: str, with_collision: bool, *, path: Path | None = None) -> ArmModel:
    """Model and collision model from URDF text (the text of ``path`` if given)."""
    model = pin.buildModelFromXML(urdf)
    geom = pin.GeometryModel()
    if with_collision:
        geom = pin.buildGeomFromUrdfString(model, urdf, pin.COLLISION)
        _pairs(model, geom)
    return ArmModel(model, geom, model.getFrameId(TOOL_FRAME), path)


def thesis_model(arm: Arm) -> ArmModel:
    """The thesis arm design (PowerCube shapes) with the lengths and limits of ``arm``, an arm of the
    thesis's Table II form (cached per arm): the shipped ``urdf/thesis_arm.urdf`` for the thesis arm,
    :func:`iik.urdf.thesis_urdf` of ``arm`` for any other."""
    return _cached_model(arm)


@lru_cache(maxsize=4)
def _cached_model(arm: Arm) -> ArmModel:
    from iik.arm import THESIS_ARM

    if arm == THESIS_ARM:
        return load_model(urdf_path())
    return dataclasses.replace(_build(thesis_urdf(arm), True), geometry="powercube")


def arm_model(arm: Arm) -> ArmModel:
    """The Pinocchio model and collision shapes of ``arm`` (cached per arm; module docstring)."""
    if not isinstance(arm, Arm):
        raise InvalidInputError("arm", f"expected an iik.Arm, got {type(arm).__name__}")
    return _arm_model(arm)


@lru_cache(maxsize=8)
def _arm_model(arm: Arm) -> ArmModel:
    if arm.urdf and (tm := _from_urdf_file(arm)) is not None:
        return tm
    try:
        return thesis_model(arm)  # an arm of the thesis's form (raises for another form or too short)
    except InvalidInputError:
        return _generated(arm)


def _from_urdf_file(arm: Arm) -> ArmModel | None:
    """The arm's own URDF file as its model, if it has shapes and the arm's joints (else None)."""
    path = Path(arm.urdf)
    text = read_text(path, "arm.urdf", limit=MAX_URDF_BYTES, what="a URDF file")
    model = pin.buildModelFromXML(text)
    if model.nq != 6 or model.njoints != 7 or any(model.parents[j] != j - 1 for j in range(1, 7)):
        return None
    geom = pin.buildGeomFromUrdfString(model, text, pin.COLLISION)
    if len(geom.geometryObjects) == 0:
        return None
    model = _with_tool(model, arm)
    if model is None:
        return None
    _pairs(model, geom)
    return ArmModel(model, geom, model.getFrameId(TOOL_FRAME), path, "urdf")


def _with_tool(model: pin.Model, arm: Arm) -> pin.Model | None:
    """``model`` with a frame ``tool`` at the arm's tool frame, if its joints are the arm's joints
    (axes agree at q = 0 and at mid-range); else None."""
    data = model.createData()
    for q in (np.zeros(6), 0.5 * (arm.q_min + arm.q_max) + 0.1):
        pin.forwardKinematics(model, data, q)
        pts, dirs = arm.joint_axes(q)
        for j in range(6):
            M = data.oMi[j + 1]
            axis = M.rotation @ _joint_axis(model, j + 1)
            off = np.cross(M.translation - pts[j], dirs[j])
            if np.linalg.norm(axis - dirs[j]) > _SAME_AXES or np.linalg.norm(off) > _SAME_AXES:
                return None
    pin.forwardKinematics(model, data, np.zeros(6))
    placement = data.oMi[6].inverse() * pin.SE3(fk(np.zeros(6), arm))
    if model.existFrame(TOOL_FRAME):
        return None
    parent = model.getFrameId(model.names[6])
    model.addFrame(pin.Frame(TOOL_FRAME, 6, parent, placement, pin.FrameType.OP_FRAME))
    return model


def _joint_axis(model: pin.Model, j: int) -> np.ndarray:
    """Unit axis of revolute joint ``j`` in its own frame."""
    jm = model.joints[j]
    short = jm.shortname()
    if short.endswith("RX") or short == "JointModelRX":
        return np.array([1.0, 0.0, 0.0])
    if short.endswith("RY"):
        return np.array([0.0, 1.0, 0.0])
    if short.endswith("RZ"):
        return np.array([0.0, 0.0, 1.0])
    return np.asarray(jm.extract().axis, float)


def _generated(arm: Arm) -> ArmModel:
    """Cylinders along the links (:func:`iik.urdf.generated_urdf`), without the pairs in contact at q = 0."""
    tm = _build(generated_urdf(arm), True)
    model, geom = tm.model, tm.collision_model
    data, gdata = model.createData(), pin.GeometryData(geom)
    pin.forwardKinematics(model, data, np.zeros(6))
    pin.updateGeometryPlacements(model, data, geom, gdata)
    pin.computeDistances(geom, gdata)
    touching = set()
    for k, pair in enumerate(geom.collisionPairs):
        if gdata.distanceResults[k].min_distance <= 0.0:
            objs = geom.geometryObjects
            touching.add(frozenset(collision_link(model, objs[i]) for i in (pair.first, pair.second)))
    fresh = pin.GeometryModel()
    for obj in geom.geometryObjects:
        fresh.addGeometryObject(obj)
    _pairs(model, fresh, frozenset(touching))
    return ArmModel(model, fresh, model.getFrameId(TOOL_FRAME), None, "generated")
