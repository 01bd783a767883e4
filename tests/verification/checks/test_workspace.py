"""verification.checks.workspace and singularities (quick mode) and their helpers."""

from __future__ import annotations

from functools import partial

import numpy as np
import pytest

import iik
from iik import THESIS_ARM
from verification.checks import singularities as S
from verification.checks import workspace as W
from verification.oracles.reachability import ReachabilityOracle
from verification.registry import Context, Verdict

D = np.pi / 180


@pytest.fixture(scope="module")
def ctx(tmp_path_factory):
    return Context(out_dir=tmp_path_factory.mktemp("report"), quick=True)


def test_oracle_agrees_with_fk():
    o = ReachabilityOracle(n_samples=20000, rng=np.random.default_rng(0))
    q = np.random.default_rng(1).uniform(iik.THESIS_ARM.q_min, iik.THESIS_ARM.q_max, size=(50, 6))
    P = iik.fk(q, THESIS_ARM)[:, :3, 3]
    assert o.classify(P).reachable.all()
    far = P * 0 + [2.0, 0.0, 0.3]
    assert not o.classify(far).reachable.any()


def test_printed_eq40_rejects_a_reachable_point():
    """Printed Eq 40 (l2 - l3 c2) calls a reachable point behind the arm 'outside'."""
    q = np.array([160 * D, 0.0, 90 * D, -0.3, 0.0, 0.0])  # joint 1 at its limit, wrist bent sideways
    p = iik.fk(q, THESIS_ARM)[:3, 3]
    assert abs(np.degrees(np.arctan2(p[1], p[0]))) >= 160
    assert not W.eq36_41_printed(p)[0]
    assert iik.in_workspace(p, THESIS_ARM)


def test_cartesian_test_verdicts_follow_the_form(ctx):
    assert W.eq36_41(ctx, W.eq36_41_printed).verdict is Verdict.ERRATUM
    assert W.eq36_41(ctx, partial(iik.in_workspace, arm=THESIS_ARM)).verdict is Verdict.HOLDS
    assert W.eq38_region1(ctx, W.eq36_41_test).verdict is Verdict.HOLDS
    regions23 = partial(W.eq36_41_test, eq39="corrected", eq40_sign=1.0)
    assert W.eq41_regions23(ctx, regions23).verdict is Verdict.HOLDS
    assert W.eq41_regions23(ctx, partial(regions23, margin=-0.005)).verdict is Verdict.ERRATUM


def test_eq36_has_its_own_row(ctx):
    row = W.eq36_azimuth(ctx, W.eq36_printed)
    assert row.verdict is Verdict.HOLDS and "base axis" in row.domain
    assert W.eq36_azimuth(ctx, lambda P: np.arctan(P[:, 1] / P[:, 0])).verdict is Verdict.ERRATUM


def test_eq39_eq40_errata_against_exact_geometry(ctx):
    r39 = W.CHECKS["eq39"](ctx, W.eq39_printed)
    assert r39.verdict is Verdict.ERRATUM and r39.errata[0].equation == "Eq 39"
    assert W.CHECKS["eq39"](ctx, W.eq39_corrected).verdict is Verdict.HOLDS
    r40 = W.CHECKS["eq40"](ctx, W.eq40_printed)
    assert r40.verdict is Verdict.ERRATUM and r40.measures[0].value > 0.1  # metres off
    assert W.CHECKS["eq40"](ctx, W.eq40_corrected).verdict is Verdict.HOLDS


def test_boundary_claims(ctx):
    assert W.three_surface_boundary(ctx, W.BOUNDARY_SURFACES_PRINTED).verdict is Verdict.DOES_NOT_HOLD
    assert W.three_surface_boundary(ctx, W.BOUNDARY_COVERING).verdict is Verdict.HOLDS
    assert W.no_interior_boundary(ctx, 0.02).verdict is Verdict.HOLDS
    assert W.no_interior_boundary(ctx, -0.05).verdict is Verdict.DOES_NOT_HOLD
    # the relocation rule is our reading of App. G: consistent with our reconstruction, not evidence
    assert W.app_g_relocation(ctx, W.radial_projection).verdict is Verdict.RECONSTRUCTION


def test_app_g_points_behind_the_arm_lie_in_the_stated_band():
    """The first half of App. G's sample lies at azimuth 160-200 deg (the row's domain says so), 0.5-1.3 m
    from (0, 0, l1); the other half is spread over every azimuth."""
    P = W.app_g_points(np.random.default_rng(0), 4000)
    az = np.degrees(np.arctan2(P[:, 1], P[:, 0])) % 360
    assert np.all((az[:2000] >= 160) & (az[:2000] <= 200))
    assert np.mean((az[2000:] < 160) | (az[2000:] > 200)) > 0.8
    r = np.linalg.norm(P - [0.0, 0.0, THESIS_ARM.l1], axis=1)
    assert np.all((r >= 0.5) & (r <= 1.3))


def test_singularity_tables_are_grouped(ctx):
    vi = S.table_vi(ctx, S.TABLE_VI)
    assert vi.verdict is Verdict.HOLDS and len(vi.details) == 37
    vii = S.table_vii(ctx, S.TABLE_VII)
    assert vii.verdict is Verdict.IDENTITY and len(vii.details) == 10  # 3x2 matrices have rank <= 2
    assert S.table_vi(ctx, S._moved(S.TABLE_VI)).verdict is Verdict.DOES_NOT_HOLD


def test_missing_singularities(ctx):
    row = S.missing_singularities(ctx, S.member_of_tables)
    assert row.verdict is Verdict.DOES_NOT_HOLD and row.measures[0].value > 0
    assert S.missing_singularities(ctx, S.member_by_rank).verdict is Verdict.HOLDS
