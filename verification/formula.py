"""A printed formula graded against the truth on a sample: most thesis checks, declared as data.

A check of a printed formula evaluates a form (the transcription, a known-good form, a slip) on a
sample, compares it with the truth, grades ``max |error|`` against a tolerance and, if it fails, records
an erratum with the worst sample as its counterexample. :class:`Formula` declares only what differs from
one formula to the next; :meth:`verification.registry.Section.formulas` registers a family in bulk::

    CHECKS = SECTION.formulas(
        sample,
        Formula("Eq 16", np.arctan2, lambda s, f: wrap(f(s.s(4), s.c(4)) - s.q[:, 3]), TOL, "rad",
                slips=(Slip(SlipKind.SWAP, "atan2(c, s)", lambda sn, cs: np.arctan2(cs, sn)),)),
    )

Derived, not written: the row id (``"Eq 16"`` -> ``"eq16"``), the check's place in the report and its
claim (the index item's position and title, :mod:`verification.thesis_index`), the numbers (the graded
measure, with the raw error where it is scaled), the erratum's counterexample (the worst sample), and the
self-test's :class:`~verification.registry.Forms` (the printed form is the good one unless ``good`` is
given; the tolerance test is the good form moved by ``eps``).

A sample is any object with ``len()``, ``domain`` (the sampled domain in words) and ``at(k)`` (sample
``k`` in words, e.g. ``"q = [...] rad"``); :class:`Points` wraps a plain array.

A check that grades several printed items with one form on one sample (Eq 9a-c, Eq 34a-c with Eq 55)
declares each item as a Formula without form, error or slips (the check's own ``Forms`` hold them) and
builds its rows with :meth:`Formula.row`: ids, claims and the graded numbers come from the declaration.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import wraps
from typing import Any

import numpy as np

from .numbers import fmt_matrix, fmt_vec, worst
from .registry import Erratum, Forms, Measure, Row, Slip, Verdict, epsilon
from .thesis_index import title_of

__all__ = ["Formula", "Points", "Printed", "error_row", "RIGHT", "per_run"]

#: What the good form is when the printed one is right.
RIGHT = "the printed form (it is right)"


@dataclass(frozen=True)
class Points:
    """A sample that is a plain array of points or parameters (``values[k]`` is sample ``k``).

    Attributes:
        values: (n, ...) array.
        domain: The sampled domain in words.
        unit: Unit of the values, for :meth:`at`.
        name: What a value is, for :meth:`at` (``"p"``, ``"theta2"``).
    """

    values: np.ndarray
    domain: str
    unit: str = "m"
    name: str = "p"

    def __len__(self) -> int:
        return len(self.values)

    def at(self, k: int) -> str:
        v = self.values[k]
        return f"{self.name} = {fmt_vec(v) if np.ndim(v) else f'{float(v):.4f}'} {self.unit}"


def error_row(
    sample,
    err,
    tol: float,
    unit: str,
    *,
    key: str,
    id: str,
    claim: str,
    method: str,
    printed: str,
    corrected: str = "-",
    note: str = "",
    fail: Verdict = Verdict.ERRATUM,
    basis: str = "",
    scale: tuple[str, np.ndarray] | None = None,
    measure: str = "max |form - truth|",
    domain: str = "",
    count: bool = False,
) -> Row:
    """A row graded on ``max |err| <= tol`` [``unit``] over ``sample`` (NaN counts as infinite).

    With ``scale = (name, x)`` it is graded on ``max |err| |x|`` (the conditioning of a division by x). A
    failing row is an erratum (printed form, ``corrected``, the worst sample as counterexample), or with
    ``fail`` DOES_NOT_HOLD a refutation naming the worst sample; with ``basis`` (why it is an identity) a
    passing row holds by construction; with ``count`` it is graded on the number of samples where ``|err| >
    tol`` (limit 0). The numbers are the measure and ``note``."""
    raw = np.abs(np.asarray(err, float))
    if scale is not None:
        measure += f" x |{scale[0]}|"
        raw_scaled = np.where(np.isnan(raw), np.inf, raw) * np.abs(scale[1])
    graded = raw if scale is None else raw_scaled
    w, k = worst(graded) if len(graded) else (0.0, 0)
    m = Measure(measure, np.sum(~(graded <= tol)), 0, unit) if count else Measure(measure, w, tol, unit)
    numbers = f"{m} over {len(graded)} samples"
    if scale is not None:
        at = np.abs(scale[1][int(np.argmax(raw))])
        numbers += f" (raw: max {worst(raw)[0]:.2g} {unit}, at |{scale[0]}| = {at:.1g})"
    erratum = None
    if fail is Verdict.ERRATUM and len(graded):
        erratum = Erratum(key, printed, corrected, f"{sample.at(k)}: |form - truth| = {raw[k]:.3g} {unit}")
    return Row.graded(
        claim,
        key,
        method,
        numbers + (f"; {note}" if note else ""),
        (m,),
        fail=fail,
        holds_as=Verdict.IDENTITY if basis else Verdict.HOLDS,
        basis=basis,
        erratum=erratum,
        reason=f"fails at {sample.at(k)}" if fail is Verdict.DOES_NOT_HOLD else "",
        id=id,
        domain=domain or sample.domain,
    )


_DEFAULT = object()


@dataclass(frozen=True)
class Formula:
    """One printed formula checked against the truth (see the module docstring).

    Attributes:
        key: Index key or reference (``"Eq 16"``): the row's reference; id, order and claim follow it.
        printed: The transcription (a function, or what the error function takes).
        error: ``error(sample, form)`` -> the (n,) error of the form against the truth.
        tol: Tolerance of ``max |error|`` [``unit``].
        unit: Unit of the error.
        slips: Realistic mistakes in the formula (:class:`~verification.registry.Slip`).
        good: A known-good form; default: the printed form (it is right).
        good_is: What the good form is.
        eps: The tolerance test: the good form moved by ``eps`` (:func:`~verification.registry.epsilon`),
            a ready :class:`~verification.registry.Slip`, or None (no tolerance test).
        eps_is: The tolerance test in words.
        corrected: The corrected form (for an erratum).
        text: The printed form in words; default: the index title.
        claim: The claim; default: the index title.
        method: How it is measured (``{n}``: the sample size).
        basis: Why the step is an identity with exact inputs (then a passing row holds by construction).
        scale: ``(name, f)``: grade ``|error| |f(sample)|`` (a division by f).
        note: ``note(sample, error)`` -> a remark added to the numbers.
        reread: ``reread(ctx, sample, form)`` -> the second reading of an erratum.
        fail: The verdict of a failing row (ERRATUM, or DOES_NOT_HOLD for a claim).
        measure: The graded measure's name.
        id: Local row id; default: the key in lower case without spaces (``"eq16"``).
        name: The check function's name; default: the id.
        depends_on: Assumptions of the row, if not the section's.
        order: The check's place in its section, if not the key's (a number, as for ``SECTION.check``).
        count: Grade the number of samples where ``|error| > tol`` (limit 0), not ``max |error|``.
    """

    key: str
    printed: Any
    error: Callable[[Any, Any], np.ndarray]
    tol: float
    unit: str
    slips: tuple[Slip, ...]
    good: Any = _DEFAULT
    good_is: str = ""
    eps: float | Slip | None = 1e-9
    eps_is: str = ""
    corrected: str = "-"
    text: str = ""
    claim: str = ""
    method: str = ""
    basis: str = ""
    scale: tuple[str, Callable] | None = None
    note: Callable | None = None
    reread: Callable | None = None
    fail: Verdict = Verdict.ERRATUM
    measure: str = "max |form - truth|"
    id: str = ""
    name: str = ""
    depends_on: tuple[str, ...] | None = None
    order: float | None = None
    count: bool = False

    @property
    def rid(self) -> str:
        return self.id or self.key.lower().replace(" ", "")

    @property
    def forms(self) -> Forms:
        """The self-test's forms: printed, good, slips, tolerance."""
        good = self.printed if self.good is _DEFAULT else self.good
        if isinstance(self.eps, Slip) or self.eps is None:
            tol = self.eps
        else:
            tol = epsilon(good, self.eps, self.eps_is)
        good_is = self.good_is or (RIGHT if self.good is _DEFAULT else "")
        return Forms(self.printed, good, good_is, tuple(self.slips), tol)

    def row(self, sample, err, *, note: str = "") -> Row:
        """The row of ``err`` (the error of a form) on ``sample``."""
        title = title_of(self.key)
        return error_row(
            sample,
            err,
            self.tol,
            self.unit,
            key=self.key,
            id=self.rid,
            claim=self.claim or f"{title}.",
            method=self.method.format(n=len(sample)),
            printed=self.text or title,
            corrected=self.corrected,
            note=note or (self.note(sample, err) if self.note else ""),
            fail=self.fail,
            basis=self.basis,
            scale=None if self.scale is None else (self.scale[0], self.scale[1](sample)),
            measure=self.measure,
            count=self.count,
        )

    def check(self, sample_of: Callable) -> Callable:
        """The check function ``check(ctx, form) -> Row`` on the sample ``sample_of(ctx)``."""

        def check(ctx, form):
            s = sample_of(ctx)
            row = self.row(s, self.error(s, form))
            if self.reread is not None and row.verdict is Verdict.ERRATUM:
                return row.reread(self.reread(ctx, s, form))
            return row

        check.__name__ = check.__qualname__ = self.name or self.rid.replace(".", "_")
        check.__doc__ = f"{self.key}: {self.claim or title_of(self.key)}"
        return check


def per_run(func: Callable) -> Callable:
    """Decorator: ``func(ctx, *args)`` computed once per run, kept in ``ctx.cache`` under the function's
    module and name, ``args`` (hashable) and ``ctx.quick``.

    For samples and ground truths that depend on no form: the self-test reruns each check with other
    forms in the same context (:class:`~verification.registry.Context`)."""

    @wraps(func)
    def cached(ctx, *args):
        key = (func.__module__, func.__qualname__, args, ctx.quick)
        if key not in ctx.cache:
            ctx.cache[key] = func(ctx, *args)
        return ctx.cache[key]

    return cached


# --- added in r6
@dataclass(frozen=True)
class Printed:
    """A printed number, vector or matrix (a table value) vs the same quantity recomputed, graded within the
    printed rounding: its row holds if ``|printed - ours| <= tol + rel |ours|`` at every entry; the measure
    is ``max |printed - ours|`` [``unit``] against ``tol`` (or the ``limit`` given to :meth:`row`).

    Attributes:
        id: Local row id. what: The quantity in words (``"N0"``). tol, unit, rel: The printed rounding
            (absolute [``unit``], and a share of ``|ours|``). digits: Decimals shown. measure: Its name.
    """

    id: str
    what: str
    tol: float
    unit: str = ""
    rel: float = 0.0
    digits: int = 4
    measure: str = "max |printed - ours|"

    def row(self, reference: str, printed, ours, *, limit: float | None = None, note: str = "", why: str = "",
            reread: Callable | None = None, **fields) -> Row:
        """The row of ``printed`` vs ``ours``. Derived: the claim, the numbers (printed and ours; of a matrix
        the entry that differs most, the whole in the row's appendix; then ``note``) and the erratum of a
        failing row (printed vs ours, ``why`` its counterexample), re-read by ``reread()`` before it stands.
        ``fields`` go to :class:`~verification.registry.Row` (with a ``basis``: a pass holds by
        construction)."""
        p, o, n = np.asarray(printed, float), np.asarray(ours, float), self.digits
        d, unit = np.abs(p - o), f" {self.unit}" if self.unit else ""
        ok = bool(np.all(d <= self.tol + self.rel * np.abs(o)))
        if p.ndim < 2:
            what, mine, theirs = self.what, fmt_vec(p, n), fmt_vec(o, n + 1)
            numbers = f"printed {mine} | ours {theirs}{unit}{note}"
        else:
            k = np.unravel_index(np.argmax(d), d.shape)
            what = f"{self.what}, entry {tuple(int(i) + 1 for i in k)}"
            mine, theirs = f"{p[k]:.{n}f}", f"{o[k]:.{n + 1}f}"
            numbers = f"largest difference {d[k]:.3g}{unit} at {what}: printed {mine}, ours {theirs}{note}"
            fields.setdefault("appendix", f"printed: {fmt_matrix(p, n)}\nours:    {fmt_matrix(o, n + 1)}")
        erratum = Erratum(reference, f"{what} = {mine}", f"{what} = {theirs}", why or numbers)
        row = Row(
            f"{self.what}{f' = {mine}{unit}' if p.ndim < 2 else ''} ({reference}).",
            reference,
            "",
            numbers,
            (Verdict.IDENTITY if fields.get("basis") else Verdict.HOLDS) if ok else Verdict.ERRATUM,
            id=self.id,
            measures=(Measure(self.measure, d.max(), self.tol if limit is None else limit, self.unit),),
            errata=() if ok else (erratum,),
            **fields,
        )
        return row.reread(reread()) if not ok and reread is not None else row
