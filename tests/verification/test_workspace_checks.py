"""Tests of the workspace / singularity / App. E / dexterity checks (quick mode) and their helpers."""

from __future__ import annotations

import numpy as np
import pytest

import iik
from verification.checks import appendix_e, dexterity, singularities, workspace
from verification.oracles.abdel_malek import normal_acceleration, position_and_jacobian
from verification.oracles.reachability import ReachabilityOracle
from verification.registry import Context, Row, Verdict

D = np.pi / 180


@pytest.fixture(scope="module")
def ctx(tmp_path_factory):
    return Context(out_dir=tmp_path_factory.mktemp("report"), quick=True)


def test_oracle_agrees_with_fk():
    o = ReachabilityOracle(n_samples=20000, rng=np.random.default_rng(0))
    q = np.random.default_rng(1).uniform(iik.THESIS_ARM.q_min, iik.THESIS_ARM.q_max, size=(50, 6))
    P = iik.fk(q)[:, :3, 3]
    assert o.classify(P).reachable.all()
    far = P * 0 + [2.0, 0.0, 0.3]
    assert not o.classify(far).reachable.any()


def test_printed_eq40_rejects_a_reachable_point():
    """Printed Eq 40 (l2 - l3 c2) calls a reachable point behind the arm 'outside'."""
    q = np.array([160 * D, 0.0, 90 * D, -0.3, 0.0, 0.0])  # joint 1 at its limit, wrist bent sideways
    p = iik.fk(q)[:3, 3]
    assert abs(np.degrees(np.arctan2(p[1], p[0]))) >= 160
    assert not workspace.eq36_41_printed(p)[0]
    assert iik.in_workspace(p)


def test_abdel_malek_a1_reproduces_thesis():
    r = normal_acceleration([-7 * np.pi / 9, 0, 0, 0, 0], (1, 2), normal_hint=[0.766, 0.6428, 0])
    mm = r.in_mm()
    assert r.N0 == pytest.approx([0.7660, 0.6428, 0.0], abs=1e-4)
    # off-diagonal entries and Q* were not used to recover the link lengths
    assert mm["H"][1, 3] == pytest.approx(-1703, abs=0.5)
    assert mm["H"][1, 4] == pytest.approx(-1025.7, abs=0.1)
    assert mm["Q"][3, 3] == pytest.approx(825.96, abs=0.05)
    assert mm["Q"][3, 4] == pytest.approx(497.45, abs=0.05)
    assert mm["Q"][4, 4] == pytest.approx(754.25, abs=0.05)
    assert np.sort(mm["eig"])[-2:] == pytest.approx([291.4, 1288.9], abs=0.1)
    assert np.allclose(r.Q, r.Q.T, atol=1e-9)
    assert r.verdict == "+N0"


def test_abdel_malek_a2_sigma():
    q0 = [-160 * D, np.pi / 12, 90 * D, -np.pi / 3, 0]
    r = normal_acceleration(q0, (2, 4), normal_hint=[0.75, 0.6486, 0.1294])
    assert r.at_limit == ((1, "lower"),)
    assert abs(r.in_mm()["sigma"][1]) == pytest.approx(389.2341, abs=1e-3)
    _, Gq = position_and_jacobian(np.array(q0))
    assert np.abs(r.N0 @ Gq[:, [1, 3]]).max() < 1e-12  # normal to the surface f(2)


def test_checks_quick(ctx):
    rows = []
    for mod in (workspace, singularities, appendix_e, dexterity):
        for name in dir(mod):
            f = getattr(mod, name)
            if callable(f) and getattr(f, "__module__", "") == mod.__name__ and name in CHECKS:
                out = f(ctx)
                rows += [out] if isinstance(out, Row) else list(out)
    assert all(isinstance(r, Row) for r in rows)
    by_ref = {r.reference: r for r in rows}
    assert by_ref["Sec 3.4.4, Eq 36-41"].verdict is Verdict.ERRATUM
    assert any(e.equation == "Eq 40" for e in by_ref["Sec 3.4.4, Eq 36-41"].errata)
    a2 = by_ref["App. E, point A2 (Eq 59-67)"]
    assert a2.verdict is Verdict.DOES_NOT_HOLD
    assert by_ref["Sec 3.5.1, Eq 42"].verdict is Verdict.HOLDS
    assert by_ref["Eq 42 vs Eq 43-47"].verdict is Verdict.ERRATUM
    assert by_ref["Sec 3.4.3"].verdict is Verdict.HOLDS  # no interior boundary
    assert by_ref["App. G (Figs 61-62), Sec 3.6.1"].verdict is Verdict.HOLDS
    for r in rows:
        for f in r.figures:
            assert (ctx.out_dir / f).exists()


CHECKS = {"eq36_41", "three_surface_boundary", "no_interior_boundary", "app_g_relocation", "table_vi",
          "table_vii",
          "missing_singularities", "appendix_e", "beta_convention", "dexterity_soundness", "gamma_free"}
