"""iik.urdf: the committed URDF is the generator's output, it loads in Pinocchio with
Table I limits, the generator maps both DH conventions right, rejects inconsistent
input, and reproduces the UR5 of example-robot-data."""

import math

import numpy as np
import pinocchio as pin
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import iik
from iik import THESIS_ARM, InvalidInputError
from iik.arm import thesis_arm
from iik.cli import main
from iik.dh import DHRow, DHTable, dh_chain
from iik.planning.robot_model import load_model, thesis_model
from iik.resources import urdf_path
from iik.urdf import (
    POWERCUBE,
    BoxShape,
    CylinderShape,
    adjacent_pairs,
    thesis_geometry,
    thesis_urdf,
    urdf_from_dh,
)
from verification.oracles.ur5 import UR5_BASE, UR5_TOOL, solve_base_tool, ur5_fk_pair

ARM = iik.THESIS_ARM


def test_committed_urdf_equals_generator_output():
    assert urdf_path().read_text(encoding="utf-8") == thesis_urdf(THESIS_ARM), (
        "urdf/thesis_arm.urdf is stale: run `iik urdf`")


def test_cli_check_mode(tmp_path):
    out = tmp_path / "a.urdf"
    assert main(["urdf", "--out", str(out)]) == 0
    assert main(["urdf", "--out", str(out), "--check"]) == 0
    out.write_text(out.read_text() + " ")
    assert main(["urdf", "--out", str(out), "--check"]) == 1


def test_loads_in_pinocchio_with_table_i_limits():
    tm = thesis_model(THESIS_ARM)
    m = tm.model
    assert m.nq == 6 and m.nv == 6 and m.njoints == 7
    assert [m.names[i] for i in range(1, 7)] == [f"joint{i}" for i in range(1, 7)]
    assert all(m.joints[i].shortname() == "JointModelRZ" for i in range(1, 7))
    table_i_deg = [(-160, 160), (-120, 95), (-160, 160), (-119, 119), (-119, 119), (-180, 180)]
    np.testing.assert_array_equal(m.lowerPositionLimit, [math.radians(lo) for lo, _ in table_i_deg])
    np.testing.assert_array_equal(m.upperPositionLimit, [math.radians(hi) for _, hi in table_i_deg])
    np.testing.assert_array_equal(m.velocityLimit, ARM.velocity)
    np.testing.assert_array_equal(m.effortLimit, ARM.effort)
    assert m.frames[tm.tool_frame_id].name == "tool"


def test_every_link_has_collision_geometry_and_home_is_collision_free():
    tm = thesis_model(THESIS_ARM)
    links = {tm.model.frames[g.parentFrame].name for g in tm.collision_model.geometryObjects}
    assert links == {"base_link"} | {f"link{i}" for i in range(1, 7)}
    data, gdata = tm.model.createData(), pin.GeometryData(tm.collision_model)
    pin.computeDistances(tm.model, data, tm.collision_model, gdata, np.zeros(6))
    dmin = min(r.min_distance for r in gdata.distanceResults)
    assert dmin >= POWERCUBE.gap - 1e-9
    # adjacent pairs are not registered, all other inter-link pairs are
    for cp in tm.collision_model.collisionPairs:
        a = tm.model.frames[tm.collision_model.geometryObjects[cp.first].parentFrame].name
        b = tm.model.frames[tm.collision_model.geometryObjects[cp.second].parentFrame].name
        assert (a, b) not in adjacent_pairs() and (b, a) not in adjacent_pairs() and a != b


def test_folded_arm_collides():
    """The collision model is not vacuous: folding the elbow back onto the upper arm collides."""
    tm = thesis_model(THESIS_ARM)
    data, gdata = tm.model.createData(), pin.GeometryData(tm.collision_model)
    q = np.array([0.0, 0.0, 0.0, 2.9, 0.0, 0.0])  # beyond Table I: link 4 folded onto link 2
    assert pin.computeCollisions(tm.model, data, tm.collision_model, gdata, q, False)


def _tool_fk(text, qs, frame="tool"):
    m = pin.buildModelFromXML(text)
    d = m.createData()
    fid = m.getFrameId(frame)
    out = []
    for q in qs:
        pin.framesForwardKinematics(m, d, q)
        out.append(d.oMf[fid].homogeneous)
    return np.array(out)


angles = st.floats(-math.pi, math.pi, allow_nan=False)
lengths = st.floats(-0.5, 0.5, allow_nan=False)


@settings(max_examples=25)
@given(st.sampled_from(["modified", "standard"]),
       st.lists(st.tuples(angles, lengths, lengths, angles), min_size=1, max_size=7),
       st.randoms(use_true_random=False))
def test_generator_reproduces_dh_chain(convention, rows, rnd):
    n = len(rows)
    table = DHTable(rows=tuple(DHRow(alpha=a, a=b, d=c, offset=o) for a, b, c, o in rows),
                    convention=convention, lower=(-3.0,) * n, upper=(3.0,) * n, velocity=(1.0,) * n)
    tool = np.eye(4)
    tool[:3, :3] = pin.rpy.rpyToMatrix(rnd.uniform(-3, 3), rnd.uniform(-1.5, 1.5), rnd.uniform(-3, 3))
    tool[:3, 3] = [rnd.uniform(-0.2, 0.2) for _ in range(3)]
    qs = np.random.default_rng(rnd.randint(0, 2**31)).uniform(-3, 3, (5, n))
    got = _tool_fk(urdf_from_dh(table, name="r", tool=tool), qs)
    want = dh_chain(table, qs) @ tool
    assert np.abs(got - want).max() <= 1e-12


def test_generator_base_transform():
    table = ARM.dh_table()
    base = np.eye(4)
    base[:3, 3] = [0.1, -0.2, 0.45]
    base[:3, :3] = pin.rpy.rpyToMatrix(0.1, 0.2, 0.3)
    qs = np.random.default_rng(3).uniform(-1, 1, (5, 6))
    got = _tool_fk(urdf_from_dh(table, name="r", base=base), qs)
    assert np.abs(got - base @ iik.fk(qs, THESIS_ARM)).max() <= 1e-12


def _corrupt(table, **fields):
    for k, v in fields.items():
        object.__setattr__(table, k, v)  # a table altered after construction
    return table


@pytest.mark.parametrize("kwargs,arg", [
    (dict(table=_corrupt(ARM.dh_table(), lower=ARM.lower[:5])), "lower"),
    (dict(table=_corrupt(ARM.dh_table(), upper=tuple(-x for x in ARM.upper))), "lower[0]"),
    (dict(table=_corrupt(ARM.dh_table(), velocity=(1.0,) * 5 + (-1.0,))), "velocity"),
    (dict(table=_corrupt(ARM.dh_table(), convention="craig")), "convention"),
    (dict(table=_corrupt(ARM.dh_table(), rows=ARM.dh_table().rows[:5])), "lower"),
    (dict(table=_corrupt(ARM.dh_table(), rows=(DHRow(math.nan, 0, 0),) + ARM.dh_table().rows[1:])),
     "rows[0]"),
    (dict(table="not a table"), "table"),
    (dict(effort=(1.0,) * 5), "effort"),
    (dict(effort=(1.0,) * 5 + (0.0,)), "effort"),
    (dict(tool=np.diag([1.0, 1.0, -1.0, 1.0])), "tool"),
    (dict(tool=np.ones((4, 4))), "tool"),
    (dict(base=np.full((4, 4), np.nan)), "base"),
    (dict(links={"link7": (BoxShape((0.1, 0.1, 0.1)),)}), "links"),
    (dict(links={"link1": (BoxShape((0.1, -0.1, 0.1)),)}), "links['link1'][0]"),
    (dict(links={"link1": (CylinderShape(0.0, 0.1),)}), "links['link1'][0]"),
    (dict(links={"link1": ("sphere",)}), "links['link1'][0]"),
    (dict(name=""), "name"),
    (dict(adjacent=[("link1", "link9")]), "adjacent"),
])
def test_generator_rejects_inconsistent_input(kwargs, arg):
    kw = dict(table=ARM.dh_table(), name="r")
    kw.update(kwargs)
    with pytest.raises(InvalidInputError) as exc:
        urdf_from_dh(**kw)
    assert exc.value.argument == arg


def test_geometry_rejects_arm_too_short_for_modules():
    short = thesis_arm(l1=0.1, l2=0.05, l3=0.1, l4=0.05, l5=0.1, lower=ARM.lower, upper=ARM.upper)
    with pytest.raises(InvalidInputError, match="too short"):
        thesis_geometry(short)


def test_geometry_follows_other_arm_lengths(tmp_path):
    longer = thesis_arm(l1=0.35, l2=0.15, l3=0.45, l4=0.25, l5=0.3, lower=ARM.lower, upper=ARM.upper)
    path = tmp_path / "long.urdf"
    path.write_text(thesis_urdf(longer))
    tm = load_model(path)
    data, gdata = tm.model.createData(), pin.GeometryData(tm.collision_model)
    assert not pin.computeCollisions(tm.model, data, tm.collision_model, gdata, np.zeros(6), False)
    for q in np.random.default_rng(4).uniform(ARM.q_min, ARM.q_max, (20, 6)):
        pin.framesForwardKinematics(tm.model, data, q)
        np.testing.assert_allclose(data.oMf[tm.tool_frame_id].homogeneous, iik.fk(q, longer), atol=1e-12)


def test_ur5_generated_matches_example_robot_data():
    qs = np.random.default_rng(11).uniform(-np.pi, np.pi, (300, 6))
    Tg, Tr = ur5_fk_pair(qs)
    Tm = UR5_BASE @ Tg @ UR5_TOOL
    assert np.abs(Tm[:, :3, 3] - Tr[:, :3, 3]).max() <= 1e-9
    assert np.abs(Tm[:, :3, :3] - Tr[:, :3, :3]).max() <= 1e-9
    # the frozen constants are what the closed-form solver finds
    B, E = solve_base_tool(Tg[:20], Tr[:20])
    assert np.abs(B - UR5_BASE).max() <= 1e-9 and np.abs(E - UR5_TOOL).max() <= 1e-9


def test_ur5_without_base_transform_does_not_match():
    """The base transform is needed (the test above is not vacuous)."""
    qs = np.random.default_rng(12).uniform(-np.pi, np.pi, (20, 6))
    Tg, Tr = ur5_fk_pair(qs)
    assert np.abs(Tg[:, :3, 3] - Tr[:, :3, 3]).max() > 0.1


def test_rpy_round_trip_including_gimbal_lock():
    from itertools import permutations, product

    from iik.urdf import _rpy, _rpy_matrix

    mats = []
    for perm in permutations(range(3)):  # the 24 axis-aligned rotations (gimbal cases included)
        for signs in product((1.0, -1.0), repeat=3):
            R = np.zeros((3, 3))
            R[range(3), perm] = signs
            if np.linalg.det(R) > 0:
                mats.append(R)
    rng = np.random.default_rng(0)
    mats += [pin.rpy.rpyToMatrix(*rng.uniform(-3, 3, 3)) for _ in range(50)]
    for R in mats:
        np.testing.assert_allclose(_rpy_matrix(_rpy(R)), R, atol=1e-15)


def test_generator_rejects_rows_that_are_not_dh_rows():
    t = _corrupt(ARM.dh_table(), rows=((0.0, 0.0, 0.0, 0.0),) * 6)
    with pytest.raises(InvalidInputError) as exc:
        urdf_from_dh(t, name="r")
    assert exc.value.argument == "table"


def _distance_to_shapes(p, shapes):
    """Distance [m] from point p to the union of coal BoxShape/CylinderShape shapes at placements (4x4)."""
    import coal

    best = np.inf
    for geom, M in shapes:
        x = M[:3, :3].T @ (p - M[:3, 3])
        if isinstance(geom, coal.Box):
            d = np.linalg.norm(np.maximum(np.abs(x) - np.asarray(geom.halfSide), 0.0))
        else:
            d = math.hypot(max(math.hypot(x[0], x[1]) - geom.radius, 0.0),
                           max(abs(x[2]) - geom.halfLength, 0.0))
        best = min(best, d)
    return best


def test_collision_shapes_cover_the_kinematic_skeleton():
    """Points along base -> J1 -> J2 -> J34 -> J5 -> tool lie inside the shapes of the links that
    segment joins (a joint module belongs to the link before it), up to the clearance gap, at random q."""
    tm = thesis_model(THESIS_ARM)
    data, gdata = tm.model.createData(), pin.GeometryData(tm.collision_model)
    owner = [tm.model.frames[g.parentFrame].name for g in tm.collision_model.geometryObjects]
    rng = np.random.default_rng(5)
    for q in rng.uniform(ARM.q_min, ARM.q_max, (20, 6)):
        pin.forwardKinematics(tm.model, data, q)
        pin.updateGeometryPlacements(tm.model, data, tm.collision_model, gdata)
        F = iik.joint_frames(q, THESIS_ARM)
        O = [np.zeros(3)] + [F[i, :3, 3] for i in range(6)]
        palm_end = O[6] + (O[5] - O[6]) * POWERCUBE.finger[2] / ARM.l5  # between the fingers: open
        segments = [(O[0], O[1], ("base_link", "link1")), (O[1], O[2], ("link1",)),
                    (O[2], O[3], ("link1", "link2", "link3")), (O[4], O[5], ("link3", "link4")),
                    (O[5], palm_end, ("link4", "link5", "link6"))]
        for a, b, links in segments:
            shapes = [(g.geometry, gdata.oMg[k].homogeneous)
                      for k, g in enumerate(tm.collision_model.geometryObjects) if owner[k] in links]
            for t in np.linspace(0, 1, 25):
                assert _distance_to_shapes(a + t * (b - a), shapes) <= POWERCUBE.gap + 1e-9, (q, links, t)


def test_panda_modified_dh_matches_example_robot_data():
    from verification.oracles.panda import panda_fk_pair, panda_models

    _, _, ref, _ = panda_models()
    qs = np.random.default_rng(13).uniform(ref.lowerPositionLimit[:7], ref.upperPositionLimit[:7], (200, 7))
    Tg, Tr = panda_fk_pair(qs)
    assert np.abs(Tg - Tr).max() <= 1e-12
