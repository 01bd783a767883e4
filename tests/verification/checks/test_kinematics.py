"""verification.checks.kinematics: verdicts of the kinematics checks, and that they follow the form."""

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


def _by_id(rows):
    return {r.id: r for r in rows}


def test_eq4_holds_with_figures(ctx):
    row = K.eq4_vs_pinocchio(ctx, K.eq4_printed)
    assert row.verdict is Verdict.HOLDS
    assert row.measures[0].value <= 1e-12
    for rel in row.figures:
        assert (ctx.out_dir / rel).stat().st_size > 1000


def test_eq4_check_detects_a_nanometre(ctx):
    def off_by_a_nanometre(q, arm=K.THESIS_ARM):
        T = K.eq4_printed(q, arm)
        T[..., 2, 3] += 1e-9
        return T

    row = K.eq4_vs_pinocchio(ctx, off_by_a_nanometre)
    assert row.verdict is Verdict.ERRATUM and row.errata[0].counterexample.startswith("q = [")


def test_table_ii_product_follows_the_table(ctx):
    assert K.table_ii_vs_eq4(ctx, K.table_ii_printed()).verdict is Verdict.HOLDS
    assert K.table_ii_vs_eq4(ctx, K.TABLE_NUDGED).verdict is Verdict.DOES_NOT_HOLD


def test_table_checks_hold_by_construction(ctx):
    """Transcription and byte round trips are shown, not counted as evidence: they say why."""
    rows = K.table_ii_encoding(ctx) + [K.urdf_is_generated(ctx)]
    assert all(r.verdict is Verdict.IDENTITY and r.basis for r in rows)


def test_appendix_b_verdicts(ctx):
    rows = _by_id(K.appendix_b(ctx, K.appb_modified_printed))
    for name in ("t01", "t12", "t34", "t45"):
        assert rows[f"appb.{name}"].verdict is Verdict.HOLDS
    for name in ("t23", "t56"):
        r = rows[f"appb.{name}"]
        assert r.verdict is Verdict.ERRATUM and r.errata[0].counterexample.startswith("q = [")
        # the second reading searched the DH row's readings: no reading of the row alone reproduces the
        # printed matrix; one printed sign does (2_3T), or d6 = +l5 (Eq 9's) with that sign (5_6T):
        # still errata
        sr = r.second_reading
        assert sr.searched >= 5 and not any(t.sides == {"input"} and t.reproduces for t in sr.trials)
        assert sr.slip.name == {"t23": "TYPO", "t56": "INPUT_AND_TYPO"}[name]
        assert "P(3,2) printed with its sign flipped" in sr.explanation.text
    assert rows["appb.product"].verdict is Verdict.ERRATUM
    first = _by_id(K.appendix_b_first_set(ctx, K.appb_first_printed))
    assert first["appb.first_legible"].verdict is Verdict.HOLDS
    assert first["appb.first_set"].verdict is Verdict.NOT_CHECKABLE


def test_appendix_b_printed_5_6T_has_plus_l5():
    """The transcription itself: printed 5_6T carries +l5 where Table II's d6 = -l5 gives -l5."""
    T = K.appb_modified_printed(np.zeros(6))[5]
    assert T[1, 3] == pytest.approx(+K.THESIS_ARM.l5)


def test_appendix_c_is_one_grouped_row_with_15_entries(ctx):
    rows = _by_id(K.appendix_c(ctx, K.appc_printed))
    group = rows["appc"]
    assert group.verdict is Verdict.HOLDS and len(group.details) == 15 and group.figures
    assert rows["eq35"].verdict is Verdict.IDENTITY  # the definition of the Jacobian: re-measures App. C


def test_appendix_c_check_detects_a_sign_error(ctx):
    def wrong(q, arm=K.THESIS_ARM):
        d = K.appc_printed(q, arm)
        d["df2/dth3"] = -d["df2/dth3"]
        return d

    group = _by_id(K.appendix_c(ctx, wrong))["appc"]
    entries = {d.reference.split()[-1]: d for d in group.details}
    assert group.verdict is Verdict.ERRATUM
    assert (
        entries["df2/dth3"].verdict is Verdict.ERRATUM
        and "printed" in entries["df2/dth3"].errata[0].counterexample
    )
    assert entries["df2/dth4"].verdict is Verdict.HOLDS


def test_eq42_printed_differs_from_zyz_only_in_r21():
    rng = np.random.default_rng(0)
    a, b, g = rng.uniform(-3, 3, (3, 200))
    P = K.eq42_printed(a, b, g)
    Z = Rotation.from_euler("ZYZ", np.stack([a, b, g], -1)).as_matrix()
    d = np.abs(P - Z).max(axis=0)
    assert d[1, 0] > 0.5
    d[1, 0] = 0
    assert d.max() < 1e-14


def test_closed_form_euler_matrices_match_scipy():
    rng = np.random.default_rng(1)
    a, b, g = rng.uniform(-3, 3, (3, 100))
    for f, seq in ((K.eq42_zyz, "ZYZ"), (K.eq42_zxz, "ZXZ")):
        assert (
            np.abs(f(a, b, g) - Rotation.from_euler(seq, np.stack([a, b, g], -1)).as_matrix()).max() < 1e-14
        )


def test_eq42_verdicts_follow_the_matrix(ctx):
    """A correct Z-Y-Z (or Z-X-Z) matrix in place of the printed one holds (issue 11: it did not before)."""
    assert K.eq42_matrix(ctx, K.eq42_printed).verdict is Verdict.ERRATUM
    assert K.eq42_matrix(ctx, K.eq42_zyz).verdict is Verdict.HOLDS
    assert K.eq42_matrix(ctx, K.eq42_zxz).verdict is Verdict.HOLDS
    row = K.eq42_matrix(ctx, K.eq42_printed)
    assert row.errata[0].equation == "Eq 42 r21"
    assert K.eq42_convention(ctx, K.eq42_zxz).verdict is Verdict.HOLDS
    # the printed matrix is right for Z-Y-Z (r21 aside): the slip is in the stated convention
    conv = K.eq42_convention(ctx, K.eq42_printed)
    assert conv.verdict is Verdict.INPUT_SLIP
    assert "ZYZ intrinsic" in conv.second_reading.explanation.text
    # r21 is reproduced by no Euler convention, sign or transposition: it stays an erratum
    assert row.second_reading.slip.name == "RESULT" and row.second_reading.searched >= 27


def test_ur5_check_holds_and_sees_a_micrometre(ctx):
    row = K.ur5_generator_check(ctx, K.urdf_from_dh)
    assert row.verdict is Verdict.HOLDS and row.measures[0].value <= 1e-9
    assert K.ur5_generator_check(ctx, K.SHIFTED_GENERATOR).verdict is Verdict.DOES_NOT_HOLD


def test_table_i_self_collision_claim_refuted_geometry_independently(ctx):
    row = K.table_i_self_collision(ctx, K.TABLE_I_LIMITS)
    assert row.verdict is Verdict.DOES_NOT_HOLD
    assert row.measures[0].value < 1e-3  # the tool point reaches the upper-arm axis [m]
    q = np.array([0.0, 0.0, 0.0, 1.9, 1.9, 0.0])  # within Table I: tool point on the upper-arm axis
    assert K.THESIS_ARM.within_limits(q)
    assert K._tool_to_upper_arm(q[None])[0] < 0.005
    assert K.table_i_self_collision(ctx, K.SAFE_LIMITS).verdict is Verdict.HOLDS


@given(joint_vectors())
def test_printed_eq4_and_appendix_c_match_pinocchio_at_hypothesis_q(q):
    T_pin = tool_poses(q[None])[0]
    assert np.abs(K.eq4_printed(q)[0] - T_pin).max() <= 1e-12
    J_pin = tool_jacobians(q[None])[0]
    for key, val in K.appc_printed(q).items():
        assert abs(val[0] - J_pin[int(key[2]) - 1, int(key[-1]) - 1]) <= 1e-12, key
