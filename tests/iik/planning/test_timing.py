"""TOPP-RA timing within an arm's limits and the thesis's timing (iik.planning.timing)."""

import dataclasses

import numpy as np
import pytest

from iik import THESIS_ARM
from iik.planning import TimingError, thesis_timing, time_parameterize

PATH = np.array([[0.0, 0.0, 0.0, 0.0, 0.0, 0.0], [0.6, -0.3, 0.2, 0.1, 0.4, -0.5],
                 [1.0, 0.2, -0.2, 0.0, 0.0, 0.3]])


@pytest.mark.parametrize("scale", [1.0, 0.25])
def test_every_sample_respects_the_arms_limits(scale):
    arm = dataclasses.replace(THESIS_ARM, velocity=tuple(v * scale for v in THESIS_ARM.velocity),
                              acceleration=tuple(a * scale for a in THESIS_ARM.acceleration))
    tr = time_parameterize(PATH, arm)
    assert not tr.violations
    assert np.all(np.abs(tr.qd) <= np.asarray(arm.velocity) * (1 + 1e-9))
    assert np.all(np.abs(tr.qdd) <= np.asarray(arm.acceleration) * (1 + 1e-9))
    assert np.allclose(tr.q[0], PATH[0]) and np.allclose(tr.q[-1], PATH[-1])
    assert np.allclose(tr.qd[[0, -1]], 0, atol=1e-6)  # from rest to rest


def test_slower_limits_take_longer():
    slow = dataclasses.replace(THESIS_ARM, velocity=tuple(v / 4 for v in THESIS_ARM.velocity),
                               acceleration=tuple(a / 4 for a in THESIS_ARM.acceleration))
    assert time_parameterize(PATH, slow).duration > 2 * time_parameterize(PATH).duration
    assert thesis_timing(PATH, slow).duration == pytest.approx(4 * thesis_timing(PATH).duration)


def test_a_single_configuration_is_a_static_trajectory():
    tr = time_parameterize(np.zeros((3, 6)))
    assert tr.duration == 0.0 and tr.method == "static"


def test_toppra_failures_are_timing_errors(monkeypatch):
    import toppra.algorithm as algo

    monkeypatch.setattr(algo.TOPPRA, "compute_trajectory", lambda self, *a, **k: None)
    with pytest.raises(TimingError, match="no feasible parameterisation"):
        time_parameterize(PATH)

    def boom(self, *a, **k):
        raise ValueError("solver exploded")

    monkeypatch.setattr(algo.TOPPRA, "compute_trajectory", boom)
    with pytest.raises(TimingError, match="solver exploded") as exc:
        time_parameterize(PATH)
    assert isinstance(exc.value.__cause__, ValueError) and isinstance(exc.value, RuntimeError)
