"""Scenario files: parsing, reconstruction notes and ScenarioError(field, reason)."""

import pytest

from iik.errors import ScenarioError
from iik.planning.scenario_io import load_scenario, thesis_scenario_paths

GOOD = """
name = "x"
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
    with pytest.raises(ScenarioError, match="does not exist"):
        load_scenario(tmp_path / "nope.toml")
