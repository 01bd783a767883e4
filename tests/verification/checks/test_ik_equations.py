"""verification.checks.ik_equations and ik: Eq 5-33 one by one, the method's claims."""

from __future__ import annotations

import numpy as np
import pytest

from verification.checks import ik as C
from verification.checks import ik_equations as Q
from verification.registry import Context, Verdict


@pytest.fixture(scope="module")
def ctx(tmp_path_factory):
    return Context(out_dir=tmp_path_factory.mktemp("report"), quick=True)


def test_sample_points_are_the_joints(ctx):
    s = Q.sample(ctx)
    assert np.allclose(np.linalg.norm(s.C - s.B, axis=1), Q.L3)
    assert np.allclose(np.linalg.norm(s.D - s.C, axis=1), Q.L4)
    assert np.allclose(np.linalg.norm(s.E - s.D, axis=1), Q.L5)


def test_errata_found_per_equation(ctx):
    rows = {r.id: r for r in Q.wrist_point(ctx, Q.eq9abc_printed)}
    # Eq 9a-c are right for d6 = +l5: the second reading puts the slip in the sign of Table II's d6
    for k in ("eq9a", "eq9b", "eq9c"):
        assert rows[k].verdict is Verdict.INPUT_SLIP and rows[k].errata, k
        assert "d6 = +l5" in rows[k].second_reading.explanation.text
    assert Q.wrist_point(ctx, Q._wrist_length)[0].verdict is Verdict.ERRATUM  # no reading explains l4 for l5
    assert Q.CHECKS["eq14"](ctx, Q.eq14_printed).verdict is Verdict.ERRATUM
    assert Q.CHECKS["eq14"](ctx, Q.eq14_corrected).verdict is Verdict.HOLDS
    t56 = {r.id: r for r in Q.eq30_matrices(ctx, lambda q: (Q.eq30_row3_printed(q), Q.eq30_t56_printed(q)))}
    assert t56["eq30.row3"].verdict is Verdict.HOLDS and t56["eq30.t56"].verdict is Verdict.ERRATUM
    assert t56["eq30.t56"].second_reading.slip.name == "TYPO"  # the -l5 printed one row down


def test_eq27_holds_near_c3_zero_and_fails_at_it(ctx):
    """Issue 19: sampled down to |c3| = 1e-10 and graded on |error| |c3| (the conditioning of a division by
    c3), Eq 27-28 hold; the raw error there exceeds 1e-9 rad, and only c3 = 0 itself fails."""
    row = Q.eq27_s45(ctx, Q.eq27_printed)
    assert row.verdict is Verdict.HOLDS and "|c3|" in row.measures[0].name
    assert "1e-10" in row.domain or "-10" in row.domain
    near = Q._near_c3_zero(ctx)
    assert np.abs(np.cos(near.q[:, 2])).min() < 1e-7
    exact = Q.eq27_c3_zero(ctx, Q.eq27_printed)
    assert exact.verdict is Verdict.DOES_NOT_HOLD and exact.measures[0].value == 0.0
    assert Q.eq27_c3_zero(ctx, Q.eq27_companion).verdict is Verdict.HOLDS


@pytest.mark.parametrize("deepest", [-6, -7, -10, -13])
def test_eq27s_verdict_does_not_depend_on_how_near_c3_zero_it_samples(monkeypatch, tmp_path, deepest):
    """Issue 19: the old raw tolerance flipped between a sample down to |c3| = 1e-6 and one down to 1e-7;
    graded on |error| |c3| the printed Eq 27 holds at every depth and its sign slip fails at every depth."""
    monkeypatch.setattr(Q, "_C3_EXP", (deepest, -3))
    fresh = Context(out_dir=tmp_path, quick=True)
    row = Q.eq27_s45(fresh, Q.eq27_printed)
    assert row.verdict is Verdict.HOLDS, row.numbers
    assert np.abs(np.cos(Q._near_c3_zero(fresh).q[:, 2])).min() < 10.0 ** (deepest + 1)
    assert not Q.eq27_s45(fresh, Q._eq27_plus).verdict.passes


def test_eq12_eq13_graded_on_the_extrema_of_E(ctx):
    """The minimum of ||E|| (not of |E|) is near the wrist azimuth, not the end-effector's (Eq 12)."""
    r12 = Q.eq12_minimum(ctx, Q.eq12_printed)
    assert r12.verdict is Verdict.ERRATUM and "atan2(yD, xD)" in r12.errata[0].corrected
    assert Q.eq13_maximum(ctx, Q.eq13_corrected).verdict is Verdict.HOLDS
    # Eq 13 is right for the wrist point D in place of the tool point p; Eq 12 is not (the wrist's azimuth
    # misses the global minimum on a few per cent of poses)
    assert Q.eq13_maximum(ctx, Q.eq13_printed).verdict is Verdict.INPUT_SLIP
    assert r12.second_reading.slip.name == "RESULT"


def test_solution_counts_with_and_without_limits(ctx):
    free = C.solution_counts(ctx, C.CountClaim(8, 2))
    limited = C.solution_counts_table_i(ctx, C.CountClaim(8, 2))
    assert free.verdict is Verdict.DOES_NOT_HOLD and limited.verdict is Verdict.DOES_NOT_HOLD
    assert limited.measures[1].value < 2  # "at least two" fails with Table I
    assert C.solution_counts_table_i(ctx, C.CountClaim(16, 1)).verdict is Verdict.HOLDS
