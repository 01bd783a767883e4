"""Render a report document (the dict of :func:`verification.report.report_document`) as markdown.

Layout: header (commit, versions, seed, machine); summary per chapter; the Sec 5.2
scorecard; the index of every equation, table, appendix and claim; the assumption
legend; then one part per section -- a compact table (id, reference, claim, measured,
verdict) followed by one block per row with its check, method, numbers, assumptions,
errata, details and figures beside it; finally the errata, the long numbers
(appendix), software failures and timing. Every row id is an anchor.
"""

from __future__ import annotations

__all__ = ["render"]

_INTRO = (
    "Each row is one claim of C. A. Mondragon Sanchez, *Dynamics and Motion of a Six Degree of "
    "Freedom Robot Manipulator*, M.Sc. thesis, University of Saskatchewan, 2012, checked by machine: "
    "the printed form is measured against an independent reference and the verdict follows the "
    "measurement and its tolerance. Rows marked *project standard* grade a stricter standard of this "
    "project, not the thesis, and are counted apart. Units: SI (m, rad) unless a cell says otherwise. "
    "Every row lists what its verdict depends on (legend under *Assumptions*)."
)
_KINDS = (
    ("equation", "Equations"),
    ("table", "Tables"),
    ("appendix", "Appendices"),
    ("claim", "Explicit claims (Chapters 3-4)"),
    ("conclusion", "Conclusions (Sec 5.2)"),
)
_VERDICTS = ("holds", "erratum", "does not hold", "not checkable")


def _cell(text) -> str:
    return str(text).replace("|", "\\|").replace("\n", "<br>")


def _anchor(row_id: str) -> str:
    return "row-" + row_id.replace(".", "-")


def _link(row_id: str, verdict: str | None = None) -> str:
    v = f" ({verdict})" if verdict else ""
    return f"[`{row_id}`](#{_anchor(row_id)}){v}"


def _counts_line(c: dict) -> str:
    return ", ".join(f"{c[v]} {v}" for v in _VERDICTS)


def _mode(h: dict) -> str:
    """Quick or full samples; a partial run (``--only``) says so and is never "full"."""
    if not h.get("only"):
        return "quick (small samples)" if h["quick"] else "full"
    only = ", ".join(f"`{s}`" for s in h["only"])
    return f"partial (only the checks matching {only}), {'small' if h['quick'] else 'report-size'} samples"


def _header(doc: dict) -> list[str]:
    h = doc["header"]
    dirty = {True: " (uncommitted changes)", False: "", None: ""}[h["dirty"]]
    versions = ", ".join(f"{k} {v}" for k, v in h["versions"].items())
    m = h["machine"]
    quick = (
        "> **Quick mode:** small samples and only some scenarios; verdicts may differ from the full report. "
        "Run `iik verify` (without `--quick`) for the report of record."
    )
    banner = [quick, ""] if h["quick"] else []
    return [
        f"# {doc['title']}",
        "",
        *banner,
        _INTRO,
        "",
        f"- iik {h.get('version', '?')}, commit: `{h['commit']}`{dirty} ({h.get('commit_from', '?')})",
        f"- created: {h['created']} (checks ran {h['seconds']} s)",
        f"- seed: {h['seed']}; mode: {_mode(h)}",
        f"- python {h['python']}; {versions}",
        f"- machine: {m.get('platform', '')}, {m.get('processor', '')}, {m.get('cpus', '?')} CPUs",
        "",
    ]


def _summary(doc: dict) -> list[str]:
    s = doc["summary"]
    lines = [
        "## Summary",
        "",
        f"Thesis claims: {_counts_line(s['thesis'])}. Project standards: {_counts_line(s['project'])}. "
        f"Software failures: {s['failures']}. Grouped claims (App. C entries, Table VI sets, Table VII "
        "groups) count once; their entries are listed under them.",
        "",
        "| chapter | " + " | ".join(_VERDICTS) + " |",
        "|---|" + "---|" * len(_VERDICTS),
    ]
    for ch, c in s["chapters"].items():
        lines.append(f"| {ch} | " + " | ".join(str(c[v]) for v in _VERDICTS) + " |")
    lines += [
        "",
        "### Scorecard of the conclusions (Sec 5.2)",
        "",
        "| conclusion | rows | verdicts |",
        "|---|---|---|",
    ]
    for it in doc["index"]:
        if it["kind"] == "conclusion":
            rows = ", ".join(_link(r["id"]) for r in it["rows"]) or f"*{it['status']}: {it['note']}*"
            verdicts = ", ".join(sorted({r["verdict"] for r in it["rows"]})) or it["status"]
            lines.append(f"| {it['key']}: {_cell(it['title'])} | {rows} | **{verdicts}** |")
    return lines + [""]


def _index(doc: dict) -> list[str]:
    lines = [
        "## Index",
        "",
        "Every numbered equation, table, appendix and explicit claim of the thesis, with the rows "
        "that grade it. *MISSING* would mark an item with no row.",
        "",
    ]
    for kind, title in _KINDS:
        lines += [f"### {title}", "", "| item | where | what | rows |", "|---|---|---|---|"]
        for it in doc["index"]:
            if it["kind"] != kind:
                continue
            rows = ", ".join(_link(r["id"], r["verdict"]) for r in it["rows"])
            if it["status"] != "checked":
                rows = f"*{it['status']}: {_cell(it['note'])}*" + (f"; {rows}" if rows else "")
            elif it["missing"]:
                rows = "**MISSING**"
            lines.append(f"| {it['key']} | {it['where']} | {_cell(it['title'])} | {rows} |")
        lines.append("")
    return lines


def _short(rec: dict) -> str:
    if rec["measures"]:
        parts = [
            f"{m['name']} = {m['value']:.3g}" if m["value"] is not None else f"{m['name']} = n/a"
            for m in rec["measures"][:3]
        ]
        return "; ".join(parts)
    n = rec["numbers"].replace("\n", " ")
    return n if len(n) <= 160 else n[:157] + "..."


def _row_block(rec: dict, details: list[dict]) -> list[str]:
    verdict = rec["verdict"] + (f": {rec['reason']}" if rec["reason"] else "")
    scope = " *(project standard)*" if rec["scope"] == "project standard" else ""
    lines = [
        f'<a id="{_anchor(rec["id"])}"></a>',
        f"#### `{rec['id']}`{scope}: {_cell(rec['claim'])}",
        "",
        f"- reference: {rec['reference']}; check: `{rec['check']}`",
        f"- verdict: **{_cell(verdict)}**",
        f"- method: {_cell(rec['method'])}",
        f"- numbers: {_cell(rec['numbers'])}",
    ]
    if rec["measures"]:
        ms = "; ".join(
            f"{m['name']} = {m['value'] if m['value'] is None else format(m['value'], '.3g')}"
            f"{(' ' + m['unit']) if m['unit'] else ''} (tolerance {m['bound']} "
            f"{m['limit'] if m['limit'] is None else format(m['limit'], '.3g')}: "
            f"{'within' if m['holds'] else 'outside'})"
            for m in rec["measures"]
        )
        lines.append(f"- graded on: {_cell(ms)}")
    lines.append("- depends on: " + (", ".join(f"`{a}`" for a in rec["depends_on"]) or "none declared"))
    if rec["appendix"]:
        lines.append(f"- long numbers: [appendix](#{_anchor(rec['id'])}-appendix)")
    for e in rec["errata"]:
        lines.append(
            f"- erratum **{_cell(e['equation'])}**: printed `{_cell(e['printed'])}`; corrected "
            f"`{_cell(e['corrected'])}`; counterexample: {_cell(e['counterexample'])}"
        )
    if details:
        lines += ["", "| entry | claim | numbers | verdict |", "|---|---|---|---|"]
        for d in details:
            dv = d["verdict"] + (f": {d['reason']}" if d["reason"] else "")
            lines.append(
                f'| <a id="{_anchor(d["id"])}"></a>`{d["id"]}` | {_cell(d["claim"])} | '
                f"{_cell(d['numbers'])} | **{_cell(dv)}** |"
            )
    lines.append("")
    for v in rec["views"]:
        name = v.split("/")[1]
        lines += [
            f"- 3D view of `{name}` (the planned motion with the arm's collision shapes, the scene, the tool "
            f"path and the nearest link's clearance; opens from disk in a browser, no server, no network): "
            f"[{v}]({v})",
            "",
        ]
    for f in rec["figures"]:
        lines += [f"![{_cell(rec['id'])}]({f})", ""]
    return lines


def _sections(doc: dict) -> list[str]:
    recs = doc["rows"]
    details: dict[str, list] = {}
    for r in recs:
        if r["parent"]:
            details.setdefault(r["parent"], []).append(r)
    lines = []
    for sec in doc["sections"]:
        ids = [i for c in sec["checks"] for i in c["rows"]]
        top = [r for r in recs if r["id"] in set(ids) and r["parent"] is None]
        lines += [
            "",
            f"## {sec['title']}",
            "",
            "| id | reference | claim | measured | verdict |",
            "|---|---|---|---|---|",
        ]
        for c in sec["checks"]:
            if c["error"]:
                lines.append(f"| `{c['check']}` | | | | **software failure** (see below) |")
        for r in top:
            scope = " (project standard)" if r["scope"] == "project standard" else ""
            lines.append(
                f"| {_link(r['id'])} | {_cell(r['reference'])} | {_cell(r['claim'])}{scope} | "
                f"{_cell(_short(r))} | **{r['verdict']}** |"
            )
        lines.append("")
        for r in top:
            lines += _row_block(r, details.get(r["id"], []))
    return lines


def _tail(doc: dict) -> list[str]:
    recs = doc["rows"]
    lines = ["", "## Errata", "", "| row | equation | printed | corrected |", "|---|---|---|---|"]
    for r in recs:
        for e in r["errata"]:
            lines.append(
                f"| {_link(r['id'])} | {_cell(e['equation'])} | {_cell(e['printed'])} | "
                f"{_cell(e['corrected'])} |"
            )
    long = [r for r in recs if r["appendix"]]
    if long:
        lines += ["", "## Appendix: long numbers", ""]
        for r in long:
            lines += [
                f'<a id="{_anchor(r["id"])}-appendix"></a>',
                f"### {_link(r['id'])}",
                "",
                "```",
                r["appendix"].rstrip(),
                "```",
                "",
            ]
    failed = [c for s in doc["sections"] for c in s["checks"] if c["error"]]
    if failed:
        lines += ["", "## Software failures", ""]
        for c in failed:
            lines += [f"### `{c['check']}`", "", "```", c["error"].rstrip(), "```", ""]
    lines += [
        "",
        "## Checks: falsifiability and timing",
        "",
        "| check | self-test | seconds |",
        "|---|---|---|",
    ]
    lines += [
        f"| `{c['check']}` | {_cell(c['falsifiable'])} | {c['seconds']:.2f} |"
        for s in doc["sections"]
        for c in s["checks"]
    ]
    return lines


def render(doc: dict) -> str:
    """The markdown text of a report document."""
    legend = ["## Assumptions", "", "| id | assumption |", "|---|---|"]
    legend += [f"| `{a['id']}` | {_cell(a['text'])} |" for a in doc["assumptions"]]
    lines = _header(doc) + _summary(doc) + _index(doc) + legend + _sections(doc) + _tail(doc)
    return "\n".join(lines) + "\n"
