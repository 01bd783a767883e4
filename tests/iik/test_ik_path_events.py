"""Path following on a cuspidal arm: the FANUC CRX-10iA changes IK solution without a singularity,
follow_path keeps the joint path continuous through it and names it (iik.ik.path_events).

The construction follows the theory of cuspidal robots (Wenger; Salunkhe, Chablat, Wenger): near a
cusp point of the singular surface's image, a 2D slice of pose space shows a horn (the cusp
region) where two more IK solutions exist. Three of the solutions merge at the cusp; two of them
(the "top" and "bottom" sheets) have the same sign of det J. A closed Cartesian loop that starts
inside the horn and goes once around the cusp point takes the one to the other: the branch is
followed continuously, det J keeps its sign, and the loop ends at the start pose on another IK
solution. That is the definition of a nonsingular change of solution (a cuspidal arm), measured
here on our model of the CRX-10iA (its FK equals Pinocchio's on FANUC's URDF, test_arms.py).

What the test proves: on this loop, the joint path that follow_path returns (i) is continuous:
its largest step shrinks in proportion when the loop is sampled four times finer (a jump would
not), (ii) has det J of one sign at every step and at four points between consecutive steps, with
|det J| bounded away from 0, and (iii) ends on an exact IK solution of the start pose 0.4 rad
from the start configuration; follow_path reports exactly one event, "cusp", at the last step.
The same loop that does not go around the cusp returns every branch to its start, with no event.
What it does not prove: that det J cannot vanish between the sampled points (it is sampled, not
bounded), nor anything about cusps elsewhere.
"""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import iik
import iik.arms
from iik.ik.path_events import path_events

ARM = iik.arms.get("crx10ia")
#: A cusp point of the CRX-10iA's singular set, found by Newton on det J = 0 and grad(det J) . v = 0
#: (v the kernel vector of J) from a random start; the test checks these properties below.
Q_CUSP = np.array([1.2498260925051046, -0.9388118498369861, -0.4179919152138452, 1.5220603751581936,
                   0.15898527143062197, -1.4903568242574066])
RHO = 2e-3  # half-size of the loop in the slice [m, rad] (the horn narrows as |a|^(3/2))


def _det(q):
    return np.linalg.det(iik.jacobian(np.atleast_2d(q), ARM).reshape(-1, 6, 6))


def _grad_det(q, h=1e-6):
    return np.array([(_det(q + e)[0] - _det(q - e)[0]) / (2 * h) for e in np.eye(6) * h])


@pytest.fixture(scope="module")
def slice_():
    """The pose slice through the cusp: a along J . grad(det J) (transverse to the cusp edge), b
    along the cokernel w of J (normal to the fold); pose(a, b) moves the tool point by the linear
    part and turns it by the angular part (the Jacobian's [v; w] convention)."""
    J = iik.jacobian(Q_CUSP, ARM)
    U, s, Vt = np.linalg.svd(J)
    grad = _grad_det(Q_CUSP)
    # Q_CUSP is a cusp: J singular (rank 5, well separated) and its kernel tangent to det J = 0
    assert s[-1] <= 1e-12 and s[-2] >= 0.1 and abs(grad @ Vt[-1]) <= 1e-7 * np.linalg.norm(grad)
    w = U[:, -1]
    u = J @ grad
    u -= (u @ w) * w
    u /= np.linalg.norm(u)
    X = iik.fk(Q_CUSP, ARM)

    def pose(a, b):
        d = a * u + b * w
        T = X.copy()
        T[:3, 3] += d[:3]
        T[:3, :3] = Rotation.from_rotvec(d[3:]).as_matrix() @ X[:3, :3]
        return T

    return pose


def _counts(pose, points):
    return np.array([r.count for r in iik.solve_many(np.array([pose(a, b) for a, b in points]), arm=ARM,
                                                    within_limits=False)])


def _loop(pose, corners, per_rho: int):
    """Poses along the closed polygon through ``corners`` ((a, b) pairs, last = first)."""
    pts = []
    for (a1, b1), (a2, b2) in zip(corners[:-1], corners[1:], strict=True):
        m = max(1, int(np.ceil(np.hypot(a2 - a1, b2 - b1) / RHO * per_rho)))
        pts += [(a1 + (a2 - a1) * t, b1 + (b2 - b1) * t) for t in np.arange(m) / m]
    pts.append(corners[-1])
    return np.array([pose(a, b) for a, b in pts])


@pytest.fixture(scope="module")
def horn(slice_):
    """The cusp region's extent in b at a = -RHO: there the pose has more IK solutions."""
    bs = np.linspace(-RHO / 5, RHO / 5, 801)
    n = _counts(slice_, [(-RHO, b) for b in bs])
    inside = bs[n > np.bincount(n).argmax()]
    # four more solutions inside: each root of the eliminant gives two wrist branches, so the
    # folds (two roots merging) come in pairs
    assert len(inside) and n.max() == np.bincount(n).argmax() + 4
    return float(inside.min()), float(inside.max())


def _around(horn, b_top=4e-4, b_bottom=-4e-4):
    b0 = 0.5 * sum(horn)  # start inside the horn, leave it upwards, go round the cusp, come back
    return [(-RHO, b0), (-RHO, b_top), (RHO, b_top), (RHO, b_bottom), (-RHO, b_bottom), (-RHO, b0)]


def _largest_step(q0, path) -> float:
    return float(np.abs(np.diff(np.vstack([q0, path.q]), axis=0)).max())


def _runs(Ts):
    """follow_path from every solution of the first pose, in both directions: (q0, way, path)."""
    from iik.ik.nearest import Candidates

    for q0 in Candidates.of(iik.solve(Ts[0], arm=ARM, within_limits=False), arm=ARM).configurations():
        for way in (1, -1):
            yield q0, way, iik.follow_path(Ts[::way], q0, arm=ARM)


def test_a_loop_around_a_cusp_changes_the_solution_without_a_singularity(slice_, horn):
    Ts = _loop(slice_, _around(horn), 100)
    assert np.abs(Ts[0] - Ts[-1]).max() <= 1e-15  # a closed loop
    runs = list(_runs(Ts))
    for q0, _, p in runs:  # every jump is named, also those below the 0.5 rad switch threshold:
        steps = np.abs(np.diff(np.vstack([q0, p.q]), axis=0)).max(axis=1)  # here 0.3-0.42 rad,
        named = {e.step for e in p.events if e.kind == "switch"}  # the other steps <= 0.034 rad
        assert named == set(np.flatnonzero(steps > 0.1).tolist())
    cusp_runs = [(q0, way, p) for q0, way, p in runs if any(e.kind == "cusp" for e in p.events)]
    # the top sheet one way round and the bottom sheet the other, for each of the two wrist
    # branches; the middle sheet (det J of the other sign) meets the fold and jumps
    assert len(cusp_runs) == 4
    jumped = next((q0, way, p) for q0, way, p in runs if p.events and p.events[0].kind == "switch")
    finer = _loop(slice_, _around(horn), 400)
    for q0, way, p in cusp_runs:
        assert [e.kind for e in p.events] == ["cusp"] and p.events[0].step == len(Ts) - 1
        assert p.events[0].earlier == 0 and p.switches == ()
        assert "cusp: branch change without singularity" in p.events[0].detail
        # (iii) the end is another exact solution of the start pose, in the same det J sign
        assert np.abs(np.mod(p.q[-1] - q0 + np.pi, 2 * np.pi) - np.pi).max() >= 0.3
        assert np.abs(iik.fk(p.q[-1], ARM) - Ts[0]).max() <= 1e-9
        # (ii) det J keeps one sign at every step and at points between the steps, away from 0
        steps = np.vstack([q0, p.q])
        sub = steps[:-1, None, :] + np.linspace(0, 1, 5)[None, :, None] * np.diff(steps, axis=0)[:, None, :]
        dets = _det(sub.reshape(-1, 6))
        assert np.all(np.sign(dets) == np.sign(dets[0]))
        assert np.abs(dets).min() >= 1e-5  # [m^3]; ~1e-2 away from singularities
        # (i) continuity: sampled four times finer, the same end and a quarter of the largest step
        fine = iik.follow_path(finer[::way], q0, arm=ARM)
        assert [e.kind for e in fine.events] == ["cusp"]
        assert np.abs(fine.q[-1] - p.q[-1]).max() <= 1e-6
        assert _largest_step(q0, fine) <= 0.35 * _largest_step(q0, p)
    # a jump is a jump: sampled four times finer it stays as large
    q0, way, p = jumped
    assert _largest_step(q0, iik.follow_path(finer[::way], q0, arm=ARM)) >= 0.7 * _largest_step(q0, p)


def test_the_same_loop_away_from_the_cusp_returns_every_branch_to_its_start(slice_, horn):
    Ts = _loop(slice_, [(-RHO, 2e-4), (-RHO, 4e-4), (RHO, 4e-4), (RHO, 2e-4), (-RHO, 2e-4)], 100)
    assert _counts(slice_, [(-RHO, 3e-4)]).item() == _counts(slice_, [(RHO, 3e-4)]).item()  # outside the horn
    for q0, _, p in _runs(Ts):
        assert not p.events
        assert np.abs(np.mod(p.q[-1] - q0 + np.pi, 2 * np.pi) - np.pi).max() <= 1e-6


def test_events_name_singular_crossings_and_nothing_on_a_smooth_path():
    q = np.array([0.3, -0.5, 0.7, 0.9, 0.4, -0.4])
    smooth = q + np.linspace(0, 1, 200)[:, None] * np.array([0.0, 0.0, 0.3, 0.1, -0.2, 0.5])
    assert path_events(smooth, ARM, 0.5) == ()
    # a continuous joint path through det J = 0: joint 3 moved across a root of det J
    grid = np.tile(q, (721, 1))
    grid[:, 2] = np.linspace(-np.pi, np.pi, 721)
    d = _det(grid)
    k = int(np.flatnonzero(np.sign(d[1:]) != np.sign(d[:-1]))[0])
    across = np.tile(q, (41, 1))
    across[:, 2] = np.linspace(grid[k, 2] - 0.01, grid[k + 1, 2] + 0.01, 41)
    events = path_events(across, ARM, 0.5)
    assert [e.kind for e in events] == ["singular"] and "det J went from" in events[0].detail
