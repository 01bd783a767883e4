"""Scenario files: parsing, ScenarioError(field, reason), writing back (iik.planning.scenario_io)."""

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from iik import THESIS_ARM
from iik.planning import (
    Box,
    Scenario,
    ScenarioError,
    Waypoint,
    load_scenario,
    scenario_path,
    scenario_to_toml,
    thesis_scenario_paths,
    write_scenario,
)
from iik.resources import scenarios_dir

GOOD = """
name = "x"
arm = "thesis"
frame = "floor"
[start]
position = [0.30, 0.25, 0.10]
beta_deg = 0.0
[goal]
position = [0.30, -0.25, 0.10]
beta_deg = 0.0
[[obstacles]]
name = "box"
center = [0.32, 0.0, 0.10]
size = [0.12, 0.12, 0.20]
"""


def _write(tmp_path, text, name="s.toml"):
    p = tmp_path / name
    p.write_text(text)
    return p


def test_thirteen_shipped_scenarios_load_and_say_what_is_reconstructed():
    paths = thesis_scenario_paths()
    assert [p.stem for p in paths] == ["p1", "p2", "p3", *"abcdefghij"]
    for p in paths:
        sc = load_scenario(p)
        assert "reconstruct" in sc.reconstruction.lower()
        assert sc.title and sc.reference


def test_floor_frame_is_converted_with_the_scene(tmp_path):
    from iik.scene import THESIS_SCENE

    sc = load_scenario(_write(tmp_path, GOOD))
    assert sc.start.position[2] == pytest.approx(0.10 + THESIS_SCENE.floor.z)


@pytest.mark.parametrize("text,field,needle", [
    ("name = \n", "file", "not valid TOML"),
    (GOOD.replace("[start]\nposition = [0.30, 0.25, 0.10]\nbeta_deg = 0.0\n", ""), "start", "missing"),
    (GOOD.replace("beta_deg = 0.0", "beta_deg = 'flat'", 1), "start.beta_deg", "number"),
    (GOOD.replace("frame", "frme"), "frme", "unknown key"),
    (GOOD.replace("beta_deg = 0.0", "beta_deg = 0.0\nbeta = 0.0", 1), "start.beta", "given twice"),
    (GOOD.replace("[0.30, 0.25, 0.10]", "[0.30, 0.25]"), "start.position", "3 numbers"),
    (GOOD.replace("[0.30, 0.25, 0.10]", "[0.32, 0.0, 0.10]"), "start.position", "inside obstacle"),
    (GOOD.replace("[0.30, -0.25, 0.10]", "[-0.3, 0.0, 0.30]"), "goal.position", "inside the mobile platform"),
    (GOOD.replace("[0.30, -0.25, 0.10]", "[0.30, -0.25, -0.05]"), "goal.position", "below the floor"),
    (GOOD.replace("size = [0.12, 0.12, 0.20]", "size = [0.12, -0.12, 0.20]"), "obstacles[0]", "positive"),
])
def test_malformed_or_impossible_files_name_the_field(tmp_path, text, field, needle):
    with pytest.raises(ScenarioError) as exc:
        load_scenario(_write(tmp_path, text))
    assert exc.value.field == field
    assert needle in exc.value.reason


def test_unreachable_goal_reports_the_closest_reachable_point(tmp_path):
    with pytest.raises(ScenarioError) as exc:
        load_scenario(_write(tmp_path, GOOD.replace("[0.30, -0.25, 0.10]", "[1.60, -0.25, 0.90]")))
    assert exc.value.field == "goal.position"
    assert "outside the workspace" in exc.value.reason and "closest reachable point" in exc.value.reason


def test_missing_file_is_a_scenario_error(tmp_path):
    with pytest.raises(ScenarioError, match="no such file"):
        load_scenario(tmp_path / "nope.toml")


def test_shipped_names_and_files_resolve(tmp_path):
    assert scenario_path("j") == scenarios_dir() / "j.toml"
    own = _write(tmp_path, GOOD)
    assert scenario_path(own) == own and scenario_path(str(own)) == own
    assert scenario_path(tmp_path / "nope.toml") == tmp_path / "nope.toml"  # a path: load says it is missing
    with pytest.raises(ScenarioError) as exc:
        scenario_path("zz")
    assert exc.value.field == "scenario" and "p1, p2, p3, a, b" in exc.value.reason


@pytest.mark.parametrize("name", ["p1", "a", "d", "j"])
def test_shipped_scenarios_round_trip_through_a_written_file(tmp_path, name):
    sc = load_scenario(scenarios_dir() / f"{name}.toml")
    back = load_scenario(write_scenario(sc, tmp_path / "x.toml"))
    assert back == sc  # exact: every float and string (the frame is written as "base")
    assert "_deg = " in (tmp_path / "x.toml").read_text()  # degrees stay degrees where they read back


def test_angles_in_rad_are_read_and_written_when_degrees_cannot_round_trip(tmp_path):
    x = 1.24539  # no float d has math.radians(d) == x (checked over +-200 ulps of degrees(x) below)
    d = lo = hi = math.degrees(x)
    near = [d]
    for _ in range(200):
        lo, hi = math.nextafter(lo, -math.inf), math.nextafter(hi, math.inf)
        near += [lo, hi]
    assert all(math.radians(c) != x for c in near)
    sc = Scenario(name="r", start=Waypoint((0.3, 0.25, -0.35), x, math.radians(30.0), -0.2),
                  goal=Waypoint((0.3, -0.25, -0.35), None, 0.2), arm=THESIS_ARM)
    text = scenario_to_toml(sc)
    assert "alpha = 1.24539\n" in text and "beta_deg = 30.0\n" in text
    assert load_scenario(write_scenario(sc, tmp_path / "r.toml"), check_workspace=False) == sc


coords = st.floats(-0.3, 0.3, allow_nan=False)
angles = st.floats(-math.pi, math.pi, allow_nan=False)


@given(start=st.tuples(coords, coords), angles=st.tuples(angles, angles, angles), alpha_free=st.booleans(),
       steps=st.one_of(st.none(), st.integers(1, 60)), zone=st.floats(0.0, 0.1),
       title=st.text(max_size=20))
def test_any_scenario_round_trips_exactly(tmp_path_factory, start, angles, alpha_free, steps, zone, title):
    a, b, g = angles
    sc = Scenario(name="h", title=title,
                  start=Waypoint((0.45 + start[0], start[1], 0.1), None if alpha_free else a, b, g),
                  goal=Waypoint((0.35, -0.3, 0.05), a, b, 0.0), steps_per_segment=steps, safety_zone=zone,
                  via_points=((0.5, 0.0, 0.4),), segments=("line", "arc"), orientation="slerp", mode="LJI",
                  obstacles=(Box((1.0, 0.0, 0.1), (0.1, 0.2, 0.3), name='b"ox', kind="support"),),
                  arm=THESIS_ARM)
    path = write_scenario(sc, tmp_path_factory.mktemp("rt") / "s.toml")
    assert load_scenario(path, check_workspace=False) == sc


def test_writing_a_non_finite_value_names_the_field():
    sc = Scenario(name="n", start=Waypoint((0.3, 0.25, 0.1), None, 0.0),
                  goal=Waypoint((0.3, -0.25, 0.1), None, 0.0))
    object.__setattr__(sc.start, "position", (0.3, 0.25, np.nan))  # past the Waypoint's own check
    with pytest.raises(ScenarioError) as exc:
        scenario_to_toml(sc)
    assert exc.value.field == "start.position[2]"


def test_written_text_is_the_documented_format():
    sc = dataclasses.replace(load_scenario(scenarios_dir() / "j.toml"), name="j2")
    text = scenario_to_toml(sc)
    assert 'frame = "base"' in text and 'name = "j2"' in text and "[[obstacles]]" in text


VIAS = "\n[planning]\nvia_points = {}\n"


@pytest.mark.parametrize("text,field,needle", [
    (GOOD + VIAS.format("[[0.3, 0.0, -10.0]]"), "planning.via_points[0]", "below the floor"),
    (GOOD + VIAS.format("[[0.3, 0.1, 0.1], [50.0, 0.0, 0.9]]"), "planning.via_points[1]",
     "outside the workspace"),
    (GOOD + VIAS.format("[[0.32, 0.0, 0.05]]"), "planning.via_points[0]", "inside obstacle 'box'"),
    (GOOD + VIAS.format("[[-0.3, 0.0, 0.3]]"), "planning.via_points[0]", "inside the mobile platform"),
    (GOOD + VIAS.format("[[0.3, 0.0, nan]]"), "planning.via_points[0][2]", "finite"),
    (GOOD + VIAS.format("[[0.3, 0.0, 1e300]]"), "planning.via_points[0][2]", "[-100, 100] m"),
    (GOOD + VIAS.format("[[0.3, 0.0]]"), "planning.via_points[0]", "3 numbers"),
    (GOOD + VIAS.format("'[[0.3, 0.0, 0.1]]'"), "planning.via_points", "'auto' or a list"),
    (GOOD + "\n[planning]\nmax_step = 1e-7\n", "planning.max_step", "at most 5000"),
    (GOOD + "\n[planning]\nmax_step = -0.01\n", "planning.max_step", "(0, 0.5]"),
    (GOOD + "\n[planning]\nsteps_per_segment = 100000\n", "planning.steps_per_segment", "1..10000"),
    (GOOD + "\n[planning]\nsegments = ['arc']\n", "planning.segments", "explicit planning.via_points"),
    (GOOD.replace("beta_deg = 0.0", "beta_deg = 1e6", 1), "start.beta_deg", "[-360, 360] deg"),
    (GOOD.replace("[0.30, 0.25, 0.10]", "[1e300, 0.25, 0.10]"), "start.position[0]", "[-100, 100] m"),
    (GOOD.replace('name = "box"', "name = 7"), "obstacles[0].name", "string"),
    (GOOD.replace('frame = "floor"', "frame = 'x'"), "frame", "'base' or 'floor'"),
    ("a = " + "[" * 3000 + "]" * 3000, "file", "too deeply"),
])
def test_requested_via_points_and_bounds_are_checked_naming_the_field(tmp_path, text, field, needle):
    with pytest.raises(ScenarioError) as exc:
        load_scenario(_write(tmp_path, text))
    assert exc.value.field == field and needle in exc.value.reason


def test_unreadable_files_are_scenario_errors(tmp_path):
    bad = tmp_path / "bytes.toml"
    bad.write_bytes(GOOD.encode() + b"\n# \xff\xfe not UTF-8\n")
    with pytest.raises(ScenarioError, match="cannot read") as exc:
        load_scenario(bad)
    assert exc.value.field == "file"
    big = _write(tmp_path, GOOD + "#" * 1_000_001 + "\n", "big.toml")
    with pytest.raises(ScenarioError, match="more than 1 MB, the limit of a scenario file") as exc:
        load_scenario(big)


def _suggested(reason: str) -> str:
    """The "[x, y, z]" of "closest reachable point [x, y, z] m (floor frame)" in a message."""
    return reason.split("closest reachable point ", 1)[1].split(" m (", 1)[0]


@pytest.mark.parametrize("frame", ["floor", "base"])
@pytest.mark.parametrize("where", ["goal", "via"])
def test_the_suggested_point_is_in_the_file_frame_and_pasting_it_back_passes(tmp_path, frame, where):
    from iik.scene import THESIS_SCENE
    from iik.workspace import closest_reachable

    dz = 0.0 if frame == "floor" else THESIS_SCENE.floor.z  # the same scene written in either frame
    text = GOOD.replace('frame = "floor"', f'frame = "{frame}"')
    for xy in ("0.30, 0.25, ", "0.30, -0.25, ", "0.32, 0.0, "):  # the points' z (not the box size)
        text = text.replace(f"[{xy}0.10]", f"[{xy}{0.10 + dz!r}]")
    far = f"[2.0, -0.25, {0.9 + dz!r}]"
    if where == "goal":
        text, field = text.replace(f"[0.30, -0.25, {0.10 + dz!r}]", far), "goal.position"
    else:
        text, field = text + VIAS.format(f"[{far}]"), "planning.via_points[0]"
    assert far in text
    with pytest.raises(ScenarioError) as exc:
        load_scenario(_write(tmp_path, text))
    assert exc.value.field == field
    assert f"[2.000, -0.250, {0.9 + dz:.3f}] m ({frame} frame) is outside the workspace" in exc.value.reason
    assert f"m ({frame} frame) (" in exc.value.reason.split("closest reachable point", 1)[1]
    sc = load_scenario(_write(tmp_path, text.replace(far, _suggested(exc.value.reason)), "fixed.toml"))
    pasted = sc.goal.position if where == "goal" else sc.via_points[0]  # base frame, as loaded
    closest = closest_reachable([2.0, -0.25, 0.9 + THESIS_SCENE.floor.z], THESIS_ARM).point
    assert np.linalg.norm(np.subtract(pasted, closest)) <= 0.011  # the same point (mm rounding, <= 10 mm in)


def test_dexterity_notes_are_exact_and_name_the_waypoint():
    """A note exactly where no alpha with the waypoint's beta has an IK solution within the limits."""
    import iik
    from iik.dexterity import admissible
    from iik.planning import dexterity_notes

    arm = iik.THESIS_ARM
    sc = load_scenario(scenario_path("j"), arm=arm)
    assert dexterity_notes(sc, arm) == []
    alphas = np.linspace(-np.pi, np.pi, 721)
    assert admissible(np.asarray(sc.start.position), alphas, sc.start.beta, arm).any()
    up = dataclasses.replace(sc, start=dataclasses.replace(sc.start, beta=0.0))  # tool z straight up
    assert not admissible(np.asarray(up.start.position), alphas, 0.0, arm).any()
    notes = dexterity_notes(up, arm)
    assert len(notes) == 1 and notes[0].startswith("start.beta_deg = 0.0 deg is outside the dexterity range")
