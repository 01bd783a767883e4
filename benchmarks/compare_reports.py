"""Compare two ``iik verify`` reports row by row, and optionally two ``iik verify --self-test`` outputs.

For a refactoring of the checks that must keep every verdict (issue 21):

    python benchmarks/compare_reports.py BEFORE/verification.json AFTER/verification.json \
        [--self-test BEFORE_SELF_TEST.txt AFTER_SELF_TEST.txt]

Rows are matched by id. Compared per row: verdict, scope, covers (index keys), depends_on, the number
of measures and each measure's pass/fail (values are listed only where a graded measure changed side),
the number of errata and the second reading's slip location. Also: the ids' order, the index items'
rows and verdicts, the summary counts. Self-test lines are matched through the row ids their checks
write (a check may be renamed): status, verdicts with the printed and the good form, every slip caught
(matched by kind and words) and the tolerance test. Exit status 1 if anything graded differs.
"""

from __future__ import annotations

import argparse
import json
import re
import sys
from pathlib import Path


def _rows(path: Path) -> tuple[dict, list[str], dict]:
    report = json.loads(Path(path).read_text(encoding="utf-8"))
    rows = {r["id"]: r for r in report["rows"]}
    return rows, [r["id"] for r in report["rows"]], report


def _graded(row: dict) -> dict:
    sr = row.get("second_reading") or {}
    return {
        "verdict": row["verdict"],
        "scope": row["scope"],
        "covers": tuple(row["covers"]),
        "depends_on": tuple(row["depends_on"]),
        "measures": tuple(m["holds"] for m in row["measures"]),
        "errata": len(row["errata"]),
        "slip": sr.get("slip"),
        "parent": row.get("parent"),
    }


def compare_rows(before: Path, after: Path, partial: bool = False) -> list[str]:
    """Differences between two reports' rows (empty if every graded field agrees); ``partial``: ``after``
    is a partial run (``iik verify --only``): only its rows are compared, not the index and summary."""
    a, order_a, ra = _rows(before)
    b, order_b, rb = _rows(after)
    if partial:
        a = {k: v for k, v in a.items() if k in b}
        order_a = [r for r in order_a if r in b]
    out = []
    for rid in sorted(set(a) - set(b)):
        out.append(f"row {rid}: only before")
    for rid in sorted(set(b) - set(a)):
        out.append(f"row {rid}: only after")
    for rid in order_a:
        if rid not in b:
            continue
        ga, gb = _graded(a[rid]), _graded(b[rid])
        for k in ga:
            if ga[k] != gb[k]:
                out.append(f"row {rid}: {k} {ga[k]!r} -> {gb[k]!r}")
    if partial:
        return out
    idx_a = {i["key"]: [(r["id"], r["verdict"]) for r in i["rows"]] for i in ra["index"]}
    idx_b = {i["key"]: [(r["id"], r["verdict"]) for r in i["rows"]] for i in rb["index"]}
    for key in sorted(set(idx_a) | set(idx_b)):
        if sorted(idx_a.get(key, [])) != sorted(idx_b.get(key, [])):
            out.append(f"index {key}: {idx_a.get(key)} -> {idx_b.get(key)}")
    for scope in ("thesis", "project"):
        if ra["summary"][scope] != rb["summary"][scope]:
            out.append(f"summary {scope}: {ra['summary'][scope]} -> {rb['summary'][scope]}")
    return out


def notes_rows(before: Path, after: Path) -> list[str]:
    """What changed but is not graded: the order of the rows, claims, numbers, checks' names."""
    a, order_a, _ = _rows(before)
    b, order_b, _ = _rows(after)
    order_a = [r for r in order_a if r in b]
    common = [r for r in order_a if r in b]
    notes = []
    if common != [r for r in order_b if r in a]:
        moved = [r for r, s in zip(common, [r for r in order_b if r in a], strict=True) if r != s]
        notes.append(f"order of rows differs ({len(moved)} positions), e.g. {moved[:6]}")
    else:
        notes.append("order of rows: identical")
    for field in ("claim", "numbers", "method", "check", "domain"):
        n = sum(a[r][field] != b[r][field] for r in common)
        notes.append(f"{field}: {n} of {len(common)} rows changed")
    values = sum(
        any(x["value"] != y["value"] for x, y in zip(a[r]["measures"], b[r]["measures"], strict=False))
        for r in common
    )
    notes.append(f"measured values: {values} of {len(common)} rows differ in a value (pass/fail is compared)")
    return notes


_LINE = re.compile(r"^\| `([^`]+)` \| ([^|]+) \| (.*)$")


def _self_test(path: Path) -> dict[str, dict]:
    out = {}
    for line in Path(path).read_text(encoding="utf-8").splitlines():
        m = _LINE.match(line)
        if not m:
            continue
        cells = [c.strip() for c in re.split(r"(?<!\\)\|", line.strip().strip("|"))]
        check, status, printed, good, n, caught, missed, tol = cells[:8]
        out[check.strip("`")] = {
            "status": status,
            "printed": printed,
            "good": good,
            "n": n,
            "caught": tuple(sorted(s.strip() for s in caught.split("; ") if s.strip() != "-")),
            "missed": missed,
            "tolerance": tol,
        }
    return out


def _checks_by_rows(report: Path) -> dict[str, frozenset]:
    rep = json.loads(Path(report).read_text(encoding="utf-8"))
    out = {}
    for section in rep["sections"]:
        for c in section["checks"]:
            out[c["check"]] = frozenset(c["rows"])
    return out


def compare_self_tests(before: Path, after: Path, report_before: Path, report_after: Path,
                       partial: bool = False) -> list[str]:
    """Differences between two self-tests: each check matched through its rows' ids."""
    sa, sb = _self_test(before), _self_test(after)
    ra, rb = _checks_by_rows(report_before), _checks_by_rows(report_after)
    if partial:
        sa = {n: v for n, v in sa.items() if ra.get(n, frozenset()) & set().union(*rb.values())}
    by_rows_b = {rows: name for name, rows in rb.items()}
    out = []
    for name, line in sa.items():
        other = by_rows_b.get(ra.get(name)) if name in ra else None
        other = other or (name if name in sb else None)
        if other is None or other not in sb:
            out.append(f"self-test {name}: no matching check after")
            continue
        new = sb[other]
        for k in ("status", "printed", "good", "n", "caught", "missed", "tolerance"):
            if line[k] != new[k]:
                out.append(f"self-test {name} -> {other}: {k} {line[k]!r} -> {new[k]!r}")
    matched = {by_rows_b.get(ra.get(n)) or n for n in sa}
    print(f"self-test: {len(sa)} checks compared, {len(matched & set(sb))} matched after")
    for name in sorted(set(sb) - matched):
        out.append(f"self-test {name}: only after")
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("before", type=Path)
    ap.add_argument("after", type=Path)
    ap.add_argument("--self-test", nargs=2, type=Path, metavar=("BEFORE", "AFTER"))
    ap.add_argument("--partial", action="store_true", help="AFTER is an `iik verify --only` run")
    args = ap.parse_args(argv)
    diffs = compare_rows(args.before, args.after, args.partial)
    _, order_a, ra = _rows(args.before)
    print(f"rows: {len(order_a)} before, {len(_rows(args.after)[1])} after")
    for line in notes_rows(args.before, args.after):
        print(f"  note: {line}")
    if args.self_test:
        st = compare_self_tests(*args.self_test, args.before, args.after, args.partial)
        a = _self_test(args.self_test[0])
        b = _self_test(args.self_test[1])
        print(f"self-test: {len(a)} checks before, {len(b)} after; last lines:")
        for path in args.self_test:
            print("  " + Path(path).read_text(encoding="utf-8").strip().splitlines()[-1])
        diffs += st
    for d in diffs:
        print(f"DIFF {d}")
    print("identical in every graded field" if not diffs else f"{len(diffs)} differences")
    return 1 if diffs else 0


if __name__ == "__main__":
    sys.exit(main())
