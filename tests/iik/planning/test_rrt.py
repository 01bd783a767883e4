"""The OMPL RRT-Connect fallback on Coal checks (iik.planning.rrt)."""

import numpy as np

from iik import THESIS_ARM
from iik.planning import Obstacle
from iik.planning.collision import SceneCollision
from iik.planning.rrt import rrt_connect


def test_rrt_connect_goes_around_a_box_with_certified_clearance():
    chk = SceneCollision([Obstacle((0.5, 0.0, 0.1), (0.2, 0.2, 0.4), name="pillar")])
    q0 = np.array([0.8, 0.3, 0.0, 0.5, -1.0, 0.0])
    q1 = np.array([-0.8, 0.3, 0.0, 0.5, -1.0, 0.0])
    assert chk.path_clearance(np.array([q0, q1]), 0.03).minimum < 0.03  # the direct motion collides
    P = rrt_connect(q0, q1, chk, required=0.03, time_limit=5.0, seed=7)
    assert P is not None
    assert np.allclose(P[0], q0) and np.allclose(P[-1], q1)
    assert np.abs(np.diff(P, axis=0)).max() <= 0.05 + 1e-12
    assert np.all(THESIS_ARM.within_limits(P))
    pc = chk.path_clearance(P, 0.03)
    assert pc.minimum >= 0.03  # certified on the motions too
