"""`iik verify`: the report it writes, and the same report from Python (`verification.verify`)."""

import json
import re
import subprocess
import sys

import pytest

from iik.cli import main

#: Report headings that are not check sections.
_NOT_SECTIONS = ("Errata", "Figures", "Software failures", "Timing")


def sections_and_rows(text: str) -> dict[str, int]:
    """{section: number of claim rows} of a verification.md, in report order."""
    out, section = {}, None
    for line in text.splitlines():
        if line.startswith("## "):
            title = line[3:].strip()
            section = None if title in _NOT_SECTIONS else title
            if section:
                out[section] = 0
        elif section and line.startswith("| ") and not line.startswith("| claim"):
            out[section] += 1
    return out


@pytest.fixture(scope="module")
def cli_report(tmp_path_factory):
    out = tmp_path_factory.mktemp("verify-cli")
    code = main(["verify", "--quick", "--out", str(out)])
    return code, out


def test_iik_verify_quick_writes_report(cli_report, capsys):
    code, out_dir = cli_report
    assert code == 0
    text = (out_dir / "verification.md").read_text(encoding="utf-8")
    assert "Summary:" in text and "## Timing" in text
    rows = [line.split(" | ") for line in text.splitlines()
            if line.startswith("| ") and not line.startswith("| claim") and line.count(" | ") >= 4]
    verdicts = ("holds", "erratum", "does not hold", "not checkable")
    for ref in ("Eq 4", "App. B", "App. C", "Table II", "Eq 42", "Sec 4.3.1", "Table V"):
        hits = [r for r in rows if ref in r[1]]
        assert hits, f"no report row for {ref}"
        for r in hits:
            assert any(v in r[4] for v in verdicts), f"{ref}: no verdict in {r[4]!r}"
            if "not checkable" not in r[4]:
                assert re.search(r"\d", r[3]), f"{ref}: no numbers in {r[3]!r}"
    assert (out_dir / "figures" / "eq4_errors.png").exists()


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
    cli = sections_and_rows((cli_dir / "verification.md").read_text(encoding="utf-8"))
    written = sections_and_rows((tmp_path / "verification.md").read_text(encoding="utf-8"))
    assert "Hardware execution (Sec 4.3, App. A)" in cli
    assert list(py["sections"].items()) == list(cli.items()) == list(written.items())
    assert sum(cli.values()) == sum(py["sections"].values()) > 100
