"""Every file a command reads goes through the bounded reader (issue 20, item 6): a device is
refused at once by name, before any byte is read (these commands used to read /dev/zero and
/dev/urandom until the kernel killed them at 14-24 GB)."""

import pytest

from iik.cli import main


@pytest.mark.parametrize(("argv", "typed"), [
    (["plan", "/dev/zero"], "SCENARIO"),
    (["run", "--trajectory", "/dev/zero"], "--trajectory"),
    (["view", "--run", "/dev/urandom"], "/dev/urandom"),
])
def test_a_device_given_as_a_file_is_one_error_line_exit_2(argv, typed, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # iik run would otherwise write its run log into the working folder
    assert main(argv) == 2
    err = [line for line in capsys.readouterr().err.splitlines() if "error" in line]
    assert len(err) == 1 and typed in err[0], err
    assert "character device, not a regular file" in err[0], err
