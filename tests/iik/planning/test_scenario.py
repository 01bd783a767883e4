"""The Scenario dataclass and its geometric checks (iik.planning.scenario)."""

import numpy as np
import pytest

from iik.planning import Box, Scenario, ScenarioError, Waypoint, check_scenario

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
    crate = Box((0.3, 0.25, -0.35), (0.1, 0.1, 0.1), name="crate")
    sc = Scenario(name="t", start=S, goal=G, obstacles=(crate,))
    with pytest.raises(ScenarioError, match="crate") as exc:
        check_scenario(sc)
    assert exc.value.field == "start.position"


def test_workspace_check_uses_the_injected_callables():
    sc = Scenario(name="t", start=S, goal=G)
    with pytest.raises(ScenarioError, match=r"closest reachable point \[0.100, 0.000, 0.000\] m"):
        check_scenario(sc, in_workspace=lambda p: False, closest_reachable=lambda p: np.array([0.1, 0, 0]))
    check_scenario(sc, in_workspace=lambda p: True)  # no error


NAN, INF = float("nan"), float("inf")
P = (0.3, 0.25, -0.35)


@pytest.mark.parametrize("make,field", [
    (lambda: Waypoint((NAN, 0.0, 0.0), None, 0.0), "position[0]"),
    (lambda: Waypoint((0.3, "0.25", 0.0), None, 0.0), "position[1]"),
    (lambda: Waypoint("0.3, 0.25, 0.1", None, 0.0), "position"),
    (lambda: Waypoint((0.3, 0.25), None, 0.0), "position"),
    (lambda: Waypoint((0.3, 0.25, 1e9), None, 0.0), "position[2]"),
    (lambda: Waypoint(P, "0", 0.0), "alpha"),
    (lambda: Waypoint(P, None, NAN), "beta"),
    (lambda: Waypoint(P, None, True), "beta"),
    (lambda: Waypoint(P, None, 0.0, INF), "gamma"),
    (lambda: Waypoint(P, None, 100.0), "beta"),
    (lambda: Scenario(name="t", start=S, goal=G, max_step="0.03"), "planning.max_step"),
    (lambda: Scenario(name="t", start=S, goal=G, max_step=NAN), "planning.max_step"),
    (lambda: Scenario(name="t", start=S, goal=G, safety_zone=INF), "planning.safety_zone"),
    (lambda: Scenario(name="t", start=S, goal=G, via_points=((0.3, NAN, 0.1),)), "planning.via_points[0][1]"),
    (lambda: Scenario(name="t", start=S, goal=G, via_points=((0.3, 0.1),)), "planning.via_points[0]"),
    (lambda: Scenario(name="t", start=S, goal=G, via_points="auto"), "planning.via_points"),
    (lambda: Scenario(name="t", start=S, goal=G, steps_per_segment=2.5), "planning.steps_per_segment"),
    (lambda: Scenario(name="t", start=S, goal=G, steps_per_segment=True), "planning.steps_per_segment"),
    (lambda: Scenario(name="t", start=S, goal=G, segments=("line",)), "planning.segments"),
    (lambda: Scenario(name="t", start=S, goal=G, mode=["LEI"]), "planning.mode"),
    (lambda: Scenario(name="t", start="start", goal=G), "start"),
    (lambda: Scenario(name=7, start=S, goal=G), "name"),
    (lambda: Scenario(name="../out", start=S, goal=G), "name"),
    (lambda: Scenario(name="t", start=S, goal=G, title=b"x"), "title"),
    (lambda: Scenario(name="t", start=S, goal=G, obstacles=("box",)), "obstacles[0]"),
    (lambda: Scenario(name="t", start=S, goal=G, obstacles=[Box((0.5, 0, 0), (1, 1, 1))] * 101),
     "obstacles"),
    (lambda: Scenario(name="t", start=S, goal=G, obstacles=(Box((500.0, 0, 0), (1, 1, 1)),)),
     "obstacles[0].center[0]"),
])
def test_waypoint_and_scenario_reject_nan_strings_and_absurd_values_naming_the_field(make, field):
    with pytest.raises(ScenarioError) as exc:
        make()
    assert exc.value.field == field


def test_noisy_but_valid_numbers_are_accepted_and_stored_as_floats():
    w = Waypoint(np.array([0.3, 0.25, -0.35], np.float32), np.float32(0.5), np.int64(0))
    assert all(type(v) is float for v in (*w.position, w.alpha, w.beta, w.gamma))
    sc = Scenario(name="t", start=w, goal=G, via_points=[np.array([0.4, 0.0, 0.1])],
                  steps_per_segment=np.int32(5))
    assert sc.via_points == ((0.4, 0.0, 0.1),) and type(sc.steps_per_segment) is int


def _placed(**kw):
    return Scenario(name="t", start=S, goal=G, **kw)


@pytest.mark.parametrize("via,needle", [
    ((0.3, 0.0, -0.35), "inside obstacle 'crate'"),
    ((-0.3, 0.0, -0.2), "inside the mobile platform"),
    ((0.3, 0.0, -0.60), "below the floor"),
    ((0.5, 0.5, 0.0), "outside the workspace; closest reachable point [0.100, 0.000, 0.000] m (base frame)"),
])
def test_requested_via_points_are_checked_like_start_and_goal(via, needle):
    from iik.scene import THESIS_SCENE

    crate = Box((0.3, 0.0, -0.35), (0.1, 0.1, 0.1), name="crate")
    sc = _placed(via_points=((0.4, 0.1, 0.0), via), obstacles=(crate,))
    with pytest.raises(ScenarioError) as exc:
        check_scenario(sc, platform=THESIS_SCENE.platform, floor_z=-0.45, in_workspace=lambda p: p[1] < 0.4,
                       closest_reachable=lambda p: np.array([0.1, 0.0, 0.0]))
    assert exc.value.field == "planning.via_points[1]" and needle in exc.value.reason


def test_points_are_shown_in_the_file_frame_and_say_which():
    sc = _placed(via_points=((0.3, 0.0, -0.60),))
    with pytest.raises(ScenarioError) as exc:
        check_scenario(sc, floor_z=-0.45, frame="floor")
    assert exc.value.reason == ("[0.300, 0.000, -0.150] m (floor frame) is below the floor "
                                "(z = 0.000 m in the floor frame)")


def test_too_many_step_points_name_the_limit_and_the_smallest_max_step_that_fits():
    from iik.planning import MAX_STEP_POINTS, check_step_points

    with pytest.raises(ScenarioError) as exc:
        check_step_points(_placed(max_step=1e-7))
    assert exc.value.field == "planning.max_step" and f"at most {MAX_STEP_POINTS}" in exc.value.reason
    fits = float(exc.value.reason.rsplit(">= ", 1)[1].split()[0])
    assert check_step_points(_placed(max_step=fits)) <= MAX_STEP_POINTS  # the suggestion passes
    with pytest.raises(ScenarioError):  # and it is tight (three significant digits)
        check_step_points(_placed(max_step=fits / 1.05))
    with pytest.raises(ScenarioError) as exc:
        check_step_points(_placed(via_points=((0.4, 0.1, 0.0),), steps_per_segment=MAX_STEP_POINTS // 2))
    assert exc.value.field == "planning.steps_per_segment"


def test_an_obstacle_name_is_a_string():
    from iik.errors import InvalidInputError

    with pytest.raises(InvalidInputError) as exc:
        Box((0.5, 0.0, 0.0), (0.1, 0.1, 0.1), name=7)
    assert exc.value.argument == "name"
