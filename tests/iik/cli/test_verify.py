"""`iik verify`: the report it writes, and the same report from Python (`verification.verify`)."""

import json
import re
import signal
import subprocess
import sys
import time

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


def _tree(folder) -> dict:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def test_ctrl_c_mid_way_leaves_the_previous_report_unmixed(tmp_path):
    """SIGINT while `iik verify --only kinematics` is writing figures: the previous report folder is
    exactly as it was (no new figure beside it), and no temporary is left behind."""
    out = tmp_path / "r"
    assert main(["verify", "--quick", "--only", "table_ii_encoding", "--out", str(out)]) == 0
    before = _tree(out)
    proc = subprocess.Popen([sys.executable, "-m", "iik.cli", "verify", "--quick", "--only", "kinematics",
                             "--out", str(out)], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 300
        while not list(tmp_path.rglob("*.png")) and time.monotonic() < deadline:  # a figure is being written
            time.sleep(0.05)
        assert list(tmp_path.rglob("*.png")), "no figure was written"
        proc.send_signal(signal.SIGINT)
        err = proc.communicate(timeout=120)[1]
    finally:
        proc.kill()
    assert proc.returncode == 130 and "iik verify: interrupted by SIGINT" in err, err[-2000:]
    assert _tree(out) == before
    assert [p.name for p in tmp_path.iterdir()] == ["r"]


def test_a_selection_that_matches_nothing_is_an_error_and_writes_nothing(tmp_path, capsys):
    out = tmp_path / "r"
    assert main(["verify", "--quick", "--only", "table_ii_encoding", "--out", str(out)]) == 0
    before = _tree(out)
    capsys.readouterr()
    assert main(["verify", "--only", "zzzz", "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1
    assert err[0].startswith("iik verify: error: SelectionError: --only: 'zzzz' matches no check")
    assert main(["verify", "--self-test", "--only", "table_ii_encoding", "zzzz"]) == 2  # each item must match
    assert _tree(out) == before


def test_a_partial_run_says_so_first_and_never_claims_full_mode(tmp_path):
    assert main(["verify", "--only", "table_ii_encoding", "--out", str(tmp_path)]) == 0
    md = (tmp_path / "verification.md").read_text(encoding="utf-8")
    doc = json.loads((tmp_path / "verification.json").read_text(encoding="utf-8"))
    first = "# PARTIAL verification report (only the checks matching 'table_ii_encoding'"
    assert md.splitlines()[0].startswith(first)
    assert doc["title"].startswith("PARTIAL") and doc["header"]["only"] == ["table_ii_encoding"]
    assert "mode: full" not in md and "mode: partial (only the checks matching `table_ii_encoding`)" in md


@pytest.mark.parametrize(("argv", "typed"), [
    (["--seed", "-5"], "InvalidInputError: --seed: expected an integer in 0 .. 2**63 - 1, got -5"),
    (["--out", "FILE"], "FileError: --out: {tmp}/FILE is a file, not a folder"),
    (["--out", "."], "FileError: --out: '.' names no folder to write"),
])
def test_bad_options_are_one_line_errors_exit_2(tmp_path, capsys, argv, typed):
    (tmp_path / "FILE").write_text("mine")
    argv = [str(tmp_path / a) if a == "FILE" else a for a in argv]
    assert main(["verify", "--quick", "--only", "table_ii_encoding", *argv]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and typed.format(tmp=tmp_path) in err[0], err
    assert (tmp_path / "FILE").read_text() == "mine"
