"""The figures of a plan (iik.planning.output's plotting functions): the arm's collision bodies placed by
Pinocchio, equal axis scales, a legend, the frame and units, the nearest link and its clearance."""

import numpy as np
import pinocchio as pin
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from matplotlib.figure import Figure
from mpl_toolkits.mplot3d.art3d import Poly3DCollection

import iik
from iik import THESIS_ARM
from iik.planning import plan
from iik.planning.output import collision_faces, plot_scene
from iik.planning.robot_model import thesis_model


@settings(max_examples=10, deadline=None)
@given(st.lists(st.floats(-1.0, 1.0), min_size=6, max_size=6))
def test_collision_faces_are_the_shapes_placed_by_pinocchio(values):
    """link2's one box: its 24 face corners are the box's +-half sides around Pinocchio's oMg placement."""
    q = np.clip(np.array(values), iik.THESIS_ARM.q_min, iik.THESIS_ARM.q_max)
    tm = thesis_model(THESIS_ARM)
    faces = collision_faces(tm.model, tm.collision_model, q)
    k = next(i for i, g in enumerate(tm.collision_model.geometryObjects) if g.name == "link2_0")
    data, gdata = tm.model.createData(), pin.GeometryData(tm.collision_model)
    pin.forwardKinematics(tm.model, data, q)
    pin.updateGeometryPlacements(tm.model, data, tm.collision_model, gdata)
    M = gdata.oMg[k]
    local = (np.vstack(faces["link2"]) - M.translation) @ M.rotation
    half = np.asarray(tm.collision_model.geometryObjects[k].geometry.halfSide)
    assert np.allclose(np.abs(local), half, atol=1e-12)
    assert set(faces) == {"base_link", "link1", "link2", "link3", "link4", "link5", "link6"}


@pytest.fixture(scope="module")
def scene_axes():
    res = plan("b")
    ax = Figure(figsize=(7, 6)).add_subplot(111, projection="3d")
    plot_scene(res, ax, n_arms=3)
    return res, ax


def test_scene_draws_the_arm_bodies_with_equal_axes(scene_axes):
    res, ax = scene_axes
    polys = [c for c in ax.collections if isinstance(c, Poly3DCollection)]
    boxes = 1 + len(res.scenario.obstacles)  # platform and the scenario's boxes
    assert len(polys) >= boxes + 3 * 7  # every link of the arm at each drawn instant
    spans = np.array([np.ptp(ax.get_xlim()), np.ptp(ax.get_ylim()), np.ptp(ax.get_zlim())])
    assert np.allclose(spans, spans[0])
    aspect = np.asarray(ax.get_box_aspect())
    assert np.allclose(aspect / aspect[0], spans / spans[0])


def test_scene_states_frame_units_legend_and_nearest_link(scene_axes):
    res, ax = scene_axes
    labels = " | ".join(t.get_text() for t in ax.get_legend().get_texts())
    wanted = ("arm (URDF collision shapes)", "obstacle", "platform", "ellipsoid", "tool path", "step-points")
    for want in (*wanted, "nearest link"):
        assert want in labels
    assert "base frame 0" in ax.get_title() and "[m]" in ax.get_title() and "mm" in ax.get_title()
    assert (ax.get_xlabel(), ax.get_ylabel(), ax.get_zlabel()) == ("x [m]", "y [m]", "z [m]")
    i = int(np.argmin(res.clearance.step))
    assert f"{res.clearance.step[i] * 1e3:.1f} mm" in labels and str(res.clearance.step_link[i]) in labels
