"""Whole-arm Coal checks (iik.planning.collision)."""

import coal
import numpy as np
import pytest

import iik
from iik import THESIS_ARM
from iik.arm import thesis_arm
from iik.planning import Box
from iik.planning.collision import SceneCollision


@pytest.fixture(scope="module")
def checker():
    return SceneCollision([Box((0.55, 0.0, 0.0), (0.2, 0.2, 0.4), name="box")], arm=THESIS_ARM)


@pytest.mark.parametrize("required", [0.0, 0.03, 0.1])
def test_motion_clearance_is_certified_or_a_witnessed_violation(checker, required):
    rng = np.random.default_rng(3)
    lo, hi = iik.THESIS_ARM.q_min, iik.THESIS_ARM.q_max
    certified = violated = 0
    for _ in range(8):
        q0 = rng.uniform(lo, hi) * 0.6
        q1 = np.clip(q0 + rng.normal(0, 0.15, 6), lo, hi)
        pc = checker.path_clearance(np.array([q0, q1]), required=required, resolution=0.002)
        samples = [checker.nearest(q0 + s * (q1 - q0)).distance for s in np.linspace(0, 1, 201)]
        if pc.motion[0] >= required:  # a lower bound of the whole motion
            assert min(samples) >= pc.motion[0] - 1e-9
            certified += 1
        else:  # a sampled configuration that really violates
            assert min(samples) < required + 1e-9
            violated += 1
    assert certified + violated == 8


def test_penetration_is_negative_and_named(checker):
    q = np.zeros(6)  # arm stretched along +x at z = l1 through the box's top region
    tall = SceneCollision([Box((0.6, 0.0, 0.3), (0.1, 0.1, 0.1), name="hit")], arm=THESIS_ARM)
    n = tall.nearest(q)
    assert n.distance < 0 and n.object == "hit" and n.link.startswith("link")
    assert checker.nearest(q).distance > 0


def test_floor_distance_matches_geometry():
    sc = SceneCollision([], platform=False, arm=THESIS_ARM)
    # home pose: lowest collision point is the base_link bottom at z = 0, floor at z = -0.45
    d = sc.link_clearances(np.zeros(6))
    assert abs(d["base_link"] - 0.45) < 1e-6


def test_base_is_not_reported_against_the_platform():
    sc = SceneCollision([], floor=False, arm=THESIS_ARM)
    assert "base_link" not in {sc.arm_link[i] for i, k in sc.pairs if sc.env_names[k] == "platform"}
    assert sc.nearest(np.zeros(6)).distance > 0.1


def test_keeps_is_the_clearance_and_self_contact_rule(checker):
    rng = np.random.default_rng(5)
    lo, hi = iik.THESIS_ARM.q_min, iik.THESIS_ARM.q_max
    seen = set()
    for q in rng.uniform(lo, hi, size=(40, 6)):
        d = checker.nearest(q).distance
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

    a = iik.THESIS_ARM
    longer = thesis_arm(a.l1, a.l2, a.l3 * 1.2, a.l4 * 1.2, a.l5)
    q = np.zeros(6)  # stretched along +x: the longer arm's gripper is further out
    box = [Box((1.3, 0.0, 0.3), (0.1, 0.4, 0.4), name="far")]
    d_thesis = SceneCollision(box, floor=False, platform=False, arm=THESIS_ARM).nearest(q).distance
    d_longer = SceneCollision(box, arm=longer, floor=False, platform=False).nearest(q).distance
    reach = (longer.l3 + longer.l4) - (a.l3 + a.l4)
    assert d_thesis - d_longer == pytest.approx(reach, abs=1e-6)


def _coal_nearest(q, boxes, scene=iik.scene.THESIS_SCENE):
    """The closest (link, object) pair by Coal directly: the URDF loaded by Pinocchio, every
    arm shape against every box, the platform and the floor (base link not against the platform)."""
    import pinocchio as pin

    from iik.planning.robot_model import thesis_model

    model, gm = pin.buildModelsFromUrdf(str(thesis_model(THESIS_ARM).path),
                                        geometry_types=pin.GeometryType.COLLISION)
    data, gd = model.createData(), pin.GeometryData(gm)
    pin.forwardKinematics(model, data, np.asarray(q, float))
    pin.updateGeometryPlacements(model, data, gm, gd)
    p = scene.platform
    env = [(b.name, coal.Box(*b.size), coal.Transform3s(np.eye(3), np.asarray(b.center, float)))
           for b in boxes]
    env += [("platform", coal.Box(*p.size), coal.Transform3s(np.eye(3), np.asarray(p.center, float))),
            ("floor", coal.Halfspace(np.array([0.0, 0.0, 1.0]), scene.floor.z), coal.Transform3s())]
    best = None
    for g, placement in zip(gm.geometryObjects, gd.oMg, strict=True):
        link = model.frames[g.parentFrame].name
        for name, shape, tf in env:
            if link == "base_link" and name == "platform":
                continue
            arm_tf = coal.Transform3s(placement.rotation, placement.translation)
            d = coal.distance(g.geometry, arm_tf, shape, tf, coal.DistanceRequest(), coal.DistanceResult())
            if best is None or d < best[0]:
                best = (d, link, name, (g.geometry, arm_tf), (shape, tf))
    return best


def _gap(point, shape_tf) -> float:
    """Coal distance [m] from a point to a placed shape (0 on its surface)."""
    dot = coal.Sphere(1e-12)
    shape, tf = shape_tf
    return coal.distance(dot, coal.Transform3s(np.eye(3), np.asarray(point, float)), shape, tf,
                         coal.DistanceRequest(), coal.DistanceResult())


def test_nearest_is_coals_closest_pair_with_its_points():
    """Distances and points agree within Coal's GJK tolerance (1e-6 m; it warm-starts from the last call)."""
    tol = coal.DistanceRequest().gjk_tolerance
    boxes = [Box((0.55, 0.0, 0.45), (0.1, 0.8, 0.1), name="shelf"),
             Box((0.0, 0.45, 0.3), (0.3, 0.1, 0.3), name="post")]
    sc = SceneCollision(boxes, arm=THESIS_ARM)
    rng = np.random.default_rng(11)
    lo, hi = iik.THESIS_ARM.q_min, iik.THESIS_ARM.q_max
    objects = set()
    for q in rng.uniform(lo, hi, size=(40, 6)):
        n = sc.nearest(q)
        d, link, name, on_arm, on_env = _coal_nearest(q, boxes)
        assert n.distance == pytest.approx(d, abs=tol)
        assert (n.link, n.object) == (link, name)
        if n.distance > tol:  # the points (not unique for parallel faces) lie on the two shapes, d apart
            assert _gap(n.on_link, on_arm) == pytest.approx(0.0, abs=tol)
            assert _gap(n.on_object, on_env) == pytest.approx(0.0, abs=tol)
            assert np.linalg.norm(n.on_link - n.on_object) == pytest.approx(n.distance, abs=tol)
        if n.object in ("shelf", "post") and n.distance > tol:  # and by the box's own distance
            box = next(b for b in boxes if b.name == n.object)
            assert box.distance(n.on_object) == pytest.approx(0.0, abs=tol)
            assert box.distance(n.on_link) == pytest.approx(n.distance, abs=tol)
        objects.add((n.object, n.distance > tol))
    assert {("shelf", True), ("post", True), ("platform", True), ("floor", True)} <= objects


def test_nearest_takes_one_configuration():
    with pytest.raises(iik.InvalidInputError, match="one configuration"):
        SceneCollision([], arm=THESIS_ARM).nearest(np.zeros((2, 6)))
