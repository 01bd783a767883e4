"""Outputs whole or not at all, bounded reads (iik.files)."""

import os
import signal
import subprocess
import sys
import textwrap

import pytest

from iik.errors import FileError, InvalidInputError
from iik.files import PARTIAL_PREFIX, atomic_output, check_output, read_bytes, read_text, write_text


def _partials(folder):
    return [p.name for p in folder.iterdir() if p.name.startswith(PARTIAL_PREFIX)]


# ----------------------------------------------------------------------------- reading
def test_a_device_is_refused_at_once_naming_the_argument():
    with pytest.raises(FileError) as info:
        read_bytes("/dev/zero", "trajectory", limit=10**12)  # a read would never end
    e = info.value
    assert isinstance(e, InvalidInputError) and isinstance(e, OSError)
    assert e.argument == "trajectory" and "/dev/zero" in e.reason and "character device" in e.reason


def test_a_fifo_without_a_writer_is_refused_without_blocking(tmp_path):
    fifo = tmp_path / "pipe.csv"
    os.mkfifo(fifo)
    code = f"from iik.files import read_text\nread_text({str(fifo)!r}, 'scenario', limit=100)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert out.returncode == 1 and "FileError: scenario: cannot read" in out.stderr
    assert "a FIFO (named pipe), not a regular file" in out.stderr


def test_a_folder_and_a_missing_file_are_refused(tmp_path):
    with pytest.raises(FileError, match="it is a folder, not a regular file"):
        read_text(tmp_path, "run", limit=100)
    with pytest.raises(FileError, match="no such file"):
        read_text(tmp_path / "missing.jsonl", "run", limit=100)


def test_the_limit_counts_the_bytes_read_not_the_size_stat_reports():
    status = "/proc/self/status"  # a regular file whose stat size is 0, with ~1 kB to read
    assert os.stat(status).st_size == 0 and len(read_bytes(status, "x", limit=10**6)) > 200
    with pytest.raises(FileError, match="more than 100 bytes, the limit of a test file"):
        read_bytes(status, "x", limit=100, what="a test file")


def test_a_file_at_the_limit_is_read_and_one_byte_more_is_refused(tmp_path):
    p = tmp_path / "f.txt"
    p.write_bytes(b"a" * 1000)
    assert read_text(p, "x", limit=1000) == "a" * 1000
    p.write_bytes(b"a" * 1001)
    with pytest.raises(FileError, match="more than 1000 bytes"):
        read_text(p, "x", limit=1000)


def test_text_that_is_not_utf8_is_refused_with_its_offset(tmp_path):
    p = tmp_path / "f.toml"
    p.write_bytes(b"name = 1\n\xff")
    with pytest.raises(FileError, match=r"not UTF-8 text \(byte 0xff at offset 9\)"):
        read_text(p, "file", limit=100)
    p.write_bytes(b"\xef\xbb\xbft,q1")  # a byte-order mark
    assert read_text(p, "file", limit=100, encoding="utf-8-sig") == "t,q1"


# ----------------------------------------------------------------------------- writing
def test_a_folder_is_replaced_whole_when_the_block_completes(tmp_path):
    out = tmp_path / "out"
    with atomic_output(out, "out", folder=True, owns=("a.txt", "b.txt")) as o:
        (o.path / "a.txt").write_text("1")
        (o.path / "b.txt").write_text("1")
        assert not out.exists()  # nothing in place before the end
    with atomic_output(out, "out", folder=True, owns=("a.txt", "b.txt")) as o:
        (o.path / "a.txt").write_text("2")
    assert sorted(p.name for p in out.iterdir()) == ["a.txt"] and (out / "a.txt").read_text() == "2"
    assert _partials(tmp_path) == []


def test_an_error_in_the_block_leaves_the_previous_output_and_no_temporary(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / "a.txt").write_text("old")
    with pytest.raises(RuntimeError), atomic_output(out, "out", folder=True, owns=("a.txt",)) as o:
        (o.path / "a.txt").write_text("new")
        raise RuntimeError("boom")
    assert (out / "a.txt").read_text() == "old" and _partials(tmp_path) == []


def test_a_folder_holding_other_things_or_a_file_is_refused_before_any_work(tmp_path):
    (tmp_path / "mine.txt").write_text("keep")
    with pytest.raises(FileError) as info:
        check_output(tmp_path, "out", folder=True, owns=("a.txt",))
    assert info.value.argument == "out" and "holds other things (mine.txt)" in info.value.reason
    with pytest.raises(FileError, match="is a file, not a folder"):
        check_output(tmp_path / "mine.txt", "out", folder=True)
    with pytest.raises(FileError, match="names no folder"):
        check_output(".", "out", folder=True)
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    with pytest.raises(FileError, match="a FIFO"):  # a file output never replaces a device or a FIFO
        write_text(fifo, "out", "x")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["mine.txt", "pipe"]


def test_a_file_is_replaced_by_one_rename(tmp_path):
    p = tmp_path / "a.urdf"
    write_text(p, "out", "one")
    inode = p.stat().st_ino
    write_text(p, "out", "two")
    assert p.read_text() == "two" and p.stat().st_ino != inode and _partials(tmp_path) == []


WRITER = textwrap.dedent("""
    import sys, time
    from iik.files import atomic_output
    out = sys.argv[1]
    with atomic_output(out, "out", folder=True, owns=("a.txt", "b.txt")) as o:
        (o.path / "a.txt").write_text("new")
        print("half written", flush=True)
        time.sleep(60)
        (o.path / "b.txt").write_text("new")
""")


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM, signal.SIGHUP])
def test_a_signal_mid_way_leaves_the_previous_output_intact(tmp_path, sig):
    out = tmp_path / "out"
    out.mkdir()
    for name in ("a.txt", "b.txt"):
        (out / name).write_text("old")
    proc = subprocess.Popen([sys.executable, "-c", WRITER, str(out)], stdout=subprocess.PIPE, text=True)
    try:
        assert proc.stdout.readline().strip() == "half written"
        proc.send_signal(sig)
        proc.wait(timeout=60)
    finally:
        proc.kill()
    assert proc.returncode != 0
    assert {p.name: p.read_text() for p in out.iterdir()} == {"a.txt": "old", "b.txt": "old"}
    assert _partials(tmp_path) == []  # the temporary was discarded, not left behind


SWAP = textwrap.dedent("""
    import os, signal, sys
    from iik.files import atomic_output
    real, calls = os.replace, []
    def replace(a, b):  # Ctrl-C right after the old folder was moved aside
        real(a, b)
        calls.append(b)
        if len(calls) == 1:
            os.kill(os.getpid(), signal.SIGINT)
    os.replace = replace
    try:
        with atomic_output(sys.argv[1], "out", folder=True, owns=("a.txt",)) as o:
            (o.path / "a.txt").write_text("new")
    except KeyboardInterrupt:
        print("interrupted after", len(calls), "renames")
""")


def test_an_interrupt_cannot_fall_between_the_two_renames_of_a_swap(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / "a.txt").write_text("old")
    res = subprocess.run([sys.executable, "-c", SWAP, str(out)], capture_output=True, text=True, timeout=60)
    assert res.stdout.strip() == "interrupted after 2 renames", res.stderr
    assert (out / "a.txt").read_text() == "new" and _partials(tmp_path) == []
