"""Render a report document (the dict of :func:`verification.report.report_document`) as markdown.

Layout: header (commit, versions, seed, machine); *what this report finds* (confirmed, refuted,
input slips, untestable, not evidence); *how to read this report*; one quotable line per
section; counts per chapter and grade; the Sec 5.2 scorecard; the index of every equation,
table, appendix and claim; the assumption legend; then one part per section -- its one-line
verdict, a compact table (id, reference, claim, measured, verdict) and one block per row with
its check, method, domain, numbers, assumptions, basis, second reading, errata, details and
figures; finally the errata and input slips with their second readings, the long numbers
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
_HOW_TO_READ = (
    "## How to read this report",
    "",
    "- **Grades.** *holds*: measured against an independent reference (Pinocchio, Coal, finite "
    "differences, exact geometry, ground-truth sampling) on the stated domain; it could have failed. "
    "*holds by construction*: an identity (sin^2 + cos^2 = 1, atan2 of a true sine and cosine, a product "
    "of transforms from the same table) or a round trip through our own code; shown for completeness, "
    "**not counted as evidence**. *consistent with our reconstruction*: the thesis does not print what "
    "the check needs (scenes, via-points, the real arm's lag), so the verdict rests on the named "
    "reconstruction (its *basis*); *not reproduced on our reconstruction* is its failing twin. "
    "*not checkable*: says why (mostly: it needs the real arm). *erratum*: a printed formula or number "
    "is wrong; *input slip*: the printed result is right, but for a nearby reading of its stated input "
    "(a sign, the other joint limit, which angle or set), so the slip is in the input; *does not hold*: "
    "a claim refuted by measurement.",
    "- **Second reading.** No printed value is called wrong before the nearby readings of its inputs "
    "and conventions were searched (signs of angles, the other joint limit, degrees vs radians, swapped "
    "or transposed indices, row vs column conventions, the other Euler convention, which angle or set, "
    "dropped or misplaced digits or signs), re-deriving the value by a route of its own. A reading of an "
    "input must also keep the values printed beside it from the same input (A1's N0 pins its theta1). "
    "Each erratum row shows the readings searched, whether one reproduces the printed value and where the "
    "slip is: nowhere (withdrawn), the stated input (*input slip*), a typo of the printed result, or the "
    "result itself (both stay *errata*). Every erratum and input slip is also re-derived apart from the "
    "code that found it (sympy, a hand-written Table II chain: tests/verification/test_errata_rederived.py).",
    "- **Domain.** Each row states the domain it sampled; formulas are sampled where they are hardest "
    "(near their singular values, across the whole joint range), and the tolerance says why it is what "
    "it is.",
    "- **Falsifiability.** `iik verify --self-test` reruns every check with a known-good form (it must "
    "pass) and with the mistakes a person could make in that formula (sign, swapped index, atan for "
    "asin, a wrong link length, degrees for radians, a transposed rotation, the other branch of a "
    "square root, an off-by-one), plus an epsilon tolerance test; each must be caught (some graded row "
    "fails). The table at the end lists each check's slips.",
    "- **Scope.** Thesis rows grade the thesis by its own claims; *project standard* rows grade our "
    "stricter standards and are counted apart.",
    "",
)
_KINDS = (
    ("equation", "Equations"),
    ("table", "Tables"),
    ("appendix", "Appendices"),
    ("claim", "Explicit claims (Chapters 3-4)"),
    ("conclusion", "Conclusions (Sec 5.2)"),
)
_VERDICTS = (
    "holds",
    "holds by construction",
    "consistent with our reconstruction",
    "input slip",
    "erratum",
    "does not hold",
    "not reproduced on our reconstruction",
    "not checkable",
)
_GROUP_OF = {
    "holds": "confirmed",
    "holds by construction": "not evidence",
    "consistent with our reconstruction": "not evidence",
    "input slip": "input slip",
    "erratum": "refuted",
    "does not hold": "refuted",
    "not reproduced on our reconstruction": "not evidence",
    "not checkable": "untestable",
}


def _cell(text) -> str:
    return str(text).replace("|", "\\|").replace("\n", "<br>")


def _anchor(row_id: str) -> str:
    return "row-" + row_id.replace(".", "-")


def _link(row_id: str, verdict: str | None = None) -> str:
    v = f" ({verdict})" if verdict else ""
    return f"[`{row_id}`](#{_anchor(row_id)}){v}"


def _counts_line(c: dict) -> str:
    return ", ".join(f"{c[v]} {v}" for v in _VERDICTS if c[v]) or "none"


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


def _top_thesis(doc: dict) -> list[dict]:
    return [r for r in doc["rows"] if r["parent"] is None and r["scope"] == "thesis"]


def _refs(rows: list[dict], limit: int = 40) -> str:
    out = ", ".join(f"{_link(r['id'])} ({_cell(r['reference'])})" for r in rows[:limit])
    return out + (f", and {len(rows) - limit} more" if len(rows) > limit else "")


def _findings(doc: dict) -> list[str]:
    """The opening: what is confirmed, refuted, a slip of the input, untestable, and what is not evidence."""
    top = _top_thesis(doc)
    by = {v: [r for r in top if r["verdict"] == v] for v in _VERDICTS}
    g = doc["summary"]["groups"]["thesis"]
    lines = [
        "## What this report finds",
        "",
        f"Of {len(top)} thesis claims (grouped claims counted once):",
        "",
        f"- **Confirmed by measurement: {g['confirmed']}** (each could have failed; listed per section "
        "below).",
        f"- **Refuted: {g['refuted']}** -- {len(by['erratum'])} errata (a printed formula or number is wrong "
        f"under every nearby reading of its inputs): {_refs(by['erratum'])}; {len(by['does not hold'])} "
        f"claims that do not hold: {_refs(by['does not hold'])}.",
        f"- **Input slips: {g['input slip']}** -- the printed result is right for a nearby reading of its "
        f"stated input, so the slip is in the input: {_refs(by['input slip'])}.",
        f"- **Untestable here: {g['untestable']}** (not checkable, with the reason in the row): "
        f"{_refs(by['not checkable'])}.",
        f"- **Not evidence: {g['not evidence']}** -- {len(by['holds by construction'])} hold by construction "
        f"(identities, round trips through our own code), {len(by['consistent with our reconstruction'])} "
        f"are consistent with our reconstruction ({_refs(by['consistent with our reconstruction'])}), "
        f"{len(by['not reproduced on our reconstruction'])} are not reproduced on it "
        f"({_refs(by['not reproduced on our reconstruction'])}).",
        "",
        f"Project standards (ours, stricter, counted apart): {_counts_line(doc['summary']['project'])}.",
        "",
    ]
    return lines


def _section_verdict(sec: dict, recs: list[dict]) -> str:
    """One quotable line for a section: the confirmed count, then the refuted, slipped and untestable
    references."""
    ids = {i for c in sec["checks"] for i in c["rows"]}
    top = [r for r in recs if r["id"] in ids and r["parent"] is None and r["scope"] == "thesis"]
    if not top:
        proj = [r for r in recs if r["id"] in ids and r["parent"] is None]
        return f"Project standards only: {_counts_line(dict(_zero(), **_count(proj)))}."
    c = _count(top)
    parts = [f"{c.get('holds', 0)} of {len(top)} thesis claims confirmed by measurement"]
    for verdict, word in (("erratum", "errata"), ("input slip", "input slips"), ("does not hold",
        "do not hold"),
                          ("not reproduced on our reconstruction", "not reproduced on our reconstruction"),
                          ("not checkable", "not checkable")):
        refs = [r["reference"] for r in top if r["verdict"] == verdict]
        if refs:
            parts.append(f"{word}: {'; '.join(dict.fromkeys(refs))}")
    rest = c.get("holds by construction", 0) + c.get("consistent with our reconstruction", 0)
    if rest:
        parts.append(f"{rest} shown but not evidence (by construction or on our reconstruction)")
    return "; ".join(parts) + "."


def _zero() -> dict:
    return dict.fromkeys(_VERDICTS, 0)


def _count(rows: list[dict]) -> dict:
    out = _zero()
    for r in rows:
        out[r["verdict"]] += 1
    return out


def _per_section(doc: dict) -> list[str]:
    lines = ["## Verdict per section", "", "| section | verdict |", "|---|---|"]
    for sec in doc["sections"]:
        lines.append(f"| {_cell(sec['title'])} | {_cell(_section_verdict(sec, doc['rows']))} |")
    return lines + [""]


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
    ]
    if rec["basis"]:
        lines.append(f"- rests on (not a measurement): {_cell(rec['basis'])}")
    lines += [f"- method: {_cell(rec['method'])}"]
    if rec["domain"]:
        lines.append(f"- domain: {_cell(rec['domain'])}")
    lines += [f"- numbers: {_cell(rec['numbers'])}"]
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
        what = "input slip" if rec["verdict"] == "input slip" else "erratum"
        lines.append(
            f"- {what} **{_cell(e['equation'])}**: printed `{_cell(e['printed'])}`; corrected "
            f"`{_cell(e['corrected'])}`; counterexample: {_cell(e['counterexample'])}"
        )
    if rec["second_reading"]:
        lines += _reading_lines(rec["second_reading"])
    if details:
        lines += ["", "| entry | claim | numbers | verdict |", "|---|---|---|---|"]
        for d in details:
            dv = d["verdict"] + (f": {d['reason']}" if d["reason"] else "")
            sr = d["second_reading"]
            if sr:
                dv += f" (second reading: {sr['result']}; slip {sr['where']})"
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


def _reading_lines(sr: dict) -> list[str]:
    before = f" (verdict before it: {sr['before']})" if sr["before"] else ""
    return [
        f"- second reading of `{_cell(sr['printed'])}` (stated: {_cell(sr['stated'])}){before}: re-derived "
        f"by {_cell(sr['route'])}; {sr['searched']} readings searched ({_cell(', '.join(sr['kinds']))}); "
        f"{_cell(sr['result'])}; **the slip is {_cell(sr['where'])}**",
    ]


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
            f"**Verdict:** {_section_verdict(sec, recs)}",
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
    lines = [
        "",
        "## Errata and input slips, with their second readings",
        "",
        "| row | verdict | equation | printed | corrected | readings searched | result | where the slip is |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for r in recs:
        sr = r["second_reading"]
        for e in r["errata"]:
            searched = f"{sr['searched']} ({', '.join(sr['kinds'])})" if sr else "-"
            before = f" (was {sr['before']})" if sr and sr["before"] and sr["before"] != r["verdict"] else ""
            lines.append(
                f"| {_link(r['id'])} | {r['verdict']}{before} | {_cell(e['equation'])} | "
                f"{_cell(e['printed'])} | "
                f"{_cell(e['corrected'])} | {_cell(searched)} | {_cell(sr['result'] if sr else '-')} | "
                f"{_cell(sr['where'] if sr else '-')} |"
            )
    withdrawn = [r for r in recs if r["second_reading"] and r["verdict"] == "holds"]
    if withdrawn:
        lines += ["", "Errata withdrawn by their second reading (the printed value is right as stated):", ""]
        lines += [f"- {_link(r['id'])} ({_cell(r['reference'])}): {_cell(r['second_reading']['result'])}"
                  for r in withdrawn]
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
    lines = (_header(doc) + _findings(doc) + list(_HOW_TO_READ) + _per_section(doc) + _summary(doc)
             + _index(doc) + legend + _sections(doc) + _tail(doc))
    return "\n".join(lines) + "\n"
