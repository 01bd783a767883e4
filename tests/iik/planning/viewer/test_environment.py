"""The scene's surroundings and the initial camera."""

import numpy as np
import pytest

from iik.planning.viewer.environment import camera_pose, view_top

from .conftest import project


@pytest.mark.parametrize("look_at", [(0.3, 0.0, 0.15), (0.5, -0.4, 0.3)])
@pytest.mark.parametrize("fraction", [0.5, 0.9])
def test_view_top_is_at_the_top_centre_of_the_initial_view(look_at, fraction):
    eye, target = camera_pose(look_at)
    rect = (0.0, 0.0, 1280.0, 800.0)
    u, v = project(view_top(eye, target, 50.0, fraction), eye, target, fov_deg=50.0, rect=rect)[0]
    assert u == pytest.approx(640.0, abs=1e-6)  # centred, whatever the window's width
    assert v == pytest.approx(400.0 * (1.0 - fraction), abs=1e-6)  # fraction of the way up from the middle
    assert np.linalg.norm(view_top(eye, target, 50.0, 0.0) - target) == pytest.approx(0.0, abs=1e-12)
