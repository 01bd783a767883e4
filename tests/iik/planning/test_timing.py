"""TOPP-RA timing within an arm's limits and the thesis's timing (iik.planning.timing)."""


import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from iik import THESIS_ARM
from iik.planning import TimingError, thesis_timing, time_parameterize
from iik.planning.timing import EXECUTION_MARGIN, MIN_STEP, STEP_RESOLUTION, step_schedule

PATH = np.array([[0.0, 0.0, 0.0, 0.0, 0.0, 0.0], [0.6, -0.3, 0.2, 0.1, 0.4, -0.5],
                 [1.0, 0.2, -0.2, 0.0, 0.0, 0.3]])


@pytest.mark.parametrize("scale", [1.0, 0.25])
def test_every_sample_respects_the_arms_limits(scale):
    arm = THESIS_ARM.with_limits(velocity=tuple(v * scale for v in THESIS_ARM.velocity),
                                 acceleration=tuple(a * scale for a in THESIS_ARM.acceleration))
    tr = time_parameterize(PATH, arm)
    assert not tr.violations
    assert np.all(np.abs(tr.qd) <= np.asarray(arm.velocity) * (1 + 1e-9))
    assert np.all(np.abs(tr.qdd) <= np.asarray(arm.acceleration) * (1 + 1e-9))
    assert np.allclose(tr.q[0], PATH[0]) and np.allclose(tr.q[-1], PATH[-1])
    assert np.allclose(tr.qd[[0, -1]], 0, atol=1e-6)  # from rest to rest


def test_slower_limits_take_longer():
    slow = THESIS_ARM.with_limits(velocity=tuple(v / 4 for v in THESIS_ARM.velocity),
                                  acceleration=tuple(a / 4 for a in THESIS_ARM.acceleration))
    assert time_parameterize(PATH, slow).duration > 2 * time_parameterize(PATH, THESIS_ARM).duration
    assert thesis_timing(PATH, slow).duration == pytest.approx(4 * thesis_timing(PATH, THESIS_ARM).duration)


def test_a_single_configuration_is_a_static_trajectory():
    tr = time_parameterize(np.zeros((3, 6)), THESIS_ARM)
    assert tr.duration == 0.0 and tr.method == "static"


def test_toppra_failures_are_timing_errors(monkeypatch):
    import toppra.algorithm as algo

    monkeypatch.setattr(algo.TOPPRA, "compute_trajectory", lambda self, *a, **k: None)
    with pytest.raises(TimingError, match="no feasible parameterisation"):
        time_parameterize(PATH, THESIS_ARM)

    def boom(self, *a, **k):
        raise ValueError("solver exploded")

    monkeypatch.setattr(algo.TOPPRA, "compute_trajectory", boom)
    with pytest.raises(TimingError, match="solver exploded") as exc:
        time_parameterize(PATH, THESIS_ARM)
    assert isinstance(exc.value.__cause__, ValueError) and isinstance(exc.value, RuntimeError)


def test_samples_keep_the_execution_margin_inside_table_i():
    """Waypoints just inside the execution margin: the plain spline overshoots the stop; the
    timing falls back to a curve that keeps every sample inside Table I less the margin."""
    lo = THESIS_ARM.q_min[1] + EXECUTION_MARGIN + 0.001
    path = np.array([[0.0, lo + 0.6, 0, 0, 0, 0], [0.1, lo, 0, 0, 0, 0], [0.5, lo, 0, 0, 0, 0],
                     [0.6, lo + 0.1, 0, 0, 0, 0]])  # steeply down to the stop, then along it
    tr = time_parameterize(path, THESIS_ARM)
    assert not tr.violations, tr.violations
    assert np.all(tr.q >= THESIS_ARM.q_min + EXECUTION_MARGIN - 1e-12)
    assert np.all(tr.q <= THESIS_ARM.q_max - EXECUTION_MARGIN + 1e-12)
    loose = time_parameterize(path, THESIS_ARM, joint_margin=0.0)  # only Table I itself: a curve that ...
    assert not loose.violations and loose.q[:, 1].min() < lo - 1e-3  # ... overshoots the waypoints
    assert tr.method != loose.method


def test_a_path_on_the_margin_is_a_named_violation():
    path = PATH.copy()
    path[1, 3] = THESIS_ARM.q_max[3] - 0.5 * EXECUTION_MARGIN  # a waypoint inside the margin
    tr = time_parameterize(path, THESIS_ARM)
    assert any(v.startswith("joint q4 comes") and "execution margin of 0.5 deg" in v for v in tr.violations)


def test_step_times_are_the_curves_passing_times_on_the_fstep_clock():
    tr = time_parameterize(PATH, THESIS_ARM, dt=0.001)
    assert tr.step_q.shape == PATH.shape and np.array_equal(tr.step_q, PATH)
    st = tr.step_t
    assert st[0] == 0 and np.all(np.diff(st) >= MIN_STEP)
    np.testing.assert_allclose(st / STEP_RESOLUTION, np.rint(st / STEP_RESOLUTION), atol=1e-9)  # whole ms
    assert abs(st[-1] - tr.duration) <= STEP_RESOLUTION  # the plan's duration
    # the dense curve is at each step-point when the step time says (0.5 ms rounding, dt sampling)
    qi = np.array([np.interp(st, tr.t, tr.q[:, j]) for j in range(6)]).T
    assert np.abs(qi - PATH).max() < 0.002 * max(THESIS_ARM.velocity)
    speeds = np.abs(np.diff(PATH, axis=0)) / np.diff(st)[:, None]
    assert np.all(speeds <= np.asarray(THESIS_ARM.velocity))


@given(st.data())
def test_step_schedule_is_executable_and_as_early_as_allowed(data):
    n = data.draw(st.integers(2, 12))
    dts = data.draw(st.lists(st.floats(0.0, 0.3), min_size=n - 1, max_size=n - 1))
    t = np.concatenate([[0.0], np.cumsum(dts)])
    dq = np.array(data.draw(st.lists(st.lists(st.floats(-0.3, 0.3), min_size=6, max_size=6),
                                     min_size=n - 1, max_size=n - 1)))
    q = np.concatenate([np.zeros((1, 6)), np.cumsum(dq, axis=0)])
    out = step_schedule(t, q, THESIS_ARM)
    steps = np.diff(out)
    assert out[0] == 0 and np.all(steps >= MIN_STEP - 1e-12)
    np.testing.assert_allclose(out * 1000, np.rint(out * 1000), atol=1e-6)
    assert np.all(np.abs(np.diff(q, axis=0)) / steps[:, None] <= np.asarray(THESIS_ARM.velocity) * (1 + 1e-9))
    assert np.all(out >= np.rint(t * 1000) / 1000 - 1e-12)  # never earlier than the rounded time
    # a step-point is held back only by the step before it
    need = np.ceil(np.maximum(np.max(np.abs(np.diff(q, axis=0)) / np.asarray(THESIS_ARM.velocity), axis=1),
                              MIN_STEP) * 1000 - 1e-9) / 1000
    late = out[1:] > np.rint(t[1:] * 1000) / 1000 + 1e-12
    np.testing.assert_allclose(steps[late], need[late], atol=1e-9)
