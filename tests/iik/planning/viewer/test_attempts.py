"""The attempt log as shown: each outcome and why, the panel's table, the scene's caption."""

import dataclasses

import numpy as np
import pytest

from iik.planning import Attempt, PlanOptions, plan
from iik.planning.viewer import PlanScene, plan_scene
from iik.planning.viewer.attempts import MAX_LABEL_ATTEMPTS, attempt_lines, attempt_table, outcome, plan_log

ZONE = 0.03


@pytest.mark.parametrize("attempt,expected", [
    (Attempt("a", True, 0.05, 0.07, "link4", "box"), "accepted"),
    (Attempt("a", False, 0.012, 0.07, "link6", "box"), "rejected: clearance below the 30 mm safety zone"),
    (Attempt("a", False, 0.05, 0.0, "link6", "box"), "rejected: two non-adjacent links touch"),
    (Attempt("a", False, 0.05, 0.07, "link6", "box", "misses the requested via-point planning.via_points[0]"),
     "rejected: misses the requested via-point planning.via_points[0]"),
    (Attempt("a", False, -0.01, -0.002, "link3", "platform"),
     "rejected: clearance below the 30 mm safety zone; two non-adjacent links touch"),
    (Attempt("rrt-connect", reason="no path in 3.0 s"), "no path checked: no path in 3.0 s"),
])
def test_each_outcome_says_why(attempt, expected):
    assert outcome(attempt, ZONE) == expected


@pytest.fixture(scope="module")
def result_b():
    """Scenario b: the thesis path's branches are rejected, a redesign is accepted."""
    return plan("b")


def test_the_panel_lists_every_attempt_in_order_with_the_accepted_one_in_bold(result_b):
    view = plan_scene(result_b)
    rows = [line for line in attempt_table(view).splitlines() if line.startswith("| ") and "---" not in line]
    assert len(rows) == len(result_b.attempts) + 1  # header + one row per attempt
    for row, a in zip(rows[1:], result_b.attempts, strict=True):
        assert a.label in row and (f"{a.clearance * 1000:.1f}" in row if not np.isnan(a.clearance) else True)
        assert row.count("**") == (10 if a.accepted else 0)
    assert sum(a.accepted for a in result_b.attempts) == 1 and not result_b.attempts[0].accepted
    assert attempt_table(view).startswith(f"**OK via {result_b.method}; accepted attempt: ")


def test_the_scene_caption_carries_the_verdict_and_the_log(result_b):
    scene = PlanScene(plan_scene(result_b))
    lines = scene.caption.splitlines()
    assert lines[0].startswith("scenario b: clearances in mm (zone 30 mm); base frame 0, m")
    assert lines[1].startswith(f"OK via {result_b.method}")
    text = " ".join(line.strip() for line in lines)
    for k, a in enumerate(result_b.attempts, 1):
        assert f"{k}. {a.label}: {a.clearance * 1000:.1f} mm" in text
    assert plan_log(plan_scene(result_b))[-1].endswith("accepted")


def test_the_caption_of_a_failed_plan_names_the_reason_and_the_best_attempt():
    view = plan_scene(plan("a", PlanOptions(fallbacks=False, timing=False)))
    text = " ".join(line.strip() for line in attempt_lines(view).splitlines())
    assert text.startswith(f"FAILED: {view.reason} best attempt: {view.best.label}")
    assert "the arm shows the start pose" in text


def test_a_long_log_is_cut_in_the_caption_not_in_the_panel(result_b):
    many = tuple(dataclasses.replace(result_b.attempts[0], label=f"try {k}") for k in range(12))
    view = dataclasses.replace(plan_scene(result_b), attempts=many)
    caption = attempt_lines(view)
    assert f"try {MAX_LABEL_ATTEMPTS - 1}" in caption and f"try {MAX_LABEL_ATTEMPTS}:" not in caption
    assert f"... {12 - MAX_LABEL_ATTEMPTS} more" in caption
    assert all(len(line) <= 100 for line in caption.splitlines())
    assert "try 11" in attempt_table(view)
