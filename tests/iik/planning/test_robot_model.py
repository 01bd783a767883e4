"""iik.planning.robot_model and verification.testing.strategies."""

import numpy as np
from hypothesis import given

import iik
from iik.planning.robot_model import thesis_model
from iik.resources import urdf_path
from verification.oracles.pinocchio_model import tool_frame_id
from verification.testing.strategies import BEYOND, joint_batches, joint_vectors, sample_joints


def test_thesis_model_is_cached_and_unpacks():
    tm = thesis_model()
    assert thesis_model() is tm
    model, collision = tm
    assert model.nq == 6 and len(collision.geometryObjects) > 7
    assert tm.path == urdf_path()
    assert model.frames[tool_frame_id()].name == "tool"


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
