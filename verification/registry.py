"""The registry of thesis checks behind ``iik verify``.

A check is a function ``check(ctx) -> Row | Iterable[Row]`` registered with
:func:`register`. Every module in :mod:`verification.checks` is imported by
:func:`load_checks`, so a new feature adds its checks by adding a module there;
no central list is edited.

Each :class:`Row` is one thesis claim with its reference (equation, table or
section), the method used to check it, the measured numbers, and a
:class:`Verdict`. A printed formula that is wrong gives ``Verdict.ERRATUM``
with one or more :class:`Erratum` records; that is a finding, not a failure.
Only an exception inside a check (the software failing) makes ``iik verify``
exit non-zero.
"""

from __future__ import annotations

import importlib
import pkgutil
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from enum import Enum
from pathlib import Path

import numpy as np

__all__ = [
    "Verdict",
    "Erratum",
    "Row",
    "Context",
    "Check",
    "register",
    "registered_checks",
    "load_checks",
]


class Verdict(str, Enum):
    """Outcome of checking one thesis claim."""

    HOLDS = "holds"
    ERRATUM = "erratum"  # a printed formula/number is wrong; corrected form recorded
    DOES_NOT_HOLD = "does not hold"  # a claim (not a formula) is refuted by measurement
    NOT_CHECKABLE = "not checkable"  # with its reason


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
    """

    claim: str
    reference: str
    method: str
    numbers: str
    verdict: Verdict
    reason: str = ""
    errata: tuple[Erratum, ...] = ()
    figures: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if self.verdict is Verdict.NOT_CHECKABLE and not self.reason:
            raise ValueError("a NOT_CHECKABLE row needs a reason")
        if self.verdict is Verdict.ERRATUM and not self.errata:
            raise ValueError("an ERRATUM row needs at least one Erratum record")


@dataclass
class Context:
    """What a check may use.

    Attributes:
        out_dir: Folder of the report; figures go to ``out_dir / "figures"``.
        seed: Seed for every random sample a check draws.
        quick: If true, checks use small sample sizes (tests, notebooks).
        cache: Scratch space shared by checks in one run (e.g. a loaded model).
    """

    out_dir: Path
    seed: int = 20120101
    quick: bool = False
    cache: dict = field(default_factory=dict)

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
    """A registered check."""

    name: str
    section: str
    order: float
    func: Callable[[Context], Row | Iterable[Row]]

    def run(self, ctx: Context) -> list[Row]:
        out = self.func(ctx)
        rows = [out] if isinstance(out, Row) else list(out)
        for r in rows:
            if not isinstance(r, Row):
                raise TypeError(f"check {self.name} returned {type(r).__name__}, not Row")
        return rows


_REGISTRY: dict[str, Check] = {}


def register(section: str, order: float = 0.0, name: str | None = None):
    """Decorator: register ``func(ctx)`` as a check in report ``section``.

    ``order`` sorts sections (by their smallest order) and checks within them.
    """

    def deco(func):
        key = name or f"{func.__module__}.{func.__qualname__}"
        if key in _REGISTRY and _REGISTRY[key].func is not func:
            raise ValueError(f"check {key!r} registered twice")
        _REGISTRY[key] = Check(name=key, section=section, order=order, func=func)
        return func

    return deco


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
