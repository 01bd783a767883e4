"""One arm on the scene: the URDF's collision shapes placed as Pinocchio places them."""

import numpy as np
import pinocchio as pin
import pytest

from iik import THESIS_ARM
from iik.planning.robot_model import thesis_model
from iik.planning.viewer.bodies import ArmBody
from iik.planning.viewer.session import open_server


@pytest.fixture(scope="module")
def server():
    s = open_server("127.0.0.1", 0)
    yield s
    s.stop()


def test_shapes_follow_pinocchio_placements(server):
    tm = thesis_model(THESIS_ARM)
    q = np.array([0.3, -0.5, 0.4, 0.8, 0.2, -0.6])
    offset = np.array([0.0, 1.2, 0.0])
    body = ArmBody(server, "/t/arm", colour=(1, 2, 3), model=tm, offset=offset)
    body.show(q)
    data, gdata = tm.model.createData(), pin.GeometryData(tm.collision_model)
    pin.forwardKinematics(tm.model, data, q)
    pin.updateGeometryPlacements(tm.model, data, tm.collision_model, gdata)
    first = {}  # (the CRX's own URDF shapes are checked in tests/iik/planning/test_robot_model.py)
    for g, M in zip(tm.collision_model.geometryObjects, gdata.oMg, strict=True):
        first.setdefault(tm.model.frames[g.parentFrame].name, M.translation.copy())
    assert set(body.links) == set(first)
    for link, p in first.items():
        assert np.allclose(body.link_position(link), p + offset, atol=1e-6)


def test_paint_colours_one_link(server):
    body = ArmBody(server, "/t/arm2", colour=(40, 90, 200), model=thesis_model(THESIS_ARM))
    body.paint({"link4": (220, 30, 30)}, opacity=0.5)
    assert all(tuple(h.color) == (220, 30, 30) for h in body.shapes("link4"))
    assert all(tuple(h.color) == (40, 90, 200) and h.opacity == 0.5 for h in body.shapes("link2"))
