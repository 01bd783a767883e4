"""verification.self_test: every declared check flips with its good and bad forms; constants are caught."""

from __future__ import annotations

import io

from verification import Check, Context, Forms, Row, Verdict, self_test
from verification.self_test import self_test_check


def test_self_test_passes_in_quick_mode(tmp_path):
    out = io.StringIO()
    code = self_test(Context(out_dir=tmp_path, quick=True), out=out)
    text = out.getvalue()
    assert code == 0, text
    summary = text.strip().splitlines()[-1]
    assert summary.startswith("self-test: ") and " 0 cannot flip" in summary and " 0 errors" in summary
    assert int(summary.split("self-test: ")[1].split(" checks flip")[0]) >= 70


def _constant(ctx, form):
    return Row("c", "Eq 1", "m", "1", Verdict.HOLDS)


def _follows(ctx, form):
    return Row("c", "Eq 1", "m", str(form), Verdict.HOLDS if form == 0 else Verdict.DOES_NOT_HOLD)


def test_a_constant_verdict_cannot_flip(tmp_path):
    forms = Forms(printed=1, good=0, bad=1, good_is="0", bad_is="1")
    ctx = Context(out_dir=tmp_path, quick=True)
    const = self_test_check(Check("t.c", "S", 0, _constant, forms=forms, prefix="t"), ctx)
    assert const.status == "CANNOT FLIP" and const.failed
    ok = self_test_check(Check("t.f", "S", 0, _follows, forms=forms, prefix="t"), ctx)
    assert ok.status == "flips" and (ok.printed, ok.good, ok.bad) == (
        "does not hold",
        "holds",
        "does not hold",
    )


def test_labels_and_errors(tmp_path):
    ctx = Context(out_dir=tmp_path, quick=True)
    assert (
        self_test_check(Check("t.b", "S", 0, lambda c: None, by_construction="bytes", prefix="t"), ctx).status
        == "by construction"
    )
    assert self_test_check(Check("t.u", "S", 0, lambda c: None, prefix="t"), ctx).status == "UNDECLARED"

    def boom(ctx, form):
        raise RuntimeError("kaput")

    err = self_test_check(Check("t.e", "S", 0, boom, forms=Forms(1, 0, 1, "g", "b"), prefix="t"), ctx)
    assert err.status == "ERROR" and "kaput" in err.note
