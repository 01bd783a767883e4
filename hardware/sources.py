"""Trajectories to execute: a planned scenario, a CSV file, or the built-in demo.

Each source returns :class:`StepTargets`: the step times [s], joint targets (n, 6)
[rad], the planned tool poses (n, 4, 4) [m] that :func:`hardware.validate`
checks the targets against, and the arm they are for (a scenario's own arm, or the
arm given for a CSV file or the demo): its limits and FK are the ones validated against.
Nothing here prints; what a source has to say (which planner method succeeded, the
clearance) is in :attr:`StepTargets.note`.

A scenario runs exactly the trajectory ``iik plan`` writes: the planner's step-points
at the times its TOPP-RA timing passes them, on the FSTEP millisecond clock
(:attr:`iik.planning.Trajectory.step_t`, the ``t`` column of ``steps.csv``). A CSV file
runs as written (``iik plan``'s ``steps.csv`` and ``trajectory.csv`` both qualify).
:meth:`StepTargets.slowed` stretches any of them (``iik run --speed``).
"""

from __future__ import annotations

import csv
import io
import math
import os
import re
from array import array
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from iik.arm import Arm
from iik.errors import InvalidInputError
from iik.extras import require
from iik.files import read_text
from iik.ik import select, solve
from iik.kinematics import fk
from iik.trajectory_csv import REQUIRED
from iik.validation import bounded_number

from .errors import SafetyError, target_name
from .executor import ValidatedTrajectory, ValidationOptions, time_steps, validate

if TYPE_CHECKING:  # the planning layer is imported only when a scenario is planned
    from iik.planning import Scenario

__all__ = ["StepTargets", "demo_trajectory", "csv_trajectory", "scenario_trajectory", "check_speed",
           "CSV_COLUMNS", "MAX_CSV_ROWS", "MAX_CSV_BYTES", "DEMO_SPEED"]

#: Largest Cartesian step between two step-points of the demo line [m] (Sec 4.2.1).
DEMO_STEP = 0.030
#: Fraction of the joint speed limits the demo line is timed at: gentle, so that the simulated run
#: (20 ms tracking lag) stays inside the 10 mm zone of Sec 4.3.1 it is judged by.
DEMO_SPEED = 0.25
#: Columns a trajectory CSV must name in its header line (others are ignored): the schema's
#: :data:`iik.trajectory_csv.REQUIRED`, the columns ``iik plan`` writes.
CSV_COLUMNS = REQUIRED
#: A number in a trajectory CSV: plain decimal, optional exponent (no "1_000", no non-ASCII digits).
NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")
#: Bounds of a trajectory CSV (memory and time stay bounded): rows of step-points and file size.
MAX_CSV_ROWS = 200_000  # 33 min of 10 ms steps
MAX_CSV_BYTES = 50_000_000  # largest trajectory file [bytes]: reading stops there


@dataclass(frozen=True)
class StepTargets:
    """Step-points to execute, before validation.

    Attributes:
        name: Name of the run (scenario name, CSV file stem, ``"demo"``).
        times: (n,) step times [s].
        q: (n, 6) joint targets [rad].
        poses: (n, 4, 4) planned tool poses in the arm's base frame [m].
        arm: The arm the step-points are for (validation: its limits, speeds and FK).
        orientation_free: (n,) bool: steps at which only the position is compared
            (the planner changed alpha/beta/gamma there on purpose, Sec 3.6), or None.
        note: What the source reports about itself (e.g. the planner's method), or "".
        origin: The file the step-points were read from ("" otherwise).
        lines: (n,) the line of ``origin`` (counting from 1) of each step-point, or None.
        scenario: The planned scenario (:class:`iik.planning.Scenario`: its safety zone, Sec 4.3.2, and
            its boxes, which the run log records), or None for a file or the demo.
    """

    name: str
    times: np.ndarray
    q: np.ndarray
    poses: np.ndarray
    arm: Arm
    orientation_free: np.ndarray | None = None
    note: str = ""
    origin: str = ""
    lines: np.ndarray | None = None
    scenario: Scenario | None = None

    def __len__(self) -> int:
        return len(self.times)

    def validate(self, options: ValidationOptions | None = None, *,
                 limit: int | None = None) -> ValidatedTrajectory:
        """:func:`hardware.validate` of the first ``limit`` step-points (all if None), with
        ``options`` (default :class:`ValidationOptions`). A refused step-point of a file is
        named by its line too."""
        n = len(self) if limit is None else min(int(limit), len(self))
        options = ValidationOptions() if options is None else options
        free = None if self.orientation_free is None else self.orientation_free[:n]
        try:
            return validate(self.times[:n], self.q[:n], self.poses[:n], arm=self.arm, options=options,
                            orientation_free=free)
        except SafetyError as exc:
            if exc.step is None or self.lines is None:
                raise
            where = f"{self.origin} line {self.lines[exc.step]} ({target_name(exc.step)})"
            where += "" if exc.joint is None else f", joint q{exc.joint + 1}"
            raise SafetyError(where, exc.reason, step=exc.step, joint=exc.joint) from None

    def slowed(self, speed: float) -> StepTargets:
        """The same step-points at ``speed`` (0, 1] of their speed: every step lasts
        1/``speed`` as long, rounded up to whole ms (so no joint goes faster than before).

        Raises:
            InvalidInputError: (``speed``) not a finite number in (0, 1].
        """
        if check_speed(speed) == 1.0:
            return self
        with np.errstate(over="ignore", invalid="ignore"):  # absurd times: validation refuses them
            dt = np.ceil(np.diff(self.times) / speed * 1000.0 - 1e-6) / 1000.0
        return replace(self, times=self.times[0] + np.concatenate([[0.0], np.cumsum(dt)]))


def check_speed(speed) -> float:
    """A speed factor (a finite number in (0, 1]) as a float; else InvalidInputError (``speed``)."""
    return bounded_number(speed, "speed", 0.0, 1.0, unit=" (fraction of the planned speed)", open_lo=True)


def demo_trajectory(arm: Arm, speed: float = DEMO_SPEED) -> StepTargets:
    """A straight line of ``arm``'s tool between the poses of two configurations (inside the limits of
    every shipped arm) with step-points at most :data:`DEMO_STEP` apart (Sec 4.2.1), the least-effort
    IK solution (Eq 54) at each, timed at ``speed`` of the joint speed limits.

    Raises:
        InvalidInputError: (``arm``) the two configurations are outside the arm's limits.
        UnreachablePoseError: a step-point of the line has no solution inside the limits.
    """
    from scipy.spatial.transform import Rotation, Slerp

    qa = np.array([0.5, 0.1, 0.0, 0.4, 1.0, 0.0])  # away from the wrist singularity (q5 = 0)
    qb = np.array([0.0, 0.4, 0.0, 0.4, 1.0, 0.0])
    if not (arm.within_limits(qa, -0.05) and arm.within_limits(qb, -0.05)):
        raise InvalidInputError("arm", f"the demo's configurations are outside the limits of {arm.name!r}")
    Ta, Tb = fk(qa, arm), fk(qb, arm)
    dist = float(np.linalg.norm(Tb[:3, 3] - Ta[:3, 3]))
    n = max(2, math.ceil(dist / DEMO_STEP)) + 1
    s = np.linspace(0.0, 1.0, n)
    slerp = Slerp([0.0, 1.0], Rotation.from_matrix(np.stack([Ta[:3, :3], Tb[:3, :3]])))
    poses = np.tile(np.eye(4), (n, 1, 1))
    poses[:, :3, :3] = slerp(s).as_matrix()
    poses[:, :3, 3] = (1 - s)[:, None] * Ta[:3, 3] + s[:, None] * Tb[:3, 3]
    q = np.empty((n, 6))
    prev = qa
    for k, T in enumerate(poses):
        q[k] = prev = select(solve(T, arm), prev, arm=arm)  # Eq 54: least effort from the previous
    return StepTargets("demo", time_steps(q, arm=arm, speed_fraction=speed), q, poses, arm)


def csv_trajectory(path: str | os.PathLike, arm: Arm) -> StepTargets:
    """Step-points from a CSV file whose header line names the columns ``t,q1..q6`` [s, rad]
    (in any order; other columns are ignored), for ``arm`` (a joint file does not say which arm
    it is for). The planned poses are FK of the file's joints (Eq 4 for the thesis arm), so
    validation cannot catch a wrong IK.

    Raises:
        FileError: (argument ``trajectory``) the file is missing, not a regular file, not UTF-8 or
            larger than :data:`MAX_CSV_BYTES` (:func:`iik.files.read_text` stops reading there).
        InvalidInputError: (argument ``trajectory``) the file is empty, has no header line, or a
            cell is missing, not a number or not finite -- naming the line and column (both
            counted from 1) -- or it exceeds :data:`MAX_CSV_ROWS`.
    """
    path = Path(path)

    def bad(reason: str) -> InvalidInputError:
        return InvalidInputError("trajectory", f"{path}: {reason}")

    text = read_text(path, "trajectory", limit=MAX_CSV_BYTES, what="a trajectory file", encoding="utf-8-sig")
    try:
        rows = _csv_rows(csv.reader(io.StringIO(text, newline="")), bad)
    except csv.Error as exc:
        raise bad(f"not CSV ({exc})") from None
    lines, values = rows
    if len(lines) < 2:
        raise bad(f"needs at least 2 data lines (step-points) below the header, has {len(lines)}")
    data = np.array(values, dtype=float).reshape(len(lines), len(CSV_COLUMNS))
    q = data[:, 1:]
    return StepTargets(path.stem, data[:, 0], q, fk(q, arm), arm, origin=str(path), lines=np.asarray(lines))


def _csv_rows(reader, bad) -> tuple[array, array]:
    """(line numbers, t, q1..q6 of every data line in one flat array) of a trajectory CSV;
    ``bad(reason)`` builds the error."""
    header, index = None, {}
    lines, values = array("q"), array("d")
    for row in reader:
        line = reader.line_num
        cells = [c.strip() for c in row]
        if not any(cells):
            continue  # blank line
        if header is None:
            header = cells
            index = _header_index(cells, line, bad)
            continue
        if len(cells) != len(header):
            raise bad(f"line {line} has {len(cells)} cells, the header has {len(header)} "
                      "(lines count from 1)")
        if len(lines) >= MAX_CSV_ROWS:
            raise bad(f"more than {MAX_CSV_ROWS} data lines (the limit of a trajectory file)")
        values.extend(_cell(cells[index[name]], line, index[name], name, bad) for name in CSV_COLUMNS)
        lines.append(line)
    if header is None:
        raise bad("the file is empty: it needs a header line naming the columns " + ",".join(CSV_COLUMNS))
    return lines, values


def _header_index(cells: list[str], line: int, bad) -> dict[str, int]:
    """Column of each of :data:`CSV_COLUMNS` in the header line ``cells``."""
    need = ",".join(CSV_COLUMNS)
    if all(_is_number(c) for c in cells):
        raise bad(f"line {line} holds numbers, not a header: the first line must name the columns {need}")
    index: dict[str, int] = {}
    for col, name in enumerate(cells):
        if name in CSV_COLUMNS and name in index:
            raise bad(f"line {line}: column {name!r} appears twice (columns {index[name] + 1} and {col + 1}, "
                      "counting from 1)")
        index.setdefault(name, col)
    missing = [c for c in CSV_COLUMNS if c not in index]
    if missing:
        raise bad(f"line {line} (the header) lacks the column(s) {', '.join(missing)}: it must name {need}")
    return index


def _is_number(text: str) -> bool:
    return NUMBER.fullmatch(text) is not None or text.lower() in ("nan", "inf", "-inf", "+inf")


def _cell(text: str, line: int, col: int, name: str, bad) -> float:
    where = f"line {line}, column {col + 1} ({name}; lines and columns count from 1)"
    if text.lower().lstrip("+-") in ("nan", "inf", "infinity"):
        raise bad(f"{where}: {text[:40]!r} is not a finite number")
    if NUMBER.fullmatch(text) is None:
        raise bad(f"{where}: {text[:40]!r} is not a number")
    value = float(text)
    if not math.isfinite(value):
        raise bad(f"{where}: {text[:40]!r} is not a finite number")
    return value


def _plan(path: Path, arm: Arm | None):
    """The planner's result for a scenario file, timed as ``iik plan`` times it."""
    from iik.planning import PlanningFailed, plan

    res = plan(path, arm=arm)
    if not res.success:
        raise PlanningFailed(res)
    return res


def scenario_trajectory(name: str | Path, speed: float = 1.0, *, arm: Arm | None = None) -> StepTargets:
    """Step-points of a scenario (file or shipped name, :func:`iik.planning.scenario_path`) planned by
    the project's planner (thesis planner of Sec 3.6 with its fallbacks and the whole-arm
    Coal check) at the times ``iik plan`` writes for them (TOPP-RA on the FSTEP clock,
    :attr:`iik.planning.Trajectory.step_t`), slowed to ``speed`` (0, 1] of that (:meth:`StepTargets.slowed`).

    The planned poses are those of the thesis Cartesian path; where the planner
    changed alpha/beta (Sec 3.6) only the position is checked. For an RRT-Connect
    fallback path there is no Cartesian plan and the poses are FK of the joints.

    The arm is the scenario's own; ``arm``, if given, must be the same arm (:func:`iik.planning.plan`).
    The step targets carry the arm the plan was made for.

    Raises:
        MissingExtraError: the 'planning' extra is not installed (a trajectory file or the demo
            needs only 'hardware').
    """
    require("planning", "a scenario run (hardware.sources.scenario_trajectory)")
    from iik.planning import poses_of, scenario_path

    check_speed(speed)  # before planning
    res = _plan(scenario_path(name), arm)
    q = np.asarray(res.q, dtype=float)
    cart = res.cartesian
    free = np.zeros(len(q), dtype=bool)
    notes = []
    if cart is not None and len(cart.points) == len(q):
        poses = poses_of(np.asarray(cart.points), np.asarray(cart.euler))
        free[list(res.beta_changed_steps) + list(res.alpha_changed_steps)
             + list(res.gamma_changed_steps)] = True
    else:
        notes.append(f"{res.scenario.name}: planned by {res.method}; no Cartesian plan, poses are FK of "
                     "the joints")
        poses = fk(q, res.arm)
    times = np.asarray(res.trajectory.step_t, dtype=float)
    notes.append(f"{res.scenario.name}: planned for the arm {res.arm.name!r} via {res.method} ({len(q)} "
                 f"step-points, {times[-1]:.3f} s "
                 f"as iik plan times them, whole-arm clearance certified >= "
                 f"{res.min_clearance * 1e3:.1f} mm)")
    return StepTargets(res.scenario.name, times, q, poses, res.arm, free, "\n".join(notes),
                       scenario=res.scenario).slowed(speed)
