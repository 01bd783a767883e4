"""verification.report: the JSON document (schema, index, counts), the markdown rendered from it, and
stable verdicts across two runs."""

from __future__ import annotations

import json
from collections import Counter

import jsonschema
import pytest

from verification import Context, ReportError, read_report, run_checks, write_report
from verification.assumptions import ASSUMPTIONS
from verification.markdown import render
from verification.schema import schema, schema_errors


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """Two quick runs of every check, each in a fresh context (same seed)."""
    out = []
    for k in range(2):
        folder = tmp_path_factory.mktemp(f"run{k}")
        results = run_checks(Context(out_dir=folder, quick=True))
        out.append((folder, results, write_report(results, folder / "verification.md")))
    return out


@pytest.fixture(scope="module")
def doc(runs):
    return json.loads(runs[0][2].with_suffix(".json").read_text(encoding="utf-8"))


def test_no_software_failures(runs):
    for _, results, _ in runs:
        assert not [r.check.name for r in results if r.error]


def test_json_follows_the_schema(doc):
    jsonschema.validate(doc, schema())  # the reference validator
    assert schema_errors(doc) == []  # the package's own, used by read_report
    broken = dict(doc, rows=[dict(doc["rows"][0], verdict="maybe")])
    assert schema_errors(broken) and schema_errors(dict(doc, extra=1))


def test_markdown_is_rendered_from_the_json(runs, doc):
    assert runs[0][2].read_text(encoding="utf-8") == render(doc)


def test_index_lists_all_69_equations_and_7_tables(doc):
    keys = {it["key"]: it for it in doc["index"]}
    for n in range(1, 70):
        assert f"Eq {n}" in keys, n
    for sub in ("9a", "9b", "9c", "34a", "34b", "34c"):
        assert f"Eq {sub}" in keys
    for t in ("I", "II", "III", "IV", "V", "VI", "VII"):
        assert f"Table {t}" in keys
    for a in "ABCDEFGHI":
        assert f"App. {a}" in keys
    assert sum(it["kind"] == "conclusion" for it in doc["index"]) == 7
    assert not [k for k, it in keys.items() if it["missing"]], "index items without a row"
    for it in doc["index"]:
        assert it["rows"] or it["status"] != "checked", it["key"]
        assert it["status"] == "checked" or it["note"], it["key"]


def test_every_equation_of_17_33_and_43_51_has_its_own_row(doc):
    """Each has a row covering that equation alone (not only a range)."""
    for n in list(range(17, 34)) + list(range(43, 52)):
        own = [r for r in doc["rows"] if r["covers"] == [f"Eq {n}"]]
        assert own, f"Eq {n}"


def test_rows_are_navigable_and_declare_assumptions(doc):
    ids = [r["id"] for r in doc["rows"]]
    assert len(ids) == len(set(ids))
    for r in doc["rows"]:
        assert ":" in r["check"], r["id"]
        assert set(r["depends_on"]) <= set(ASSUMPTIONS), r["id"]
        for f in r["figures"]:
            assert f.startswith("figures/")
    assert all(r["depends_on"] for r in doc["rows"] if r["scope"] == "thesis" and r["parent"] is None)


def test_grouped_claims_count_once(doc):
    top = [r for r in doc["rows"] if r["parent"] is None]
    counts = Counter(r["verdict"] for r in top if r["scope"] == "thesis")
    assert doc["summary"]["thesis"] == {v: counts.get(v, 0) for v in doc["summary"]["thesis"]}
    groups = {r["id"]: r for r in top}
    for gid, n in (("kinematics.appc", 15), ("singularities.table_vi", 37), ("singularities.table_vii", 10)):
        assert sum(r["parent"] == gid for r in doc["rows"]) == n and gid in groups


def test_header_names_commit_versions_seed_machine(doc):
    h = doc["header"]
    assert h["commit"] and h["seed"] == 20120101 and h["quick"] is True
    assert h["versions"]["numpy"] and h["machine"]["cpus"]


def test_two_quick_runs_give_the_same_verdicts(runs):
    """Same seed, fresh contexts: identical verdicts of every row of every check module (the Sec 4.3 rows
    included: their simulated clock leaves out the host's latency), details included."""
    verdicts = [{r.id: r.verdict for res in results for top in res.rows for r in (top, *top.details)}
                for _, results, _ in runs]
    modules = {res.check.func.__module__ for res in runs[0][1]}
    assert {"verification.checks.planning", "verification.checks.hardware"} <= modules
    assert verdicts[0].keys() == verdicts[1].keys()
    differ = {
        k: (verdicts[0][k].value, verdicts[1][k].value)
        for k in verdicts[0]
        if verdicts[0][k] != verdicts[1][k]
    }
    assert not differ, differ


def test_read_report(runs, tmp_path):
    doc = read_report(runs[0][2].with_suffix(".json"))
    assert doc["format"] == "iik-verification-report/2"
    with pytest.raises(ReportError, match="no such file"):
        read_report(tmp_path / "none.json")
    (tmp_path / "bad.json").write_text("{", encoding="utf-8")
    with pytest.raises(ReportError, match="not a JSON"):
        read_report(tmp_path / "bad.json")
    (tmp_path / "wrong.json").write_text(json.dumps({"format": "x"}), encoding="utf-8")
    with pytest.raises(ReportError, match="schema"):
        read_report(tmp_path / "wrong.json")


def test_planning_links_the_exported_3d_view(runs, doc):
    """Issue 13 item 2: the Planning section links the offline 3D view exported into the report folder
    (quick mode: scenario j only)."""
    folder, _, md_path = runs[0]
    row = next(r for r in doc["rows"] if r["id"] == "planning.scenarios")
    assert row["views"] == ["views/j/index.html"]
    page = folder / "views" / "j" / "index.html"
    assert page.stat().st_size > 100_000 and "<html" in page.read_text(encoding="utf-8")[:2000].lower()
    planning = md_path.read_text(encoding="utf-8").split("\n## Planning")[1].split("\n## ")[0]
    assert "](views/j/index.html)" in planning


def test_quick_report_is_marked(runs, doc):
    assert doc["title"].startswith("QUICK")
    assert runs[0][2].read_text(encoding="utf-8").startswith("# QUICK")
    assert runs[0][2].with_suffix(".json").read_text(encoding="utf-8").startswith('{"title": "QUICK')


def test_every_erratum_carries_its_second_reading(doc):
    """Issue 19: no printed value is called wrong (or an input slip) without the search behind it."""
    from verification.report import unread_errata

    assert unread_errata(doc) == []
    read = [r for r in doc["rows"] if r["verdict"] in ("erratum", "input slip") and r["second_reading"]]
    assert len(read) >= 25
    for r in read:
        sr = r["second_reading"]
        assert sr["searched"] >= 1 and sr["trials"][0]["sides"] == ["as stated"], r["id"]
        assert (r["verdict"] == "input slip") == (sr["slip"] == "input"), r["id"]
    broken = dict(doc, rows=[dict(read[0], second_reading=None)])
    assert unread_errata(broken) == [read[0]["id"]]


def test_a_report_with_an_unread_erratum_is_refused(runs, tmp_path):
    from verification import RowError
    from verification.registry import Erratum, Row, Verdict
    from verification.report import CheckResult

    res = runs[0][1][0]
    bad = Row("c", "Eq 1", "m", "n", Verdict.ERRATUM, errata=(Erratum("Eq 1", "p", "c", "x"),), id="k.x")
    with pytest.raises(RowError, match="second reading"):
        write_report([CheckResult(res.check, (bad,), 0.0)], tmp_path / "verification.md")


def test_grades_are_counted_apart_and_rest_on_a_basis(doc):
    s = doc["summary"]
    assert set(s["thesis"]) == set(schema()["$defs"]["counts"]["required"])
    top = [r for r in doc["rows"] if r["parent"] is None and r["scope"] == "thesis"]
    for grade in ("holds", "holds by construction", "consistent with our reconstruction", "input slip",
                  "erratum", "does not hold", "not checkable"):
        assert s["thesis"][grade] > 0, grade
    assert sum(s["groups"]["thesis"].values()) == len(top)
    for r in doc["rows"]:
        if r["verdict"] in ("holds by construction", "consistent with our reconstruction",
                            "not reproduced on our reconstruction"):
            assert r["basis"], r["id"]
    # the Sec 4.3 experimental claims are not checkable; their simulation is a project row
    sim = {r["id"]: r for r in doc["rows"] if r["id"].endswith(".sim")}
    assert len(sim) == 3 and all(r["scope"] == "project standard" for r in sim.values())
    for rid in sim:
        assert next(r for r in doc["rows"] if r["id"] == rid[:-4])["verdict"] == "not checkable"
    # every top-level row, of either scope, states its domain (what it sampled or read)
    missing = [r["id"] for r in doc["rows"] if r["parent"] is None and not r["domain"]]
    assert not missing, missing


def test_markdown_opens_with_the_findings_and_how_to_read(runs):
    md = runs[0][2].read_text(encoding="utf-8")
    head = md.split("\n## Index")[0]
    order = [head.index(h) for h in ("## What this report finds", "## How to read this report",
                                     "## Verdict per section", "## Summary")]
    assert order == sorted(order)
    for word in ("Confirmed by measurement", "Refuted", "Input slips", "Untestable here", "Not evidence"):
        assert word in head
    sections = md.count("\n**Verdict:** ")
    assert sections >= 10
    assert "## Errata and input slips, with their second readings" in md
    assert "readings searched" in md and "where the slip is" in md


def test_new_rows_cover_the_gaps(doc):
    """Issue 19's coverage gaps: Eq 36 and Eq 68 evaluated, Claim 4.9 on scenario e, Table III more than a
    symmetry, the correct App. E formulas in rows of their own."""
    keys = {it["key"]: it for it in doc["index"]}
    for key in ("Eq 36", "Eq 58", "Eq 59", "Eq 61", "Eq 62", "Eq 63", "Eq 65", "Eq 66", "Eq 67", "Eq 68"):
        own = [r for r in doc["rows"] if key in r["covers"] and r["parent"] is None
               and not r["id"].startswith("appendix_e.a")]
        assert own, key
    assert [r["id"] for r in keys["Claim 4.9"]["rows"]] == ["planning.fig42e_via_points"]
    assert "planning.check_table_iii" in {r["id"] for r in keys["Table III"]["rows"]}


def test_errata_agree_with_their_independent_rederivation(doc):
    """Issue 19: every erratum and input slip the report declares has been re-derived independently (sympy, a
    hand-written Table II chain: tests/verification/test_errata_rederived.py), with the same grade and the
    slip in the same place; a new erratum without a re-derivation fails here."""
    import importlib.util
    from pathlib import Path

    path = Path(__file__).with_name("test_errata_rederived.py")
    spec = importlib.util.spec_from_file_location("rederived", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    table = {**mod.REDERIVED, **mod.CITATIONS}
    read = {r["id"]: r for r in doc["rows"] if r["second_reading"]}
    graded = {rid: (r["verdict"], r["second_reading"]["slip"]) for rid, r in read.items()
              if r["verdict"] in ("erratum", "input slip")}
    assert graded == {rid: table[rid] for rid in graded}, "a row disagrees with (or lacks) its re-derivation"
    assert set(table) <= set(graded), sorted(set(table) - set(graded))
