"""A scenario names its arm (``arm = "NAME"`` or a URDF path): loaded, checked for that arm, planned for it.

The shipped CRX-10iA scenario (``scenarios/crx_j.toml``) plans for the CRX (its body in the whole-arm
check, its IK along the path); a file's arm is the one its workspace is checked for; a given arm must
agree with the file's; a file that names none needs one given; a bad name or URDF is a
:class:`ScenarioError` on the field ``arm``.
"""

import dataclasses
import shutil

import numpy as np
import pytest

import iik
import iik.arms
from iik import THESIS_ARM
from iik.arms import same_arm
from iik.planning import (
    PlanOptions,
    ScenarioError,
    load_scenario,
    plan,
    scenario_path,
    scenario_to_toml,
    shipped_scenario_paths,
    thesis_scenario_paths,
    write_scenario,
)
from iik.planning.robot_model import arm_model, collision_link

CRX = iik.arms.get("crx10ia")

#: A task in base frame 0 whose start (1.0 m out) only the CRX reaches; ``{arm}`` is the arm key line.
FAR = """
name = "far"
{arm}
[start]
position = [1.0, 0.0, 0.5]
beta_deg = 180.0
[goal]
position = [0.7, 0.4, 0.5]
beta_deg = 180.0
"""


def _write(folder, text, name="s.toml"):
    p = folder / name
    p.write_text(text)
    return p


def test_the_crx_scenario_is_shipped_for_the_crx_and_not_a_thesis_scenario():
    sc = load_scenario(scenario_path("crx_j"))
    assert sc.arm is CRX and sc.via_points and sc.segments == ("line", "arc", "line")
    assert scenario_path("crx_j") in shipped_scenario_paths()
    assert scenario_path("crx_j") not in thesis_scenario_paths() and len(thesis_scenario_paths()) == 13
    assert all(load_scenario(p).arm is THESIS_ARM for p in thesis_scenario_paths())


def test_the_crx_scenario_plans_for_the_crx():
    res = plan("crx_j")
    assert res.success, res.reason
    assert res.arm is CRX and res.scenario.arm is CRX
    assert np.abs(iik.fk(res.q, CRX)[:, :3, 3] - res.cartesian.points).max() < 1e-8
    tm = arm_model(CRX)
    links = {collision_link(tm.model, g) for g in tm.collision_model.geometryObjects}
    assert tm.geometry == "urdf" and set(res.clearance.step_link) <= links  # the CRX's own shapes
    assert res.min_clearance >= res.scenario.safety_zone
    for v in res.scenario.via_points:  # the requested via-points are passed
        assert np.linalg.norm(res.points - np.asarray(v), axis=1).min() < 1e-3
    # the exact dexterity (on the complete IK) serves the CRX too: its start and goal are admissible
    assert not any("dexterity" in n for n in res.notes), res.notes


def test_the_workspace_checked_is_the_files_arm(tmp_path):
    """The start is reachable by the CRX only: the CRX's file loads, the same task for the thesis arm is
    refused as outside its workspace; a point beyond the CRX's reach is refused with the CRX's closest
    reachable point."""
    sc = load_scenario(_write(tmp_path, FAR.format(arm='arm = "crx10ia"')))
    assert sc.arm is CRX
    with pytest.raises(ScenarioError, match="outside the workspace") as info:
        load_scenario(_write(tmp_path, FAR.format(arm='arm = "thesis"'), "t.toml"))
    assert info.value.field == "start.position"
    with pytest.raises(ScenarioError, match="outside the workspace") as info:
        beyond = FAR.format(arm='arm = "crx10ia"').replace("[1.0, 0.0, 0.5]", "[1.8, 0.0, 0.5]")
        load_scenario(_write(tmp_path, beyond, "beyond.toml"))
    shown = info.value.reason.split("closest reachable point [")[1].split("]")[0]
    closest = [float(v) for v in shown.split(",")]
    assert 1.2 < np.hypot(closest[0], closest[1]) < 1.5  # on the CRX's boundary (the thesis arm's is < 1 m)
    assert iik.in_workspace(closest, CRX)


def test_a_relative_urdf_path_is_read_from_the_scenario_files_folder(tmp_path, monkeypatch):
    (tmp_path / "arms").mkdir()
    (tmp_path / "tasks").mkdir()
    shutil.copy(CRX.urdf, tmp_path / "arms" / "crx.urdf")
    path = _write(tmp_path / "tasks", FAR.format(arm='arm = "../arms/crx.urdf"'))
    monkeypatch.chdir(tmp_path)  # the path is relative to the file, not to the working directory
    sc = load_scenario(path)
    assert same_arm(sc.arm, CRX) and sc.arm.urdf == str(tmp_path / "arms" / "crx.urdf")
    assert "../arms/crx.urdf" not in scenario_to_toml(sc)  # written back as the file's own path
    assert same_arm(load_scenario(write_scenario(sc, tmp_path / "back.toml")).arm, CRX)


@pytest.mark.parametrize(("arm_line", "needle"), [
    ('arm = "ur5"', "not a shipped arm; shipped: thesis, crx10ia"),
    ('arm = "missing.urdf"', "does not exist"),
    ("arm = 3", "expected a shipped arm's name or a URDF file"),
    ('arm = "bad.urdf"', "is not valid XML"),
])
def test_a_bad_arm_is_a_scenario_error_on_the_field_arm(tmp_path, arm_line, needle):
    (tmp_path / "bad.urdf").write_text("<robot name='x'><link name='a'>")
    with pytest.raises(ScenarioError) as info:
        load_scenario(_write(tmp_path, FAR.format(arm=arm_line)))
    assert info.value.field == "arm" and needle in info.value.reason


def test_no_arm_named_and_none_given_is_an_error_a_given_one_must_agree(tmp_path):
    path = _write(tmp_path, FAR.format(arm=""))
    with pytest.raises(ScenarioError, match="names no arm and none was given") as info:
        load_scenario(path)
    assert info.value.field == "arm"
    assert load_scenario(path, arm=CRX).arm is CRX  # given: the scenario is for it
    with pytest.raises(ScenarioError, match="is for the arm 'crx10ia'") as info:
        load_scenario(_write(tmp_path, FAR.format(arm='arm = "crx10ia"'), "c.toml"), arm=THESIS_ARM)
    assert info.value.field == "arm"
    with pytest.raises(ScenarioError, match="names no arm"):  # a Scenario object alike
        plan(dataclasses.replace(load_scenario(path, arm=CRX), arm=None), PlanOptions(fallbacks=False))


def test_the_arm_is_written_back_by_its_shipped_name_or_not_at_all(tmp_path):
    sc = load_scenario(scenario_path("crx_j"))
    text = scenario_to_toml(sc)
    assert 'arm = "crx10ia"\n' in text
    assert load_scenario(write_scenario(sc, tmp_path / "x.toml")) == sc
    with pytest.raises(ScenarioError, match="neither a shipped arm nor read from a URDF file") as info:
        scenario_to_toml(dataclasses.replace(sc, arm=CRX.scaled(1.1)))
    assert info.value.field == "arm"
