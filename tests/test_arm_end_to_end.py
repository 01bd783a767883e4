"""Issue 18: a test that fails if any function below the CLI uses the thesis arm when given another.

Two arms that are not the thesis arm -- the FANUC CRX-10iA (its URDF, its own scenario file
``scenarios/crx_j.toml``) and the thesis arm scaled by 1.15 with twice its speed limits (built in
code, with higher speed and acceleration limits: no name, no file; scene j laid out for it, run from
the ``steps.csv`` that planning wrote) --
go through every layer: plan -> run on the simulated arm (``hardware.run``, in-process virtual bus)
-> analyse -> view export. At each layer a measurement checks that the arm used is the given one,
where the thesis arm would give another answer:

* plan: the joints' FK (the given arm's) passes through the planned tool points, the thesis arm's
  FK does not; the whole-arm clearances are the given arm's body (its links, its distances; the
  thesis arm's body is measured to differ); the timing is the arm's (its limits reproduce the
  duration, the thesis arm's limits give another);
* run: the simulated modules' soft limits, speeds and accelerations are the arm's; the host checks
  targets against the arm; the run log's header records the arm and reads back as it;
* analyse: the end-effector errors are the arm's FK of the measured joints (small), where the thesis
  arm's FK would put the tool centimetres away;
* view: the run view and the plan view draw the arm's body (every ArmBody gets the arm's model) and
  their notes use its FK; the pages are written.
"""

from __future__ import annotations

import contextlib
import dataclasses

import numpy as np
import pinocchio as pin
import pytest

import hardware.runner as runner
import iik.arms
import iik.planning.viewer.motion as motion_module
import iik.planning.viewer.plan as plan_module
from hardware import BusConfig, ExecutionOptions, RunOptions, SimConfig, VirtualClock, read_run_log
from hardware import protocol as P
from hardware.runner import run
from hardware.sources import csv_trajectory, scenario_trajectory
from hardware.view import run_motion, view_run
from iik import THESIS_ARM, fk
from iik.arms import same_arm
from iik.planning import SceneCollision, load_scenario, plan, scenario_path, write_outputs
from iik.planning.robot_model import arm_model, collision_link
from iik.planning.timing import time_parameterize
from iik.planning.viewer import PlanScene, ViewOptions, plan_scene, show

#: The arm built in code: longer links, higher speed and acceleration limits than the thesis arm.
SCALED = THESIS_ARM.scaled(1.15, name="thesis x1.15").with_limits(
    velocity=tuple(2.0 * np.asarray(THESIS_ARM.velocity)), acceleration=(3.0,) * 6,
    name="thesis x1.15, faster")


def _links(arm) -> set[str]:
    tm = arm_model(arm)
    return {collision_link(tm.model, g) for g in tm.collision_model.geometryObjects}


def _is_body_of(tm, arm) -> bool:
    """Is the Pinocchio model ``tm`` the body of ``arm``: its tool frame at the arm's FK, its shapes the
    arm's (by name)?"""
    names = [g.name for g in tm.collision_model.geometryObjects]
    if names != [g.name for g in arm_model(arm).collision_model.geometryObjects]:
        return False
    data = tm.model.createData()
    for q in np.random.default_rng(5).uniform(arm.q_min, arm.q_max, (5, 6)):
        pin.framesForwardKinematics(tm.model, data, q)
        if np.abs(data.oMf[tm.tool_frame_id].homogeneous - fk(q, arm)).max() > 1e-9:
            return False
    return True


@contextlib.contextmanager
def _spy(monkeypatch, module, name: str, seen: list):
    """Record every call of ``module.name`` (its keyword arguments and result) while still calling it."""
    real = getattr(module, name)

    def spy(*args, **kwargs):
        out = real(*args, **kwargs)
        seen.append((kwargs, out))
        return out

    monkeypatch.setattr(module, name, spy)
    yield seen


def _run_simulated(targets, out):
    """``hardware.run`` on modules simulated in-process from the first target, on a virtual clock."""
    sim = SimConfig(initial=tuple(targets.q[0]), clock=VirtualClock())
    options = RunOptions(execution=ExecutionOptions(sample_period=0.03), figures=False)
    return run(targets, BusConfig.simulated(sim), options, out)


@pytest.fixture(scope="module", params=["crx10ia", "scaled"])
def journey(request, tmp_path_factory):
    """Plan, run (in-process simulated arm), analyse: the results of each layer, and the arm given."""
    tmp = tmp_path_factory.mktemp(request.param)
    mp = pytest.MonkeyPatch()
    sims: list = []
    real_connect = runner.connect

    @contextlib.contextmanager
    def connect(*args, **kwargs):  # the host and the sim the runner opens, recorded
        with real_connect(*args, **kwargs) as (host, sim):
            sims.append((sim, host))
            yield host, sim

    mp.setattr(runner, "connect", connect)
    try:
        if request.param == "crx10ia":
            arm = iik.arms.get("crx10ia")
            planned = plan("crx_j")  # the file names its arm
            report = _run_simulated(scenario_trajectory("crx_j"), tmp / "runs")
        else:
            arm = SCALED
            planned = plan(dataclasses.replace(load_scenario(scenario_path("j")), arm=arm))
            write_outputs(planned, tmp / "plan", figures=False)
            report = _run_simulated(csv_trajectory(tmp / "plan" / "steps.csv", arm), tmp / "runs")
    finally:
        mp.undo()
    return arm, planned, report, sims


def test_the_plan_is_the_given_arms(journey):
    arm, res, _, _ = journey
    assert res.success, res.reason
    assert res.arm is arm and res.scenario.arm is arm and not same_arm(arm, THESIS_ARM)
    # IK: the joints reach the planned tool points with the arm's FK, not with the thesis arm's
    P = res.cartesian.points
    assert np.abs(fk(res.q, arm)[:, :3, 3] - P).max() < 1e-8
    assert np.abs(fk(res.q, THESIS_ARM)[:, :3, 3] - P).max() > 0.02
    # collision: the clearances are the arm's body (its links; the thesis arm's body measures otherwise)
    assert set(res.clearance.step_link) <= _links(arm)
    own = SceneCollision(res.scenario.obstacles, arm=arm, scene=res.scene)
    assert np.allclose([own.nearest(q).distance for q in res.q], res.clearance.step, atol=1e-9)
    thesis = SceneCollision(res.scenario.obstacles, arm=THESIS_ARM, scene=res.scene)
    assert np.abs(np.array([thesis.nearest(q).distance for q in res.q]) - res.clearance.step).max() > 0.005
    # timing: the arm's limits (TOPP-RA with them gives the plan's duration; with the thesis arm's, another)
    qd = np.abs(res.trajectory.qd)
    assert np.all(qd <= np.asarray(arm.velocity) * (1 + 1e-9))
    assert time_parameterize(res.q, arm).duration == pytest.approx(res.trajectory.duration, rel=1e-9)
    assert abs(time_parameterize(res.q, THESIS_ARM).duration - res.trajectory.duration) > 0.01


def test_the_simulated_arm_and_the_host_are_the_given_arm(journey):
    arm, _, report, sims = journey
    assert len(sims) == 1
    sim, host = sims[0]
    assert host.arm is not None and same_arm(host.arm, arm)
    for j, i in enumerate(sim.module_ids):
        params = sim.modules[i].params
        assert params[P.Param.FMINPOS] == arm.lower[j] and params[P.Param.FMAXPOS] == arm.upper[j]
        assert params[P.Param.FMAXVEL] == arm.velocity[j] and params[P.Param.FMAXACC] == arm.acceleration[j]
    assert any(v != t for v, t in zip(arm.velocity, THESIS_ARM.velocity, strict=True))
    assert same_arm(report.targets.arm, arm)


def test_the_run_log_records_the_arm_and_the_analysis_uses_it(journey):
    arm, _, report, _ = journey
    run_ = read_run_log(report.result.log_path)
    assert run_.header["version"] == 2 and same_arm(run_.arm, arm)
    a = report.analysis
    assert same_arm(a.arm, arm) and a.status == "ok"
    # the end-effector errors are the arm's FK of the measured joints ...
    mine = np.linalg.norm(fk(a.q_measured, arm)[:, :3, 3] - run_.poses[a.steps, :3, 3], axis=1)
    assert np.allclose(a.ee_error, mine, atol=1e-12) and a.max_ee_error < 0.03
    # ... where the thesis arm's FK would put the tool centimetres away
    theirs = np.linalg.norm(fk(a.q_measured, THESIS_ARM)[:, :3, 3] - run_.poses[a.steps, :3, 3], axis=1)
    assert theirs.max() > 0.02


def test_the_views_draw_the_given_arm(journey, tmp_path, monkeypatch):
    arm, res, report, _ = journey
    bodies: list = []
    for module in (plan_module, motion_module):
        real = module.ArmBody

        def body(*args, _real=real, **kwargs):
            bodies.append(kwargs["model"])
            return _real(*args, **kwargs)

        monkeypatch.setattr(module, "ArmBody", body)
    # the run: drawn as the arm the log records, notes with its FK
    m = run_motion(read_run_log(report.result.log_path))
    assert same_arm(m.arm, arm)
    k = len(m.t) // 2
    cmd, meas = m.tracks[0].q[k], m.tracks[1].q[k]
    mm = np.linalg.norm(fk(meas, arm)[:3, 3] - fk(cmd, arm)[:3, 3]) * 1000
    assert f"tool {mm:.1f} mm" in m.notes[k]
    shown = view_run(report.result.log_path, ViewOptions(export=tmp_path / "run"))
    assert (tmp_path / "run" / "index.html").is_file() and shown.result.frames > 1
    # the plan: the planned arm's body and clearances
    pv = plan_scene(res)
    assert pv.arm is arm and np.allclose(fk(pv.step_q, arm)[:, :3, 3], pv.step_points, atol=1e-8)
    scene = PlanScene(pv)
    assert {n.link for n in scene.clearance} <= _links(arm)
    show(scene, ViewOptions(export=tmp_path / "plan"))
    assert (tmp_path / "plan" / "index.html").is_file()
    assert len(bodies) == 3 and all(_is_body_of(b, arm) for b in bodies)
    assert not any(_is_body_of(b, THESIS_ARM) for b in bodies)
