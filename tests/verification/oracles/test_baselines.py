"""Newton / DLS baselines on Pinocchio converge to the generating q from a nearby guess."""

import numpy as np
import pytest

import iik
from iik import THESIS_ARM
from verification.oracles.baselines import THESIS_NEWTON_TOL, damped_least_squares, newton_pinv


@pytest.mark.parametrize("method", [newton_pinv, damped_least_squares])
def test_converges_from_nearby_guess(method):
    rng = np.random.default_rng(4)
    for _ in range(10):
        q = rng.uniform(iik.THESIS_ARM.q_min, iik.THESIS_ARM.q_max)
        if np.linalg.svd(iik.jacobian(q, THESIS_ARM), compute_uv=False)[-1] < 1e-2:
            continue
        r = method(iik.fk(q, THESIS_ARM), q + rng.normal(0, 0.05, 6))
        assert r.converged
        assert r.position_error <= 1e-9 and r.rotation_error <= 1e-9
        assert np.max(np.abs(r.q - q)) <= 1e-7


def test_newton_is_one_of_the_complete_solutions():
    q = np.array([0.3, -0.5, 0.7, 1.0, -0.4, 2.0])
    T = iik.fk(q, THESIS_ARM)
    r = newton_pinv(T, np.zeros(6))
    sols = iik.solve(T, THESIS_ARM, within_limits=False).q
    if r.converged:
        d = np.abs((sols - r.q + np.pi) % (2 * np.pi) - np.pi).max(axis=1)
        assert d.min() <= 1e-6
    assert THESIS_NEWTON_TOL == pytest.approx(np.pi / 180 * 1e-6)
