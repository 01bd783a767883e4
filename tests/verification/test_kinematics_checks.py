"""verification.checks.kinematics: verdicts of the kinematics checks, and that they can fail."""

import numpy as np
import pytest
from hypothesis import given
from scipy.spatial.transform import Rotation

from verification.checks import kinematics as K
from verification.oracles.pinocchio_model import tool_jacobians, tool_poses
from verification.registry import Context, Verdict
from verification.testing.strategies import joint_vectors


@pytest.fixture
def ctx(tmp_path):
    return Context(out_dir=tmp_path, quick=True)


def _by_ref(rows):
    return {r.reference: r for r in rows}


def test_eq4_holds_with_figures(ctx):
    row = K.eq4_vs_pinocchio(ctx)
    assert row.verdict is Verdict.HOLDS
    assert "max |dp|" in row.numbers
    for rel in row.figures:
        assert (ctx.out_dir / rel).stat().st_size > 1000


def test_eq4_check_detects_a_wrong_formula(ctx, monkeypatch):
    real = K.eq4_printed

    def off_by_a_nanometre(q, arm=K.THESIS_ARM):
        T = real(q, arm)
        T[..., 2, 3] += 1e-9
        return T

    monkeypatch.setattr(K, "eq4_printed", off_by_a_nanometre)
    assert K.eq4_vs_pinocchio(ctx).verdict is Verdict.DOES_NOT_HOLD
    assert K.table_ii_vs_eq4(ctx).verdict is Verdict.DOES_NOT_HOLD


def test_table_checks_hold(ctx):
    assert all(r.verdict is Verdict.HOLDS for r in K.table_ii_encoding(ctx))
    assert K.table_ii_vs_eq4(ctx).verdict is Verdict.HOLDS
    assert K.urdf_is_generated(ctx).verdict is Verdict.HOLDS


def test_appendix_b_verdicts(ctx):
    rows = _by_ref(K.appendix_b(ctx))
    for name in ("0_1T", "1_2T", "3_4T", "4_5T"):
        assert rows[f"App. B, {name}"].verdict is Verdict.HOLDS
    for name in ("2_3T", "5_6T"):
        r = rows[f"App. B, {name}"]
        assert r.verdict is Verdict.ERRATUM and r.errata[0].counterexample.startswith("q = [")
    assert rows["App. B, Eq 4"].verdict is Verdict.ERRATUM
    assert rows["App. B, first set"].verdict is Verdict.NOT_CHECKABLE


def test_appendix_b_printed_5_6T_has_plus_l5():
    """The transcription itself: printed 5_6T carries +l5 where Table II's d6 = -l5 gives -l5."""
    T = K.appb_modified_printed(np.zeros(6))[5]
    assert T[1, 3] == pytest.approx(+K.THESIS_ARM.l5)


def test_appendix_c_all_entries_hold(ctx):
    rows = K.appendix_c(ctx)
    entries = [r for r in rows if r.reference.startswith("App. C, Eq 56 ")]
    assert len(entries) == 15
    assert all(r.verdict is Verdict.HOLDS for r in rows)
    assert rows[0].figures


def test_appendix_c_check_detects_a_sign_error(ctx, monkeypatch):
    real = K.appc_printed

    def wrong(q, arm=K.THESIS_ARM):
        d = real(q, arm)
        d["df2/dth3"] = -d["df2/dth3"]
        return d

    monkeypatch.setattr(K, "appc_printed", wrong)
    rows = _by_ref(K.appendix_c(ctx))
    bad = rows["App. C, Eq 56 df2/dth3"]
    assert bad.verdict is Verdict.ERRATUM and "printed" in bad.errata[0].counterexample
    assert rows["App. C, Eq 56 df2/dth4"].verdict is Verdict.HOLDS


def test_eq42_printed_differs_from_zyz_only_in_r21():
    rng = np.random.default_rng(0)
    a, b, g = rng.uniform(-3, 3, (3, 200))
    P = K.eq42_printed(a, b, g)
    Z = Rotation.from_euler("ZYZ", np.stack([a, b, g], -1)).as_matrix()
    d = np.abs(P - Z).max(axis=0)
    assert d[1, 0] > 0.5
    d[1, 0] = 0
    assert d.max() < 1e-14


def test_eq42_row_is_erratum_with_counterexample(ctx):
    row = K.eq42_vs_scipy(ctx)
    assert row.verdict is Verdict.ERRATUM
    assert {e.equation for e in row.errata} == {"Eq 42 r21", "Eq 42 / Sec 3.5.1 convention"}


def test_ur5_check_holds(ctx):
    row = K.ur5_generator_check(ctx)
    assert row.verdict is Verdict.HOLDS
    assert float(row.numbers.split("max |dp| = ")[1].split(" m")[0]) <= 1e-9


def test_table_i_self_collision_claim_refuted_geometry_independently(ctx):
    row = K.table_i_self_collision(ctx)
    assert row.verdict is Verdict.DOES_NOT_HOLD
    d_mm = float(row.numbers.split("min distance = ")[1].split(" mm")[0])
    assert d_mm < 1.0
    q = np.array([0.0, 0.0, 0.0, 1.9, 1.9, 0.0])  # within Table I: tool point on the upper-arm axis
    assert K.THESIS_ARM.within_limits(q)
    assert K._tool_to_upper_arm(q[None])[0] < 0.005


@given(joint_vectors())
def test_printed_eq4_and_appendix_c_match_pinocchio_at_hypothesis_q(q):
    T_pin = tool_poses(q[None])[0]
    assert np.abs(K.eq4_printed(q)[0] - T_pin).max() <= 1e-12
    J_pin = tool_jacobians(q[None])[0]
    for key, val in K.appc_printed(q).items():
        assert abs(val[0] - J_pin[int(key[2]) - 1, int(key[-1]) - 1]) <= 1e-12, key
