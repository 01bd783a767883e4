"""The registry of shipped arms and an arm as data (iik.arms): names, URDF paths, records; the forward
kinematics of each shipped Arm against Pinocchio on its URDF."""

import json
import shutil

import numpy as np
import pinocchio as pin
import pytest

import iik
import iik.arms as arms
from iik import THESIS_ARM
from iik.errors import InvalidInputError
from iik.kinematic_class import NotInClassError
from iik.resources import urdf_path
from iik.urdf import TOOL_FRAME, urdf_from_dh
from iik.urdf_read import read_urdf_chain


def test_every_shipped_arm_resolves_by_name_and_is_named_back():
    for name in arms.NAMES:
        arm = arms.get(name)
        assert arms.resolve(name) is arm and arms.name_of(arm) == name
    assert arms.get("thesis") is THESIS_ARM
    assert arms.get("crx10ia").urdf.endswith("crx10ia.urdf")  # read from its file: its shapes are its body
    assert arms.name_of(THESIS_ARM.scaled(1.1)) is None


def test_an_unknown_name_lists_the_shipped_arms():
    with pytest.raises(arms.UnknownArmError) as info:
        arms.resolve("ur5")
    assert info.value.argument == "arm" and all(n in info.value.reason for n in arms.NAMES)
    with pytest.raises(arms.UnknownArmError):
        arms.resolve("")


def test_a_relative_urdf_path_is_read_from_the_given_folder(tmp_path, monkeypatch):
    (tmp_path / "arms").mkdir()
    shutil.copy(arms.get("crx10ia").urdf, tmp_path / "arms" / "mine.urdf")
    monkeypatch.chdir(tmp_path / "arms")  # not where the path is relative to
    (tmp_path / "elsewhere").mkdir()
    arm = arms.resolve("arms/mine.urdf", relative_to=tmp_path)
    assert arms.same_arm(arm, arms.get("crx10ia")) and arm.urdf == str(tmp_path / "arms" / "mine.urdf")
    with pytest.raises(InvalidInputError, match="does not exist"):
        arms.resolve("arms/mine.urdf", relative_to=tmp_path / "elsewhere")


def test_a_urdf_outside_the_class_names_the_file_with_the_near_miss_report(tmp_path):
    src = open(arms.get("crx10ia").urdf).read()
    a = '<axis xyz="0 -1 0"/>\n    <limit lower="-1.239183768915974"'
    assert a in src
    tilt = np.radians(0.1)
    path = tmp_path / "tilted.urdf"
    path.write_text(src.replace(a, a.replace("0 -1 0", f"{np.sin(tilt):.17g} {-np.cos(tilt):.17g} 0"), 1))
    with pytest.raises(NotInClassError) as info:
        arms.resolve(str(path))
    assert info.value.argument == str(path) and "off by 0.1 deg" in info.value.reason


@pytest.mark.parametrize("arm", [*arms.NAMES, "scaled"])
def test_a_record_rebuilds_the_same_arm(arm):
    arm = THESIS_ARM.scaled(1.2).with_limits(acceleration=(3.0,) * 6) if arm == "scaled" else arms.get(arm)
    back = arms.from_record(json.loads(json.dumps(arms.to_record(arm))))  # as a run log stores it
    assert arms.same_arm(back, arm)
    q = np.random.default_rng(0).uniform(arm.q_min, arm.q_max, (20, 6))
    assert np.abs(iik.fk(q, back) - iik.fk(q, arm)).max() < 1e-12
    assert (back is arm) == (arms.name_of(arm) is not None)  # a shipped arm comes back as itself


def test_a_record_of_a_changed_urdf_file_rebuilds_the_arm_without_the_file(tmp_path):
    path = tmp_path / "crx.urdf"
    shutil.copy(arms.get("crx10ia").urdf, path)
    arm = iik.Arm.from_urdf(path, name="my crx")
    record = arms.to_record(arm)
    assert record["urdf"] == str(path) and len(record["urdf_sha256"]) == 64 and record["registry"] is None
    assert arms.from_record(record).urdf == str(path)  # unchanged file: read again
    path.write_text(path.read_text() + "<!-- edited -->\n")
    back = arms.from_record(record)
    assert back.urdf == "" and arms.same_arm(back, arm) and back.name == "my crx"


def test_same_arm_compares_the_numbers_not_the_names():
    assert arms.same_arm(THESIS_ARM, THESIS_ARM.with_limits(name="renamed"))
    assert not arms.same_arm(THESIS_ARM, THESIS_ARM.scaled(1.0 + 1e-9))
    assert not arms.same_arm(THESIS_ARM, THESIS_ARM.with_limits(velocity=(1.3,) * 6))


@pytest.mark.parametrize("record", [{"name": "x"}, {"dh": "nonsense"}, 42, "no such arm"])
def test_a_bad_record_is_a_typed_error(record):
    with pytest.raises(InvalidInputError) as info:
        arms.from_record(record, "header.arm")
    assert info.value.argument == "header.arm"


_FILES = {"thesis": "thesis_arm.urdf", "crx10ia": "crx10ia.urdf", "crx10ia_l": "crx10ia_l.urdf"}


def _urdf(name: str, arm) -> tuple[str, str]:
    """The URDF text of a shipped arm and the frame that is its tool: the shipped file (its tip
    link), or for a constructed arm the URDF generated from its DH table (frame ``tool``)."""
    if name in _FILES:
        path = urdf_path(_FILES[name])
        return path.read_text(), read_urdf_chain(path).tip_link
    return urdf_from_dh(arms.constructed_table(name), name=name, tool=np.array(arm.tool)), TOOL_FRAME


@pytest.mark.parametrize("name", arms.NAMES)
def test_fk_of_every_shipped_arm_matches_pinocchio_on_its_urdf(name):
    arm = arms.get(name)
    text, tip = _urdf(name, arm)
    model = pin.buildModelFromXML(text)
    assert model.nq == 6 and model.existFrame(tip)
    fid, data = model.getFrameId(tip), model.createData()
    qs = np.random.default_rng(18).uniform(arm.q_min, arm.q_max, (300, 6))
    want = np.empty((len(qs), 4, 4))
    for k, q in enumerate(qs):
        pin.framesForwardKinematics(model, data, q)
        want[k] = data.oMf[fid].homogeneous
    got = iik.fk(qs, arm)
    assert np.abs(got[:, :3, 3] - want[:, :3, 3]).max() <= 1e-12  # m
    assert np.abs(got[:, :3, :3] - want[:, :3, :3]).max() <= 1e-12
