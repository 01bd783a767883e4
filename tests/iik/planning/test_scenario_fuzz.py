"""Scenario files across the trust boundary, fuzzed (issue 12, item 9): iik.planning.scenario_io + plan.

Structure-aware: every case is the shipped scenario j (a valid file, with an explicit
``[planning]`` table) with one thing made hostile -- a value replaced (NaN, inf, huge,
negative, zero, wrong type, strings, dates, lists, tables), a key removed or added, absurd
via-points / step counts / step sizes / safety zones, deep nesting, or the bytes of the file
(non-UTF-8 bytes inserted, truncation). Every case must end in a typed error (``IIKError``)
or a plan -- within the time bound, and if it succeeds, a valid one. Examples: the hypothesis
profile's count, at least :data:`CI_EXAMPLES` (``thorough`` runs 5000). ``-s`` shows the figures.
"""

from __future__ import annotations

import copy
import datetime
import math
import tempfile
import time
from collections import Counter
from pathlib import Path

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from iik import fk
from iik.errors import IIKError
from iik.planning import VIA_POINT_TOLERANCE, PlanOptions, plan
from iik.resources import scenarios_dir

try:  # Python >= 3.11
    import tomllib
except ModuleNotFoundError:  # pragma: no cover - Python 3.10
    import tomli as tomllib

#: Each fuzzed plan's budget [s]; a case must end within it plus the unbudgeted loading.
OPTIONS = PlanOptions(timeout=3.0, rrt_time=0.5)
BOUND = OPTIONS.timeout + 10.0
#: At least this many examples (about 20 s; the ``thorough`` profile's count when larger).
CI_EXAMPLES = 200

BASE = tomllib.loads((scenarios_dir() / "j.toml").read_text(encoding="utf-8"))
BASE["planning"] = {"max_step": 0.03, "safety_zone": 0.03, "orientation": "euler", "mode": "LEI"}


# ---------------------------------------------------------------------------- writing TOML


def _string(s: str) -> str:
    esc = {'"': '\\"', "\\": "\\\\"}
    return '"' + "".join(esc.get(c) or (f"\\u{ord(c):04X}" if ord(c) < 0x20 or ord(c) == 0x7F else c)
                         for c in s) + '"'


def _value(v) -> str:
    """One TOML value, inline (tables as inline tables) -- built iteratively, so any nesting depth."""
    if isinstance(v, (list, dict)):
        depth, inner = 0, v
        while isinstance(inner, list) and len(inner) == 1 and isinstance(inner[0], list):
            depth, inner = depth + 1, inner[0]
        if depth > 20:  # a deep single-element nest: write it without recursion
            return "[" * depth + _value(inner) + "]" * depth
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return "nan" if math.isnan(v) else ("inf" if v > 0 else "-inf") if math.isinf(v) else repr(v)
    if isinstance(v, str):
        return _string(v)
    if isinstance(v, datetime.date):
        return v.isoformat()
    if isinstance(v, list):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    return "{" + ", ".join(f"{_string(str(k))} = {_value(x)}" for k, x in v.items()) + "}"


def _document(d: dict) -> bytes:
    return "\n".join(f"{_string(str(k))} = {_value(v)}" for k, v in d.items()).encode("utf-8")


# ---------------------------------------------------------------------------- hostile cases


def _paths(d, prefix=()):
    """Every key and index path of the document (tables, arrays and leaves)."""
    items = d.items() if isinstance(d, dict) else enumerate(d) if isinstance(d, list) else ()
    for k, v in items:
        yield (*prefix, k)
        yield from _paths(v, (*prefix, k))


def _get(d, path):
    for k in path:
        d = d[k]
    return d


PATHS = sorted(_paths(BASE), key=str)
TABLES = [()] + [p for p in PATHS if isinstance(_get(BASE, p), dict)]

NAN, INF = float("nan"), float("inf")
special = st.sampled_from([NAN, INF, -INF, 1e308, -1e308, 1e300, 1e9, 0.0, -0.0, -1.0, -1e-9, 5e-324, 1e-7,
                           0.5, 0.50001, 2**63 - 1, -(2**63), 0, 1, -1, 39, True, False, "", "nan", "0.03",
                           "auto", "line", "arc", "floor", "base", "LJI", "slerp", "obstacle", "../x",
                           datetime.date(2012, 1, 1)])
text = st.text(st.characters(exclude_categories=("Cs",)), max_size=20)
scalar = st.one_of(special, st.floats(), st.integers(-(2**63), 2**63 - 1), text)
hostile = st.one_of(scalar, st.lists(scalar, max_size=5), st.dictionaries(text, scalar, max_size=3),
                    st.lists(st.lists(scalar, min_size=3, max_size=3), max_size=4))
coordinate = st.one_of(st.sampled_from([NAN, INF, 1e308, -10.0, 50.0, 2.0, 0.0, -0.45, 1e-300]),
                       st.floats(-3.0, 3.0))


@st.composite
def replaced(draw):
    doc = copy.deepcopy(BASE)
    path = draw(st.sampled_from(PATHS))
    _get(doc, path[:-1])[path[-1]] = v = draw(hostile)
    return f"replace {'.'.join(map(str, path))}", _document(doc), repr(v)[:40]


@st.composite
def removed(draw):
    doc = copy.deepcopy(BASE)
    path = draw(st.sampled_from(PATHS))
    del _get(doc, path[:-1])[path[-1]]
    return f"remove {'.'.join(map(str, path))}", _document(doc), ""


@st.composite
def added(draw):
    doc = copy.deepcopy(BASE)
    table = _get(doc, draw(st.sampled_from(TABLES)))
    key = draw(st.one_of(text, st.sampled_from(["via_points", "frame", "position", "segments", "beta"])))
    table[key] = draw(hostile)
    return "add a key", _document(doc), key[:20]


@st.composite
def absurd_route(draw):
    doc = copy.deepcopy(BASE)
    plan_ = doc["planning"]
    kind = draw(st.sampled_from(["via_points", "steps_per_segment", "max_step", "safety_zone", "segments"]))
    if kind == "via_points":
        plan_["via_points"] = draw(st.lists(st.lists(coordinate, min_size=3, max_size=3), max_size=30))
        if draw(st.booleans()):
            plan_["segments"] = draw(st.lists(st.sampled_from(["line", "arc"]),
                                              min_size=len(plan_["via_points"]) + 1,
                                              max_size=len(plan_["via_points"]) + 1))
    elif kind == "steps_per_segment":
        plan_["steps_per_segment"] = draw(st.one_of(st.integers(-5, 20000), st.sampled_from([2**62, 4999])))
    elif kind == "segments":
        plan_["segments"] = draw(st.lists(st.sampled_from(["line", "arc", "curve"]), max_size=4))
    else:
        plan_[kind] = draw(st.one_of(st.floats(-1.0, 1.0), st.sampled_from([1e-7, 1e-300, 5e-324, 0.0, 0.6])))
    return f"absurd {kind}", _document(doc), repr(plan_.get(kind))[:40]


@st.composite
def deep(draw):
    doc = copy.deepcopy(BASE)
    path = draw(st.sampled_from(PATHS))
    v = 0.3
    for _ in range(draw(st.sampled_from([2, 10, 100, 900, 1100, 5000]))):
        v = [v]
    _get(doc, path[:-1])[path[-1]] = v
    return "deep nesting", _document(doc), ""


@st.composite
def bytes_(draw):
    data = bytearray(_document(BASE))
    if draw(st.booleans()):
        return "truncated", bytes(data[:draw(st.integers(0, len(data) - 1))]), ""
    for _ in range(draw(st.integers(1, 4))):
        at = draw(st.integers(0, len(data)))
        data[at:at] = draw(st.binary(min_size=1, max_size=4))
    return "bytes inserted", bytes(data), ""


cases = st.one_of(replaced(), removed(), added(), absurd_route(), deep(), bytes_())


# ---------------------------------------------------------------------------- the property


def _valid(r) -> None:
    """A successful result keeps its promises: zone, limits, timing, requested via-points."""
    sc = r.scenario
    assert r.min_clearance >= sc.safety_zone and r.trajectory_clearance >= sc.safety_zone
    assert np.all(r.arm.within_limits(r.q)) and r.trajectory is not None and not r.trajectory.violations
    tool = fk(r.q, r.arm)[:, :3, 3]
    for v in sc.via_points or ():
        assert np.linalg.norm(tool - v, axis=1).min() <= VIA_POINT_TOLERANCE


def _outcome(path: Path) -> tuple[str, float]:
    """Plan the file; the outcome's class and the wall time [s]. Anything but IIKError propagates."""
    t0 = time.perf_counter()
    try:
        r = plan(path, OPTIONS)
    except IIKError as exc:
        outcome = type(exc).__name__
    else:
        if r.success:
            _valid(r)
        assert r.success or r.reason
        outcome = "planned" if r.success else "timed out (result)" if r.timed_out else "no path (result)"
    return outcome, time.perf_counter() - t0


def test_fuzzed_scenario_files_end_in_a_typed_error_or_a_valid_plan_within_the_bound():
    outcomes: Counter = Counter()
    slowest = [0.0, ""]

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "fuzzed.toml"

        @settings(max_examples=max(settings().max_examples, CI_EXAMPLES),
                  suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
        @given(case=cases)
        def run(case):
            what, data, detail = case
            path.write_bytes(data)
            outcome, elapsed = _outcome(path)
            assert elapsed < BOUND, f"{what} {detail}: {elapsed:.1f} s"
            outcomes[(what.split()[0], outcome)] += 1
            if elapsed > slowest[0]:
                slowest[:] = [elapsed, f"{what} {detail}"]

        run()
    n = sum(outcomes.values())
    print(f"\nfuzzed scenario files: {n} examples, slowest {slowest[0]:.2f} s ({slowest[1]})")
    for (what, outcome), k in sorted(outcomes.items()):
        print(f"  {what:9s} {outcome:20s} {k:5d}")
    assert n > 0
