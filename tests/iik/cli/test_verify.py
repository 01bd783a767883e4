"""`iik verify --quick` runs to the end and its report covers the kinematics claims."""

import re

from iik.cli import main


def test_iik_verify_quick_writes_report(tmp_path, capsys):
    code = main(["verify", "--quick", "--out", str(tmp_path)])
    out = capsys.readouterr().out
    assert code == 0, out
    text = (tmp_path / "verification.md").read_text(encoding="utf-8")
    assert "claims from" in out and "report:" in out
    rows = [line.split(" | ") for line in text.splitlines()
            if line.startswith("| ") and not line.startswith("| claim") and line.count(" | ") >= 4]
    verdicts = ("holds", "erratum", "does not hold", "not checkable")
    for ref in ("Eq 4", "App. B", "App. C", "Table II", "Eq 42"):
        hits = [r for r in rows if ref in r[1]]
        assert hits, f"no report row for {ref}"
        for r in hits:
            assert re.search(r"\d", r[3]), f"{ref}: no numbers in {r[3]!r}"
            assert any(v in r[4] for v in verdicts), f"{ref}: no verdict in {r[4]!r}"
    assert (tmp_path / "figures" / "eq4_errors.png").exists()
