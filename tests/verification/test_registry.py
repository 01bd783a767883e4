"""verification.registry: rows, measures, forms and registration errors."""

from __future__ import annotations

import math

import numpy as np
import pytest

from iik.errors import IIKError
from verification import (
    Check,
    Erratum,
    Forms,
    Measure,
    RegistrationError,
    Row,
    RowError,
    Slip,
    SlipKind,
    Verdict,
    epsilon,
    register,
)
from verification.registry import Section, off_by, registered_checks, verdict_of
from verification.second_reading import AS_STATED, Kind, Reading, SecondReading, Trial
from verification.thesis_index import parse_refs


def _row(**kw):
    base = dict(claim="c", reference="Eq 4", method="m", numbers="1", verdict=Verdict.HOLDS)
    return Row(**{**base, **kw})


def test_row_rules_raise_typed_errors():
    with pytest.raises(RowError, match="reason"):
        _row(verdict=Verdict.NOT_CHECKABLE)
    with pytest.raises(RowError, match="errata"):
        _row(verdict=Verdict.ERRATUM)
    with pytest.raises(RowError, match="id"):
        _row(id="Bad Id")
    with pytest.raises(RowError, match="assumption"):
        _row(depends_on=("no-such-thing",))
    assert issubclass(RowError, IIKError) and issubclass(RowError, ValueError)


def test_measure_bounds_and_nan():
    assert Measure("x", 1.0, 1.0).holds and not Measure("x", 1.1, 1.0).holds
    assert Measure("x", 0.99, 0.99, bound=">=").holds and not Measure("x", 0.5, 0.99, bound=">=").holds
    assert not Measure("x", math.nan, 1.0).holds
    assert verdict_of([Measure("x", 2, 1)], fail=Verdict.DOES_NOT_HOLD) is Verdict.DOES_NOT_HOLD
    with pytest.raises(RowError):
        verdict_of([])
    with pytest.raises(RowError):
        Measure("x", 1, 1, bound="<")


def _takes_form(ctx, form):
    return _row()


def test_registration_errors():
    some = registered_checks()[0]
    with pytest.raises(RegistrationError, match="twice"):
        register("S", name=some.name)(_takes_form)
    forms = Forms(printed=1, good=1, good_is="g", slips=(Slip(SlipKind.CLAIM, "b", 2),))
    with pytest.raises(RegistrationError, match="by construction"):
        register("S", name="test.both", forms=forms, by_construction="x")(_takes_form)
    with pytest.raises(RegistrationError, match="no form argument"):
        register("S", name="test.noform", forms=forms)(lambda ctx: _row())
    with pytest.raises(RegistrationError, match="assumption"):
        register("S", name="test.assume", depends_on=("nope",))(lambda ctx: _row())
    with pytest.raises(RegistrationError, match="description"):
        register("S", name="test.desc", forms=Forms(1, 1, "", (Slip(SlipKind.CLAIM, "b", 2),)))(_takes_form)
    with pytest.raises(RegistrationError, match="realistic slip"):  # none, or the epsilon form as a slip
        Forms(1, 1, "g", ())
    with pytest.raises(RegistrationError, match="realistic"):
        Forms(1, 1, "g", (epsilon(lambda x: x, 1e-9),))
    with pytest.raises(RegistrationError, match="tolerance"):
        Forms(1, 1, "g", (Slip(SlipKind.SIGN, "s", 2),), tolerance=Slip(SlipKind.SIGN, "s", 3))
    assert all(c.name.startswith("verification.") for c in registered_checks())  # nothing leaked in


def test_check_run_assigns_ids_check_and_defaults():
    def rows(ctx, form):
        return [_row(id="a", details=(_row(), _row(id="x"))), _row(id="a"), _row()]

    chk = Check(
        name="m.rows",
        section="S",
        order=0,
        func=rows,
        depends_on=("l1",),
        prefix="m",
        forms=Forms(printed=1, good=1, good_is="g", slips=(Slip(SlipKind.CLAIM, "b", 2),)),
    )
    out = chk.run(None)
    assert [r.id for r in out] == ["m.a", "m.a-2", "m.rows"]
    assert [d.id for d in out[0].details] == ["m.a.1", "m.a.x"]
    assert all(r.check.endswith(":test_check_run_assigns_ids_check_and_defaults.<locals>.rows") for r in out)
    assert all(r.depends_on == ("l1",) for r in out)


def test_every_registered_check_is_declared():
    """Every check declares its forms or why it is by construction: none is left unconverted."""
    for c in registered_checks():
        assert c.forms is not None or c.by_construction, c.name


def test_parse_refs():
    assert parse_refs("Eq 9a-c, Table VI, App. D") == ("Eq 9a", "Eq 9b", "Eq 9c", "Table VI", "App. D")
    assert parse_refs("Sec 3.3.3 (Eq 15, 21)") == ("Eq 15", "Eq 21")
    assert parse_refs("Eq 36-41") == tuple(f"Eq {k}" for k in range(36, 42))
    assert parse_refs("Tables VI-VII") == ("Table VI", "Table VII")
    assert parse_refs("Eq 34a-c") == ("Eq 34a", "Eq 34b", "Eq 34c")
    assert parse_refs("Sec 4.3") == ()


def test_erratum_is_plain_data():
    e = Erratum("Eq 1", "p", "c", "x")
    assert _row(verdict=Verdict.ERRATUM, errata=(e,)).errata == (e,)


def test_graded_rows_keep_erratum_and_reason_only_when_failing():
    e = Erratum("Eq 1", "p", "c", "x")
    ok = Row.graded("c", "Eq 4", "m", "1", [Measure("x", 0.5, 1.0)], erratum=e, reason="why", id="a")
    assert (ok.verdict, ok.errata, ok.reason, ok.id) == (Verdict.HOLDS, (), "", "a")
    bad = Row.graded("c", "Eq 4", "m", "1", [Measure("x", 2.0, 1.0)], erratum=e, reason="why")
    assert (bad.verdict, bad.errata, bad.reason) == (Verdict.ERRATUM, (e,), "why")
    too_far = [Measure("x", 2.0, 1.0)]
    refuted = Row.graded("c", "Eq 4", "m", "1", too_far, fail=Verdict.DOES_NOT_HOLD, reason="why")
    assert (refuted.verdict, refuted.errata, refuted.reason) == (Verdict.DOES_NOT_HOLD, (), "why")
    with pytest.raises(RowError, match="errata"):  # an erratum without its record is still refused
        Row.graded("c", "Eq 4", "m", "1", [Measure("x", 2.0, 1.0)])


def test_grouped_rows_count_the_failing_details():
    """A group row is graded on how many details fail; its verdict, numbers, errata and reason follow."""
    e = Erratum("Eq 1", "p", "c", "x")
    ok, wrong = _row(id="a"), _row(id="b", verdict=Verdict.ERRATUM, errata=(e,))
    refuted = _row(id="c", verdict=Verdict.DOES_NOT_HOLD)
    held = Row.grouped("c", "Eq 4", "m", None, [ok, ok], "wrong", passing="agree", reason="why")
    assert (held.verdict, held.numbers, held.reason, held.errata, len(held.details)) == (
        Verdict.HOLDS, "2 of 2 agree", "", (), 2)
    assert held.measures == (Measure("wrong", 0, 0),)
    bad = Row.grouped("c", "Eq 4", "m", None, [ok, wrong, refuted], "wrong", fail=Verdict.ERRATUM, reason="w")
    assert (bad.verdict, bad.numbers, bad.reason, bad.errata) == (Verdict.ERRATUM, "1 of 3 pass; not: b, c",
                                                                   "w", (e,))
    assert not bad.measures[0].holds and bad.measures[0].value == 2
    worst = Row.grouped("c", "Eq 4", "m", "n", [wrong, refuted], "w", fail=None)  # the worst: does not hold
    assert worst.verdict is Verdict.DOES_NOT_HOLD
    by_construction = Row.grouped("c", "Eq 4", "m", "n", [ok], "w", holds_as=Verdict.IDENTITY, basis="b")
    assert by_construction.verdict is Verdict.IDENTITY
    read = SecondReading("p", "s", "r", "m", 0.0, (Trial((AS_STATED,), 1.0, False),
                                                     Trial((Reading(Kind.SIGN, "-1"),), 0.0, True)))
    slip = wrong.reread(read)
    worst = Row.grouped("c", "Eq 4", "m", "n", [ok, wrong, slip], "w", fail=None)  # the worst: erratum
    assert (worst.verdict, worst.second_reading) == (Verdict.ERRATUM, None)
    only_slip = Row.grouped("c", "Eq 4", "m", "n", [ok, slip], "w", fail=None)
    assert (only_slip.verdict, only_slip.second_reading) == (Verdict.INPUT_SLIP, slip.second_reading)


def test_section_defaults_reach_its_checks():
    from verification.checks import ik_equations

    checks = {c.name: c for c in registered_checks()}
    step = checks["verification.checks.ik_equations.eq6"]
    assert (step.section, step.prefix, step.depends_on) == (
        ik_equations.SECTION.title,
        "ik",
        ik_equations.SECTION.depends_on,
    )
    assert step.where == "verification.checks.ik_equations:eq6"
    assert checks["verification.checks.ik.four_configurations"].depends_on == ("l1", "lengths")  # its own
    with pytest.raises(RegistrationError, match="assumption"):  # the section's default is checked too
        Section("S", depends_on=("nope",)).check(1.0)(lambda ctx: _row())


def test_grades_that_are_not_measurements_name_their_basis():
    """Holds by construction / on our reconstruction need a basis; the groups of the report's opening."""
    for v in (Verdict.IDENTITY, Verdict.RECONSTRUCTION, Verdict.NOT_REPRODUCED):
        with pytest.raises(RowError, match="rests on"):
            _row(verdict=v)
        assert _row(verdict=v, basis="why").basis == "why"
    ok = Row.graded("c", "Eq 4", "m", "1", [Measure("x", 0.5, 1.0)], holds_as=Verdict.IDENTITY, basis="b")
    assert ok.verdict is Verdict.IDENTITY
    bad = Row.graded("c", "Eq 4", "m", "1", [Measure("x", 2.0, 1.0)], holds_as=Verdict.IDENTITY, basis="b",
                     fail=Verdict.DOES_NOT_HOLD)
    assert bad.verdict is Verdict.DOES_NOT_HOLD
    assert [v for v in Verdict if v.passes] == [Verdict.HOLDS, Verdict.IDENTITY, Verdict.RECONSTRUCTION]
    assert {v.group for v in Verdict} == {"confirmed", "refuted", "input slip", "not evidence", "untestable"}
    with pytest.raises(RowError, match="second reading"):  # an input slip needs the reading behind it
        _row(verdict=Verdict.INPUT_SLIP, errata=(Erratum("Eq 1", "p", "c", "x"),))


def test_off_by_moves_the_output_only():
    slipped = off_by(lambda x, scale=1.0: scale * x, 1e-3)
    assert slipped(2.0, scale=3.0) == pytest.approx(6.001)


def test_off_by_moves_every_array_of_the_output_or_one_entry():
    """The tolerance form of a form with structured output: the form itself is left alone."""

    def form(q):
        return {"T": np.zeros((len(q), 4, 4)), "pair": (np.ones(2), [np.zeros(3)])}

    q = np.zeros(5)
    out = off_by(form, 1e-9)(q)
    assert np.all(out["T"] == 1e-9) and np.all(out["pair"][0] == 1.0 + 1e-9)
    assert isinstance(out["pair"], tuple) and isinstance(out["pair"][1], list)
    assert np.all(out["pair"][1][0] == 1e-9)
    T = off_by(lambda q: np.zeros((len(q), 4, 4)), 1e-9, (2, 3))(q)
    assert np.all(T[:, 2, 3] == 1e-9) and np.count_nonzero(T) == len(q)
    assert np.all(form(q)["T"] == 0.0)


# --- added in r6
