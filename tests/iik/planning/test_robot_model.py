"""iik.planning.robot_model and verification.testing.strategies."""

import numpy as np
from hypothesis import given

import iik
from iik import THESIS_ARM
from iik.arm import thesis_arm
from iik.planning.robot_model import thesis_model
from iik.resources import urdf_path
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
