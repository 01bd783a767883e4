"""The Scenario dataclass and its geometric checks (iik.planning.scenario)."""

import numpy as np
import pytest

from iik.planning import Obstacle, Scenario, ScenarioError, Waypoint, check_scenario

S, G = Waypoint((0.3, 0.25, -0.35), None, 0.0), Waypoint((0.3, -0.25, -0.35), None, 0.0)


@pytest.mark.parametrize("kw,field", [
    ({"orientation": "quat"}, "planning.orientation"),
    ({"mode": "XYZ"}, "planning.mode"),
    ({"max_step": 0.0}, "planning.max_step"),
    ({"safety_zone": -0.01}, "planning.safety_zone"),
    ({"via_points": ((0.1, 0.1, 0.1),), "segments": ("line",)}, "planning.segments"),
    ({"via_points": ((0.1, 0.1, 0.1),), "segments": ("line", "curve")}, "planning.segments[1]"),
])
def test_invalid_options_name_the_field(kw, field):
    with pytest.raises(ScenarioError) as exc:
        Scenario(name="t", start=S, goal=G, **kw)
    assert exc.value.field == field


def test_start_inside_a_box_is_rejected_with_its_name():
    crate = Obstacle((0.3, 0.25, -0.35), (0.1, 0.1, 0.1), name="crate")
    sc = Scenario(name="t", start=S, goal=G, obstacles=(crate,))
    with pytest.raises(ScenarioError, match="crate") as exc:
        check_scenario(sc)
    assert exc.value.field == "start.position"


def test_workspace_check_uses_the_injected_callables():
    sc = Scenario(name="t", start=S, goal=G)
    with pytest.raises(ScenarioError, match=r"closest reachable point \[0.100, 0.000, 0.000\] m"):
        check_scenario(sc, in_workspace=lambda p: False, closest_reachable=lambda p: np.array([0.1, 0, 0]))
    check_scenario(sc, in_workspace=lambda p: True)  # no error
