"""The thesis IIK (Sec 3.3, errata corrected) and its relation to the complete solver."""

import numpy as np
from hypothesis import example, given, settings
from hypothesis import strategies as st

import iik
from iik import THESIS_ARM
from iik.ik.angles import wrap_angle as _wrap
from iik.ik.thesis import ACCEPT_TOL, thesis_candidates

ARM = iik.THESIS_ARM


@st.composite
def joints(draw):
    lims = zip(ARM.q_min, ARM.q_max, strict=True)
    return np.array([draw(st.floats(float(lo), float(hi))) for lo, hi in lims])


@settings(max_examples=25)
@given(joints())
@example(np.array([0.0, 0.0, 1.0, 0.0, 0.0, 0.0]))  # a collinear continuum (CI's failing case)
def test_complete_contains_thesis(q):
    """Every thesis solution is one of the complete solver's (to the thesis's 1e-6 deg scale)."""
    T = iik.fk(q, THESIS_ARM)
    rt = iik.solve(T, THESIS_ARM, method="thesis", within_limits=False)
    rc = iik.solve(T, THESIS_ARM, within_limits=False)
    for row in rt.q:
        # thesis rows are accurate to its 1e-6 deg bisection tolerance, hence the looser bound; a
        # row on a continuum of the complete answer is compared with that continuum's member at
        # the row's free joint (theta4 = theta5 = 0: the two methods pick different members)
        members = [c.member(float(row[c.free_joint - 1])) for cs in rc.continua for c in cs]
        cands = np.array([*rc.q, *members]).reshape(-1, 6)
        assert len(cands) and np.min(np.max(np.abs(_wrap(cands - row)), axis=1)) <= 1e-5, (row, rc.q)
    assert np.all(rt.position_residual <= ACCEPT_TOL)


def test_thesis_finds_typical_pose():
    q = np.array([0.3, -0.5, 0.7, 1.0, -0.4, 2.0])
    rt = iik.solve(iik.fk(q, THESIS_ARM), THESIS_ARM, method="thesis")
    assert np.min(np.max(np.abs(_wrap(rt.q - q)), axis=1)) <= 1e-6


def test_only_two_of_four_configurations_per_root_satisfy_fk():
    """Sec 3.3.3 claims four configurations per theta1 root; only two reach the pose."""
    rng = np.random.default_rng(2)
    q = rng.uniform(ARM.q_min, ARM.q_max, size=(200, 6))
    d = thesis_candidates(iik.fk(q, THESIS_ARM), ARM)
    per_root = np.bincount(d.root, weights=d.ok)
    real = per_root[per_root > 0]
    assert np.all(real <= 2)
    assert np.mean(real == 2) > 0.9


def test_thesis_can_miss_roots_the_complete_solver_finds():
    """A coarse grid misses close root pairs; the complete solver does not."""
    rng = np.random.default_rng(8)
    q = rng.uniform(ARM.q_min, ARM.q_max, size=(300, 6))
    T = iik.fk(q, THESIS_ARM)
    thesis = iik.solve_many(T, THESIS_ARM, method="thesis", within_limits=False)
    complete = iik.solve_many(T, THESIS_ARM, within_limits=False)
    nt = np.array([r.count for r in thesis])
    nc = np.array([r.count for r in complete])
    assert np.all(nt <= nc)
