"""verification.testing.recovery.pose_stats: what the recovery table counts as a wrong row."""

import dataclasses

import numpy as np

import iik
from verification.testing.recovery import pose_stats

ARM = iik.arms.get("thesis")
Q = np.array([0.3, -0.4, 0.5, 0.6, -0.7, 0.8])
T = iik.fk(Q, ARM)


def _with_row(q, approximate: bool):
    """The kernel's answer for T with one more row q, flagged approximate or not."""
    r = iik.solve(T, ARM, within_limits=False)
    return dataclasses.replace(
        r, q=np.vstack([r.q, q]), position_residual=np.append(r.position_residual, 0.0),
        rotation_residual=np.append(r.rotation_residual, 0.0), within_limits=np.append(r.within_limits, True),
        approximate=np.append(r.approximate, approximate), free_joints=(), continua=())


def test_an_exact_answer_has_no_wrong_row():
    assert pose_stats(ARM, Q, T, iik.solve(T, ARM, within_limits=False)).wrong == 0


def test_a_row_off_the_pose_is_wrong_unless_flagged_approximate_within_its_tolerance():
    near = Q + np.array([1e-7, 0, 0, 0, 0, 0])  # ~1e-7 m off: beyond the tolerance, within approximate_tol
    far = Q + np.array([1e-2, 0, 0, 0, 0, 0])  # ~1e-2 m off: beyond approximate_tol too
    assert pose_stats(ARM, Q, T, _with_row(near, approximate=False)).wrong == 1
    assert pose_stats(ARM, Q, T, _with_row(near, approximate=True)).wrong == 0
    assert pose_stats(ARM, Q, T, _with_row(far, approximate=True)).wrong == 1
