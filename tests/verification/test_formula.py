"""verification.formula: printed formulas declared as data, registered in bulk at their index places."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from verification import registry
from verification.errors import RegistrationError
from verification.formula import RIGHT, Formula, Points, Printed, per_run
from verification.registry import Context, Erratum, Measure, Row, Section, Slip, SlipKind, Verdict
from verification.second_reading import search
from verification.self_test import self_test_check
from verification.thesis_index import rank_of, title_of


def _sample(ctx) -> Points:
    x = np.linspace(-1.0, 1.0, 101)
    return Points(x, "101 x uniform in [-1, 1]", "m", "x")


def _sine(x):
    return np.sin(x)


#: Eq 16 (a real index key) stands in for a formula printed as sin(x), graded against np.sin.
SINE = Formula("Eq 16", _sine, lambda s, f: f(s.values) - np.sin(s.values), 1e-12, "-", (
    Slip(SlipKind.FUNCTION, "cos for sin", np.cos),
    Slip(SlipKind.SIGN, "-sin", lambda x: -np.sin(x)),
), method="the form vs numpy's sine at {n} points")


@pytest.fixture
def ctx(tmp_path: Path) -> Context:
    return Context(out_dir=tmp_path, quick=True)


def test_forms_follow_from_the_declaration():
    f = SINE.forms
    assert f.printed is _sine and f.good is _sine and f.good_is == RIGHT  # printed right: it is the good one
    assert [s.what for s in f.slips] == ["cos for sin", "-sin"]
    assert f.tolerance.kind is SlipKind.EPSILON and f.tolerance.form(0.0) == pytest.approx(1e-9)
    other = Formula("Eq 16", _sine, SINE.error, 1e-12, "-", SINE.slips, good=np.sin, good_is="np", eps=None)
    assert other.forms.good is np.sin and other.forms.tolerance is None
    assert SINE.rid == "eq16" and Formula("Eq 9a", None, None, 1, "", ()).rid == "eq9a"


def test_a_formula_row_is_graded_on_its_error(ctx):
    check = SINE.check(_sample)
    ok = check(ctx, _sine)
    assert ok.verdict is Verdict.HOLDS and ok.id == "eq16" and ok.reference == "Eq 16"
    assert ok.claim == title_of("Eq 16") + "." and ok.method == "the form vs numpy's sine at 101 points"
    assert ok.numbers.startswith(str(ok.measures[0])) and ok.domain == "101 x uniform in [-1, 1]"
    bad = check(ctx, np.cos)
    assert bad.verdict is Verdict.ERRATUM
    assert bad.measures[0].value == pytest.approx(np.max(np.abs(np.cos(_sample(ctx).values) - np.sin(
        _sample(ctx).values))))
    assert bad.errata[0].counterexample.startswith("x = -0.7800 m")  # the worst sample: near -pi/4
    assert check.__name__ == "eq16"


def test_scaled_identity_and_refutation(ctx):
    """``scale``: graded on |error| |x| (a division by x); ``basis``: a pass holds by construction;
    ``fail``: a claim fails as DOES_NOT_HOLD, naming the worst sample."""
    f = Formula("Eq 20", lambda x: 1.0 / x, lambda s, f: f(s.values) * s.values - 1.0, 1e-14, "-", SINE.slips,
                scale=("x", lambda s: s.values), basis="an identity", fail=Verdict.DOES_NOT_HOLD)
    s = Points(np.array([1e-9, 0.5, 1.0]), "three x", "-", "x")
    row = f.row(s, f.error(s, f.printed))
    assert row.verdict is Verdict.IDENTITY and row.measures[0].name.endswith("x |x|")
    wrong = f.row(s, np.array([0.0, 0.0, 1.0]))
    assert wrong.verdict is Verdict.DOES_NOT_HOLD and "x = 1.0000" in wrong.reason and not wrong.errata


def test_the_self_test_catches_each_slip(ctx):
    check = registry.Check("t.eq16", "S", 0.0, SINE.check(_sample), forms=SINE.forms, prefix="t")
    out = self_test_check(check, ctx)
    assert out.status == "flips" and all(s.caught for s in out.slips) and out.tolerance.caught


def test_sections_place_checks_at_their_index_items(monkeypatch):
    monkeypatch.setattr(registry, "_REGISTRY", {})
    s = Section("S", order=30.0)
    assert s.place(2.5) == 2.5
    assert 30.0 < s.place("Eq 5") < s.place("Eq 9") < s.place("Eq 9a") < s.place("Claim 3.2") < 31.0
    assert rank_of("Eq 9a-c") == rank_of("Eq 9a") and rank_of("Sec 5.2 (1)") > rank_of("Eq 69")
    with pytest.raises(RegistrationError, match="no item"):
        s.place("Eq 99")
    with pytest.raises(KeyError):
        title_of("Table IX")
    checks = s.formulas(_sample, SINE, Formula("Eq 6", _sine, SINE.error, 1e-12, "-", SINE.slips))
    assert list(checks) == ["eq16", "eq6"]
    reg = registry._REGISTRY
    first, second = reg[f"{__name__}.eq16"], reg[f"{__name__}.eq6"]
    assert second.order < first.order  # Eq 6 comes before Eq 16 in the index, whatever the declaration order
    assert first.where == f"{__name__}:eq16" and first.prefix == "test_formula" and first.forms is not None
    s.formulas(_sample, Formula("Eq 7", _sine, SINE.error, 1e-12, "-", SINE.slips, order=29.5))
    assert reg[f"{__name__}.eq7"].order == 29.5  # an explicit order wins over the index place


def test_rows_derive_numbers_and_reread_only_errata():
    m = (Measure("a", 1.0, 2.0, "m"), Measure("b", 3.0, 2.0))
    row = Row.graded("c", "Eq 4", "m", None, m, fail=Verdict.DOES_NOT_HOLD)
    assert row.numbers == "a = 1 m (<= 2 m); b = 3 (<= 2)" and row.verdict is Verdict.DOES_NOT_HOLD
    called = []
    assert row.reread_if_erratum(lambda: called.append(1)) is row and not called  # not an erratum: no search
    wrong = Row.graded("c", "Eq 4", "m", None, m, erratum=Erratum("Eq 4", "p", "c", "x"))
    reading = search({"x": 1.0}, [], lambda x: 0.0, 0.0, printed="p", stated_text="s", route="r", measure="m")
    assert wrong.reread_if_erratum(lambda: reading).verdict is Verdict.HOLDS  # right as stated: withdrawn


def test_per_run_computes_once_per_run_args_and_sample_size(tmp_path):
    calls = []

    @per_run
    def draw(ctx, k):
        calls.append(k)
        return ctx.rng("per-run").uniform(size=ctx.n(5, 2)) + k

    ctx = Context(out_dir=tmp_path)
    first = draw(ctx, 1)
    assert draw(ctx, 1) is first and calls == [1]  # cached: the same object, computed once
    assert draw(ctx, 2)[0] == first[0] + 1 and calls == [1, 2]  # other arguments: computed anew
    quick = Context(out_dir=tmp_path, quick=True, cache=ctx.cache)
    assert len(draw(quick, 1)) == 2 and calls == [1, 2, 1]  # the sample size is part of the key
    assert draw(Context(out_dir=tmp_path), 1) is not first  # a new run starts with an empty cache


def test_count_grades_the_samples_off_by_more_than_the_tolerance(ctx):
    """``count``: the measure is the number of samples with |error| > tol (limit 0), not the max."""
    f = Formula("Eq 16", _sine, SINE.error, 1e-12, "", SINE.slips, count=True, measure="points off")
    s = _sample(ctx)
    assert f.row(s, np.zeros(len(s))).verdict is Verdict.HOLDS
    row = f.row(s, np.r_[np.zeros(len(s) - 3), 1.0, 2.0, np.nan])
    assert row.verdict is Verdict.ERRATUM and row.measures[0].value == 3 and row.measures[0].limit == 0
    assert row.numbers.startswith("points off = 3 (<= 0)")


def test_printed_values_are_graded_within_their_rounding():
    """A printed value holds if |printed - ours| <= tol + rel |ours| at every entry; claim, numbers and
    erratum are derived; a matrix reports its worst entry and carries both matrices in its appendix."""
    n0 = Printed("n0", "N0", 1e-3)
    ok = n0.row("App. E, A1, Eq 59", [0.766, 0.6428, 0.0], [0.76604, 0.64279, 0.0], note=" (null vector)")
    assert ok.verdict is Verdict.HOLDS and ok.id == "n0" and ok.reference == "App. E, A1, Eq 59"
    assert ok.claim == "N0 = [0.7660 0.6428 0.0000] (App. E, A1, Eq 59)."
    assert ok.numbers == "printed [0.7660 0.6428 0.0000] | ours [0.76604 0.64279 0.00000] (null vector)"
    bad = n0.row("App. E, A6, Eq 59", [-0.698, 0, -0.9976], [-0.8988, 0, -0.4384], why="not a unit vector")
    assert bad.verdict is Verdict.ERRATUM and bad.measures[0].value == pytest.approx(0.5592)
    assert bad.errata[0].printed == "N0 = [-0.6980 0.0000 -0.9976]" and bad.errata[0].counterexample == (
        "not a unit vector")
    q = Printed("q", "Q*", 0.1, "mm", 2e-3, 1)
    rel = q.row("App. E", [[1000.0, 0.0], [0.0, 1.0]], [[1001.5, 0.0], [0.0, 1.0]])  # 1.5 <= 0.1 + 2.003
    assert rel.verdict is Verdict.HOLDS and not rel.measures[0].holds  # the measure is against tol alone
    calls = []

    def reread():
        calls.append(1)
        return search({}, [], lambda x: 1.0, 0.0, printed="Q*", stated_text="-", route="-", measure="-")

    off = q.row("App. E", [[1.0, 5.0], [0.0, 1.0]], [[1.0, 0.0], [0.0, 1.0]], reread=reread)
    assert off.verdict is Verdict.ERRATUM and off.claim == "Q* (App. E)." and "(1, 2)" in off.numbers
    assert off.appendix.startswith("printed: [1.0 5.0; 0.0 1.0]") and off.errata[0].printed.endswith("= 5.0")
    assert off.second_reading is not None and calls == [1]  # re-read only when it fails
    assert rel.second_reading is None
    diag = q.row("App. E", [1.0], [1.0], basis="circular")
    assert diag.verdict is Verdict.IDENTITY
