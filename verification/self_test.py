"""The self-test: every verdict can fail, and fails on the mistakes a person would make.

Every check registered with :class:`~verification.registry.Forms` is run with the printed form
(the verdict the report shows), with the known-good form (it must pass:
:attr:`~verification.registry.Verdict.passes`), with each of its realistic slips (a sign, a
swapped index, atan for asin, a wrong link length, degrees for radians, a transposed rotation,
the other branch of a square root, an off-by-one in a table index: each must make a graded row
fail) and, where a tolerance is graded, with the good form moved by a tiny epsilon (the tolerance
test: it must be caught too). A check whose verdict does not follow the form -- a constant, a method label, a
measurement of the wrong thing -- "cannot flip"; one that lets a slip through "misses" it; both
make the self-test fail. Checks that cannot flip by their nature declare ``by_construction`` and
are counted apart.

``iik verify --self-test`` prints :func:`self_test`'s table (one line per check: which slips it
catches) and its summary, and exits with its code.
"""

from __future__ import annotations

import dataclasses
import sys
import tempfile
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from .registry import Check, Context, Row, Slip, selected_checks

__all__ = ["SlipOutcome", "SelfTestOutcome", "self_test_check", "run_self_test", "self_test", "table"]

FLIPS, CANNOT_FLIP, MISSES, BY_CONSTRUCTION = "flips", "CANNOT FLIP", "MISSES A SLIP", "by construction"
UNDECLARED, ERROR = "UNDECLARED", "ERROR"
#: Statuses that make the self-test fail.
FAILING = frozenset({CANNOT_FLIP, MISSES, UNDECLARED, ERROR})


@dataclass(frozen=True)
class SlipOutcome:
    """One slip (or the tolerance test) run through a check.

    Attributes:
        kind: The slip's kind (``SlipKind`` value).
        what: The slip in words.
        verdicts: The graded rows' verdicts with it.
        caught: True if a graded row did not pass (the row that grades what the slip changed).
    """

    kind: str
    what: str
    verdicts: str
    caught: bool


@dataclass(frozen=True)
class SelfTestOutcome:
    """The self-test of one check.

    Attributes:
        check: ``module:function``.
        status: ``"flips"``, ``"CANNOT FLIP"``, ``"MISSES A SLIP"``, ``"by construction"``, ``"UNDECLARED"``
            or ``"ERROR"``.
        printed, good: The graded rows' verdicts with each form (``"-"`` if not run).
        slips: Each realistic slip's outcome.
        tolerance: The tolerance test's outcome (``None`` if the check declares none).
        note: What the good form is, or why the check is by construction, or the error.
    """

    check: str
    status: str
    printed: str = "-"
    good: str = "-"
    slips: tuple[SlipOutcome, ...] = ()
    tolerance: SlipOutcome | None = None
    note: str = ""

    @property
    def failed(self) -> bool:
        return self.status in FAILING

    @property
    def caught(self) -> tuple[SlipOutcome, ...]:
        return tuple(s for s in self.slips if s.caught)

    @property
    def missed(self) -> tuple[SlipOutcome, ...]:
        return tuple(s for s in self.slips if not s.caught)

    def line(self) -> str:
        """One markdown table row: check, status, verdicts, slips caught and missed, tolerance test (a '|' in
        a slip's words is escaped, so "|BC| - |DC|" stays in its cell)."""
        caught = "; ".join(f"{s.kind}: {_cell(s.what)}" for s in self.caught) or "-"
        missed = "; ".join(f"{s.kind}: {_cell(s.what)} ({s.verdicts})" for s in self.missed) or "-"
        tol = (
            "-"
            if self.tolerance is None
            else ("caught" if self.tolerance.caught else f"PASSES ({self.tolerance.verdicts})")
        )
        n = f"{len(self.caught)}/{len(self.slips)}" if self.slips else "-"
        return (
            f"| `{self.check}` | {self.status} | {self.printed} | {self.good} | {n} | {caught} | {missed} | "
            f"{tol} |"
        )


def _cell(text: str) -> str:
    return str(text).replace("|", "\\|")


#: The header of :meth:`SelfTestOutcome.line`'s table.
HEADER = (
    "| check | status | printed | with the good form | slips caught | caught | missed | tolerance test |\n"
    "|---|---|---|---|---|---|---|---|"
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


def _run(check: Check, ctx: Context, slip: Slip) -> SlipOutcome:
    rows = _graded(check, check.run(ctx, slip.form, use_printed=False))
    return SlipOutcome(slip.kind.value, slip.what, _verdicts(rows), not all(r.verdict.passes for r in rows))


def _same_form(a, b) -> bool:
    """True if the good form is the printed one (``Forms.right``, or an equal frozen dataclass): a check is a
    function of its context and form, so its rows with the good form are those with the printed form."""
    if a is b:
        return True
    if dataclasses.is_dataclass(a) and type(a) is type(b):
        try:
            return bool(a == b)
        except (TypeError, ValueError):  # fields that do not compare to one bool (arrays)
            return False
    return False


def self_test_check(check: Check, ctx: Context) -> SelfTestOutcome:
    """Self-test one check: printed, good, every slip and the tolerance form (or its label if it has no
    forms)."""
    where = check.where
    if check.forms is None:
        if check.by_construction:
            return SelfTestOutcome(where, BY_CONSTRUCTION, note=check.by_construction)
        return SelfTestOutcome(where, UNDECLARED, note="declares neither forms nor 'by construction'")
    f = check.forms
    try:
        printed = _graded(check, check.run(ctx))
        good = printed if _same_form(f.good, f.printed) else _graded(check, check.run(ctx, f.good,
                                                                                   use_printed=False))
        slips = tuple(_run(check, ctx, s) for s in f.slips)
        tol = _run(check, ctx, f.tolerance) if f.tolerance is not None else None
    except Exception as exc:  # reported as a failing outcome, not raised
        return SelfTestOutcome(where, ERROR, note=f"{type(exc).__name__}: {exc}")
    good_ok = all(r.verdict.passes for r in good)
    if not good_ok or not any(s.caught for s in slips):
        status = CANNOT_FLIP
    elif all(s.caught for s in slips) and (tol is None or tol.caught):
        status = FLIPS
    else:
        status = MISSES
    return SelfTestOutcome(
        where, status, _verdicts(printed), _verdicts(good), slips, tol, f"good = {f.good_is}"
    )


def run_self_test(ctx: Context, *, select: Sequence[str] | None = None) -> list[SelfTestOutcome]:
    """Self-test every registered check (or those whose name or section contains a ``select`` item)."""
    return [self_test_check(c, ctx) for c in selected_checks(select)]


def table(outcomes: Sequence[SelfTestOutcome]) -> str:
    """The self-test as a markdown table (one row per check) followed by its summary line."""
    lines = [HEADER] + [o.line() for o in outcomes]
    return "\n".join(lines + ["", summary_line(outcomes)])


def summary_line(outcomes: Sequence[SelfTestOutcome]) -> str:
    c = Counter(o.status for o in outcomes)
    slips = [s for o in outcomes for s in o.slips]
    kinds = Counter(s.kind for s in slips if s.caught)
    tols = [o.tolerance for o in outcomes if o.tolerance is not None]
    return (
        f"self-test: {c.get(FLIPS, 0)} checks flip (pass with the good form, catch every slip); "
        f"{sum(s.caught for s in slips)} of {len(slips)} slips caught "
        f"({', '.join(f'{k} {n}' for k, n in sorted(kinds.items()))}); "
        f"{sum(t.caught for t in tols)} of {len(tols)} tolerance tests caught; "
        f"{c.get(BY_CONSTRUCTION, 0)} by construction; {c.get(CANNOT_FLIP, 0)} cannot flip; "
        f"{c.get(MISSES, 0)} miss a slip; {c.get(UNDECLARED, 0)} undeclared; {c.get(ERROR, 0)} errors"
    )


def self_test(
    ctx: Context | None = None,
    *,
    quick: bool = False,
    seed: int = 20120101,
    select: Sequence[str] | None = None,
    out=None,
) -> int:
    """Run the self-test, print its table (:func:`table`) to ``out`` (stdout); return 0 if every check
    flips (or is by construction), else 1.

    Without ``ctx`` the checks run in a fresh context (``quick``, ``seed``) whose figures and
    views go to a temporary folder, so a report folder is never touched.
    """
    out = out or sys.stdout
    if ctx is None:
        with tempfile.TemporaryDirectory(prefix="iik-self-test-") as tmp:
            return self_test(Context(out_dir=Path(tmp), seed=seed, quick=quick), select=select, out=out)
    outcomes = run_self_test(ctx, select=select)
    print(table(outcomes), file=out)
    return 1 if any(o.failed for o in outcomes) else 0
