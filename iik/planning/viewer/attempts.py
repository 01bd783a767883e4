"""The planner's attempt log as the viewer shows it: a table in the live panel, lines in the scene.

Every :class:`~iik.planning.Attempt` of a plan, in order, with its certified whole-arm
clearance [mm], the nearest (link, object) pair and its outcome: accepted; rejected and
why (below the safety zone, two non-adjacent links touching, a requested via-point
missed); or no path checked and why (no IK branch covers the path, a step skipped).
The scene's label carries the same log, so an exported page (which has no panel) shows it.
"""

from __future__ import annotations

import math
import textwrap

from ..pipeline import Attempt
from .plan_data import PlanView

__all__ = ["outcome", "verdict", "plan_log", "attempt_table", "attempt_lines", "MAX_LABEL_ATTEMPTS"]

#: Attempts listed in the scene's label (the panel lists all of them).
MAX_LABEL_ATTEMPTS = 8
_WIDTH = 100  # characters per label line


def outcome(a: Attempt, zone: float) -> str:
    """``accepted``, ``rejected: why`` or ``no path checked: why`` for one attempt (``zone`` [m])."""
    if a.accepted:
        return "accepted"
    if math.isnan(a.clearance):
        return "no path checked" + (f": {a.reason}" if a.reason else "")
    checks = ((a.clearance < zone, f"clearance below the {zone * 1000:.0f} mm safety zone"),
              (a.self_clearance <= 0, "two non-adjacent links touch"), (bool(a.reason), a.reason))
    why = [text for bad, text in checks if bad]
    return "rejected" + (f": {'; '.join(why)}" if why else "")


def _brief(a: Attempt, zone: float) -> str:
    """One line: label, clearance and pair, outcome."""
    if math.isnan(a.clearance):
        return f"{a.label}: {outcome(a, zone)}"
    return (f"{a.label}: {a.clearance * 1000:.1f} mm ({a.closest_link} to {a.closest_object}), "
            f"{outcome(a, zone)}")


def verdict(plan: PlanView) -> tuple[str, ...]:
    """The outcome in lines: accepted method and attempt, or reason and best attempt; what the arm shows."""
    zone = plan.safety_zone
    if plan.success:
        a = plan.best
        rejected = sum(not b.accepted and not math.isnan(b.clearance) for b in plan.attempts)
        head = (f"OK via {plan.method}; accepted attempt: {a.label}, {a.clearance * 1000:.1f} mm "
                f"({a.closest_link} to {a.closest_object}), after {rejected} rejected path(s)")
        return head, f"the arm shows {plan.arm_shows}"
    best = "none (no path was checked)" if plan.best is None else _brief(plan.best, zone)
    return f"FAILED: {plan.reason}", f"best attempt: {best}", f"the arm shows {plan.arm_shows}"


def plan_log(plan: PlanView) -> tuple[str, ...]:
    """The plan's notes and every attempt with its outcome, one display line each (for a terminal)."""
    return plan.notes + tuple(_brief(a, plan.safety_zone) for a in plan.attempts)


def attempt_table(plan: PlanView) -> str:
    """Markdown for the live panel: the verdict and every attempt, the accepted one in bold."""
    rows = []
    for k, a in enumerate(plan.attempts, 1):
        checked = not math.isnan(a.clearance)
        cells = [str(k), a.label, f"{a.clearance * 1000:.1f}" if checked else "-",
                 f"{a.closest_link} to {a.closest_object}" if checked else "-", outcome(a, plan.safety_zone)]
        cells = [c.replace("|", "\\|") for c in cells]
        rows.append("| " + " | ".join(f"**{c}**" if a.accepted else c for c in cells) + " |")
    head = "\n\n".join(f"**{line}**" if k == 0 else line for k, line in enumerate(verdict(plan)))
    return (f"{head}\n\nAttempt log ({len(plan.attempts)} entries, in order; clearance: "
            "certified whole-arm, at the steps and the motions between them):\n\n"
            "| # | attempt | clearance [mm] | nearest | outcome |\n|---|---|---|---|---|\n" + "\n".join(rows))


def attempt_lines(plan: PlanView, most: int = MAX_LABEL_ATTEMPTS) -> str:
    """Plain text for the scene's label: the verdict and the first ``most`` attempts, wrapped."""
    lines = [f"{k}. {_brief(a, plan.safety_zone)}" for k, a in enumerate(plan.attempts[:most], 1)]
    if len(plan.attempts) > most:
        lines.append(f"... {len(plan.attempts) - most} more (all in iik plan's log and the live panel)")
    text = [*verdict(plan), f"attempt log ({len(plan.attempts)}):", *lines]
    return "\n".join(w for line in text for w in textwrap.wrap(line, _WIDTH, subsequent_indent="    "))
