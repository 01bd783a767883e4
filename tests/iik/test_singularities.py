"""Tests of iik.singularities: Tables VI and VII as data."""

from __future__ import annotations

import numpy as np
import pytest

import iik
from iik import THESIS_ARM
from iik.errors import InvalidInputError
from iik.singularities import (
    ALL_SETS,
    TABLE_VI,
    TABLE_VII,
    at_limit_mask,
    reduced_rank,
    sample_set,
    singularity_set,
)

ARM = iik.THESIS_ARM
D = np.pi / 180


def test_counts_and_indices():
    assert len(TABLE_VI) == 37 and len(TABLE_VII) == 80
    assert [s.index for s in ALL_SETS] == list(range(1, 118))
    assert {s.kind for s in TABLE_VII} == {"III"}


def test_transcription_examples():
    s1 = singularity_set(1)
    assert s1.fixed_dict() == {4: 0.0, 5: 0.0} and s1.free == (1, 2, 3)
    s2 = singularity_set(2)
    assert s2.fixed_dict() == pytest.approx({1: -160 * D, 3: 90 * D, 5: 0.0})
    s26 = singularity_set(26)  # App. E uses s(26) = [th2 = 95, th3 = 0, th4 = -119]
    assert s26.fixed_dict() == pytest.approx({2: 95 * D, 3: 0.0, 4: -119 * D})
    assert s26.free == (1, 5)
    # garbled in the extracted text: s(33) and s(34) print identically
    assert singularity_set(33).fixed == singularity_set(34).fixed
    assert "identically" in singularity_set(33).note


def test_every_set_has_two_free_joints_except_s1():
    for s in ALL_SETS:
        assert len(s.free) == (3 if s.index == 1 else 2), s.name


def test_table_vii_groups_use_distinct_triples():
    triples = {tuple(sorted(j for j, _ in s.fixed)) for s in TABLE_VII}
    assert len(triples) == 10  # all C(5, 3) combinations of three fixed joints


def test_all_listed_sets_are_singular():
    rng = np.random.default_rng(0)
    for s in ALL_SETS:
        q = sample_set(s, 5, rng, THESIS_ARM)
        rank, _ = reduced_rank(iik.position_jacobian(q, THESIS_ARM)[..., :5], at_limit_mask(q, THESIS_ARM))
        assert np.all(rank < 3), s.name


def test_generic_configuration_not_singular():
    q = np.random.default_rng(1).uniform(ARM.q_min * 0.9, ARM.q_max * 0.9, size=(50, 6))
    rank, smin = reduced_rank(iik.position_jacobian(q, THESIS_ARM)[..., :5], at_limit_mask(q, THESIS_ARM))
    assert np.all(rank == 3) and smin.min() > 1e-6


def test_unknown_set():
    with pytest.raises(InvalidInputError):
        singularity_set(118)
