"""verification.testing.recovery: what the recovery table counts as a wrong row, and the oracle
solutions missed on certified poses (silent losses) counted apart."""

import dataclasses

import numpy as np
import pytest

import iik
from verification.testing.families import family
from verification.testing.recovery import RecoveryOptions, pose_stats, recovery

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


def _dropping_first_row(certified: bool):
    """iik.solve_many with each answer's first row left out, its certificate held or not."""
    real = iik.solve_many

    def solve_many(Ts, arm, **kw):
        out = []
        for r in real(Ts, arm, **kw):
            cert = dataclasses.replace(r.certificate, certified=certified, reason="" if certified else "test")
            out.append(dataclasses.replace(r.rows(np.arange(1, r.count)), certificate=cert))
        return out

    return solve_many


@pytest.mark.parametrize("certified", [True, False])
def test_oracle_solutions_missed_on_certified_poses_are_counted_apart(monkeypatch, certified):
    monkeypatch.setattr(iik, "solve_many", _dropping_first_row(certified))
    opts = RecoveryOptions(n=2, oracle_every=1, starts=64, reference_every=0)
    row = recovery(family("uniform"), ARM, opts)
    assert row.oracle_poses == 2 and row.missed_vs_oracle >= 1
    assert row.missed_vs_oracle_certified == (row.missed_vs_oracle if certified else 0)
    # q* was dropped from some answer: a silent loss only where the certificate held, named to replay it
    assert all(0 <= i < 2 and len(q) == 6 for i, q in row.examples)
    assert (len(row.examples) == row.silent) and (row.silent > 0) == (certified and row.found < 2)
