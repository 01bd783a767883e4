"""Whole-arm Coal checks (iik.planning.collision)."""

import numpy as np
import pytest

import iik
from iik.planning import Obstacle
from iik.planning.collision import SceneCollision


@pytest.fixture(scope="module")
def checker():
    return SceneCollision([Obstacle((0.55, 0.0, 0.0), (0.2, 0.2, 0.4), name="box")])


@pytest.mark.parametrize("required", [0.0, 0.03, 0.1])
def test_motion_clearance_is_certified_or_a_witnessed_violation(checker, required):
    rng = np.random.default_rng(3)
    lo, hi = iik.THESIS_ARM.q_min, iik.THESIS_ARM.q_max
    certified = violated = 0
    for _ in range(8):
        q0 = rng.uniform(lo, hi) * 0.6
        q1 = np.clip(q0 + rng.normal(0, 0.15, 6), lo, hi)
        pc = checker.path_clearance(np.array([q0, q1]), required=required, resolution=0.002)
        samples = [checker.clearance(q0 + s * (q1 - q0))[0] for s in np.linspace(0, 1, 201)]
        if pc.motion[0] >= required:  # a lower bound of the whole motion
            assert min(samples) >= pc.motion[0] - 1e-9
            certified += 1
        else:  # a sampled configuration that really violates
            assert min(samples) < required + 1e-9
            violated += 1
    assert certified + violated == 8


def test_penetration_is_negative_and_named(checker):
    q = np.zeros(6)  # arm stretched along +x at z = l1 through the box's top region
    tall = SceneCollision([Obstacle((0.6, 0.0, 0.3), (0.1, 0.1, 0.1), name="hit")])
    d, link, obj = tall.clearance(q)
    assert d < 0 and obj == "hit" and link.startswith("link")
    d2, _, _ = checker.clearance(q)
    assert d2 > 0


def test_floor_distance_matches_geometry():
    sc = SceneCollision([], platform=False)
    # home pose: lowest collision point is the base_link bottom at z = 0, floor at z = -0.45
    d = sc.link_clearances(np.zeros(6))
    assert abs(d["base_link"] - 0.45) < 1e-6


def test_base_is_not_reported_against_the_platform():
    sc = SceneCollision([], floor=False)
    assert "base_link" not in {sc.arm_link[i] for i, k in sc.pairs if sc.env_names[k] == "platform"}
    assert sc.clearance(np.zeros(6))[0] > 0.1


def test_keeps_is_the_clearance_and_self_contact_rule(checker):
    rng = np.random.default_rng(5)
    lo, hi = iik.THESIS_ARM.q_min, iik.THESIS_ARM.q_max
    seen = set()
    for q in rng.uniform(lo, hi, size=(40, 6)):
        d = checker.clearance(q)[0]
        expected = d >= 0.03 and checker.self_distance(q) > 0
        assert checker.keeps(q, 0.03) == expected
        seen.add(expected)
    assert seen == {True, False}  # both outcomes occur


def test_path_clearance_acceptance_and_closest_pair(checker):
    q0 = np.zeros(6)
    pc = checker.path_clearance(np.array([q0, q0 + 0.1]), 0.0)
    i = int(np.argmin(pc.step))
    assert (pc.closest_link, pc.closest_object) == (pc.step_link[i], pc.step_object[i])
    assert pc.keeps(pc.minimum) and not pc.keeps(pc.minimum + 1e-6)


def test_another_arm_gets_its_own_collision_model():
    import dataclasses

    a = iik.THESIS_ARM
    longer = dataclasses.replace(a, l3=a.l3 * 1.2, l4=a.l4 * 1.2)
    q = np.zeros(6)  # stretched along +x: the longer arm's gripper is further out
    box = [Obstacle((1.3, 0.0, 0.3), (0.1, 0.4, 0.4), name="far")]
    d_thesis = SceneCollision(box, floor=False, platform=False).clearance(q)[0]
    d_longer = SceneCollision(box, arm=longer, floor=False, platform=False).clearance(q)[0]
    reach = (longer.l3 + longer.l4) - (a.l3 + a.l4)
    assert d_thesis - d_longer == pytest.approx(reach, abs=1e-6)
