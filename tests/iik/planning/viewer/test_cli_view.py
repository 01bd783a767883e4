"""``iik view``: one-line errors with exit code 2, warnings, the URL, Ctrl-C."""

import signal
import socket
import subprocess
import sys
import urllib.request

from iik.cli import main


def _run(capsys, *argv):
    code = main(["view", *argv])
    out, err = capsys.readouterr()
    return code, out, err


def _one_error(err: str, *words: str) -> None:
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("iik view: error:") and all(w in lines[0] for w in words), lines[0]


def test_scenario_that_fails_validation(capsys, tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('name = "bad"\n[start]\nposition = [0.4, 0.0, 0.2]\n[goal]\nposition = [0.4, 0.3, 0.2]\n'
                   '[[obstacles]]\nname = "box"\ncenter = [0.4, 0.0, 0.2]\nsize = [0.2, 0.2, 0.2]\n')
    code, _, err = _run(capsys, str(bad), "--export", str(tmp_path / "out"))
    assert code == 2
    _one_error(err, "ScenarioError")
    assert not (tmp_path / "out").exists()


def test_run_log_that_does_not_parse(capsys, tmp_path):
    (tmp_path / "r.jsonl").write_text('{"type": "header"}\n')
    code, _, err = _run(capsys, "--run", str(tmp_path / "r.jsonl"))
    assert code == 2
    _one_error(err, "RunLogError")


def test_port_in_use(capsys):
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        s.listen()
        port = s.getsockname()[1]
        code, _, err = _run(capsys, "--q", "0", "0", "0", "0", "0", "0", "--port", str(port))
    assert code == 2
    _one_error(err, "PortInUseError", f"port {port}")


def test_export_into_a_non_empty_folder(capsys, tmp_path):
    (tmp_path / "x.txt").write_text("keep")
    code, _, err = _run(capsys, "--q", "0", "0", "0", "0", "0", "0", "--export", str(tmp_path))
    assert code == 2
    _one_error(err, "ExportError", "--force")
    assert [p.name for p in tmp_path.iterdir()] == ["x.txt"]


def test_interactive_ik_is_not_exportable(capsys, tmp_path):
    code, _, err = _run(capsys, "--export", str(tmp_path / "o"))
    assert code == 2
    _one_error(err, "live server")


def test_q_outside_the_limits_is_shown_with_a_warning(capsys, tmp_path):
    code, out, err = _run(capsys, "--q", "0", "0", "0", "150", "0", "0", "--deg",
                          "--export", str(tmp_path / "o"))
    assert code == 0
    assert err.strip().splitlines() == [line for line in err.strip().splitlines() if "warning" in line]
    assert "q[3]" in err and "outside Table I" in err
    assert "wrote" in out and (tmp_path / "o" / "index.html").is_file()


def test_shipped_scenario_export(capsys, tmp_path):
    code, out, err = _run(capsys, "j", "--export", str(tmp_path / "j"))
    assert code == 0, err
    assert out.startswith("j: OK") and "index.html" in out


def test_serves_until_ctrl_c():
    proc = subprocess.Popen([sys.executable, "-m", "iik.cli", "view", "--q", "0", "0", "0", "0", "0", "0",
                             "--port", "0"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        for line in proc.stdout:
            if "viewer at" in line:
                break
        assert line.split()[2].startswith("http://127.0.0.1:"), line
        port = int(line.split()[2].rstrip("/").rsplit(":", 1)[1])
        with urllib.request.urlopen(f"http://127.0.0.1:{port}/", timeout=10) as page:  # the built client
            assert page.status == 200 and b"<html" in page.read(4096).lower()
        proc.send_signal(signal.SIGINT)
        out, err = proc.communicate(timeout=30)
    finally:
        proc.kill()
    assert proc.returncode == 0, err
    assert "viewer stopped" in out
