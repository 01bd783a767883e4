"""The registry of thesis checks behind ``iik verify``, and the row every check returns.

A check is a function registered with :func:`register`. Every module in
:mod:`verification.checks` is imported by :func:`load_checks`, so a feature adds its
checks by adding a module there; no central list is edited.

**A check is a measurement.** A check of a printed formula runs the same measurement
on the printed form and on an independent reference (Pinocchio, Coal, finite
differences, geometry, ground-truth sampling); its verdict comes from that comparison
and a tolerance (:class:`Measure`, :func:`verdict_of`), never from a constant. To prove
it, the check declares its :class:`Forms` -- the printed form, a known-good form and the
*slips* a person could make in that formula (a sign, a swapped index, atan for asin, a
wrong link length, degrees for radians, a transposed rotation, the other branch of a
square root, an off-by-one in a table index), plus, where a tolerance is graded, the good
form moved by a tiny epsilon -- and takes the form as its second argument::

    @SECTION.check("Eq 4", forms=Forms(printed=eq4_printed, good=eq4_from_dh, good_is="...",
                   slips=(Slip(SIGN, "p_z with -l3 s2 as +l3 s2", eq4_sign_slip),),
                   tolerance=epsilon(eq4_printed, 1e-9)))
    def eq4_vs_pinocchio(ctx, eq4) -> Row: ...

(``SECTION`` is the module's :class:`Section`, the check sits at the index item ``"Eq 4"``'s place in
the report; :func:`register` is the general form.) A printed formula graded on ``max |form - truth|``
is declared as data instead, :class:`verification.formula.Formula`, and registered in bulk with
:meth:`Section.formulas`.

``iik verify`` calls it with ``forms.printed``; :func:`verification.self_test` calls it
again with ``forms.good`` (it must pass: :attr:`Verdict.passes`), with each slip and with
the tolerance form (each must make a graded row fail). A check that cannot flip by its nature (a byte
comparison, a transcription round trip, a statement that needs the real arm) says why
with ``by_construction="..."`` and is counted apart.

**Grades.** Each :class:`Row` is one thesis claim with its reference, the method, the
sampled domain, the measured numbers, a :class:`Verdict`, what the verdict depends on (ids
of :mod:`verification.assumptions`) and whether it grades the thesis's own claim or a
stricter project standard (:class:`Scope`). The verdict says what was measured: *holds*
(a measurement that could have failed), *holds by construction* (an identity or a round
trip through our own code: shown, not evidence), *consistent with our reconstruction* (it
rests on a reconstruction or assumption, named in ``basis``), *not checkable* (with its
reason), and on the other side *erratum* (a printed formula or number is wrong),
*input slip* (the printed result is right for a nearby reading of its stated inputs: the
slip is in the input), *does not hold* and *not reproduced on our reconstruction*. An
erratum is declared only after a second reading (:mod:`verification.second_reading`,
:meth:`Row.reread`). Only an exception inside a check (the software failing) makes
``iik verify`` exit non-zero.
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import re
import sys
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field, replace
from enum import Enum
from pathlib import Path
from typing import Any

import numpy as np

from iik.errors import InvalidInputError

from .assumptions import ASSUMPTIONS
from .errors import RegistrationError, RowError, SelectionError
from .second_reading import SecondReading
from .second_reading import Slip as Where

__all__ = [
    "Verdict",
    "Scope",
    "Erratum",
    "Measure",
    "verdict_of",
    "numbers_of",
    "Row",
    "SlipKind",
    "Slip",
    "epsilon",
    "Forms",
    "off_by",
    "Context",
    "Check",
    "register",
    "Section",
    "registered_checks",
    "selected_checks",
    "load_checks",
    "check_seed",
]


class Verdict(str, Enum):
    """Outcome of checking one thesis claim: what was measured, not only whether it agreed."""

    HOLDS = "holds"  # measured against an independent reference; it could have failed
    IDENTITY = "holds by construction"  # an identity or a round trip through our own code: not evidence
    RECONSTRUCTION = "consistent with our reconstruction"  # rests on a reconstruction/assumption (basis)
    INPUT_SLIP = "input slip"  # the printed result is right for a nearby reading of its stated input
    ERRATUM = "erratum"  # a printed formula/number is wrong (after a second reading); corrected form recorded
    DOES_NOT_HOLD = "does not hold"  # a claim (not a formula) is refuted by measurement
    NOT_REPRODUCED = "not reproduced on our reconstruction"  # fails, but only on a reconstruction (basis)
    NOT_CHECKABLE = "not checkable"  # with its reason

    @property
    def passes(self) -> bool:
        """True for the verdicts a known-good form must give (and a slip must not)."""
        return self in (Verdict.HOLDS, Verdict.IDENTITY, Verdict.RECONSTRUCTION)

    @property
    def group(self) -> str:
        """Where the report's opening counts it: ``confirmed``, ``refuted``, ``input slip``, ``not evidence``
        or ``untestable``."""
        return _GROUP[self]

    @property
    def needs_basis(self) -> bool:
        """True if the row must name what the verdict rests on instead of a measurement (``Row.basis``)."""
        return self in (Verdict.IDENTITY, Verdict.RECONSTRUCTION, Verdict.NOT_REPRODUCED)


_GROUP = {
    Verdict.HOLDS: "confirmed",
    Verdict.IDENTITY: "not evidence",
    Verdict.RECONSTRUCTION: "not evidence",
    Verdict.INPUT_SLIP: "input slip",
    Verdict.ERRATUM: "refuted",
    Verdict.DOES_NOT_HOLD: "refuted",
    Verdict.NOT_REPRODUCED: "not evidence",
    Verdict.NOT_CHECKABLE: "untestable",
}


class Scope(str, Enum):
    """Whose standard a row grades."""

    THESIS = "thesis"  # the thesis's own claim under its own criterion
    PROJECT = "project standard"  # a stricter standard of this project, reported separately


@dataclass(frozen=True)
class Erratum:
    """A printed formula that is wrong, with its correction and a counterexample.

    Attributes:
        equation: Where it is printed, e.g. ``"Eq 14"``.
        printed: The printed form (plain text or LaTeX).
        corrected: The corrected form that the project uses.
        counterexample: Concrete input (e.g. a joint vector in rad) and the
            discrepancy it produces.
    """

    equation: str
    printed: str
    corrected: str
    counterexample: str


@dataclass(frozen=True)
class Measure:
    """One measured number and the bound it is graded against.

    Attributes:
        name: What was measured, e.g. ``"max |printed - Pinocchio|"``.
        value: The measured value (SI units unless ``unit`` says otherwise).
        limit: The tolerance or threshold.
        unit: Unit of ``value`` and ``limit`` (display only).
        bound: ``"<="`` (holds if ``value <= limit``) or ``">="``.
    """

    name: str
    value: float
    limit: float
    unit: str = ""
    bound: str = "<="

    def __post_init__(self) -> None:
        if self.bound not in ("<=", ">="):
            raise RowError("measures", f"bound must be '<=' or '>=', got {self.bound!r}")
        object.__setattr__(self, "value", float(self.value))
        object.__setattr__(self, "limit", float(self.limit))

    @property
    def holds(self) -> bool:
        """True if the value is within its bound (NaN never holds)."""
        if np.isnan(self.value) or np.isnan(self.limit):
            return False
        return self.value <= self.limit if self.bound == "<=" else self.value >= self.limit

    def __str__(self) -> str:
        unit = f" {self.unit}" if self.unit else ""
        return f"{self.name} = {self.value:.3g}{unit} ({self.bound} {self.limit:.3g}{unit})"


def verdict_of(measures: Iterable[Measure], *, fail: Verdict = Verdict.ERRATUM) -> Verdict:
    """``HOLDS`` if every measure is within its bound, else ``fail``."""
    measures = tuple(measures)
    if not measures:
        raise RowError("measures", "a verdict needs at least one measure")
    return Verdict.HOLDS if all(m.holds for m in measures) else fail


def numbers_of(measures: Iterable[Measure]) -> str:
    """The measures as a row's numbers: ``"name = value unit (<= limit unit); ..."``."""
    return "; ".join(str(m) for m in measures)


_ID = re.compile(r"^[a-z0-9][a-z0-9_.-]*$")


@dataclass(frozen=True)
class Row:
    """One thesis claim and its verdict.

    Attributes:
        claim: The claim in words.
        reference: Equation, table or section, e.g. ``"Eq 4"``.
        method: How it was checked (against what ground truth, how many samples).
        numbers: The measured figures, e.g. ``"max |dp| = 2.2e-16 m over 10000 q"``.
        verdict: See :class:`Verdict`.
        reason: Required for ``NOT_CHECKABLE``; optional elsewhere.
        errata: Erratum records (for ``ERRATUM``).
        figures: Paths of PNG figures (relative to the report's folder).
        views: Paths of exported 3D views (``views/NAME/index.html``, relative to the report's
            folder; pages that play from disk, :func:`iik.planning.viewer.export`).
        id: Row id. A check gives a short local id (``"eq9a"``); the registry
            prefixes it with the check's module (``"ik.eq9a"``). Default: the
            check's function name.
        scope: The thesis's claim, or a stricter project standard.
        depends_on: Ids of :data:`verification.assumptions.ASSUMPTIONS` the verdict
            rests on. Default: those declared at registration.
        covers: Index keys this row grades (``"Eq 9a"``, ``"Table VI"``,
            ``"App. E"``, ``"Sec 4.3.1"``). Default: read from ``reference``.
        measures: The graded numbers (machine-readable; the verdict follows them).
        details: Rows of a grouped claim (App. C entries, Table VI sets): the
            group counts once, its details are listed below it.
        appendix: Long numbers (matrices) printed in the report's appendix.
        check: ``module:function`` of the check (set by the registry).
        basis: What a verdict that is not a measurement rests on: the identity or round trip of a
            ``IDENTITY`` row, the reconstruction or assumption of a ``RECONSTRUCTION`` /
            ``NOT_REPRODUCED`` row (required for those).
        domain: The sampled domain (joint ranges, how near the singular values, how many samples).
        second_reading: The search of nearby readings behind an ``ERRATUM`` or ``INPUT_SLIP`` verdict
            (:meth:`reread`).
    """

    claim: str
    reference: str
    method: str
    numbers: str
    verdict: Verdict
    reason: str = ""
    errata: tuple[Erratum, ...] = ()
    figures: tuple[str, ...] = ()
    views: tuple[str, ...] = ()
    id: str = ""
    scope: Scope = Scope.THESIS
    depends_on: tuple[str, ...] = ()
    covers: tuple[str, ...] = ()
    measures: tuple[Measure, ...] = ()
    details: tuple[Row, ...] = ()
    appendix: str = ""
    check: str = ""
    basis: str = ""
    domain: str = ""
    second_reading: SecondReading | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.verdict, Verdict):
            raise RowError("verdict", f"must be a Verdict, got {self.verdict!r}")
        if self.verdict is Verdict.NOT_CHECKABLE and not self.reason:
            raise RowError("reason", "a NOT_CHECKABLE row needs a reason")
        if self.verdict in (Verdict.ERRATUM, Verdict.INPUT_SLIP) and not self.errata:
            raise RowError("errata", f"an {self.verdict.name} row needs at least one Erratum record")
        if self.verdict is Verdict.INPUT_SLIP and (
            self.second_reading is None or self.second_reading.slip is not Where.INPUT
        ):
            raise RowError("second_reading", "an INPUT_SLIP row needs the second reading that reproduces it")
        if self.verdict.needs_basis and not self.basis:
            raise RowError("basis", f"a {self.verdict.name} row must name what it rests on")
        if self.id and not _ID.match(self.id):
            raise RowError("id", f"{self.id!r} must be lowercase letters, digits, '.', '_' or '-'")
        unknown = [a for a in self.depends_on if a not in ASSUMPTIONS]
        if unknown:
            raise RowError("depends_on", f"unknown assumption(s) {unknown}; known: {', '.join(ASSUMPTIONS)}")
        for name in ("errata", "figures", "views", "depends_on", "covers", "measures", "details"):
            object.__setattr__(self, name, tuple(getattr(self, name)))

    def replace(self, **changes) -> Row:
        """A copy with ``changes`` applied (rows are frozen)."""
        return replace(self, **changes)

    @classmethod
    def graded(
        cls,
        claim: str,
        reference: str,
        method: str,
        numbers: str | None,
        measures: Iterable[Measure],
        *,
        fail: Verdict = Verdict.ERRATUM,
        holds_as: Verdict = Verdict.HOLDS,
        erratum: Erratum | None = None,
        reason: str = "",
        **fields,
    ) -> Row:
        """A row whose verdict follows its ``measures``: ``holds_as`` (HOLDS, or IDENTITY /
        RECONSTRUCTION for a row that is not evidence, with its ``basis``) if every measure is within
        its bound, else ``fail``; the ``erratum`` and the ``reason`` are recorded only if it fails.
        ``numbers`` None: the measures themselves (:func:`numbers_of`)."""
        measures = tuple(measures)
        numbers = numbers_of(measures) if numbers is None else numbers
        failed = verdict_of(measures, fail=fail) is not Verdict.HOLDS
        return cls(
            claim,
            reference,
            method,
            numbers,
            fail if failed else holds_as,
            measures=measures,
            errata=(erratum,) if failed and erratum is not None else (),
            reason=reason if failed else "",
            **fields,
        )

    @classmethod
    def grouped(
        cls,
        claim: str,
        reference: str,
        method: str,
        numbers: str | None,
        details: Iterable[Row],
        counted: str,
        *,
        fail: Verdict | None = Verdict.DOES_NOT_HOLD,
        holds_as: Verdict = Verdict.HOLDS,
        passing: str = "pass",
        failing: str = "not",
        reason: str = "",
        **fields,
    ) -> Row:
        """A group row over its ``details`` (App. C entries, Table VI sets, scenarios, the quantities
        printed at a point): it counts once and lists them below it. Graded on one measure named
        ``counted``, the number of details that do not pass (bound 0): ``holds_as`` if none fails, else
        ``fail`` (None: the worst verdict among the failing details, in the order of :data:`_WORST`). It
        carries its details' errata; an ``INPUT_SLIP`` group the second reading of its first input-slip
        detail; ``reason`` only if it fails. ``numbers`` None: ``"k of n {passing}"`` and, if any fail,
        ``"; {failing}: "`` with their ids."""
        details = tuple(details)
        bad = [d for d in details if not d.verdict.passes]
        verdict = (fail or next(v for v in _WORST if any(d.verdict is v for d in bad))) if bad else holds_as
        if numbers is None:
            numbers = f"{len(details) - len(bad)} of {len(details)} {passing}"
            numbers += f"; {failing}: {', '.join(d.id for d in bad)}" if bad else ""
        if verdict is Verdict.INPUT_SLIP:
            slips = (d.second_reading for d in bad if d.verdict is Verdict.INPUT_SLIP)
            fields.setdefault("second_reading", next(slips, None))
        return cls(
            claim,
            reference,
            method,
            numbers,
            verdict,
            measures=(Measure(counted, len(bad), 0),),
            details=details,
            errata=tuple(e for d in details for e in d.errata),
            reason=reason if bad else "",
            **fields,
        )

    def reread_if_erratum(self, second: Callable[[], SecondReading]) -> Row:
        """:meth:`reread` by ``second()`` if this row is an erratum (the search runs only then), else the
        row itself."""
        return self.reread(second()) if self.verdict is Verdict.ERRATUM else self

    def reread(self, second: SecondReading) -> Row:
        """This row after the second reading ``second`` of its printed value.

        An ``ERRATUM`` survives only if no reading of the stated inputs reproduces the printed value:
        reproduced as stated, it is withdrawn (``HOLDS``, errata dropped); reproduced by a nearby
        reading of an input, it becomes ``INPUT_SLIP`` (the errata keep the correction). Any other
        verdict is kept; the record is attached either way."""
        verdict, errata = self.verdict, self.errata
        if self.verdict is Verdict.ERRATUM:
            if second.slip is Where.NONE:
                verdict, errata = Verdict.HOLDS, ()
            elif second.slip is Where.INPUT:
                verdict = Verdict.INPUT_SLIP
        return replace(self, verdict=verdict, errata=errata,
                       second_reading=replace(second, before=self.verdict.value))


#: A failing group's verdict when it takes its details' worst (:meth:`Row.grouped`), worst first.
_WORST = (
    Verdict.DOES_NOT_HOLD,
    Verdict.ERRATUM,
    Verdict.INPUT_SLIP,
    Verdict.NOT_REPRODUCED,
    Verdict.NOT_CHECKABLE,
)
_RIGHT = "the printed form (it is right)"


class SlipKind(str, Enum):
    """The kinds of mistake a person makes in a formula (the self-test's slips), and the tolerance test."""

    SIGN = "sign"
    SWAP = "swapped index"
    FUNCTION = "wrong function"  # atan for asin, atan for atan2, cos for sin
    LENGTH = "wrong link length"
    UNIT = "degree/radian"
    TRANSPOSE = "transposed rotation"
    BRANCH = "other branch"  # of a square root, of acos, of atan2
    OFF_BY_ONE = "off by one"  # a table index, a joint number, a row
    TERM = "dropped or extra term"
    LIMIT = "other joint limit"
    CLAIM = "stronger or weaker claim"  # for claims about counts, shares, sets
    MODEL = "wrong model or method"  # a wrong frame, convention or procedure
    EPSILON = "epsilon (tolerance test)"


@dataclass(frozen=True)
class Slip:
    """A deliberately wrong form for the self-test.

    Attributes:
        kind: Which kind of mistake (:class:`SlipKind`).
        what: The mistake in words, e.g. ``"-l3 s2 written +l3 s2"``.
        form: The form with the mistake (same type as the printed one).
    """

    kind: SlipKind
    what: str
    form: Any

    def __post_init__(self) -> None:
        if not isinstance(self.kind, SlipKind):
            raise RegistrationError(self.what, f"slip kind must be a SlipKind, got {self.kind!r}")


def epsilon(form: Callable, eps: float, what: str = "", at: tuple[int, ...] = ()) -> Slip:
    """The tolerance test: ``form`` with its output moved by ``eps`` (at ``at``, :func:`off_by`)."""
    return Slip(SlipKind.EPSILON, what or f"the good form moved by {eps:g}", off_by(form, eps, at))


@dataclass(frozen=True)
class Forms:
    """The forms a falsifiable check measures (see the module docstring).

    Attributes:
        printed: The thesis's form (a function, a table, printed numbers).
        good: A known-good form: the check must pass with it (:attr:`Verdict.passes`).
        good_is: What the good form is (for the self-test listing).
        slips: Realistic mistakes in the formula (:class:`Slip`, not epsilon ones): each must be caught.
        tolerance: The good form moved by a tiny epsilon (:func:`epsilon`): shows the tolerance bites;
            ``None`` where nothing is graded against a tolerance.
        rows: Local ids of the rows the self-test grades; empty = every row of the check.
    """

    printed: Any
    good: Any
    good_is: str
    slips: tuple[Slip, ...]
    tolerance: Slip | None = None
    rows: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        object.__setattr__(self, "slips", tuple(self.slips))
        object.__setattr__(self, "rows", tuple(self.rows))
        if not self.slips:
            raise RegistrationError(self.good_is, "forms need at least one realistic slip")
        for sl in self.slips:
            if not isinstance(sl, Slip) or sl.kind is SlipKind.EPSILON:
                raise RegistrationError(sl.what if isinstance(sl, Slip) else repr(sl),
                                        "a slip must be a realistic Slip (the epsilon form is `tolerance`)")
        if self.tolerance is not None and (
            not isinstance(self.tolerance, Slip) or self.tolerance.kind is not SlipKind.EPSILON
        ):
            raise RegistrationError(self.good_is, "tolerance must be an epsilon Slip (verification.epsilon)")

    @classmethod
    def right(cls, form, slips: Iterable[Slip], *, tolerance: Slip | None = None, good_is: str = _RIGHT,
              rows=()) -> Forms:
        """Forms of a form printed right: it is also the good one."""
        return cls(form, form, good_is, tuple(slips), tolerance, tuple(rows))

    @property
    def slips_is(self) -> str:
        """The slips (and the tolerance test) in words."""
        parts = [f"{s.kind.value}: {s.what}" for s in self.slips]
        if self.tolerance is not None:
            parts.append(f"tolerance: {self.tolerance.what}")
        return "; ".join(parts)


def off_by(form: Callable, eps: float, at: tuple[int, ...] = ()) -> Callable:
    """``form`` with its output moved by ``eps`` (the tolerance test's form): every entry of an array
    output, or only the trailing index ``at`` (e.g. ``(2, 3)``: p_z of (..., 4, 4) poses); a list,
    tuple or dict of arrays is moved array by array."""

    def move(v):
        if isinstance(v, dict):
            return {k: move(x) for k, x in v.items()}
        if isinstance(v, (list, tuple)):
            return type(v)(move(x) for x in v)
        v = np.array(v, dtype=float, copy=True)
        v[(..., *at)] += eps
        return v

    return lambda *args, **kwargs: move(form(*args, **kwargs))


def check_seed(seed) -> int:
    """``seed`` if it is a non-negative integer below 2**63 (what every generator of a run derives
    from, :meth:`Context.rng`); else :class:`~iik.errors.InvalidInputError` (argument ``seed``)."""
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or not 0 <= seed < 2**63:
        raise InvalidInputError("seed", f"expected an integer in 0 .. 2**63 - 1, got {seed!r}")
    return int(seed)


@dataclass
class Context:
    """What a check may use.

    Attributes:
        out_dir: Folder of the report; figures go to ``out_dir / "figures"``.
        seed: Seed for every random sample a check draws.
        quick: If true, checks use small sample sizes (tests, notebooks).
        cache: Scratch space shared by checks in one run (e.g. a loaded model). Never
            cache anything computed from a check's form: the self-test reruns the check
            with other forms in the same context.
    """

    out_dir: Path
    seed: int = 20120101
    quick: bool = False
    cache: dict = field(default_factory=dict)

    def __post_init__(self) -> None:
        self.seed = check_seed(self.seed)

    def rng(self, salt: int | str = 0) -> np.random.Generator:
        """A generator seeded by ``seed`` and ``salt``, reproducible per check."""
        if isinstance(salt, str):
            salt = sum(ord(ch) * 131**i for i, ch in enumerate(salt)) % (2**31)
        return np.random.default_rng([self.seed, salt])

    def n(self, full: int, quick: int) -> int:
        """Sample size: ``quick`` in quick mode, else ``full``."""
        return quick if self.quick else full

    def figure_path(self, name: str) -> tuple[Path, str]:
        """Return ``(absolute path, path relative to the report)`` for a PNG."""
        fig_dir = self.out_dir / "figures"
        fig_dir.mkdir(parents=True, exist_ok=True)
        return fig_dir / name, f"figures/{name}"

    def view_path(self, name: str) -> tuple[Path, str]:
        """Return ``(absolute folder, relative page path)`` of the exported 3D view ``views/name``."""
        return self.out_dir / "views" / name, f"views/{name}/index.html"

    def save_figure(self, fig, name: str, dpi: int = 90) -> str:
        """Lay out, save as ``figures/name`` and close a matplotlib figure; return its
        path relative to the report (for :attr:`Row.figures`)."""
        import matplotlib.pyplot as plt

        path, rel = self.figure_path(name)
        fig.tight_layout()
        fig.savefig(path, dpi=dpi)
        plt.close(fig)
        return rel


@dataclass(frozen=True)
class Check:
    """A registered check.

    Attributes:
        name: ``module.function``.
        section: Report section.
        order: Sort key of the section (its smallest order) and of the check in it.
        func: ``func(ctx)`` or, with ``forms``, ``func(ctx, form)``.
        forms: The printed / good / bad forms (falsifiable checks).
        by_construction: Why the check cannot flip, for checks without forms.
        depends_on: Default assumptions of its rows.
        prefix: Prefix of its row ids (the module's short name).
    """

    name: str
    section: str
    order: float
    func: Callable[..., Row | Iterable[Row]]
    forms: Forms | None = None
    by_construction: str = ""
    depends_on: tuple[str, ...] = ()
    prefix: str = ""

    @property
    def where(self) -> str:
        """``module:function`` (what a report row names as its check)."""
        return f"{self.func.__module__}:{self.func.__qualname__}"

    def run(self, ctx: Context, form: Any = None, *, use_printed: bool = True) -> list[Row]:
        """Run the check (with ``forms.printed``, or with ``form`` if ``use_printed`` is
        false) and return its rows with ids, check name and default assumptions filled in."""
        if self.forms is not None:
            out = self.func(ctx, self.forms.printed if use_printed else form)
        else:
            out = self.func(ctx)
        rows = [out] if isinstance(out, Row) else list(out)
        for r in rows:
            if not isinstance(r, Row):
                raise TypeError(f"check {self.name} returned {type(r).__name__}, not Row")
        return self._finish(rows)

    def _finish(self, rows: list[Row]) -> list[Row]:
        seen: dict[str, int] = {}
        out = []
        for r in rows:
            local = r.id or self.func.__name__
            seen[local] = seen.get(local, 0) + 1
            if seen[local] > 1:
                local = f"{local}-{seen[local]}"
            rid = f"{self.prefix}.{local}"
            details = tuple(
                d.replace(
                    id=f"{rid}.{d.id or k + 1}",
                    check=self.where,
                    depends_on=d.depends_on or r.depends_on or self.depends_on,
                )
                for k, d in enumerate(r.details)
            )
            out.append(
                r.replace(
                    id=rid, check=self.where, details=details, depends_on=r.depends_on or self.depends_on
                )
            )
        return out

    def local_id(self, row_id: str) -> str:
        """The id a check gave a row (``row_id`` without the prefix)."""
        return row_id[len(self.prefix) + 1 :] if row_id.startswith(self.prefix + ".") else row_id


_REGISTRY: dict[str, Check] = {}


def _takes_form(func) -> bool:
    try:
        params = list(inspect.signature(func).parameters.values())
    except (TypeError, ValueError):
        return False
    positional = [p for p in params if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)]
    return len(positional) >= 2 or any(p.kind is p.VAR_POSITIONAL for p in params)


def register(
    section: str,
    order: float = 0.0,
    name: str | None = None,
    *,
    forms: Forms | None = None,
    by_construction: str = "",
    depends_on: Iterable[str] = (),
    prefix: str | None = None,
):
    """Decorator: register ``func`` as a check in report ``section``.

    Args:
        section: Report section (checks of one section are listed together).
        order: Sorts sections (by their smallest order) and checks within them.
        name: Registry key; default ``module.function``.
        forms: Printed / good / bad forms; then ``func(ctx, form)``.
        by_construction: Why the check cannot flip (no forms).
        depends_on: Default assumption ids of the check's rows.
        prefix: Row-id prefix; default the module's last name (``"kinematics"``).

    Raises:
        RegistrationError: the same name twice, forms and ``by_construction`` together,
            forms on a function without a form argument, or an unknown assumption.
    """
    depends_on = tuple(depends_on)

    def deco(func):
        key = name or f"{func.__module__}.{func.__qualname__}"
        if key in _REGISTRY and _REGISTRY[key].func is not func:
            raise RegistrationError(key, "registered twice")
        if forms is not None and by_construction:
            raise RegistrationError(key, "declares forms and 'by construction' at once")
        if forms is not None and not isinstance(forms, Forms):
            raise RegistrationError(key, f"forms must be a Forms, got {type(forms).__name__}")
        if forms is not None and not _takes_form(func):
            raise RegistrationError(
                key, "declares forms but its function takes no form argument (expected func(ctx, form))"
            )
        if forms is not None and not (forms.good_is and all(sl.what for sl in forms.slips)):
            raise RegistrationError(key, "forms need a good_is description and every slip its 'what'")
        unknown = [a for a in depends_on if a not in ASSUMPTIONS]
        if unknown:
            raise RegistrationError(key, f"unknown assumption(s) {unknown}")
        pre = prefix or func.__module__.rsplit(".", 1)[-1]
        if not _ID.match(pre):
            raise RegistrationError(key, f"row-id prefix {pre!r} is not a valid id")
        _REGISTRY[key] = Check(
            name=key,
            section=section,
            order=order,
            func=func,
            forms=forms,
            by_construction=by_construction,
            depends_on=depends_on,
            prefix=pre,
        )
        return func

    return deco


@dataclass(frozen=True)
class Section:
    """A report section and what its checks have in common.

    A check module declares its section once and registers each check through it, at the place of the
    thesis index item it grades (or at an explicit ``order``)::

        SECTION = Section("Kinematics (...)", depends_on=("l1", "lengths", "pinocchio"), order=10)

        @SECTION.check("Eq 4", forms=Forms(...))
        def eq4_vs_pinocchio(ctx, eq4) -> Row: ...

    and a family of printed formulas in bulk (:meth:`formulas`).

    Attributes:
        title: The section's heading in the report (:attr:`Check.section`).
        depends_on: Default assumptions of its checks' rows.
        prefix: Row-id prefix of its checks; default: each check's module name.
        order: The section's place among the sections; a check declared by an index key sorts at
            ``order`` plus its key's place in the thesis index (ties: in the order declared).
    """

    title: str
    depends_on: tuple[str, ...] = ()
    prefix: str | None = None
    order: float = 0.0

    def place(self, order: float | str) -> float:
        """The sort key of a check declared at ``order``: a number as given, or an index key's place
        after the section's ``order`` (:func:`verification.thesis_index.rank_of`; ties keep the order
        of declaration)."""
        if not isinstance(order, str):
            return float(order)
        from .thesis_index import rank_of

        try:
            rank = rank_of(order)
        except KeyError as exc:
            raise RegistrationError(order, str(exc)) from None
        return self.order + (rank + 1) * 1e-3 + len(_REGISTRY) * 1e-7

    def check(
        self,
        order: float | str,
        *,
        forms: Forms | None = None,
        by_construction: str = "",
        depends_on: Iterable[str] | None = None,
        name: str | None = None,
    ):
        """Decorator: :func:`register` a check of this section at ``order`` (a number or an index key,
        :meth:`place`); ``depends_on``, if given, replaces the section's default."""
        return register(
            self.title,
            self.place(order),
            name,
            forms=forms,
            by_construction=by_construction,
            depends_on=self.depends_on if depends_on is None else depends_on,
            prefix=self.prefix,
        )

    def formulas(self, sample: Callable, *formulas) -> dict[str, Callable]:
        """Register each :class:`~verification.formula.Formula` as a check of this section measured on
        ``sample(ctx)``, at its key's place in the index (or its ``order``); return the check functions by
        row id.

        The checks belong to the calling module (their names, row-id prefix and report entries)."""
        module = sys._getframe(1).f_globals.get("__name__", __name__)
        out = {}
        for f in formulas:
            func = f.check(sample)
            func.__module__ = module
            out[f.rid] = self.check(f.key if f.order is None else f.order, forms=f.forms,
                                    depends_on=f.depends_on)(func)
        return out


def load_checks() -> None:
    """Import every module of :mod:`verification.checks` (registering its checks)."""
    from . import checks

    for info in sorted(pkgutil.iter_modules(checks.__path__), key=lambda m: m.name):
        importlib.import_module(f"{checks.__name__}.{info.name}")


def registered_checks() -> list[Check]:
    """All registered checks, sorted by (section order, order, name)."""
    load_checks()
    first = {}
    for c in _REGISTRY.values():
        first[c.section] = min(first.get(c.section, c.order), c.order)
    return sorted(_REGISTRY.values(), key=lambda c: (first[c.section], c.section, c.order, c.name))


def selected_checks(select: Iterable[str] | None = None) -> list[Check]:
    """The registered checks whose name or section contains an item of ``select`` (all if it is
    None or empty), in :func:`registered_checks` order.

    Raises:
        SelectionError: an item matches no check (a typo would otherwise run nothing, or less
            than meant, and write a report of it).
    """
    checks = registered_checks()
    items = [str(s) for s in (select or ())]
    if not items:
        return checks
    unmatched = [s for s in items if not any(s in c.name or s in c.section for c in checks)]
    if unmatched:
        modules = sorted({c.name.split(".")[-2] for c in checks})
        verb = "matches" if len(unmatched) == 1 else "match"
        raise SelectionError(unmatched, f"{', '.join(map(repr, unmatched))} {verb} no check's name or "
                                        f"section (e.g. a check module: {', '.join(modules)})")
    return [c for c in checks if any(s in c.name or s in c.section for s in items)]
