"""``iik view``: one-line errors with exit code 2, warnings, failed plans, the URL, Ctrl-C."""

import signal
import socket
import subprocess
import sys
import urllib.request

import pytest

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


@pytest.mark.parametrize(("flags", "typed"), [
    (("--xyz", "nan", "0", "0", "--zyz", "0", "0", "0"), "--xyz:"),
    (("--xyz", "0.4", "0", "0.3", "--zyz", "0", "inf", "0"), "--zyz:"),
])
def test_bad_pose_names_the_flag_as_typed(capsys, tmp_path, flags, typed):
    code, _, err = _run(capsys, *flags, "--export", str(tmp_path / "out"))
    assert code == 2
    _one_error(err, "InvalidInputError", typed, "NaN or inf")
    assert not (tmp_path / "out").exists()


def test_far_pose_is_shown_unreachable_without_internal_warnings(capfd, tmp_path):
    argv = ["view", "--xyz", "1e308", "0", "0", "--zyz", "0", "0", "0", "--export", str(tmp_path / "out")]
    code = main(argv)
    out, err = capfd.readouterr()
    assert code == 0 and "0 IK solution(s)" in out and "unreachable" in out
    assert "Warning" not in err and "warning" not in err and "inf" not in out


def test_angles_that_look_like_degrees_get_a_warning(capsys, tmp_path):
    argv = ("--xyz", "0.4", "0.3", "0.2", "--zyz", "180", "120", "0", "--export", str(tmp_path / "a"))
    code, _, err = _run(capsys, *argv)
    assert code == 0 and "iik view: warning: --zyz 180 120 0 look like degrees" in err
    code, _, err = _run(capsys, *argv[:-1], str(tmp_path / "b"), "--deg")
    assert code == 0 and "warning" not in err


def test_port_in_use(capsys):
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        s.listen()
        port = s.getsockname()[1]
        code, _, err = _run(capsys, "--q", "0", "0", "0", "0", "0", "0", "--port", str(port))
    assert code == 2
    _one_error(err, "PortInUseError", f"port {port}")


@pytest.mark.parametrize(("host", "why"), [("999.1.1.1", "not an address or host name"),
                                           ("192.0.2.1", "not an address of this machine")])
def test_a_bad_host_is_a_bad_host_not_a_port_in_use(capsys, host, why):
    code, _, err = _run(capsys, "--q", "0", "0", "0", "0", "0", "0", "--host", host, "--port", "8123")
    assert code == 2
    _one_error(err, "ViewRequestError", f"--host: bad host '{host}': {why}")
    assert "port" not in err


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


def test_q_outside_the_limits_is_refused_by_default(capsys, tmp_path):
    """Bad input: one line naming --q, the joint and the way to show it anyway; exit 2; nothing written."""
    code, out, err = _run(capsys, "--q", "0", "0", "0", "150", "0", "0", "--deg",
                          "--export", str(tmp_path / "o"))
    assert code == 2 and out == ""
    _one_error(err, "OutsideLimitsError", "--q:", "q4 = 2.6180 rad (150.0 deg)", "--allow-outside-limits")
    assert not (tmp_path / "o").exists()


def test_q_outside_the_limits_is_shown_when_allowed(capsys, tmp_path):
    """Shown (exported), with exactly one warning line on stderr naming both joints; exit 0."""
    code, out, err = _run(capsys, "--q", "0", "0", "0", "150", "0", "200", "--deg", "--allow-outside-limits",
                          "--export", str(tmp_path / "o"))
    assert code == 0
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("iik view: warning: q4 = ") and "q6 = " in lines[0]
    assert "red" in lines[0]
    assert "wrote" in out and (tmp_path / "o" / "index.html").is_file()


def test_the_help_documents_the_limit_decision_and_the_exit_status(capsys):
    with pytest.raises(SystemExit):
        main(["view", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "--allow-outside-limits" in text and "exit 2, nothing shown or written" in text
    assert "1 shown, but the plan failed or timed out" in text


def test_a_failed_plan_is_shown_with_its_best_attempt(capsys, tmp_path):
    code, out, err = _run(capsys, "a", "--no-fallbacks", "--export", str(tmp_path / "a"))
    assert code == 1 and err == ""  # shown; the plan failed (as iik plan: exit 1)
    head, attempt = out.splitlines()[:2]
    assert head.startswith("a: FAILED (thesis path rejected (fallbacks off))")
    assert attempt.startswith("  - thesis path, IK branch") and "rejected: clearance below the 30" in attempt
    assert (tmp_path / "a" / "index.html").is_file()


def test_planning_options_need_a_scenario(capsys, tmp_path):
    code, _, err = _run(capsys, "--q", "0", "0", "0", "0", "0", "0", "--timeout", "5",
                        "--export", str(tmp_path / "o"))
    assert code == 2
    _one_error(err, "ViewRequestError", "need a SCENARIO")
    code, _, err = _run(capsys, "j", "--timeout", "nan", "--export", str(tmp_path / "o"))
    assert code == 2
    _one_error(err, "--timeout")
    assert not (tmp_path / "o").exists()


def test_shipped_scenario_export(capsys, tmp_path):
    code, out, err = _run(capsys, "j", "--export", str(tmp_path / "j"))
    assert code == 0, err
    assert out.startswith("j: OK") and "index.html" in out
    assert "\n  - thesis path, IK branch" in out and "accepted" in out  # the attempt log


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
