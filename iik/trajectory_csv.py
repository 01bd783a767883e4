"""The joint-trajectory CSV files: their columns, named once for the writer and the reader.

:func:`iik.planning.write_outputs` writes two (``iik plan``), and :func:`hardware.sources.csv_trajectory`
executes either as written (``iik run --trajectory``):

* ``steps.csv``, one row a step-point: :func:`steps_columns`; its ``t`` is the time the arm executes
  the step-point [s] (whole ms: :attr:`iik.planning.Trajectory.step_t`), only for a timed plan;
* ``trajectory.csv``, the timed trajectory sampled every ``dt``: :data:`TRAJECTORY_COLUMNS`.

A reader needs a header line naming :data:`REQUIRED` (time [s] and joints [rad]), in any order;
it ignores the other columns. Units: s, rad, m.
"""

from __future__ import annotations

__all__ = ["TIME", "JOINTS", "VELOCITIES", "ACCELERATIONS", "REQUIRED", "TRAJECTORY_COLUMNS",
           "STEP_COLUMNS", "steps_columns"]

#: Time [s].
TIME = "t"
#: Joint angles q1..q6 [rad].
JOINTS = tuple(f"q{i}" for i in range(1, 7))
#: Joint speeds [rad/s].
VELOCITIES = tuple(f"qd{i}" for i in range(1, 7))
#: Joint accelerations [rad/s^2].
ACCELERATIONS = tuple(f"qdd{i}" for i in range(1, 7))
#: The columns a trajectory file must name to be executed.
REQUIRED = (TIME, *JOINTS)
#: ``trajectory.csv``.
TRAJECTORY_COLUMNS = (TIME, *JOINTS, *VELOCITIES, *ACCELERATIONS)
#: ``steps.csv`` of a timed plan: step index, time [s], tool point x, y, z [m], joints [rad], Eq 54 effort
#: [rad], whole-arm clearance [m] with the closest link and object, certified clearance of the motion to
#: the next step-point [m].
STEP_COLUMNS = ("step", TIME, "x", "y", "z", *JOINTS, "effort", "clearance", "closest_link",
                "closest_object", "motion_clearance_to_next")


def steps_columns(timed: bool) -> tuple[str, ...]:
    """The columns of ``steps.csv``: :data:`STEP_COLUMNS`, without ``t`` for a plan that is not timed
    (such a file is no trajectory to execute)."""
    return STEP_COLUMNS if timed else tuple(c for c in STEP_COLUMNS if c != TIME)
