"""verification.self_test: every declared check passes with its good form and catches its slips; constants
and missed slips are caught."""

from __future__ import annotations

import io

from verification import Check, Context, Forms, Row, Slip, SlipKind, Verdict, self_test
from verification.self_test import self_test_check, table


def test_self_test_passes_in_quick_mode(tmp_path):
    out = io.StringIO()
    code = self_test(Context(out_dir=tmp_path, quick=True), out=out)
    text = out.getvalue()
    assert code == 0, text
    summary = text.strip().splitlines()[-1]
    assert summary.startswith("self-test: ") and " 0 cannot flip" in summary and " 0 errors" in summary
    assert " 0 miss a slip" in summary
    assert int(summary.split("self-test: ")[1].split(" checks flip")[0]) >= 80
    caught, total = summary.split(" slips caught")[0].rsplit("; ", 1)[1].split(" of ")
    assert caught == total and int(total) >= 150  # every realistic slip caught
    assert text.startswith("| check | status |")  # the table, one row per check


def _constant(ctx, form):
    return Row("c", "Eq 1", "m", "1", Verdict.HOLDS)


def _follows(ctx, form):
    return Row("c", "Eq 1", "m", str(form), Verdict.HOLDS if form == 0 else Verdict.DOES_NOT_HOLD)


def _tolerant(ctx, form):
    """Holds within 0.5 of 0: catches the sign slip, lets the epsilon and the 0.1 slip through."""
    return Row("c", "Eq 1", "m", str(form), Verdict.HOLDS if abs(form) <= 0.5 else Verdict.DOES_NOT_HOLD)


_FORMS = Forms(
    printed=1, good=0, good_is="0", slips=(Slip(SlipKind.SIGN, "1", 1), Slip(SlipKind.CLAIM, "2", 2))
)


def test_a_constant_verdict_cannot_flip(tmp_path):
    ctx = Context(out_dir=tmp_path, quick=True)
    const = self_test_check(Check("t.c", "S", 0, _constant, forms=_FORMS, prefix="t"), ctx)
    assert const.status == "CANNOT FLIP" and const.failed
    ok = self_test_check(Check("t.f", "S", 0, _follows, forms=_FORMS, prefix="t"), ctx)
    assert ok.status == "flips" and (ok.printed, ok.good) == ("does not hold", "holds")
    assert [s.caught for s in ok.slips] == [True, True] and ok.tolerance is None


def test_a_missed_slip_or_a_loose_tolerance_fails(tmp_path):
    ctx = Context(out_dir=tmp_path, quick=True)
    forms = Forms(0, 0, "0", slips=(Slip(SlipKind.SIGN, "-1", -1), Slip(SlipKind.TERM, "0.1", 0.1)))
    missed = self_test_check(Check("t.m", "S", 0, _tolerant, forms=forms, prefix="t"), ctx)
    assert missed.status == "MISSES A SLIP" and missed.failed
    assert [s.what for s in missed.missed] == ["0.1"]
    loose = Forms(
        0, 0, "0", slips=(Slip(SlipKind.SIGN, "-1", -1),), tolerance=Slip(SlipKind.EPSILON, "0 + 0.1", 0.1)
    )
    out = self_test_check(Check("t.l", "S", 0, _tolerant, forms=loose, prefix="t"), ctx)
    assert out.status == "MISSES A SLIP" and out.tolerance is not None and not out.tolerance.caught
    assert "PASSES" in out.line() and "| check |" in table([out])


def test_labels_and_errors(tmp_path):
    ctx = Context(out_dir=tmp_path, quick=True)
    assert (
        self_test_check(Check("t.b", "S", 0, lambda c: None, by_construction="bytes", prefix="t"), ctx).status
        == "by construction"
    )
    assert self_test_check(Check("t.u", "S", 0, lambda c: None, prefix="t"), ctx).status == "UNDECLARED"

    def boom(ctx, form):
        raise RuntimeError("kaput")

    err = self_test_check(Check("t.e", "S", 0, boom, forms=_FORMS, prefix="t"), ctx)
    assert err.status == "ERROR" and "kaput" in err.note


def test_a_form_printed_right_is_run_once_for_printed_and_good(tmp_path):
    """Forms.right: the printed form is the good one, so its rows are not computed twice (the self-test's
    time); a different good form is run."""
    calls = []

    def counted(ctx, form):
        calls.append(form)
        return _follows(ctx, form)

    ctx = Context(out_dir=tmp_path, quick=True)
    right = Forms.right(0, (Slip(SlipKind.SIGN, "1", 1),))
    out = self_test_check(Check("t.r", "S", 0, counted, forms=right, prefix="t"), ctx)
    assert out.status == "flips" and calls == [0, 1]
    calls.clear()
    self_test_check(Check("t.f", "S", 0, counted, forms=_FORMS, prefix="t"), ctx)
    assert calls == [1, 0, 1, 2]
