"""Run-log naming: a pure function of the run's name, its start time and the files already there."""

from datetime import datetime
from pathlib import Path

import pytest

from hardware.runlog import MAX_SAME_NAME, log_path, reserve_log_path
from iik.errors import InvalidInputError

WHEN = datetime(2026, 3, 14, 9, 26, 53)


def test_a_folder_gets_the_name_and_the_start_time():
    assert log_path("runs", "j", WHEN) == Path("runs/j-20260314-092653.jsonl")
    named = log_path(Path("a/b"), "demo", WHEN, existing={"other.jsonl"})
    assert named == Path("a/b/demo-20260314-092653.jsonl")


def test_a_taken_name_is_numbered_and_nothing_is_overwritten():
    first, second, third = (f"j-20260314-092653{k}.jsonl" for k in ("", "-2", "-3"))
    assert log_path("runs", "j", WHEN, {first}).name == second
    assert log_path("runs", "j", WHEN, {first, second}).name == third
    assert log_path("runs", "j", WHEN, {first, third}).name == second  # the first free number
    assert log_path("runs", "j", WHEN, {"j-20260314-092652.jsonl"}).name == first  # another second


def test_a_jsonl_file_is_written_exactly_whatever_is_there():
    assert log_path("out/mine.jsonl", "j", WHEN, {"mine.jsonl"}) == Path("out/mine.jsonl")


def test_a_folder_full_of_one_name_is_an_error_naming_out():
    stem = "j-20260314-092653"
    taken = {f"{stem}.jsonl"} | {f"{stem}-{k}.jsonl" for k in range(2, MAX_SAME_NAME + 1)}
    with pytest.raises(InvalidInputError) as info:
        log_path("runs", "j", WHEN, taken)
    assert info.value.argument == "out" and "9999" in info.value.reason


def test_reserving_creates_the_file_so_two_runs_never_share_a_name(tmp_path):
    a = reserve_log_path(tmp_path / "runs", "j", WHEN)
    b = reserve_log_path(tmp_path / "runs", "j", WHEN)
    assert (a.name, b.name) == ("j-20260314-092653.jsonl", "j-20260314-092653-2.jsonl")
    assert a.is_file() and b.is_file() and a.stat().st_size == 0
    named = reserve_log_path(tmp_path / "x" / "mine.jsonl", "j")
    assert named == tmp_path / "x" / "mine.jsonl" and named.parent.is_dir() and not named.exists()
    (tmp_path / "file").write_text("")
    with pytest.raises(InvalidInputError) as info:
        reserve_log_path(tmp_path / "file" / "runs", "j")
    assert info.value.argument == "out"
