"""`iik verify`: the report it writes, and the same report from Python (`verification.verify`)."""

import json
import re
import subprocess
import sys

import pytest

from iik.cli import main
from verification.registry import Verdict


def sections_and_rows(report_dir) -> dict[str, int]:
    """{section: number of rows} of a report folder's verification.json, in report order."""
    doc = json.loads((report_dir / "verification.json").read_text(encoding="utf-8"))
    out: dict[str, int] = {}
    for row in doc["rows"]:
        out[row["section"]] = out.get(row["section"], 0) + 1
    return out


@pytest.fixture(scope="module")
def cli_report(tmp_path_factory):
    out = tmp_path_factory.mktemp("verify-cli")
    code = main(["verify", "--quick", "--out", str(out)])
    return code, out


def test_iik_verify_quick_writes_report(cli_report, capsys):
    code, out_dir = cli_report
    assert code == 0
    assert "## Summary" in (out_dir / "verification.md").read_text(encoding="utf-8")
    rows = json.loads((out_dir / "verification.json").read_text(encoding="utf-8"))["rows"]
    verdicts = tuple(v.value for v in Verdict)
    for ref in ("Eq 4", "App. B", "App. C", "Table II", "Eq 42", "Sec 4.3.1", "Table V"):
        hits = [r for r in rows if ref in r["reference"]]
        assert hits, f"no report row for {ref}"
        for r in hits:
            assert r["verdict"] in verdicts, f"{ref}: verdict {r['verdict']!r}"
            if r["verdict"] != "not checkable":
                assert re.search(r"\d", r["numbers"]), f"{ref}: no numbers in {r['numbers']!r}"
    assert (out_dir / "figures" / "eq4_errors.png").exists()


def test_quick_report_says_so_in_its_first_line(cli_report):
    """Issue 12 item 8: a --quick report is marked on its first line, in markdown and in JSON."""
    _, out_dir = cli_report
    md = (out_dir / "verification.md").read_text(encoding="utf-8").splitlines()[0]
    js = (out_dir / "verification.json").read_text(encoding="utf-8").splitlines()[0]
    assert md.startswith("# QUICK") and '"title": "QUICK' in js


def test_iik_verify_self_test(tmp_path, capsys):
    """`--self-test` runs the checks with their good and bad forms, prints one line each, writes no report."""
    code = main(["verify", "--self-test", "--quick", "--only", "check_eq53", "check_table_v",
                 "--out", str(tmp_path)])
    out = capsys.readouterr().out
    assert code == 0, out
    assert "| `verification.checks.planning:check_eq53_ellipsoid` | flips |" in out
    assert "| `verification.checks.hardware:check_table_v` | by construction |" in out
    assert out.strip().splitlines()[-1].startswith("self-test: 1 checks flip")
    assert not any(tmp_path.iterdir())


def test_iik_verify_prints_summary(tmp_path, capsys):
    assert main(["verify", "--quick", "--only", "table_ii_encoding", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "claims from 1 checks" in out and "report:" in out


PYTHON_RUN = r"""
import json, sys
from verification import verify
done = verify(sys.argv[1], quick=True)
sections = {}
for res in done.results:
    sections[res.check.section] = sections.get(res.check.section, 0) + len(res.rows)
print(json.dumps({"sections": sections, "failed": done.failed, "cli": "iik.cli" in sys.modules}))
"""


def test_python_and_cli_give_the_same_report(cli_report, tmp_path):
    """From a fresh interpreter that never imports the CLI, the checks give the same sections
    (Sec 4.3 / App. A included) with the same row counts as `iik verify`."""
    _, cli_dir = cli_report
    proc = subprocess.run([sys.executable, "-c", PYTHON_RUN, str(tmp_path)], capture_output=True,
                          text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr[-2000:]
    py = json.loads(proc.stdout.strip().splitlines()[-1])
    assert not py["cli"] and not py["failed"]
    cli, written = sections_and_rows(cli_dir), sections_and_rows(tmp_path)
    assert "Hardware execution (Sec 4.3, App. A)" in cli
    assert list(cli.items()) == list(written.items())
    assert list(py["sections"]) == list(cli) and sum(cli.values()) > 100
