"""iik.planning.robot_model (the body of an arm) and verification.testing.strategies."""

import dataclasses
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given

import iik
import iik.arms
from iik import THESIS_ARM
from iik.arm import thesis_arm
from iik.planning.collision import SceneCollision
from iik.planning.robot_model import arm_model, collision_link, link_of_joint, thesis_model
from iik.resources import urdf_path
from iik.urdf import link_radius
from verification.oracles.pinocchio_model import tool_frame_id
from verification.testing.strategies import BEYOND, joint_batches, joint_vectors, sample_joints


def test_thesis_model_is_cached_and_unpacks():
    tm = thesis_model(THESIS_ARM)
    assert thesis_model(THESIS_ARM) is tm and thesis_model(iik.THESIS_ARM) is tm
    model, collision = tm
    assert model.nq == 6 and len(collision.geometryObjects) > 7
    assert tm.path == urdf_path()
    assert model.frames[tool_frame_id()].name == "tool"


def test_another_arm_is_built_from_its_generated_urdf():

    import pinocchio as pin

    a = iik.THESIS_ARM
    arm = thesis_arm(a.l1, a.l2 * 1.3, a.l3, a.l4, a.l5 * 0.9, lower=(-1.0,) + a.lower[1:], upper=a.upper)
    tm = thesis_model(arm)
    assert tm.path is None and thesis_model(arm) is tm
    assert tm.model.lowerPositionLimit[0] == -1.0
    pairs = thesis_model(THESIS_ARM).collision_model.collisionPairs
    assert len(tm.collision_model.collisionPairs) == len(pairs)
    data = tm.model.createData()
    for q in np.random.default_rng(2).uniform(a.q_min, a.q_max, size=(5, 6)):
        pin.framesForwardKinematics(tm.model, data, q)
        assert np.allclose(data.oMf[tm.tool_frame_id].homogeneous, iik.fk(q, arm), atol=1e-12)


@given(joint_vectors())
def test_joint_vectors_are_finite_and_near_the_limits(q):
    arm = iik.THESIS_ARM
    assert q.shape == (6,) and np.all(np.isfinite(q))
    assert np.all(q >= arm.q_min - BEYOND) and np.all(q <= arm.q_max + BEYOND)


@given(joint_batches())
def test_joint_batches_shape(qs):
    assert qs.ndim == 2 and qs.shape[1] == 6 and np.all(np.isfinite(qs))


def test_sample_joints_reaches_beyond_the_limits():
    qs = sample_joints(np.random.default_rng(0), 5000)
    arm = iik.THESIS_ARM
    assert (~arm.within_limits(qs)).any() and arm.within_limits(qs).any()
    assert np.all(qs >= arm.q_min - BEYOND) and np.all(qs <= arm.q_max + BEYOND)


# ------------------------------------------------------------------ the body of any arm (arm_model)
def _tool_matches_fk(tm, arm) -> float:
    import pinocchio as pin

    data = tm.model.createData()
    worst = 0.0
    for q in np.random.default_rng(4).uniform(arm.q_min, arm.q_max, size=(20, 6)):
        pin.framesForwardKinematics(tm.model, data, q)
        worst = max(worst, float(np.abs(data.oMf[tm.tool_frame_id].homogeneous - iik.fk(q, arm)).max()))
    return worst


def _pairs(tm) -> set[frozenset]:
    objs = tm.collision_model.geometryObjects
    return {frozenset(collision_link(tm.model, objs[i]) for i in (p.first, p.second))
            for p in tm.collision_model.collisionPairs}


def test_each_shipped_arm_has_its_body_with_its_tool_frame():
    expected = {"thesis": "urdf", "crx10ia": "urdf", "crx10ia_l": "urdf", "offset_base": "generated",
                "offset_flange": "generated"}
    for name, geometry in expected.items():
        arm = iik.arms.get(name)
        tm = arm_model(arm)
        assert tm.geometry == geometry and arm_model(arm) is tm, name
        assert _tool_matches_fk(tm, arm) < 1e-12, name
    assert arm_model(THESIS_ARM) is thesis_model(THESIS_ARM)
    assert arm_model(THESIS_ARM.scaled(1.2)).geometry == "powercube"


def test_the_crx_body_is_its_urdfs_shapes_without_the_joint_neighbours():
    crx = iik.arms.get("crx10ia")
    tm = arm_model(crx)
    assert tm.path == Path(crx.urdf)
    links = {collision_link(tm.model, g) for g in tm.collision_model.geometryObjects}
    assert links == {"base_link", "J1_link", "J2_link", "J3_link", "J4_link", "J5_link", "J6_link"}
    pairs = _pairs(tm)
    chain = ["base_link", "J1_link", "J2_link", "J3_link", "J4_link", "J5_link", "J6_link"]
    assert not any(frozenset(p) in pairs for p in zip(chain[:-1], chain[1:], strict=True))  # share a joint
    assert frozenset(("J4_link", "J6_link")) in pairs and frozenset(("base_link", "J6_link")) in pairs
    assert link_of_joint(tm, 3) == "J4_link" and link_of_joint(arm_model(THESIS_ARM), 3) == "link4"


def test_a_urdf_file_that_is_not_the_arms_chain_is_not_its_body():
    """An arm that says it was read from the CRX file but whose base moved 0.1 m: the file's joints are
    not its joints, so its body is generated along its own links (the file's would be misplaced)."""
    crx = iik.arms.get("crx10ia")
    base = np.array(crx.base)
    base[0, 3] += 0.1
    moved = dataclasses.replace(crx, base=base)
    assert moved.urdf == crx.urdf
    tm = arm_model(moved)
    assert tm.geometry == "generated" and _tool_matches_fk(tm, moved) < 1e-12
    assert crx.scaled(1.1).urdf == "" and arm_model(crx.scaled(1.1)).geometry == "generated"


def test_generated_cylinders_follow_the_links_and_skip_pairs_touching_at_home():
    import pinocchio as pin

    arm = iik.arms.get("offset_base")
    tm = arm_model(arm)
    r = link_radius(arm)
    assert 0.01 <= r == pytest.approx(0.03 * arm.reach)
    data, gdata = tm.model.createData(), pin.GeometryData(tm.collision_model)
    q = np.zeros(6)
    pin.forwardKinematics(tm.model, data, q)
    pin.updateGeometryPlacements(tm.model, data, tm.collision_model, gdata)
    frames = iik.joint_frames(q, arm)  # the DH frames the links are drawn between
    ends = [np.array(arm.base)[:3, 3], *frames[:, :3, 3], iik.fk(q, arm)[:3, 3]]
    for g, M in zip(tm.collision_model.geometryObjects, gdata.oMg, strict=True):
        axis = M.rotation[:, 2]
        tip, tail = M.translation + axis * g.geometry.halfLength, M.translation - axis * g.geometry.halfLength
        assert g.geometry.radius == pytest.approx(r)
        # each cylinder's axis lies on the chain: both ends at a frame origin or a corner of a link
        assert min(np.linalg.norm(e - tip) for e in ends) < 1e-9 or min(
            np.linalg.norm(e - tail) for e in ends) < 1e-9
    sc = SceneCollision([], arm=arm, platform=False, floor=False)
    assert sc.self_distance(q) > 0 and sc.geometry == "generated"  # no registered pair touches at home
