"""Run the registered checks and write ``verification.json`` and ``verification.md``.

The JSON document is the report: one record per row (id, claim, reference, verdict,
numbers, measures, depends_on, check, figures, ...), the index of the thesis
(:mod:`verification.thesis_index`) with the rows that grade each item, per-chapter
counts and a header (commit, versions, seed, machine). It follows
``report.schema.json``. The markdown is rendered from that document
(:func:`verification.markdown.render`), and notebooks read it back with
:func:`read_report`.

Counting: a grouped claim (App. C entries, Table VI sets, Table VII groups) is one row
with its entries as ``details``; the headline counts top-level rows only, thesis claims
and project standards apart, every :class:`~verification.registry.Verdict` separately, and
groups them (confirmed, refuted, input slips, not evidence, untestable). Every erratum and
input slip carries its second reading (:mod:`verification.second_reading`); a report whose
errata lack one is refused (a bug in a check, not a finding).
"""

from __future__ import annotations

import json
import time
import traceback
from collections import Counter
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

from iik.errors import FileError
from iik.files import atomic_output, read_text

from .assumptions import ASSUMPTIONS
from .errors import ReportError, RowError
from .markdown import render
from .provenance import provenance
from .registry import Check, Context, Row, Scope, Verdict, selected_checks
from .schema import schema_errors
from .second_reading import SecondReading
from .thesis_index import ITEMS, chapter_of, chapter_of_reference, parse_refs

__all__ = ["CheckResult", "Verification", "verify", "run_checks", "report_document", "write_report",
           "read_report", "summary", "unread_errata", "FORMAT", "GROUPS", "QUICK_TITLE", "REPORT_FILES",
           "MAX_REPORT_BYTES", "partial_title"]

#: The ``format`` field of every report document.
FORMAT = "iik-verification-report/2"
#: The title of a ``--quick`` report: its first line says so (markdown heading, first JSON field).
QUICK_TITLE = "QUICK verification report (small samples, not the report of record: run `iik verify`)"
#: What :func:`verify` writes into its folder (a folder holding anything else is not replaced).
REPORT_FILES = ("verification.md", "verification.json", "figures", "views")
#: Largest ``verification.json`` :func:`read_report` reads [bytes] (a full report is about 1 MB).
MAX_REPORT_BYTES = 50_000_000


def partial_title(select: Sequence[str], quick: bool) -> str:
    """The title of a run of only some checks (``iik verify --only``): its first line says so."""
    only = ", ".join(f"'{s}'" for s in select)
    small = "; small samples" if quick else ""
    return (f"PARTIAL verification report (only the checks matching {only}{small}: not the report of record: "
            "run `iik verify`)")


@dataclass(frozen=True)
class CheckResult:
    """Outcome of running one check: its rows, or the error it raised.

    Attributes:
        check: The check.
        rows: Its rows (ids and check name filled in).
        seconds: Wall time of the check [s].
        error: Traceback text if the software failed.
        seed, quick: The run's context (for the report header).
    """

    check: Check
    rows: tuple[Row, ...]
    seconds: float
    error: str | None = None
    seed: int = 0
    quick: bool = False


def run_checks(
    ctx: Context,
    *,
    select: Sequence[str] | None = None,
    progress: Callable[[int, int, Check, CheckResult | None], None] | None = None,
) -> list[CheckResult]:
    """Run every registered check (or those whose name or section contains a ``select`` item;
    :class:`~verification.errors.SelectionError` if an item matches none).

    ``progress(i, n, check, result)`` is called before (result None) and after each check.
    """
    checks = selected_checks(select)
    results = []
    for i, chk in enumerate(checks):
        if progress:
            progress(i, len(checks), chk, None)
        t0 = time.perf_counter()
        try:
            rows, err = tuple(chk.run(ctx)), None
        except Exception:  # a failing check is a software failure, reported
            rows, err = (), traceback.format_exc()
        res = CheckResult(chk, rows, time.perf_counter() - t0, err, ctx.seed, ctx.quick)
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
    every module of :mod:`verification.checks` registers its checks on loading. The folder
    is written whole or not at all (:func:`iik.files.atomic_output`): figures, views and
    the report go into a temporary sibling that replaces ``out_dir`` when complete, so an
    error or an interrupt (Ctrl-C, SIGTERM, SIGHUP) leaves the previous report as it was.
    A run of only some checks (``select``) is titled as such (:func:`partial_title`).

    Raises:
        SelectionError: an item of ``select`` matches no check (nothing is run or written).
        InvalidInputError: ``seed`` is not an integer in 0 .. 2**63 - 1.
        FileError: (argument ``out_dir``) ``out_dir`` is a file, holds other things than
            :data:`REPORT_FILES`, or cannot be written.
    """
    t0 = time.perf_counter()
    select = list(select or ())
    selected_checks(select)  # a selection that matches nothing fails here, before anything is written
    ctx = Context(out_dir=Path(out_dir), seed=seed, quick=quick)  # (checks the seed)
    with atomic_output(out_dir, "out_dir", folder=True, owns=REPORT_FILES) as out:
        ctx.out_dir = out.path
        results = run_checks(ctx, select=select, progress=progress)
        title = partial_title(select, quick) if select else None
        write_report(results, out.path / "verification.md", title=title, only=select or None)
    return Verification(tuple(results), Path(out_dir) / "verification.md", time.perf_counter() - t0)


def _counts(rows: Iterable[dict]) -> dict:
    c = Counter(r["verdict"] for r in rows)
    return {v.value: c.get(v.value, 0) for v in Verdict}


#: The groups of the report's opening, in order.
GROUPS = ("confirmed", "refuted", "input slip", "not evidence", "untestable")


def _groups(counts: dict) -> dict:
    out = dict.fromkeys(GROUPS, 0)
    for v in Verdict:
        out[v.group] += counts[v.value]
    return out


def _reading_record(sr: SecondReading | None) -> dict | None:
    if sr is None:
        return None
    return {
        "printed": sr.printed,
        "stated": sr.stated,
        "route": sr.route,
        "measure": sr.measure,
        "tolerance": _num(sr.tolerance),
        "slip": sr.slip.name.lower(),
        "where": sr.slip.value,
        "result": sr.result(),
        "searched": sr.searched,
        "kinds": sr.kinds(),
        "before": sr.before,
        "trials": [
            {
                "reading": t.text,
                "sides": sorted(t.sides),
                "misfit": _num(t.misfit),
                "reproduces": t.reproduces,
            }
            for t in sr.trials
        ],
    }


def _covers(row: Row) -> tuple[str, ...]:
    return row.covers or parse_refs(row.reference)


def _record(row: Row, section: str, parent: str | None) -> dict:
    covers = _covers(row)
    chapter = (
        "Project"
        if row.scope is Scope.PROJECT
        else (chapter_of(covers[0]) if covers else chapter_of_reference(row.reference))
    )
    return {
        "id": row.id,
        "claim": row.claim,
        "reference": row.reference,
        "verdict": row.verdict.value,
        "reason": row.reason,
        "scope": row.scope.value,
        "method": row.method,
        "numbers": row.numbers,
        "measures": [
            {
                "name": m.name,
                "value": _num(m.value),
                "limit": _num(m.limit),
                "unit": m.unit,
                "bound": m.bound,
                "holds": m.holds,
            }
            for m in row.measures
        ],
        "depends_on": list(row.depends_on),
        "check": row.check,
        "figures": list(row.figures),
        "views": list(row.views),
        "errata": [
            {
                "equation": e.equation,
                "printed": e.printed,
                "corrected": e.corrected,
                "counterexample": e.counterexample,
            }
            for e in row.errata
        ],
        "covers": list(covers),
        "section": section,
        "chapter": chapter,
        "parent": parent,
        "appendix": row.appendix,
        "basis": row.basis,
        "domain": row.domain,
        "second_reading": _reading_record(row.second_reading),
    }


def _num(x: float):
    return None if x != x or x in (float("inf"), float("-inf")) else float(x)


def _falsifiable(check: Check) -> str:
    if check.forms is not None:
        return f"forms: good = {check.forms.good_is}; slips = {check.forms.slips_is}"
    if check.by_construction:
        return f"by construction: {check.by_construction}"
    return "not declared"


def _index(records: list[dict]) -> list[dict]:
    top = [r for r in records if r["parent"] is None]
    parent_of = {r["id"]: r["parent"] for r in records}
    verdict = {r["id"]: r["verdict"] for r in records}
    out = []
    for item in ITEMS:
        ids = [r["id"] for r in top if item.key in r["covers"] or r["check"] in item.checks]
        ids += [
            parent_of[r["id"]]
            for r in records
            if r["parent"] is not None and item.key in r["covers"] and parent_of[r["id"]] not in ids
        ]
        ids = list(dict.fromkeys(ids))
        out.append(
            {
                "key": item.key,
                "kind": item.kind,
                "where": item.where,
                "title": item.title,
                "status": item.status,
                "note": item.note,
                "rows": [{"id": i, "verdict": verdict[i]} for i in ids],
                "missing": item.status == "checked" and not ids,
            }
        )
    return out


def report_document(results: Iterable[CheckResult], *, title: str | None = None,
                    only: Sequence[str] | None = None) -> dict:
    """The report as a JSON-ready dict (see ``report.schema.json``); ``only``: the selection of a
    partial run (in the header)."""
    results = list(results)
    seed = results[0].seed if results else 0
    quick = results[0].quick if results else False
    records, sections = [], []
    for res in results:
        sec = res.check.section
        if not sections or sections[-1]["title"] != sec:
            sections.append({"title": sec, "checks": []})
        sections[-1]["checks"].append(
            {
                "check": res.check.where,
                "seconds": round(res.seconds, 3),
                "error": res.error,
                "falsifiable": _falsifiable(res.check),
                "rows": [r.id for r in res.rows],
            }
        )
        for r in res.rows:
            records.append(_record(r, sec, None))
            records += [_record(d, sec, r.id) for d in r.details]
    top = [r for r in records if r["parent"] is None]
    chapters: dict[str, list] = {}
    for r in top:
        if r["scope"] == Scope.THESIS.value:
            chapters.setdefault(r["chapter"], []).append(r)
    header = provenance(seed, quick, only).as_dict()
    header["seconds"] = round(sum(r.seconds for r in results), 2)
    thesis = _counts(r for r in top if r["scope"] == Scope.THESIS.value)
    project = _counts(r for r in top if r["scope"] == Scope.PROJECT.value)
    return {
        "title": title or (QUICK_TITLE if quick else "Verification report"),
        "format": FORMAT,
        "header": header,
        "assumptions": [{"id": a.id, "text": a.text} for a in ASSUMPTIONS.values()],
        "summary": {
            "thesis": thesis,
            "project": project,
            "groups": {"thesis": _groups(thesis), "project": _groups(project)},
            "failures": sum(1 for res in results if res.error),
            "chapters": {k: _counts(v) for k, v in sorted(chapters.items())},
        },
        "index": _index(records),
        "sections": sections,
        "rows": records,
    }


def unread_errata(doc: dict) -> list[str]:
    """Ids of the report's erratum and input-slip rows that carry no second reading (must be none); a
    grouped row is read through its entries (each of its erratum entries must carry one)."""
    wrong = (Verdict.ERRATUM.value, Verdict.INPUT_SLIP.value)
    entries: dict[str, list[dict]] = {}
    for r in doc["rows"]:
        if r["parent"]:
            entries.setdefault(r["parent"], []).append(r)
    out = []
    for r in doc["rows"]:
        if r["verdict"] not in wrong or r["second_reading"] is not None:
            continue
        own = [d for d in entries.get(r["id"], []) if d["verdict"] in wrong]
        if not own or any(d["second_reading"] is None for d in own):
            out.append(r["id"])
    return out


def write_report(results: Iterable[CheckResult], path: Path, *, title: str | None = None,
                 only: Sequence[str] | None = None) -> Path:
    """Write ``verification.json`` and the markdown report ``path`` (same folder); return ``path``.

    Raises:
        RowError: an erratum row has no second reading (a check declared a printed value wrong
            without searching the nearby readings of its inputs: a bug in that check).
    """
    path = Path(path)
    doc = report_document(results, title=title, only=only)
    unread = unread_errata(doc)
    if unread:
        raise RowError("second_reading", "errata without a second reading: " + ", ".join(unread))
    errors = schema_errors(doc)
    if errors:  # a bug in this module, not bad input: fail loudly
        raise AssertionError("report document breaks report.schema.json: " + "; ".join(errors[:5]))
    path.parent.mkdir(parents=True, exist_ok=True)
    text = json.dumps(doc, indent=1, ensure_ascii=False)
    # the title on the first line (a --quick report says so there), then one field per line
    path.with_suffix(".json").write_text("{" + text[1:].lstrip() + "\n", encoding="utf-8")
    path.write_text(render(doc), encoding="utf-8")
    return path


def read_report(path) -> dict:
    """Read and validate a ``verification.json`` (for notebooks and tools).

    Raises:
        ReportError: the file is missing, not a regular file, over :data:`MAX_REPORT_BYTES`, not
            JSON, or does not follow the schema.
    """
    p = Path(path)
    if not p.exists():
        raise ReportError(str(path), "no such file (write one first: verification.verify(out_dir))")
    try:
        doc = json.loads(read_text(p, "path", limit=MAX_REPORT_BYTES, what="a report"))
    except FileError as exc:
        raise ReportError(str(path), exc.reason) from None
    except json.JSONDecodeError as exc:
        raise ReportError(str(path), f"not a JSON report ({exc})") from None
    errors = schema_errors(doc)
    if errors:
        raise ReportError(str(path), "does not follow report.schema.json: " + "; ".join(errors[:3]))
    return doc


def summary(results: Iterable[CheckResult]) -> str:
    """A few lines for the terminal: grouped counts, findings, failures."""
    results = list(results)
    top = [r for res in results for r in res.rows]
    lines = []
    for scope in Scope:
        rows = [r for r in top if r.scope is scope]
        if rows:
            c = Counter(r.verdict for r in rows)
            lines.append(f"  {scope.value}: " + ", ".join(f"{c.get(v, 0)} {v.value}" for v in Verdict))
    lines[0:0] = [f"{len(top)} claims from {len(results)} checks (grouped claims counted once)"]
    for r in top:
        if r.scope is Scope.THESIS and r.verdict in (Verdict.ERRATUM, Verdict.INPUT_SLIP):
            where = "; ".join(e.equation for e in r.errata)
            lines.append(f"  {r.verdict.value}: {r.id} ({r.reference}): {where}")
        elif r.scope is Scope.THESIS and r.verdict is Verdict.DOES_NOT_HOLD:
            lines.append(f"  does not hold: {r.id} ({r.reference})")
    failed = [res.check.name for res in results if res.error]
    if failed:
        lines.append(f"  {len(failed)} check(s) FAILED TO RUN: " + ", ".join(failed))
    return "\n".join(lines)
