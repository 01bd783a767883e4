"""Tests of iik.ik.members on theta1 continua (the wrist centre on the joint-1 axis with theta4 = 0):
the shared, compiled marches give what their definitions by :func:`follow` give."""

import dataclasses

import numpy as np
import pytest

import iik
from iik.arm import LIMIT_TOL
from iik.ik.angles import angle_distance, into_limits
from iik.ik.members import (
    BAND_PROBE,
    RESOLUTION,
    STEP,
    closes,
    follow,
    inside_member,
    on_continuum,
    theta1_bands,
    theta1_branches,
)
from iik.ik.result import Continuum
from verification.testing.families import family

ARM = iik.THESIS_ARM


def _inside(q) -> bool:
    return bool(into_limits(q, ARM.q_min, ARM.q_max, LIMIT_TOL)[1])


def _theta1_continua(seed: int, n: int = 4):
    """The theta1 continua of n poses of the wrist-on-axis1-theta4 family (limits not applied)."""
    Q = family("wrist-on-axis1-theta4").sample(ARM, np.random.default_rng(seed), n)
    out = []
    for T in iik.fk(Q, ARM):
        r = iik.solve(T, ARM, within_limits=False)
        out.extend(cs[0] for cs in r.continua if cs and cs[0].kind == "theta1")
    assert out, "the family gave no theta1 continuum"
    return out


def _branches_by_definition(continua):
    """theta1_branches as its docstring defines it, one follow per test."""
    out = []
    for i, c in enumerate(continua):
        rep = c.representative
        owner = next((k for k in range(i) if out[k] == k and on_continuum(continua[k], rep)), None)
        if owner is None:
            x = float(c.representative[0])
            m, r = follow(c, [x - STEP, x + STEP])
            ok = (r[:, 0] <= c.tolerance[0]) & (r[:, 1] <= c.tolerance[1])
            owner = i if bool(np.all(ok & (angle_distance(m, c.representative) <= 2.0))) else None
        out.append(owner)
    return out


@pytest.mark.parametrize("seed", [1, 2])
def test_theta1_branches_agree_with_their_definition_on_members_of_each_branch(seed):
    """Candidate rows: each continuum's representative and its members at other values of joint 1
    inside and beyond the limits (the same branch), in mixed order."""
    cands = []
    for c in _theta1_continua(seed):
        for th in (-3.0, -1.0, 0.5, 3.0):
            m = follow(c, [th])[0][0]
            cands.append(dataclasses.replace(c, representative=m))
        cands.insert(len(cands) // 2, c)
    got = theta1_branches(cands)
    assert got == _branches_by_definition(cands)
    assert any(o is not None and o != i for i, o in enumerate(got))  # some row lies on an earlier branch


def test_follow_marches_each_value_from_the_representative():
    """Several values in one call: the same members as one call per value."""
    c = _theta1_continua(3)[0]
    ths = [-2.5, 0.01, float(c.representative[0]), 2.0]
    q, r = follow(c, ths)
    for i, th in enumerate(ths):
        q1, r1 = follow(c, [th])
        assert np.array_equal(q[i], q1[0]) and np.array_equal(r[i], r1[0])


@pytest.mark.parametrize("seed", [4, 5])
def test_interval_ends_are_feasible_and_the_members_fail_just_beyond(seed):
    lo_lim, hi_lim = float(ARM.q_min[0]), float(ARM.q_max[0])
    for c in _theta1_continua(seed):
        lo, hi = c.interval
        if np.isnan(lo):
            assert not _inside(c.representative)
            continue
        for end, beyond, limit in ((lo, lo - 10 * RESOLUTION, lo_lim), (hi, hi + 10 * RESOLUTION, hi_lim)):
            (m, m2), r = follow(c, [end, beyond])
            assert _inside(m) and r[0, 0] <= c.tolerance[0] and r[0, 1] <= c.tolerance[1]
            if end != limit:
                fails = (
                    not _inside(m2)
                    or r[1, 0] > c.tolerance[0]
                    or r[1, 1] > c.tolerance[1]
                    or angle_distance(m, m2) > 0.5
                )
                assert fails, (end, limit)


@pytest.mark.parametrize("seed", [6, 7])
def test_inside_member_is_the_first_inside_member_on_a_grid_of_follows(seed):
    for c in _theta1_continua(seed):
        m = inside_member(c)
        if m is None:
            continue
        assert _inside(m)
        assert np.allclose(iik.fk(m, ARM), c.pose, atol=1e-9)


def _reach(c, r) -> np.ndarray:
    return (r[:, 0] <= c.tolerance[0]) & (r[:, 1] <= c.tolerance[1])


#: A near-wrist-on-axis1-theta4 configuration (the wrist point just off the joint-1 axis): the
#: configurations within the tolerance form a band of joint 1, 1.93 ... 2.12 rad.
BAND_Q = np.array([2.0892141898825627, -1.8104374472579947, -2.2258776810259655, 4.7e-17,
                   -0.009284016978601706, 2.204080270915197])


def test_closes_holds_on_exact_theta1_continua_and_not_on_a_band():
    """closes(c) against members followed to 8 points around the circle (each march from the
    representative): all reach the pose on an exact continuum (theta4 = pi there, where the
    wrist joints swing by 1.2 rad within one step), some miss on the band."""
    grid = np.linspace(0.0, 2.0 * np.pi, 9)[1:]
    for c in _theta1_continua(1, n=2):
        x = float(c.representative[0])
        assert closes(c) and bool(np.all(_reach(c, follow(c, x + grid)[1])))
    r = iik.solve(iik.fk(BAND_Q, ARM), ARM, within_limits=False)
    band = [cs[0] for cs in r.continua if cs and cs[0].kind == "theta1"]
    assert band
    for c in band:
        x = float(c.representative[0])
        assert not closes(c) and not bool(np.all(_reach(c, follow(c, x + grid)[1])))


def test_theta1_bands_puts_members_of_one_band_together_and_an_isolated_point_alone():
    """Candidates: members of a band of joint 1 (followed by refits with joint 1 held) at
    several values of joint 1, the band's wrist flip, and a configuration of another pose's
    solution set moved 0.3 rad (no band through it: not a band's member)."""
    T = iik.fk(BAND_Q, ARM)
    tol = (1e-10, 1e-10)
    band = Continuum("numerical", 1, None, 0, BAND_Q.copy(), None, ARM, T, tol)
    flip = BAND_Q + np.array([0.0, 0.0, np.pi, 0.0, 0.0, np.pi])
    flip[4] = -flip[4]
    members, r = follow(band, BAND_Q[0] + np.array([-0.1, -0.04, 0.01]))
    assert bool(np.all(_reach(band, r)))
    rows = [BAND_Q, *members, flip, BAND_Q + 0.3]
    got = theta1_bands([Continuum("numerical", 1, None, 0, q, None, ARM, T, tol) for q in rows])
    assert got == [0, 0, 0, 0, 4, None]
    m, r = follow(Continuum("numerical", 1, None, 0, BAND_Q + 0.3, None, ARM, T, tol),
                  [BAND_Q[0] + 0.3 - BAND_PROBE, BAND_Q[0] + 0.3 + BAND_PROBE])
    assert not bool(np.any(_reach(band, r)))  # (the last row is no band: its probes miss)
