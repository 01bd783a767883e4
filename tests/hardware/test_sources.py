"""`hardware.sources`: step targets as typed results; CSV errors name the line and column."""

import dataclasses

import numpy as np
import pytest

import iik
import iik.arms
from hardware import StepTargets
from hardware.errors import SafetyError
from hardware.sources import DEMO_STEP, csv_trajectory, demo_trajectory, scenario_trajectory
from iik import THESIS_ARM
from iik.errors import InvalidInputError
from iik.planning import ScenarioError

Q = np.linspace(0, 1, 4)[:, None] * np.array([0.05, 0.04, -0.03, 0.02, 0.1, 0.0])
HEADER = "t,q1,q2,q3,q4,q5,q6"


def write(path, rows, header=HEADER):
    path.write_text("".join(f"{r}\n" for r in ([header] if header is not None else []) + rows))
    return path


def good_rows():
    return [",".join(f"{v:.9f}" for v in [k * 0.1, *Q[k]]) for k in range(4)]


def test_demo_is_a_short_step_line_solved_by_ik():
    t = demo_trajectory(THESIS_ARM, 0.5)
    assert isinstance(t, StepTargets) and t.name == "demo" and t.orientation_free is None
    with pytest.raises(dataclasses.FrozenInstanceError):
        t.name = "x"
    p = t.poses[:, :3, 3]
    assert np.max(np.linalg.norm(np.diff(p, axis=0), axis=1)) <= DEMO_STEP + 1e-12
    np.testing.assert_allclose(iik.fk(t.q, THESIS_ARM), t.poses, atol=1e-9)  # every target solves its pose
    assert np.all(np.diff(t.times) > 0) and len(t.validate()) == len(t)
    assert len(t.validate(limit=4)) == 4


def test_csv_targets(tmp_path):
    t = csv_trajectory(write(tmp_path / "traj.csv", good_rows()), THESIS_ARM)
    assert t.name == "traj" and t.q.shape == (4, 6) and list(t.lines) == [2, 3, 4, 5]
    np.testing.assert_allclose(t.poses, iik.fk(t.q, THESIS_ARM))
    np.testing.assert_allclose(t.q, Q, atol=1e-9)
    # columns in another order, extra columns and blank lines are fine
    rows = [",".join([f"{v:.9f}" for v in Q[k][::-1]] + ["x", f"{k * 0.1}"]) for k in range(4)]
    shuffled = csv_trajectory(write(tmp_path / "s.csv", rows[:2] + [""] + rows[2:],
                                    header="q6,q5,q4,q3,q2,q1,note,t"), THESIS_ARM)
    np.testing.assert_allclose(shuffled.q, t.q)
    np.testing.assert_allclose(shuffled.times, t.times)
    assert list(shuffled.lines) == [2, 3, 5, 6]


@pytest.mark.parametrize(("content", "match"), [
    ("", r"the file is empty: it needs a header line naming the columns t,q1,q2,q3,q4,q5,q6"),
    ("\n\n", r"the file is empty"),
    (None, r"line 1 holds numbers, not a header"),  # headerless: the data alone
    (HEADER + "\n", r"needs at least 2 data lines \(step-points\) below the header, has 0"),
    ("t,q1,q2\n0,1,2\n", r"line 1 \(the header\) lacks the column\(s\) q3, q4, q5, q6"),
    ("t,q1,q1,q2,q3,q4,q5,q6\n", r"line 1: column 'q1' appears twice \(columns 2 and 3, counting from 1\)"),
    (HEADER + "\n0,0,0,0,0,0,0\n0.1,0,0,abc,0,0,0\n",
     r"line 3, column 4 \(q3; lines and columns count from 1\): 'abc' is not a number"),
    (HEADER + "\n0,0,0,0,0,0,0\n0.1,0,0,0,0,nan,0\n", r"line 3, column 6 \(q5; .*\): 'nan' is not a finite"),
    (HEADER + "\n0,0,0,0,0,0,0\n0.1,0,0,0,0,0,\n", r"line 3, column 7 \(q6; .*\): '' is not a number"),
    (HEADER + "\n0,0,0,0,0,0,0\n0.1,0,0,0\n", r"line 3 has 4 cells, the header has 7"),
])
def test_bad_csv_files_are_typed_errors_naming_line_and_column(tmp_path, content, match):
    path = tmp_path / "bad.csv"
    if content is None:
        write(path, good_rows(), header=None)
    else:
        path.write_text(content)
    with pytest.raises(InvalidInputError, match=match) as info:
        csv_trajectory(path, THESIS_ARM)
    assert info.value.argument == "trajectory" and str(path) in str(info.value)


def test_unreadable_and_binary_files(tmp_path):
    with pytest.raises(InvalidInputError, match="cannot read .*missing.csv: no such file"):
        csv_trajectory(tmp_path / "missing.csv", THESIS_ARM)
    with pytest.raises(InvalidInputError, match="it is a folder, not a regular file"):
        csv_trajectory(tmp_path, THESIS_ARM)  # a folder
    (tmp_path / "bin.csv").write_bytes(b"t,q1\x00\xff\xfe")
    with pytest.raises(InvalidInputError, match=r"not UTF-8 text|not CSV"):
        csv_trajectory(tmp_path / "bin.csv", THESIS_ARM)


def test_a_refused_csv_step_point_is_named_by_its_line(tmp_path):
    rows = good_rows()
    rows[2] = ",".join(["0.2", "0", "4.0", "0", "0", "0", "0"])  # q2 = 4 rad, outside Table I
    t = csv_trajectory(write(tmp_path / "far.csv", rows), THESIS_ARM)
    with pytest.raises(SafetyError) as info:
        t.validate()
    assert (info.value.step, info.value.joint) == (2, 1)
    assert str(info.value).startswith(f"{tmp_path / 'far.csv'} line 4 (step-point 2 (counting from 0)), "
                                      "joint q2: 4.000000 rad outside Table I")


def test_slowed_lengthens_every_step_and_keeps_whole_ms():
    t = demo_trajectory(THESIS_ARM)
    half = t.slowed(0.5)
    assert half is not t and t.slowed(1.0) is t
    np.testing.assert_allclose(np.diff(half.times), 2 * np.diff(t.times), atol=1e-9)
    odd = t.slowed(0.7)
    steps_ms = np.diff(odd.times) * 1000
    np.testing.assert_allclose(steps_ms, np.rint(steps_ms), atol=1e-6)  # whole ms
    assert np.all(np.diff(odd.times) >= np.diff(t.times) / 0.7 - 1e-9)  # never faster than asked


def test_scenario_runs_the_step_times_the_plan_writes():
    from iik.planning import plan

    res = plan("j")
    t = scenario_trajectory("j")
    np.testing.assert_array_equal(t.times, res.trajectory.step_t)
    np.testing.assert_array_equal(t.q, res.q)
    assert t.times[-1] == pytest.approx(res.trajectory.duration, abs=0.01)  # the plan's duration
    assert "as iik plan times them" in t.note
    t.validate()  # executable as planned: Table I less the margin, speeds, FK vs the planned poses


def test_the_step_targets_carry_the_arm_they_are_for(tmp_path):
    """A scenario's targets are its arm's (the CRX's for crx_j; refused for another arm); a CSV file and the
    demo are for the arm given: their planned poses are its FK, and validation uses its limits."""
    crx = iik.arms.get("crx10ia")
    t = scenario_trajectory("crx_j")
    assert t.arm is crx and "planned for the arm 'crx10ia'" in t.note
    np.testing.assert_allclose(iik.fk(t.q, crx)[:, :3, 3], t.poses[:, :3, 3], atol=1e-8)
    assert len(t.validate()) == len(t)
    with pytest.raises(ScenarioError, match="is for the arm"):
        scenario_trajectory("j", arm=crx)
    demo = demo_trajectory(crx)
    assert demo.arm is crx and np.abs(iik.fk(demo.q, crx) - demo.poses).max() < 1e-9
    assert len(demo.validate()) == len(demo)
    rows = [",".join(f"{v:.9f}" for v in [k * 0.1, 0.0, 0.0, 3.5 * k / 3, 0.0, 0.0, 0.0]) for k in range(4)]
    path = write(tmp_path / "j3.csv", rows)  # joint 3 to 3.5 rad: inside the CRX's limits, not Table I's
    on_crx = csv_trajectory(path, crx)
    np.testing.assert_allclose(on_crx.poses, iik.fk(on_crx.q, crx))
    with pytest.raises(SafetyError, match="outside Table I"):
        csv_trajectory(path, THESIS_ARM).validate()
    assert len(dataclasses.replace(on_crx, times=on_crx.times * 20).validate()) == 4
    beyond = write(tmp_path / "j3far.csv", [r.replace("3.500000000", "4.500000000") for r in rows])
    with pytest.raises(SafetyError, match=r"outside the joint limits \[-1.2392, 4.3808\]") as info:
        csv_trajectory(beyond, crx).validate()  # the CRX's J3 limits, not called Table I
    assert "Table I" not in str(info.value)


@pytest.mark.parametrize("timed", [True, False])
def test_the_reader_takes_the_files_the_planner_writes_by_their_one_schema(tmp_path, timed):
    """iik.trajectory_csv names the columns once: a file with the columns of trajectory.csv or of a
    timed steps.csv is executed as written; steps.csv without its t is refused for lack of it."""
    from iik.trajectory_csv import REQUIRED, TRAJECTORY_COLUMNS, steps_columns

    for columns in (TRAJECTORY_COLUMNS, steps_columns(timed)):
        rows = []
        for k in range(4):
            value = {"t": k * 0.1, "step": k, "closest_link": "link3", "closest_object": "floor",
                     **{f"q{j + 1}": Q[k, j] for j in range(6)}}
            rows.append(",".join(str(value.get(c, 0.5)) for c in columns))
        path = write(tmp_path / "f.csv", rows, header=",".join(columns))
        if set(REQUIRED) <= set(columns):
            t = csv_trajectory(path, THESIS_ARM)
            np.testing.assert_allclose(t.q, Q)
            np.testing.assert_allclose(t.times, 0.1 * np.arange(4))
        else:
            assert not timed
            with pytest.raises(InvalidInputError, match="lacks the column"):
                csv_trajectory(path, THESIS_ARM)
