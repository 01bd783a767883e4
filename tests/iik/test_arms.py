"""The shipped arms (iik.arms): the forward kinematics of each Arm against Pinocchio on its URDF."""

import numpy as np
import pinocchio as pin
import pytest

import iik
import iik.arms
from iik.resources import urdf_path
from iik.urdf import TOOL_FRAME, urdf_from_dh
from iik.urdf_read import read_urdf_chain

_FILES = {"thesis": "thesis_arm.urdf", "crx10ia": "crx10ia.urdf", "crx10ia_l": "crx10ia_l.urdf"}


def _urdf(name: str, arm) -> tuple[str, str]:
    """The URDF text of a shipped arm and the frame that is its tool: the shipped file (its tip
    link), or for a constructed arm the URDF generated from its DH table (frame ``tool``)."""
    if name in _FILES:
        path = urdf_path(_FILES[name])
        return path.read_text(), read_urdf_chain(path).tip_link
    return urdf_from_dh(iik.arms.constructed_table(name), name=name, tool=np.array(arm.tool)), TOOL_FRAME


@pytest.mark.parametrize("name", iik.arms.NAMES)
def test_fk_of_every_shipped_arm_matches_pinocchio_on_its_urdf(name):
    arm = iik.arms.get(name)
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
