"""The thesis planner (Sec 3.6): Cartesian step-points, repulsion, orientations, IK along the path.

Pure NumPy. The IK solver, the rotation convention and the effort index are
injected (defaults: ``iik.solve``, ``iik.rotations.zxz_matrix``,
``iik.effort_index``), so this module also runs with a test double.

Pipeline (Sec 3.6.1-3.6.3, Sec 4.2):

1. :func:`build_path` -- start, via-points (Table IV or explicit) and goal are
   joined by straight lines (or arcs, Sec 4.2.1.1) divided into step-points
   (<= 30 mm, or a fixed count such as 39 per segment); points inside an
   obstacle's padded ellipsoid are repelled (Eq 52-53, Sec 3.6.2.2); step-points
   under the platform or floor safety level are lifted; too-long steps created by
   repulsion are subdivided and repelled again. Orientations follow the
   gradual Euler change (or slerp).
2. :func:`track_branches` -- all IK solutions at every step (``iik.solve``);
   from each start solution the branch is followed by the minimum effort index
   (Eq 54). A step without any solution is retried with beta changed slightly
   (Sec 3.6: "another path with slight change in the beta orientation").
   A jump larger than ``switch_threshold`` between consecutive steps is
   reported as a branch switch.
3. :func:`track_dp` (ours, used when some step has no solution at the nominal
   orientation even after the slight beta changes): a least-effort dynamic
   programme over IK branches and a small grid of alpha/beta changes (alpha is
   free in Sec 3.6; beta changes are penalised), with a penalty per branch switch.

Solutions within :data:`LIMIT_MARGIN` of a joint stop are not used, so the
timed curve through the step-points cannot overshoot a stop.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidInputError
from ..joint_path import BRANCH_SWITCH_STEP, JointPath, branch_switches, path_effort
from .obstacles import Obstacle, ellipsoid_value, enclosing_radii, repel_points
from .path import arc_steps, densify, interpolate_orientation, straight_steps
from .scenario import Scenario
from .viapoints import via_point_path

__all__ = [
    "CartesianPath",
    "BETA_STEPS",
    "build_path",
    "poses_of",
    "all_solutions",
    "track_branches",
    "track_dp",
]

#: Slight beta changes tried at a step without IK solutions [rad] (Sec 3.6), smallest first.
BETA_STEPS = tuple(math.radians(d) * s for d in (2, 4, 6, 8, 10, 15, 20) for s in (1, -1))


def _orientation_offsets() -> tuple[tuple[float, float], ...]:
    """(d_alpha, d_beta) [rad] tried after the slight beta changes, cheapest first.

    Sec 3.6: alpha "does not tilt the end-effector ... any alpha angle could be
    assigned by the path planning algorithm"; beta is moved further only if
    that fails. Cost: |d_beta| + |d_alpha| / 2.
    """
    da = [0, 20, -20, 45, -45, 90, -90, 135, -135, 180]
    db = [0, 10, -10, 20, -20, 30, -30, 45, -45, 60, -60]
    offs = sorted(((a, b) for a in da for b in db if (a, b) != (0, 0)),
                  key=lambda ab: (abs(ab[1]) + abs(ab[0]) / 2, abs(ab[1])))
    return tuple((math.radians(a), math.radians(b)) for a, b in offs)


#: Orientation changes tried when the slight beta changes fail (ours, beyond the thesis).
ORIENTATION_OFFSETS = _orientation_offsets()


@dataclass(frozen=True)
class CartesianPath:
    """End-effector step-points and orientations (base frame, m, rad).

    Attributes:
        points: (n, 3) tool points [m].
        euler: (n, 3) Z-X-Z angles (alpha, beta, gamma) [rad] per point (Eq 42).
        segment: (n,) index of the segment each point belongs to.
        key_index: Indices of start, via-points and goal in ``points``.
        via_points: (k, 3) via-points used [m] (after repulsion).
        via_numbers: Table III numbers when chosen by Table IV, else ().
        routes: Route per segment (``"line"`` / ``"arc"``).
        repelled: (n,) True where Sec 3.6.2.2 moved the point.
        lifted: (n,) True where the platform/floor rule lifted the point.
        min_ellipsoid_value: Smallest Eq 52 value over points and padded ellipsoids
            (>= 1 means every point is outside every padded ellipsoid).
    """

    points: np.ndarray
    euler: np.ndarray
    segment: np.ndarray
    key_index: tuple[int, ...]
    via_points: np.ndarray
    via_numbers: tuple[int, ...]
    routes: tuple[str, ...]
    repelled: np.ndarray
    lifted: np.ndarray
    min_ellipsoid_value: float

    @property
    def n(self) -> int:
        return len(self.points)


def _alpha_auto(points: np.ndarray) -> np.ndarray:
    """"Any alpha" default: the tool tilts outward (wrist nearer the base than the tool).

    Eq 46's alpha' = atan2(py, px) is the azimuth of the approach direction
    (wrist -> tool). Our z6 points tool -> wrist (d6 = -l5, Table II), so the
    same tool attitude is alpha' + pi in the corrected Eq 42.
    """
    return np.arctan2(points[:, 1], points[:, 0]) + np.pi  # Eq 46, expressed for z6


def _lift(points: np.ndarray, platform: Obstacle | None, floor_z: float | None, s: float, keep: set[int]):
    """Platform/floor avoidance: lift step-points into the safety level above them."""
    pts = points.copy()
    lifted = np.zeros(len(pts), bool)
    for i in range(len(pts)):
        if i in keep:
            continue
        if platform is not None:
            c, h = np.asarray(platform.center), platform.half
            if np.all(np.abs(pts[i, :2] - c[:2]) <= h[:2] + s) and pts[i, 2] < c[2] + h[2] + s:
                pts[i, 2] = c[2] + h[2] + s
                lifted[i] = True
        if floor_z is not None and pts[i, 2] < floor_z + s:
            pts[i, 2] = floor_z + s
            lifted[i] = True
    return pts, lifted


def build_path(sc: Scenario, *, platform: Obstacle | None = None, floor_z: float | None = None,
               via_points=None, routes: tuple[str, ...] | None = None,
               zxz_matrix: Callable | None = None, zxz_from_matrix: Callable | None = None,
               ) -> CartesianPath:
    """Cartesian step-points with orientations for scenario ``sc`` (Sec 3.6).

    Args:
        sc: The scenario (base frame, m, rad).
        platform: The mobile platform box (lifted over, never repelled: Sec 3.6.3).
        floor_z: Floor height in the base frame [m].
        via_points: Override the via-points ((k, 3) [m]); default: ``sc.via_points``,
            else Table IV by region.
        routes: Override the per-segment routes.
        zxz_matrix, zxz_from_matrix: Rotation helpers for ``orientation="slerp"``.
    """
    p0 = np.asarray(sc.start.position, float)
    p1 = np.asarray(sc.goal.position, float)
    nums: tuple[int, ...] = ()
    if via_points is not None:
        vias = np.asarray(via_points, float).reshape(-1, 3)
    elif sc.via_points is not None:
        vias = np.asarray(sc.via_points, float).reshape(-1, 3)
    else:
        vias, nums = via_point_path(p0, p1)  # Table IV
    keys = np.vstack([p0, vias, p1])
    nseg = len(keys) - 1
    routes = tuple(routes or sc.segments or ("line",) * nseg)
    if len(routes) != nseg:
        raise InvalidInputError("routes", f"needs {nseg} entries, got {len(routes)}")
    # Via-points may be repelled by ordinary obstacles too (Sec 3.6.3).
    if len(vias):
        vias, _ = repel_points(np.vstack([p0, vias, p1]), sc.obstacles, p0, p1,
                               safety_zone=sc.safety_zone)
        vias = vias[1:-1]
        keys = np.vstack([p0, vias, p1])
    pts, seg, key_index = [keys[:1]], [0], [0]
    for k in range(nseg):
        f = arc_steps if routes[k] == "arc" else straight_steps
        s = f(keys[k], keys[k + 1], max_step=sc.max_step, n_steps=sc.steps_per_segment)
        pts.append(s[1:])
        seg.extend([k] * (len(s) - 1))
        key_index.append(key_index[-1] + len(s) - 1)
    points = np.concatenate(pts)
    segment = np.asarray(seg)
    fixed = set(key_index)
    repelled = np.zeros(len(points), bool)
    lifted = np.zeros(len(points), bool)
    for _ in range(6):
        keep = np.zeros(len(points), bool)
        keep[list(fixed)] = True
        moved_pts, moved = repel_points(points, sc.obstacles, p0, p1, safety_zone=sc.safety_zone)
        # via-points stay where they are (already repelled above)
        moved_pts[keep] = points[keep]
        moved &= ~keep
        lifted_pts, lift = _lift(moved_pts, platform, floor_z, sc.safety_zone, fixed)
        repelled |= moved
        lifted |= lift
        points = lifted_pts
        dense, src = densify(points, sc.max_step if sc.steps_per_segment is None else
                             max(sc.max_step, _max_step(keys, sc.steps_per_segment)))
        if len(dense) == len(points):
            break
        old = np.rint(src).astype(int)
        kept = np.isclose(src, old)
        idx_map = {int(o): j for j, o in enumerate(old) if kept[j]}
        fixed = {idx_map[i] for i in fixed}
        key_index = [idx_map[i] for i in key_index]
        segment = segment[np.minimum(np.ceil(src - 1e-9).astype(int), len(segment) - 1)]
        repelled = np.where(kept, repelled[old], False)
        lifted = np.where(kept, lifted[old], False)
        points = dense
    # Orientations (Sec 4.2.1: changed gradually from start to goal).
    # "Any alpha" (alpha None): alpha' + pi with gamma + pi (a half turn of the
    # symmetric gripper about its axis), which keeps theta6 mid-range.
    a0 = sc.start.alpha if sc.start.alpha is not None else float(_alpha_auto(p0[None])[0])
    a1 = sc.goal.alpha if sc.goal.alpha is not None else float(_alpha_auto(p1[None])[0])
    g0 = sc.start.gamma + (np.pi if sc.start.alpha is None else 0.0)
    g1 = sc.goal.gamma + (np.pi if sc.goal.alpha is None else 0.0)
    e0 = np.array([a0, sc.start.beta, g0])
    e1 = np.array([a1, sc.goal.beta, g1])
    # cumulative-length parameter so the change is gradual along the travelled path
    cum = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(points, axis=0), axis=1))])
    t = cum / cum[-1] if cum[-1] > 0 else np.linspace(0, 1, len(points))
    if sc.orientation == "euler":
        euler = e0 + t[:, None] * (e1 - e0)
        if sc.start.alpha is None and sc.goal.alpha is None:
            euler[:, 0] = _alpha_auto(points)  # "any alpha" (Sec 3.6): face along the azimuth
    else:
        if zxz_matrix is None or zxz_from_matrix is None:
            from ..rotations import zxz_from_matrix as _fm
            from ..rotations import zxz_matrix as _zm
            zxz_matrix, zxz_from_matrix = zxz_matrix or _zm, zxz_from_matrix or _fm
        grid = interpolate_orientation(e0, e1, 201, method="slerp", zxz_matrix=zxz_matrix)
        R = grid[np.rint(t * 200).astype(int)]
        euler = np.array([np.asarray(zxz_from_matrix(r), float).reshape(-1)[:3] for r in R])
    vmin = np.inf
    for box in sc.obstacles:
        if box.kind == "obstacle" and len(points) > 2:
            v = ellipsoid_value(points[1:-1], box.center, enclosing_radii(box) + sc.safety_zone)
            vmin = min(vmin, float(v.min()))
    return CartesianPath(points=points, euler=euler, segment=segment, key_index=tuple(key_index),
                         via_points=vias, via_numbers=nums, routes=routes, repelled=repelled,
                         lifted=lifted, min_ellipsoid_value=vmin)


def _max_step(keys: np.ndarray, n: int) -> float:
    return float(np.linalg.norm(np.diff(keys, axis=0), axis=1).max() / n) * 1.0000001


def poses_of(points: np.ndarray, euler: np.ndarray, *, pose_from_zxz: Callable | None = None) -> np.ndarray:
    """(n, 4, 4) tool poses from points [m] and Z-X-Z angles [rad] (corrected Eq 42)."""
    if pose_from_zxz is None:
        from ..rotations import pose_from_zxz as pose_of

        T = pose_of(points, euler[:, 0], euler[:, 1], euler[:, 2])
        return T.reshape(-1, 4, 4)
    return np.stack([np.asarray(pose_from_zxz(p, *e), float) for p, e in zip(points, euler, strict=True)])


#: Solutions closer than this to a joint stop are not used [rad]: a smooth timed
#: curve through a waypoint *on* a stop would overshoot it (e.g. theta6 = pi exactly).
LIMIT_MARGIN = 0.01


def _within(res) -> np.ndarray:
    from ..arm import THESIS_ARM

    q = np.asarray(res.q, float).reshape(-1, 6)
    wl = getattr(res, "within_limits", None)
    if wl is not None and len(q):
        q = q[np.asarray(wl, bool).reshape(-1)]
    if len(q):
        q = q[np.all((q >= THESIS_ARM.q_min + LIMIT_MARGIN) & (q <= THESIS_ARM.q_max - LIMIT_MARGIN), axis=1)]
    return q


def all_solutions(points: np.ndarray, euler: np.ndarray, *, solve_many: Callable | None = None,
                  beta_steps: tuple[float, ...] = BETA_STEPS, adapt_orientation: bool = True,
                  ramp: int = 8) -> tuple[list[np.ndarray], np.ndarray]:
    """Within-limit IK solutions at every step, with orientation changes where needed.

    First the nominal orientation; then, at steps without a solution, the slight
    beta changes of Sec 3.6 (``beta_steps``); then (``adapt_orientation``) the
    alpha/beta changes of :data:`ORIENTATION_OFFSETS`, cheapest first.

    Args:
        points, euler: (n, 3) tool points [m] and Z-X-Z angles [rad].
        solve_many: ``(Ts (m, 4, 4)) -> list of IKResult`` (default ``iik.solve_many``).
        ramp: Spread every needed change linearly over this many steps on each
            side, then solve again (gradual orientation change, Sec 4.2.1).

    Returns:
        ``(solutions, offsets)``: a list of (k_i, 6) arrays [rad] and the (n, 2)
        (d_alpha, d_beta) used at each step [rad].
    """
    if solve_many is None:
        import iik

        solve_many = iik.solve_many
    sols, offs = _solve_with_offsets(points, euler, solve_many, beta_steps, adapt_orientation)
    if ramp > 0 and np.any(offs) and len(points) > 2:
        # Spread each needed change over +-ramp steps so orientation (and the joints)
        # change gradually instead of jumping at the first step that needs it.
        base = _ramp(offs, ramp)
        e2 = euler.copy()
        e2[:, 0] += base[:, 0]
        e2[:, 1] += base[:, 1]
        sols2, offs2 = _solve_with_offsets(points, e2, solve_many, beta_steps, adapt_orientation)
        if sum(len(q) == 0 for q in sols2) <= sum(len(q) == 0 for q in sols):
            sols, offs = sols2, base + offs2
    return sols, offs


def _ramp(offs: np.ndarray, w: int) -> np.ndarray:
    """Triangular envelope: each step takes the strongest nearby offset, tapered over ``w`` steps."""
    n = len(offs)
    i = np.arange(n)
    tri = np.maximum(0.0, 1.0 - np.abs(i[:, None] - i[None, :]) / (w + 1))
    out = np.zeros_like(offs)
    for c in range(offs.shape[1]):
        m = np.abs(offs[None, :, c]) * tri
        j = np.argmax(m, axis=1)
        out[:, c] = offs[j, c] * tri[i, j]
    return out


def _solve_with_offsets(points, euler, solve_many, beta_steps, adapt_orientation):
    n = len(points)
    sols = [_within(r) for r in solve_many(poses_of(points, euler))]
    offs = np.zeros((n, 2))
    tries = [(0.0, db) for db in beta_steps]
    if adapt_orientation:
        tries += list(ORIENTATION_OFFSETS)
    for da, db in tries:
        missing = [i for i in range(n) if len(sols[i]) == 0]
        if not missing:
            break
        e = euler[missing].copy()
        e[:, 0] += da
        e[:, 1] += db
        for i, r in zip(missing, solve_many(poses_of(points[missing], e)), strict=True):
            q = _within(r)
            if len(q):
                sols[i], offs[i] = q, (da, db)
    return sols, offs


#: Orientation grid of :func:`track_dp`: (d_alpha, d_beta) [rad].
DP_OFFSETS = tuple((math.radians(a), math.radians(b))
                   for a in (0, 90, -90, 180) for b in (0, 10, -10, 20, -20, 35, -35))


def track_dp(path: CartesianPath, *, solve_many: Callable | None = None,
             effort_index: Callable | None = None, offsets=DP_OFFSETS, w_change: float = 3.0,
             w_offset: float = 0.05, w_switch: float = 2.0, half_turn: bool = True,
             w_half_turn: float = 1.0, switch_threshold: float = BRANCH_SWITCH_STEP,
             ) -> tuple[list[JointPath], dict]:
    """Least-effort joint path over IK branches *and* small orientation changes (dynamic programming).

    Used when the nominal orientations leave steps without solutions. At every
    step the candidates are the within-limit solutions for each orientation
    offset in ``offsets`` (alpha is free, Sec 3.6; beta changes are penalised).
    The path minimises ``sum_i E_i + w_change |d offset_i| + w_offset |offset_i|
    + w_switch [max |dq_i| > switch_threshold]`` with ``E_i`` the effort index of
    Eq 54, i.e. the global form of the thesis's step-by-step least-effort choice
    (plus a penalty per branch switch). With ``half_turn`` every candidate is
    also offered with gamma + pi (theta6 -/+ pi): the same grasp for the
    thesis's parallel gripper, symmetric about z6 (URDF link6 shapes too); it
    removes theta6 swings of nearly a full turn at its +-180 deg stops. The
    half turn itself is free, switching it mid-path costs ``w_half_turn``.
    One path per start solution.
    """
    if solve_many is None:
        import iik

        solve_many = iik.solve_many
    if effort_index is None:
        import iik

        effort_index = iik.effort_index
    n, K = path.n, len(offsets)
    off = np.asarray(offsets, float)
    e = np.repeat(path.euler[None], K, axis=0).copy()
    e[:, :, 0] += off[:, 0, None]
    e[:, :, 1] += off[:, 1, None]
    pts = np.tile(path.points, (K, 1))
    res = solve_many(poses_of(pts, e.reshape(-1, 3)))
    from ..arm import THESIS_ARM

    lim6 = THESIS_ARM.q_max[5] - LIMIT_MARGIN
    layers_q, layers_o = [], []
    for i in range(n):
        qs, os_ = [], []
        for k in range(K):
            q = _within(res[k * n + i])
            if len(q):
                o3 = np.repeat(np.append(off[k], 0.0)[None], len(q), axis=0)
                qs.append(q)
                os_.append(o3)
                if half_turn:
                    # gamma + pi: the same grasp for a gripper symmetric about z6 (theta6 -/+ pi)
                    qf = q.copy()
                    qf[:, 5] -= np.pi * np.where(q[:, 5] >= 0, 1.0, -1.0)
                    keep = np.abs(qf[:, 5]) <= lim6
                    if keep.any():
                        of = o3[keep].copy()
                        of[:, 2] = np.pi
                        qs.append(qf[keep])
                        os_.append(of)
        layers_q.append(np.concatenate(qs) if qs else np.zeros((0, 6)))
        layers_o.append(np.concatenate(os_) if os_ else np.zeros((0, 3)))
    info = {"solutions_per_step": np.array([len(q) for q in layers_q])}
    if np.any(info["solutions_per_step"] == 0):
        info["beta_changed_steps"] = info["alpha_changed_steps"] = ()
        return [], info
    # start candidates: nominal orientation (up to the gripper's half turn) if possible
    nominal0 = np.all(layers_o[0][:, :2] == 0, axis=1)
    starts = np.flatnonzero(nominal0) if nominal0.any() else np.arange(len(layers_q[0]))
    branches = []
    for s0 in starts:
        cost = np.full(len(layers_q[0]), np.inf)
        cost[s0] = 0.0
        back = []
        for i in range(1, n):
            qa, qb = layers_q[i - 1], layers_q[i]
            D = np.abs(qb[None, :, :] - qa[:, None, :])
            E = D.sum(-1) / 6.0  # Eq 54 for all pairs
            dO = np.abs(layers_o[i][None] - layers_o[i - 1][:, None])
            C = (E + w_change * dO[..., :2].sum(-1) + w_half_turn * (dO[..., 2] > 0)
                 + w_offset * np.abs(layers_o[i][:, :2]).sum(-1)[None]
                 + w_switch * (D.max(-1) > switch_threshold))  # avoid branch switches
            tot = cost[:, None] + C
            arg = np.argmin(tot, axis=0)
            back.append(arg)
            cost = tot[arg, np.arange(len(qb))]
        if not np.isfinite(cost.min()):
            continue
        idx = [int(np.argmin(cost))]
        for arg in reversed(back):
            idx.append(int(arg[idx[-1]]))
        idx.reverse()
        q = np.array([layers_q[i][j] for i, j in enumerate(idx)])
        o = np.array([layers_o[i][j] for i, j in enumerate(idx)])
        branches.append(JointPath(q=q, ok=np.ones(n, bool), effort=path_effort(q),
                                  switches=branch_switches(q, switch_threshold), beta_change=o[:, 1],
                                  alpha_change=o[:, 0], start_solution=int(s0),
                                  gamma_change=o[:, 2]))
    branches.sort(key=lambda b: (len(b.switches), b.total_effort))
    if branches:
        b = branches[0]
        info["beta_changed_steps"] = tuple(int(i) for i in np.flatnonzero(b.beta_change))
        info["alpha_changed_steps"] = tuple(int(i) for i in np.flatnonzero(b.alpha_change))
        info["gamma_changed_steps"] = tuple(int(i) for i in np.flatnonzero(b.gamma_change))
    else:
        info["beta_changed_steps"] = info["alpha_changed_steps"] = ()
    return branches, info


def track_branches(path: CartesianPath, *, solve_many: Callable | None = None,
                   effort_index: Callable | None = None,
                   beta_steps: tuple[float, ...] = BETA_STEPS, switch_threshold: float = BRANCH_SWITCH_STEP,
                   adapt_orientation: bool = True) -> tuple[list[JointPath], dict]:
    """Follow every IK branch along the path, choosing by the effort index (Eq 54).

    Args:
        path: From :func:`build_path`.
        solve_many: Batched IK (default ``iik.solve_many``); within-limit solutions are used.
        effort_index: ``(q_prev, q) -> E`` (default ``iik.effort_index``, Eq 54).
        beta_steps: Beta offsets [rad] tried when a step has no solution (Sec 3.6).
        adapt_orientation: Then also try the alpha/beta changes of :data:`ORIENTATION_OFFSETS`.
        switch_threshold: A step whose largest joint change exceeds this [rad] is
            reported as a branch switch.

    Returns:
        ``(branches, info)``: one :class:`JointPath` per start solution, sorted
        by (complete first, number of switches, total effort); ``info`` has
        ``"solutions_per_step"`` and ``"beta_changed_steps"``,
        ``"alpha_changed_steps"``.
    """
    if effort_index is None:
        import iik

        effort_index = iik.effort_index
    sols, offs = all_solutions(path.points, path.euler, solve_many=solve_many, beta_steps=beta_steps,
                               adapt_orientation=adapt_orientation)
    n = path.n
    info = {"solutions_per_step": np.array([len(s) for s in sols]),
            "beta_changed_steps": tuple(int(i) for i in np.flatnonzero(offs[:, 1])),
            "alpha_changed_steps": tuple(int(i) for i in np.flatnonzero(offs[:, 0]))}
    branches = []
    for j, q0 in enumerate(sols[0]):
        qs = np.empty((n, 6))
        ok = np.zeros(n, bool)
        eff = np.zeros(n)
        qs[0], ok[0] = q0, True
        for i in range(1, n):
            cand = sols[i]
            if len(cand) == 0:
                qs[i] = qs[i - 1]
                continue
            e = np.atleast_1d(np.asarray(effort_index(qs[i - 1], cand), float))  # Eq 54, batched
            k = int(np.argmin(e))
            qs[i], ok[i], eff[i] = cand[k], True, e[k]
        branches.append(JointPath(q=qs, ok=ok, effort=eff, switches=branch_switches(qs, switch_threshold),
                                  beta_change=offs[:, 1].copy(), alpha_change=offs[:, 0].copy(),
                                  start_solution=j))
    branches.sort(key=lambda b: (not b.complete, len(b.switches), b.total_effort))
    return branches, info
