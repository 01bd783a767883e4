"""The sampling-based fallback: OMPL RRT-Connect in joint space on Coal clearance checks.

Used when the thesis planner's paths collide on every IK branch and after
moving the via-points (Sec 3.6: "the entire path is redesigned"). A state is
valid when the whole arm keeps ``required`` clearance from the scene
(:class:`iik.planning.collision.SceneCollision`) and no two non-adjacent links
touch. The motion between states is checked by OMPL's discrete validity
resolution; the final path is re-checked by the certified continuous check of
:meth:`SceneCollision.path_clearance` by the caller.
"""

from __future__ import annotations

import numpy as np

from iik.arm import Arm
from iik.errors import IIKError, InvalidInputError
from iik.validation import as_joints

from .collision import SceneCollision
from .errors import SamplingError

__all__ = ["rrt_connect"]


def rrt_connect(q_start, q_goal, checker: SceneCollision, *, required: float, arm: Arm,
                time_limit: float = 3.0, seed: int = 1, max_joint_step: float = 0.05,
                margin: float = 0.003) -> np.ndarray | None:
    """Plan a joint path from ``q_start`` to ``q_goal`` [rad] keeping ``required`` clearance [m].

    States must keep ``required + margin`` [m] so that the motions between the
    states OMPL checks (every ~0.01 rad) keep ``required`` under the certified check.

    Reproducible: ``seed`` seeds every random generator the attempt creates (OMPL's
    sampler, planner and path simplifier), whatever OMPL did before in the process, and
    the path is simplified by bounded passes, not for a time; so one seed gives one path
    (unless ``time_limit`` runs out first, on a slow machine).

    Returns:
        (n, 6) joint path [rad] with consecutive configurations at most
        ``max_joint_step`` apart per joint, or ``None`` if OMPL found no solution
        within ``time_limit`` seconds.

    Raises:
        InvalidInputError: ``seed`` is not an integer in 1 .. 2**32 - 1 (OMPL ignores 0).
        SamplingError: OMPL raised (its exception is the cause).
    """
    qa, qb = as_joints(q_start, "q_start")[0][0], as_joints(q_goal, "q_goal")[0][0]
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or not 1 <= seed < 2**32:
        raise InvalidInputError("seed", f"expected an integer in 1 .. 2**32 - 1, got {seed!r}")
    try:
        states = _solve(qa, qb, checker, required + margin, arm, time_limit, seed)
    except IIKError:
        raise
    except (RuntimeError, ValueError, TypeError) as exc:  # OMPL's bindings raise plain exceptions
        raise SamplingError(f"OMPL RRT-Connect failed: {exc}") from exc
    if states is None:
        return None
    out = [states[0]]
    for a, b in zip(states[:-1], states[1:], strict=True):
        n = max(1, int(np.ceil(np.abs(b - a).max() / max_joint_step)))
        for j in range(1, n + 1):
            out.append(a + (b - a) * j / n)
    return np.array(out)


def _solve(q_start, q_goal, checker: SceneCollision, clearance: float, arm: Arm, time_limit: float,
           seed: int) -> list[np.ndarray] | None:
    """OMPL RRT-Connect states (simplified) from ``q_start`` to ``q_goal``, or None."""
    from ompl import base as ob
    from ompl import geometric as og
    from ompl import util as ou

    ou.setLogLevel(ou.LOG_ERROR)
    _reseed(int(seed))
    space = ob.RealVectorStateSpace(6)
    bounds = ob.RealVectorBounds(6)
    for i in range(6):
        bounds.setLow(i, float(arm.q_min[i]))
        bounds.setHigh(i, float(arm.q_max[i]))
    space.setBounds(bounds)

    def valid(state) -> bool:
        return checker.keeps(np.array([state[i] for i in range(6)]), clearance)

    si = ob.SpaceInformation(space)
    si.setStateValidityChecker(valid)
    # resolution as a fraction of the space's extent: ~0.01 rad per check
    si.setStateValidityCheckingResolution(0.01 / space.getMaximumExtent())
    si.setup()
    ss = og.SimpleSetup(si)
    start, goal = space.allocState(), space.allocState()
    for i in range(6):
        start[i] = float(q_start[i])
        goal[i] = float(q_goal[i])
    ss.setStartAndGoalStates(start, goal)
    ss.setPlanner(og.RRTConnect(si))
    solved = ss.solve(time_limit)
    if not solved or not ss.haveExactSolutionPath():
        return None
    path = ss.getSolutionPath()
    ss.getPathSimplifier().simplifyMax(path)  # bounded passes, no clock: the same states for the same seed
    return [np.array([path.getState(k)[i] for i in range(6)]) for k in range(path.getStateCount())]


def _reseed(seed: int) -> None:
    """Seed OMPL's seed generator: every generator OMPL creates from now on derives from ``seed``.

    OMPL logs "Random number generation already started. Changing seed now will not lead to
    deterministic sampling" when it handed out seeds before, and re-seeds all the same: the
    generators created earlier keep their state, but an attempt creates all of its own after
    this call (``test_rrt`` checks that one seed gives one path in a fresh process and after
    other attempts). The message is therefore silenced here, not for the whole program.
    """
    from ompl import util as ou

    level = ou.getLogLevel()
    ou.setLogLevel(ou.LOG_NONE)
    try:
        ou.RNG.setSeed(seed)
    finally:
        ou.setLogLevel(level)
