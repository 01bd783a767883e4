"""Members and feasible intervals of the continua that are not linear (:class:`~iik.ik.result.Continuum`
of kind ``"theta1"`` and ``"numerical"``).

A member with the free joint at theta is found by continuation from the representative: the
free joint is stepped towards theta (steps of at most :data:`STEP` rad), and at each step the
other joints are refit by Levenberg-Marquardt with the free joint held (the compiled
:func:`iik.ik.kernel.continuum_members`), or, for theta1 and theta2 continua, the exact
closed-form configuration nearest the previous member is taken (the compiled
:func:`iik.ik.kernel.closed_form_march`). The feasible interval is where the members reach the
pose within the tolerance and lie inside the joint limits, found by marching from the
representative in both directions and bisecting (to :data:`RESOLUTION` rad) between the last
good member and the first failure, each trial one continuation step from the last good member.
The march towards each limit is computed once per continuum object, and only as far as asked.

Units: radians.
"""

from __future__ import annotations

import math

import numpy as np

from .angles import angle_distance, into_limits, wrap_angle

__all__ = [
    "follow",
    "feasible_interval",
    "on_continuum",
    "theta1_branches",
    "inside_member",
    "closes",
    "theta1_bands",
    "along",
    "STEP",
    "RESOLUTION",
]

#: Largest continuation step of the free joint [rad].
STEP = 0.05
#: Resolution of the ends of a feasible interval [rad].
RESOLUTION = 1e-6
_JUMP = 0.5  # a member more than this from the previous one [rad]: the continuation lost the curve
#: The orthonormality bound the marches check the continuum's pose against: the pose passed
#: iik.solve's check with the caller's IKOptions.orthonormal_tol (always below this), and the
#: marches need only its projected rotation. (A fixed 1e-4 or 1e-3 refused poses the IK had
#: solved with the default 1e-3 or a larger option: ValueError from a continuum's members.)
POSE_CHECK_TOL = 0.5


def _kernel():
    from . import kernel

    return kernel


def _march(c, thetas: np.ndarray, q0=None):
    """Members (n, 6) and residuals (n, 2) along the free-joint values ``thetas`` (in order,
    starting next to the member ``q0``: the representative by default)."""
    k = _kernel()
    j = c.free_joint - 1
    cols = np.array([i for i in range(6) if i != j], dtype=np.int64)
    coupled = -1 if c.coupled_joint is None else c.coupled_joint - 1
    out_q = np.empty((len(thetas), 6))
    out_r = np.empty((len(thetas), 2))
    opt = np.array([c.tolerance[0], c.tolerance[1], 1e-5, POSE_CHECK_TOL, 1e-7])
    data = k.arm_data(c.arm).vector
    ok = k.continuum_members(
        np.ascontiguousarray(c.pose, dtype=float),
        data,
        opt,
        np.array(c.representative if q0 is None else q0, dtype=float),
        cols,
        j,
        coupled,
        float(c.sign),
        np.ascontiguousarray(thetas, dtype=float),
        k.scratch(),
        out_q,
        out_r,
    )
    if not ok:  # pragma: no cover (the pose passed the IK's check)
        raise ValueError("the continuum's pose does not pass the pose check")
    return out_q, out_r


def _path(start: float, end: float) -> np.ndarray:
    n = max(1, math.ceil(abs(end - start) / STEP))
    return start + (end - start) * np.arange(1, n + 1) / n


def _march_closed(c, thetas: np.ndarray, q0=None, starts=None):
    """theta1 and theta2 continua: the exact closed-form configurations at each value (theta2:
    solver joint 1 held at the representative's), the one nearest the previous member taken
    (continuation without a polish: the members are exact), starting from the member ``q0``
    (the representative by default). With ``starts`` (n,): q0 is (k, 6) and a march begins
    from ``q0[starts[i]]`` at each i where that is >= 0 (several marches in one call).
    Compiled: :func:`iik.ik.kernel.closed_form_march`."""
    k = _kernel()
    n = len(thetas)
    thetas = np.ascontiguousarray(thetas, dtype=float)
    if c.kind == "theta2":  # (solver joint 1 is user joint 1, or 6 for an arm read from the flange)
        j1 = 5 if c.arm.solver.reversed else 0
        joint1, joint2 = np.full(n, float(c.representative[j1])), thetas
    else:
        joint1, joint2 = thetas, np.full(n, np.nan)
    if starts is None:
        starts = np.full(n, -1, dtype=np.int64)
        starts[:1] = 0
    out_q, out_r = np.empty((n, 6)), np.empty((n, 2))
    ok = k.closed_form_march(
        np.ascontiguousarray(c.pose, dtype=float),
        k.arm_data(c.arm).vector,
        np.array([c.tolerance[0], c.tolerance[1], 1e-5, POSE_CHECK_TOL, 1e-7]),
        np.array(c.representative if q0 is None else q0, dtype=float).reshape(-1, 6),
        np.asarray(starts, dtype=np.int64),
        joint1,
        joint2,
        k.scratch(),
        out_q,
        out_r,
    )
    if not ok:  # pragma: no cover (the pose passed the IK's check)
        raise ValueError("the continuum's pose does not pass the pose check")
    return out_q, out_r


def _marcher(c):
    """How c's members are followed: by closed forms (theta1, theta2 continua) or by refits."""
    return _march_closed if c.kind in ("theta1", "theta2") else _march


def follow(c, thetas) -> tuple[np.ndarray, np.ndarray]:
    """Members (n, 6) of continuum ``c`` at the free-joint values ``thetas`` [rad] and their
    residuals (n, 2) [m, rad], each by continuation from the representative."""
    j = c.free_joint - 1
    start = float(c.representative[j])
    paths = [_path(start, float(th)) for th in np.atleast_1d(np.asarray(thetas, dtype=float))]
    if not paths:
        return np.zeros((0, 6)), np.zeros((0, 2))
    ends = np.cumsum([len(p) for p in paths]) - 1
    if _marcher(c) is _march_closed:  # every march in one call
        starts = np.full(ends[-1] + 1, -1, dtype=np.int64)
        starts[np.r_[0, ends[:-1] + 1]] = 0
        q, r = _march_closed(c, np.concatenate(paths), c.representative, starts)
        return q[ends], r[ends]
    marched = [_march(c, p) for p in paths]
    return np.array([q[-1] for q, _ in marched]), np.array([r[-1] for _, r in marched])


def _inside(arm, q):
    """q (..., 6) turned into the limits where a turn by 2 pi brings a joint in, and whether each
    is in."""
    from ..arm import LIMIT_TOL

    return into_limits(q, arm.q_min, arm.q_max, LIMIT_TOL)


_CHUNK = 16  # steps of a march first computed where it may stop early (then doubled)


def _toward(c, end: float, march=None, steps: int | None = None):
    """c's march from the representative towards the free-joint value ``end`` (``march``: the
    continuum's own by default), its first ``steps`` (all by default): the values (n,) [rad],
    members (n, 6) and residuals (n, 2). Computed once per continuum and end (kept in
    ``c.marches``), and only as far as asked (a march continues from its last member: the same
    members as in one go). The interval, the inside member, the samples and the theta1 branches
    share it."""
    march = march or _marcher(c)
    key = (float(end), march)
    rep, pose = np.array(c.representative, dtype=float), np.array(c.pose, dtype=float)
    hit = c.marches.get(key)
    if hit is not None and np.array_equal(hit[0], rep) and np.array_equal(hit[1], pose):
        path, q, r = hit[2]
    else:
        path, q, r = _path(float(rep[c.free_joint - 1]), float(end)), np.zeros((0, 6)), np.zeros((0, 2))
    n = len(path) if steps is None else min(steps, len(path))
    if len(q) < n:
        qn, rn = march(c, path[len(q) : n], rep if len(q) == 0 else q[-1])
        q, r = np.vstack([q, qn]), np.vstack([r, rn])
        c.marches[key] = (rep, pose, (path, q, r))
    return path[:n], q[:n], r[:n]


def _scan(c, end: float, found):
    """c's march towards ``end`` (:func:`_toward`), extended until ``found(path, members,
    residuals)`` (bool (n,)) holds somewhere: (path, members, the first index where it holds, or
    None)."""
    n = _CHUNK
    while True:
        path, q, r = _toward(c, end, steps=n)
        hit = found(path, q, r)
        if hit.any():
            return path, q, int(hit.argmax())
        if len(path) < n:
            return path, q, None
        n *= 2


def _reaches(c, r) -> np.ndarray:
    """Do the residuals r (..., 2) [m, rad] reach c's pose within its tolerance?"""
    return (r[..., 0] <= c.tolerance[0]) & (r[..., 1] <= c.tolerance[1])


def _good(c, q, r, prev) -> np.ndarray:
    """Are the members q (..., 6) with residuals r (..., 2) inside the limits, within the
    tolerance and (marched by refits) no more than _JUMP from the members ``prev`` before them?
    A closed-form march halves its steps where a member jumps
    (:func:`iik.ik.kernel.closed_form_march`): between its steps the curve itself swings (joints 3
    and 6 by ~pi within 0.02 rad of joint 1 near a wrist singularity), and the feasible interval
    of a thesis theta1 continuum ended there, 2.5 rad short of the limit."""
    ok = _inside(c.arm, q)[1] & _reaches(c, r)
    return ok if _marcher(c) is _march_closed else ok & (angle_distance(q, prev) <= _JUMP)


def _edge(c, start: float, limit: float) -> float:
    """How far from the representative the feasible members reach towards ``limit``: the march
    to the first member that fails, then bisection (to RESOLUTION) between the last good
    member and it, each trial member one continuation step from the last good one."""
    if abs(limit - start) <= RESOLUTION:
        return start
    rep = np.asarray(c.representative, dtype=float)[None]
    path, q, i = _scan(c, limit, lambda p, q, r: ~_good(c, q, r, np.vstack([rep, q[:-1]])))
    if i is None:
        return limit
    lo, hi, q_lo = (start if i == 0 else float(path[i - 1])), float(path[i]), (rep[0] if i == 0 else q[i - 1])
    march = _marcher(c)
    while abs(hi - lo) > RESOLUTION:
        mid = 0.5 * (lo + hi)
        qm, rm = march(c, np.array([mid]), q_lo)
        if _good(c, qm[0], rm[0], q_lo):
            lo, q_lo = mid, qm[0]
        else:
            hi = mid
    return lo


def along(c) -> tuple[np.ndarray, np.ndarray]:
    """Members of continuum ``c`` across its free joint's limits, by continuation from the
    representative in both directions (steps of at most :data:`STEP` rad): the free-joint values
    (n,) [rad] in increasing order and the members (n, 6) [rad] that reach the pose within the
    tolerance. A member that misses it is left out and the march goes on (a numerical tube can
    be thinner than the tolerance in places); a march by refits ends where the members jump (more
    than 0.5 rad from the last one kept: the curve is lost; a closed-form march follows the curve
    through its swings, :func:`_good`). The other joints' limits are not applied (their windings
    are the caller's, :mod:`iik.ik.nearest`)."""
    j = c.free_joint - 1
    start = float(c.representative[j])
    march = _march_closed if c.kind == "theta1" else _march
    thetas, members = [start], [np.array(c.representative, dtype=float)]
    for limit in (float(c.arm.q_min[j]), float(c.arm.q_max[j])):
        if abs(limit - start) <= RESOLUTION:
            continue
        path, q, r = _toward(c, limit, march)
        prev = members[0]
        for i, th in enumerate(path):
            if march is _march and float(angle_distance(q[i], prev)) > _JUMP:
                break
            if _reaches(c, r[i]):
                thetas.append(float(th))
                members.append(q[i])
                prev = q[i]
    order = np.argsort(thetas, kind="stable")
    return np.array(thetas)[order], np.array(members)[order]


def feasible_interval(c) -> tuple[float, float]:
    """The feasible interval of continuum ``c``'s free joint (the piece containing the
    representative), or (nan, nan) if the representative itself is not feasible."""
    j = c.free_joint - 1
    start = float(c.representative[j])
    if not _inside(c.arm, c.representative)[1]:
        return (math.nan, math.nan)
    lo, hi = float(c.arm.q_min[j]), float(c.arm.q_max[j])
    return (_edge(c, start, lo), _edge(c, start, hi))


def on_continuum(c, q, tol: float = 1e-7) -> bool:
    """Is the configuration q (6,) a member of continuum c (its member at q's free joint)?"""
    m, r = follow(c, [float(q[c.free_joint - 1])])
    return bool(angle_distance(m[0], q) <= tol and _reaches(c, r[0]))


def _on_branch(c, Q, tol: float = 1e-7) -> np.ndarray:
    """:func:`on_continuum` for each configuration of Q (n, 6), by the shared marches towards
    the limits: each member one continuation step from the marched member before its value of
    the free joint (all in one call), or by :func:`follow` beyond the limits."""
    j = c.free_joint - 1
    start, rep = float(c.representative[j]), np.array(c.representative, dtype=float)
    Q = np.asarray(Q, dtype=float).reshape(-1, 6)
    ths = Q[:, j]
    prev, marched = np.empty((len(ths), 6)), np.zeros(len(ths), dtype=bool)
    for limit, side in ((float(c.arm.q_min[j]), ths < start), (float(c.arm.q_max[j]), ths >= start)):
        sel = side & (np.abs(ths - start) <= abs(limit - start)) & ((ths - start) * (limit - start) >= 0.0)
        if sel.any():
            path = _path(start, limit)
            k = np.count_nonzero(np.abs(path[None] - start) < np.abs(ths[sel, None] - start), axis=1)
            members = _toward(c, limit, steps=int(k.max()))[1]
            prev[sel] = np.vstack([rep[None], members])[k]
            marched |= sel
    out = np.array([not marched[i] and on_continuum(c, q, tol) for i, q in enumerate(Q)], dtype=bool)
    if marched.any():
        m, r = _march_closed(c, ths[marched], prev[marched], np.arange(marched.sum()))
        out[marched] = (angle_distance(m, Q[marched]) <= tol) & _reaches(c, r)
    return out


def _continues(c) -> bool:
    """Do c's members continue on both sides of the representative (a curve, not a point)?"""
    x = float(c.representative[c.free_joint - 1])
    m, r = follow(c, [x - STEP, x + STEP])
    jump = angle_distance(m, c.representative)
    return bool(np.all(_reaches(c, r) & (jump <= 2.0)))


def theta1_branches(continua) -> list[int | None]:
    """For the candidate rows of a degenerate pose (one theta1 :class:`Continuum` each, in the
    result's order): the index of the row whose branch each row lies on (itself for the first
    of a branch), or None for a row that is an isolated solution (no curve through it). The
    later rows are tested against each branch's members at once (:func:`_on_branch`)."""
    out: list[int | None] = []
    on: dict[int, np.ndarray] = {}  # branch -> which of the rows after it lie on it
    reps = np.array([c.representative for c in continua], dtype=float).reshape(-1, 6)
    for i, c in enumerate(continua):
        owner = next((k for k in range(i) if out[k] == k and on[k][i - k - 1]), None)
        if owner is None and _continues(c):
            owner = i
            on[i] = _on_branch(c, reps[i + 1 :])
        out.append(owner)
    return out


def inside_member(c):
    """A member of continuum c inside the joint limits, nearest the representative along the free
    joint (members every :data:`STEP` rad or closer, followed once towards each of the free joint's
    limits), or None if none is found."""
    arm = c.arm
    rep, ok = _inside(arm, np.array(c.representative, dtype=float))
    if ok:
        return rep
    j = c.free_joint - 1
    start = float(c.representative[j])
    found = []  # (distance along the free joint, member) of the first inside member each way

    def inside(path, q, r):
        return _inside(arm, q)[1] & _reaches(c, r)

    for end in (arm.q_min[j], arm.q_max[j]):
        path, qs, i = _scan(c, float(end), inside)
        if i is not None:
            found.append((abs(path[i] - start), _inside(arm, qs[i])[0]))
    return min(found, key=lambda f: f[0])[1] if found else None


def closes(c) -> bool:
    """Does the theta1 continuum c close around the circle: its members, followed from the
    representative once around (steps of at most :data:`STEP` rad), all reach the pose? False
    for a band beside the continuum (the wrist point just off the joint-1 axis: members within
    the tolerance only over part of the circle, docs/IK_CLASS.md section 5). (Jumps are allowed:
    on an exact continuum the wrist joints swing by more than 1 rad within one step where the
    curve passes near a wrist singularity.)"""
    x = float(c.representative[c.free_joint - 1])
    return bool(np.all(_reaches(c, _toward(c, x + 2.0 * math.pi)[2])))


#: A row is on a band of joint 1 when its member this far [rad] along joint 1, on either side,
#: reaches the pose (an isolated solution's set within the tolerance is ~1e-10 rad wide).
BAND_PROBE = 1e-3
#: A row lies on a band when the band's member at its joint 1 is within this [rad] of it in
#: every joint and the segment between them stays within the tolerance (7 points).
BAND_NEAR = 1e-3


def _on_band(c, Q) -> np.ndarray:
    """Is each configuration of Q (n, 6) on the band c: c's member at its joint 1 (followed from
    the representative) reaches the pose, lies within BAND_NEAR of it and is joined to it by a
    segment within the tolerance?"""
    from .compare import pose_residuals

    j = c.free_joint - 1
    out = np.zeros(len(Q), dtype=bool)
    for i, q in enumerate(Q):
        m, r = follow(c, [float(q[j])])
        m = m[0]
        if not _reaches(c, r[0]) or float(angle_distance(m, q)) > BAND_NEAR:
            continue
        pts = q + np.linspace(0.0, 1.0, 9)[1:-1, None] * wrap_angle(m - q)[None]
        pres, rres = pose_residuals(pts, np.broadcast_to(c.pose, (len(pts), 4, 4)), c.arm)
        out[i] = bool(np.all(pres <= c.tolerance[0]) and np.all(rres <= c.tolerance[1]))
    return out


def theta1_bands(continua) -> list[int | None]:
    """For the isolated rows of a degenerate pose (one numerical :class:`Continuum` of joint 1
    each, in the result's order): the index of the row whose band each row lies on (itself for
    the first of a band), or None for a row that is no band's (its members one BAND_PROBE away
    along joint 1 miss the pose on both sides). Beside the theta1 continuum the configurations
    within the tolerance form bands in joint 1 (0.09 rad wide with the wrist point 3.4e-7 m off
    the joint-1 axis) in which the eliminant's rounded roots fall anywhere: one row per band."""
    out: list[int | None] = []
    reps = np.array([c.representative for c in continua], dtype=float).reshape(-1, 6)
    for i, c in enumerate(continua):
        owner = next((k for k in range(i) if out[k] == k and _on_band(continua[k], reps[i : i + 1])[0]), None)
        if owner is None:
            x = float(c.representative[c.free_joint - 1])
            _, r = follow(c, [x - BAND_PROBE, x + BAND_PROBE])
            if _reaches(c, r).any():
                owner = i
        out.append(owner)
    return out
