"""Joint vectors within the joint limits and a little beyond, no NaN/inf: Hypothesis strategies for
the tests (Hypothesis, of the ``test`` extra, is imported when a strategy is built) and a NumPy
sampler that ``iik verify`` uses."""

from __future__ import annotations

import numpy as np

from iik.arm import THESIS_ARM, Arm
from iik.extras import require

__all__ = ["BEYOND", "joint_vectors", "joint_batches", "sample_joints"]

#: How far beyond the joint limits samples may go [rad] (the formulas hold everywhere).
BEYOND = 0.2


def joint_vectors(arm: Arm = THESIS_ARM, beyond: float = BEYOND):
    """Strategy for one q (6,) [rad] with each q_i in [lower_i - beyond, upper_i + beyond]."""
    require("test", "verification.testing.strategies.joint_vectors")
    from hypothesis import strategies as st

    return st.tuples(*(
        st.floats(lo - beyond, hi + beyond, allow_nan=False, allow_infinity=False)
        for lo, hi in zip(arm.lower, arm.upper, strict=True)
    )).map(lambda t: np.array(t, dtype=float))


def joint_batches(arm: Arm = THESIS_ARM, beyond: float = BEYOND, max_size: int = 8):
    """Strategy for a batch (n, 6) of joint vectors, 1 <= n <= ``max_size``."""
    require("test", "verification.testing.strategies.joint_batches")
    from hypothesis import strategies as st

    return st.lists(joint_vectors(arm, beyond), min_size=1, max_size=max_size).map(np.array)


def sample_joints(rng: np.random.Generator, n: int, arm: Arm = THESIS_ARM,
                  beyond: float = BEYOND) -> np.ndarray:
    """``n`` joint vectors (n, 6) drawn uniformly within the limits widened by ``beyond`` [rad]."""
    return rng.uniform(arm.q_min - beyond, arm.q_max + beyond, size=(n, 6))
