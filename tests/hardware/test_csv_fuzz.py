"""Trajectory CSVs cross a trust boundary: fuzzed, structure-aware (a valid file with one
field, line or byte made hostile), under a time budget. Every case ends in a typed error
(:class:`iik.errors.IIKError`) or a validated trajectory -- never another exception, never a hang.
"""

import math
import time
from datetime import timedelta

import numpy as np
import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

import iik
from hardware import ValidatedTrajectory
from hardware.sources import CSV_COLUMNS, csv_trajectory
from iik import THESIS_ARM
from iik.cli import main
from iik.errors import IIKError

pytestmark = pytest.mark.filterwarnings("error")  # no internal warning may leak either

ARM = iik.THESIS_ARM
#: Per-case budget: parsing and validating one file of at most a few hundred lines takes
#: milliseconds; 10 s catches a hang without failing on a loaded machine.
BUDGET = timedelta(seconds=10)

HOSTILE_CELLS = ["", " ", "nan", "NaN", "inf", "-inf", "Infinity", "1e308", "-1e308", "1e-320", "-0",
                 "+0", "abc", "0x10", "1_000", "1,5", '"', '"1"', "\x00", "１", "٣", "9" * 5000, "1e999",
                 "--1", "1e", "\u202e1", "🤖", "None", "True", "[1]", "1 2", "\t", "\\N"]


@st.composite
def valid_file(draw):
    """(header cells, rows of cells, line ending, BOM) of a valid trajectory file."""
    n = draw(st.integers(2, 12))
    q0 = np.array([draw(st.floats(float(ARM.q_min[j]) + 0.05, float(ARM.q_max[j]) - 0.05)) for j in range(6)])
    dts = [draw(st.floats(0.02, 0.4)) for _ in range(n - 1)]
    q = [q0]
    for dt in dts:  # within half the speed limits and inside Table I less the margin
        step = np.array([draw(st.floats(-0.5, 0.5)) for _ in range(6)]) * np.asarray(ARM.velocity) * dt
        q.append(np.clip(q[-1] + step, ARM.q_min + 0.01, ARM.q_max - 0.01))
    t = draw(st.floats(0, 100)) + np.concatenate([[0.0], np.cumsum(dts)])  # need not start at 0
    extra = draw(st.lists(st.sampled_from(["note", "qd1", "x", "q7", ""]), max_size=2, unique=True))
    header = list(CSV_COLUMNS) + extra
    order = draw(st.permutations(range(len(header))))
    rows = [[f"{t[k]:.6f}"] + [f"{v:.9f}" for v in q[k]] + ["1"] * len(extra) for k in range(n)]
    return ([header[i] for i in order], [[r[i] for i in order] for r in rows],
            draw(st.sampled_from(["\n", "\r\n"])), draw(st.booleans()))


def _render(header, rows, newline, bom) -> bytes:
    text = newline.join(",".join(r) for r in [header, *rows]) + newline
    return (b"\xef\xbb\xbf" if bom else b"") + text.encode("utf-8")


@st.composite
def hostile_file(draw):
    """A valid file with one thing made hostile; returns (bytes, what was done)."""
    header, rows, newline, bom = draw(valid_file())
    kind = draw(st.sampled_from(["cell", "header", "row", "lines", "bytes", "value", "none"]))
    rows = [list(r) for r in rows]
    if kind == "cell":
        k, c = draw(st.integers(0, len(rows) - 1)), draw(st.integers(0, len(header) - 1))
        rows[k][c] = draw(st.sampled_from(HOSTILE_CELLS) | st.text(max_size=20))
    elif kind == "header":
        c = draw(st.integers(0, len(header) - 1))
        header = list(header)
        how = draw(st.sampled_from(["rename", "drop", "duplicate", "blank", "numbers", "remove"]))
        if how == "rename":
            header[c] = draw(st.sampled_from(["Q1", "q 1", "time", "t ", "q0"]) | st.text(max_size=8))
        elif how == "drop":
            del header[c]
        elif how == "duplicate":
            header.append(header[c])
        elif how == "blank":
            header[c] = ""
        elif how == "numbers":
            header = rows[0]
        else:
            return _render(header, rows, newline, bom).split(newline.encode(), 1)[1], "header:remove"
        kind += ":" + how
    elif kind == "row":
        k = draw(st.integers(0, len(rows) - 1))
        how = draw(st.sampled_from(["short", "long", "swap", "repeat", "empty-all", "blank", "comment"]))
        if how == "short":
            rows[k] = rows[k][:-1]
        elif how == "long":
            rows[k] = rows[k] + ["0"]
        elif how == "swap" and len(rows) > 1:
            rows[k], rows[k - 1] = rows[k - 1], rows[k]
        elif how == "repeat":
            rows.insert(k, list(rows[k]))
        elif how == "empty-all":
            rows = []
        elif how == "blank":
            rows.insert(k, [""])
        else:
            rows.insert(k, ["# a comment"])
        kind += ":" + how
    elif kind == "lines":  # line structure: old-Mac or mixed endings, blank lines, no final newline
        how = draw(st.sampled_from(["cr", "mixed", "no-final", "trailing-blanks", "leading-blanks"]))
        body = [",".join(r) for r in [header, *rows]]
        if how == "cr":
            text = "\r".join(body) + "\r"
        elif how == "mixed":
            text = "".join(line + draw(st.sampled_from(["\n", "\r\n", "\r"])) for line in body)
        elif how == "no-final":
            text = newline.join(body)
        elif how == "trailing-blanks":
            text = newline.join(body) + newline * draw(st.integers(2, 50))
        else:
            text = newline * draw(st.integers(1, 50)) + newline.join(body) + newline
        return (b"\xef\xbb\xbf" if bom else b"") + text.encode(), kind + ":" + how
    elif kind == "value":  # a joint or a time pushed out of range, still a number
        k, j = draw(st.integers(0, len(rows) - 1)), draw(st.integers(1, 6))
        col = header.index(CSV_COLUMNS[j]) if draw(st.booleans()) else header.index("t")
        rows[k][col] = repr(draw(st.floats(allow_nan=True, allow_infinity=True, width=64)))
    data = _render(header, rows, newline, bom)
    if kind == "bytes":
        how = draw(st.sampled_from(["truncate", "garbage", "nul", "latin1", "empty", "huge-line"]))
        cut = draw(st.integers(0, max(len(data) - 1, 0)))
        if how == "truncate":
            data = data[:cut]
        elif how == "garbage":
            data = data[:cut] + draw(st.binary(min_size=1, max_size=32)) + data[cut:]
        elif how == "nul":
            data = data[:cut] + b"\x00" + data[cut:]
        elif how == "latin1":
            data = data[:cut] + "é".encode("latin-1") + data[cut:]
        elif how == "empty":
            data = b""
        else:
            data = data + b"1" * 300_000 + b"\n"
        kind += ":" + how
    return data, kind


def _outcome(path) -> str:
    """'validated' or the typed error's class; anything else propagates and fails the test."""
    try:
        tr = csv_trajectory(path, THESIS_ARM).validate()
    except IIKError as exc:
        assert str(exc) and "Traceback" not in str(exc)
        return type(exc).__name__
    assert isinstance(tr, ValidatedTrajectory)
    assert np.all(np.isfinite(tr.q)) and np.all(np.diff(tr.times) > 0)
    return "validated"


@settings(deadline=BUDGET, suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(case=hostile_file())
def test_hostile_csv_ends_in_a_typed_error_or_a_validated_trajectory(tmp_path, case):
    data, kind = case
    path = tmp_path / "fuzz.csv"
    path.write_bytes(data)
    t0 = time.perf_counter()
    outcome = _outcome(path)
    event(f"{kind.split(':')[0]} -> {outcome}")
    assert time.perf_counter() - t0 < BUDGET.total_seconds()


@settings(deadline=BUDGET, max_examples=40,
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(case=valid_file())
def test_valid_files_always_validate(tmp_path, case):
    path = tmp_path / "ok.csv"
    path.write_bytes(_render(*case))
    assert _outcome(path) == "validated"


@settings(deadline=timedelta(seconds=60), max_examples=8, suppress_health_check=list(HealthCheck))
@given(case=hostile_file())
def test_hostile_csv_through_iik_run(tmp_path, capfd, case):
    """The same files through the command: exit 0/1 after a run, or 2 with one error line."""
    data, kind = case
    path = tmp_path / "fuzz.csv"
    path.write_bytes(data)
    rc = main(["run", "--trajectory", str(path), "--sim-start", "plan", "--out", str(tmp_path / "r.jsonl"),
               "--no-figures"])
    out, err = capfd.readouterr()
    event(f"iik run exit {rc}")
    assert rc in (0, 1, 2) and "Traceback" not in err
    if rc == 2:
        assert len([x for x in err.splitlines() if x.startswith("iik run: error: ")]) == 1, err
    else:
        assert out.splitlines()[-1].startswith("status: ")


def test_a_long_file_is_bounded(tmp_path):
    """Past MAX_CSV_ROWS a file is refused by name, without reading it all into memory first."""
    from hardware import sources

    rows = math.ceil(sources.MAX_CSV_ROWS) + 1
    path = tmp_path / "long.csv"
    with path.open("w") as f:
        f.write(",".join(CSV_COLUMNS) + "\n")
        for k in range(rows):
            f.write(f"{k * 0.01:.2f},0,0,0,0,0,0\n")
    t0 = time.perf_counter()
    try:
        csv_trajectory(path, THESIS_ARM)
    except IIKError as exc:
        assert f"more than {sources.MAX_CSV_ROWS} data lines" in str(exc)
    else:
        raise AssertionError("a file past the row limit was read")
    assert time.perf_counter() - t0 < 60
