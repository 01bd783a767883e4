"""``iik urdf``: the same from any install -- stdout, --out FILE, --check FILE."""

from iik import THESIS_ARM
from iik.cli import main
from iik.urdf import thesis_urdf


def test_prints_writes_and_checks_where_asked(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)  # no source checkout around: nothing is written by default
    assert main(["urdf"]) == 0
    assert capsys.readouterr().out == thesis_urdf(THESIS_ARM) and list(tmp_path.iterdir()) == []
    out = tmp_path / "sub" / "arm.urdf"
    assert main(["urdf", "--out", str(out)]) == 0 and out.read_text() == thesis_urdf(THESIS_ARM)
    assert main(["urdf", "--check", str(out)]) == 0
    assert f"{out}: up to date" in capsys.readouterr().out
    out.write_text(thesis_urdf(THESIS_ARM) + " ")
    assert main(["urdf", "--check", str(out)]) == 1
    assert "DIFFERS" in capsys.readouterr().out


def test_check_needs_a_file(tmp_path, capsys):
    assert main(["urdf", "--check"]) == 2
    assert "--check: name the file to compare" in capsys.readouterr().err
    assert main(["urdf", "--check", str(tmp_path / "missing.urdf")]) == 2
    assert "--check: cannot read" in capsys.readouterr().err
