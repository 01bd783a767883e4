"""The self-test: every verdict can fail.

Every check registered with :class:`~verification.registry.Forms` is run three times:
with the printed form (the verdict the report shows), with the known-good form (it must
say "holds") and with the deliberately perturbed form (it must not). A check whose
verdict does not follow the form -- a constant, a method label, a measurement of the
wrong thing -- "cannot flip" and makes the self-test fail. Checks that cannot flip by
their nature declare ``by_construction`` and are counted apart.

``iik verify --self-test`` prints :func:`self_test`'s lines and exits with its code.
"""

from __future__ import annotations

import sys
import tempfile
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from .registry import Check, Context, Row, Verdict, selected_checks

__all__ = ["SelfTestOutcome", "self_test_check", "run_self_test", "self_test"]

FLIPS, CANNOT_FLIP, BY_CONSTRUCTION = "flips", "CANNOT FLIP", "by construction"
UNDECLARED, ERROR = "UNDECLARED", "ERROR"
#: Statuses that make the self-test fail.
FAILING = frozenset({CANNOT_FLIP, UNDECLARED, ERROR})


@dataclass(frozen=True)
class SelfTestOutcome:
    """The self-test of one check.

    Attributes:
        check: ``module:function``.
        status: ``"flips"``, ``"CANNOT FLIP"``, ``"by construction"``, ``"UNDECLARED"`` or ``"ERROR"``.
        printed, good, bad: The graded rows' verdicts with each form (``"-"`` if not run).
        note: What the good and bad forms are, or why the check is by construction, or the error.
    """

    check: str
    status: str
    printed: str = "-"
    good: str = "-"
    bad: str = "-"
    note: str = ""

    @property
    def failed(self) -> bool:
        return self.status in FAILING

    def line(self) -> str:
        return (
            f"{self.status:>17}  {self.check}  printed: {self.printed} | with good: {self.good} | "
            f"with bad: {self.bad}"
        )


def _graded(check: Check, rows: list[Row]) -> list[Row]:
    wanted = check.forms.rows if check.forms is not None else ()
    if not wanted:
        return rows
    picked = [r for r in rows if check.local_id(r.id) in wanted]
    if len(picked) != len(wanted):
        missing = set(wanted) - {check.local_id(r.id) for r in picked}
        raise LookupError(f"forms.rows names rows the check did not return: {sorted(missing)}")
    return picked


def _verdicts(rows: list[Row]) -> str:
    c = Counter(r.verdict.value for r in rows)
    if len(c) == 1:
        v, k = next(iter(c.items()))
        return v if k == 1 else f"{v} x{k}"
    return ", ".join(f"{v} x{k}" for v, k in sorted(c.items()))


def self_test_check(check: Check, ctx: Context) -> SelfTestOutcome:
    """Self-test one check: printed, good and bad forms (or its label if it has no forms)."""
    where = check.where
    if check.forms is None:
        if check.by_construction:
            return SelfTestOutcome(where, BY_CONSTRUCTION, note=check.by_construction)
        return SelfTestOutcome(where, UNDECLARED, note="declares neither forms nor 'by construction'")
    f = check.forms
    try:
        printed = _graded(check, check.run(ctx))
        good = _graded(check, check.run(ctx, f.good, use_printed=False))
        bad = _graded(check, check.run(ctx, f.bad, use_printed=False))
    except Exception as exc:  # reported as a failing outcome, not raised
        return SelfTestOutcome(where, ERROR, note=f"{type(exc).__name__}: {exc}")
    flips = all(r.verdict is Verdict.HOLDS for r in good) and not any(r.verdict is Verdict.HOLDS for r in bad)
    return SelfTestOutcome(
        where,
        FLIPS if flips else CANNOT_FLIP,
        _verdicts(printed),
        _verdicts(good),
        _verdicts(bad),
        f"good = {f.good_is}; bad = {f.bad_is}",
    )


def run_self_test(ctx: Context, *, select: Sequence[str] | None = None) -> list[SelfTestOutcome]:
    """Self-test every registered check (or those whose name or section contains a ``select`` item)."""
    return [self_test_check(c, ctx) for c in selected_checks(select)]


def self_test(ctx: Context | None = None, *, quick: bool = False, seed: int = 20120101,
              select: Sequence[str] | None = None, out=None) -> int:
    """Run the self-test, print one line per check and a summary to ``out`` (stdout);
    return 0 if every check flips (or is by construction), else 1.

    Without ``ctx`` the checks run in a fresh context (``quick``, ``seed``) whose figures and
    views go to a temporary folder, so a report folder is never touched.
    """
    out = out or sys.stdout
    if ctx is None:
        with tempfile.TemporaryDirectory(prefix="iik-self-test-") as tmp:
            return self_test(Context(out_dir=Path(tmp), seed=seed, quick=quick), select=select, out=out)
    outcomes = run_self_test(ctx, select=select)
    for o in outcomes:
        print(o.line(), file=out)
    c = Counter(o.status for o in outcomes)
    print(
        f"self-test: {c.get(FLIPS, 0)} checks flip (holds with the good form, not with the bad one); "
        f"{c.get(BY_CONSTRUCTION, 0)} by construction; {c.get(CANNOT_FLIP, 0)} cannot flip; "
        f"{c.get(UNDECLARED, 0)} undeclared; {c.get(ERROR, 0)} errors",
        file=out,
    )
    return 1 if any(o.failed for o in outcomes) else 0
