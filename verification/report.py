"""Run the registered checks and write ``verification.md``.

The report has one table row per thesis claim (claim, reference, method,
numbers, verdict), grouped by section, followed by the errata with their
printed and corrected forms and counterexamples, and the figures.
"""

from __future__ import annotations

import time
import traceback
from collections import Counter
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

from .registry import Check, Context, Row, Verdict, registered_checks

__all__ = ["CheckResult", "Verification", "verify", "run_checks", "write_report", "summary"]


@dataclass(frozen=True)
class CheckResult:
    """Outcome of running one check: its rows, or the error it raised."""

    check: Check
    rows: tuple[Row, ...]
    seconds: float
    error: str | None = None  # traceback text if the software failed


def run_checks(
    ctx: Context,
    *,
    select: Sequence[str] | None = None,
    progress: Callable[[int, int, Check, CheckResult | None], None] | None = None,
) -> list[CheckResult]:
    """Run every registered check (or those whose name contains a ``select`` item).

    ``progress(i, n, check, result)`` is called before (result None) and after
    each check.
    """
    checks = registered_checks()
    if select:
        checks = [c for c in checks if any(s in c.name or s in c.section for s in select)]
    results = []
    for i, chk in enumerate(checks):
        if progress:
            progress(i, len(checks), chk, None)
        t0 = time.perf_counter()
        try:
            rows, err = tuple(chk.run(ctx)), None
        except Exception:  # a failing check is a software failure, reported
            rows, err = (), traceback.format_exc()
        res = CheckResult(chk, rows, time.perf_counter() - t0, err)
        results.append(res)
        if progress:
            progress(i, len(checks), chk, res)
    return results


@dataclass(frozen=True)
class Verification:
    """Outcome of :func:`verify`: every check's result, the report written, the time taken [s]."""

    results: tuple[CheckResult, ...]
    report: Path
    seconds: float

    @property
    def failed(self) -> bool:
        """True if any check failed to run (a software failure, not a verdict)."""
        return any(r.error for r in self.results)

    def summary(self) -> str:
        """A few lines for the terminal (:func:`summary`)."""
        return summary(self.results)


def verify(out_dir: Path, *, quick: bool = False, seed: int = 20120101, select: Sequence[str] | None = None,
           progress: Callable[[int, int, Check, CheckResult | None], None] | None = None) -> Verification:
    """Run every registered check (:func:`run_checks`) and write ``out_dir/verification.md``.

    The report is the same whether this is called from Python or by ``iik verify``:
    every module of :mod:`verification.checks` registers its checks on loading.
    """
    t0 = time.perf_counter()
    Path(out_dir).mkdir(parents=True, exist_ok=True)  # fail before the checks run, not after
    results = run_checks(Context(out_dir=Path(out_dir), seed=seed, quick=quick), select=select,
                         progress=progress)
    path = write_report(results, Path(out_dir) / "verification.md")
    return Verification(tuple(results), path, time.perf_counter() - t0)


def _cell(text: str) -> str:
    return str(text).replace("|", "\\|").replace("\n", "<br>")


def write_report(results: Iterable[CheckResult], path: Path, *, title: str | None = None) -> Path:
    """Write the markdown report to ``path`` and return it."""
    results = list(results)
    path.parent.mkdir(parents=True, exist_ok=True)
    counts = Counter(r.verdict for res in results for r in res.rows)
    failures = [res for res in results if res.error]
    lines = [f"# {title or 'Verification report'}", ""]
    lines.append(
        "Each row is one claim of C. A. Mondragon Sanchez, *Dynamics and Motion of a Six "
        "Degree of Freedom Robot Manipulator*, M.Sc. thesis, University of Saskatchewan, 2012, "
        "checked by machine. Units: SI (m, rad) unless a cell says otherwise. "
        "`l1 = 0.300 m` is an assumption (see `iik.THESIS_ARM.assumptions`)."
    )
    lines.append("")
    lines.append(
        "Summary: "
        + ", ".join(f"{counts.get(v, 0)} {v.value}" for v in Verdict)
        + f"; {len(failures)} check(s) failed to run."
    )
    lines.append("")
    section = None
    errata = []
    figures = []
    for res in results:
        if res.check.section != section:
            section = res.check.section
            lines += ["", f"## {section}", "",
                      "| claim | reference | method | numbers | verdict |",
                      "|---|---|---|---|---|"]
        if res.error:
            lines.append(f"| `{res.check.name}` | | | | **software failure** (see below) |")
        for r in res.rows:
            verdict = r.verdict.value + (f": {r.reason}" if r.reason else "")
            lines.append(
                f"| {_cell(r.claim)} | {_cell(r.reference)} | {_cell(r.method)} | "
                f"{_cell(r.numbers)} | **{_cell(verdict)}** |"
            )
            errata += r.errata
            figures += [(r.claim, f) for f in r.figures]
    if errata:
        lines += ["", "## Errata", "",
                  "| equation | printed | corrected | counterexample |", "|---|---|---|---|"]
        for e in errata:
            lines.append(
                f"| {_cell(e.equation)} | {_cell(e.printed)} | {_cell(e.corrected)} | "
                f"{_cell(e.counterexample)} |"
            )
    if figures:
        lines += ["", "## Figures", ""]
        for claim, f in figures:
            lines += [f"![{_cell(claim)}]({f})", ""]
    if failures:
        lines += ["", "## Software failures", ""]
        for res in failures:
            lines += [f"### `{res.check.name}`", "", "```", res.error.rstrip(), "```", ""]
    lines += ["", "## Timing", "", "| check | seconds |", "|---|---|"]
    lines += [f"| `{res.check.name}` | {res.seconds:.2f} |" for res in results]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def summary(results: Iterable[CheckResult]) -> str:
    """A few lines for the terminal."""
    results = list(results)
    counts = Counter(r.verdict for res in results for r in res.rows)
    n_err = sum(1 for res in results if res.error)
    out = [
        f"{sum(counts.values())} claims from {len(results)} checks: "
        + ", ".join(f"{counts.get(v, 0)} {v.value}" for v in Verdict)
    ]
    for res in results:
        for r in res.rows:
            if r.verdict is Verdict.ERRATUM:
                out.append(f"  erratum: {r.reference}: " + "; ".join(e.equation for e in r.errata))
            elif r.verdict is Verdict.DOES_NOT_HOLD:
                out.append(f"  does not hold: {r.reference}: {r.claim}")
    if n_err:
        out.append(f"  {n_err} check(s) FAILED TO RUN: "
                   + ", ".join(res.check.name for res in results if res.error))
    return "\n".join(out)
