"""``iik sim-arm``: hostile options are refused before any bus is opened."""

import pytest

from iik.cli import main


@pytest.mark.parametrize(("argv", "named"), [
    (["--initial", "10", "0", "0", "0", "0", "0"], "--initial: joint q1 at 10 rad is outside its soft"),
    (["--initial", "0", "0", "0", "0", "0"], "--initial: need 6 finite positions"),
    (["--duration", "-5"], "--duration: must be a positive finite number of seconds, got -5.0"),
    (["--duration", "nan"], "--duration: must be a positive finite number of seconds"),
    (["--lag", "nan"], "--lag: must be a finite number in [0, 1] s"),
    (["--lag", "-1"], "--lag: must be a finite number in [0, 1] s"),
    (["--bitrate", "-5"], "--bitrate: must be a PowerCube bit rate"),
    (["--port", "70000"], "--port: must be a UDP port in 1..65535"),
    (["--modules", "0", "1"], "--modules"),
])
def test_bad_options_are_one_line_and_exit_2(argv, named, capfd):
    assert main(["sim-arm", "--interface", "virtual", "--channel", "sim-arm-cli-test", *argv]) == 2
    out, err = capfd.readouterr()
    assert err.strip().startswith("iik sim-arm: error: ") and named in err, err
    assert "ready" not in out and "not properly shut down" not in err and "Traceback" not in err


def test_serves_for_its_duration(capsys):
    assert main(["sim-arm", "--interface", "virtual", "--channel", "sim-cli-ok", "--duration", "0.2"]) == 0
    assert "sim-arm ready: modules [1, 2, 3, 4, 5, 6]" in capsys.readouterr().out
