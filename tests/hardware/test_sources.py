"""`hardware.sources`: step targets as typed results."""

import dataclasses

import numpy as np
import pytest

import iik
from hardware import StepTargets
from hardware.sources import DEMO_STEP, csv_trajectory, demo_trajectory
from iik.errors import InvalidInputError


def test_demo_is_a_short_step_line_solved_by_ik():
    t = demo_trajectory(0.5)
    assert isinstance(t, StepTargets) and t.name == "demo" and t.orientation_free is None
    with pytest.raises(dataclasses.FrozenInstanceError):
        t.name = "x"
    p = t.poses[:, :3, 3]
    assert np.max(np.linalg.norm(np.diff(p, axis=0), axis=1)) <= DEMO_STEP + 1e-12
    np.testing.assert_allclose(iik.fk(t.q), t.poses, atol=1e-9)  # every target solves its pose
    assert np.all(np.diff(t.times) > 0) and len(t.validate()) == len(t)
    assert len(t.validate(limit=4)) == 4


def test_csv_targets_and_bad_files(tmp_path):
    q = np.linspace(0, 1, 4)[:, None] * np.array([0.05, 0.04, -0.03, 0.02, 0.1, 0.0])
    path = tmp_path / "traj.csv"
    np.savetxt(path, np.column_stack([np.arange(4) * 0.1, q]), delimiter=",",
               header="t,q1,q2,q3,q4,q5,q6", comments="")
    t = csv_trajectory(path)
    assert t.name == "traj" and t.q.shape == (4, 6)
    np.testing.assert_allclose(t.poses, iik.fk(q))
    bad = tmp_path / "bad.csv"
    bad.write_text("t,q1,q2\n0,1,2\n")
    with pytest.raises(InvalidInputError, match="header columns"):
        csv_trajectory(bad)


