"""Table III, Table IV and the inferred region layout of Fig 29."""

import itertools

import numpy as np
import pytest

from iik.errors import InvalidInputError
from iik.planning.viapoints import REGIONS, TABLE_IV, VIA_POINTS, region_bounds, region_of, via_point_path


def test_table_iv_covers_every_pair_and_is_reversible():
    for a, b in itertools.product(REGIONS, REGIONS):
        assert TABLE_IV[(a, b)] == tuple(reversed(TABLE_IV[(b, a)]))
    assert TABLE_IV[("A", "G")] == (1, 2, 3, 4)
    assert TABLE_IV[("G", "A")] == (4, 3, 2, 1)


def test_regions_are_contiguous_sectors_in_order():
    b = region_bounds()
    phi = np.linspace(-np.pi + 1e-6, np.pi - 1e-6, 3601)
    pts = np.column_stack([np.cos(phi), np.sin(phi), np.zeros_like(phi)])
    labels = region_of(pts)
    # decreasing azimuth runs A -> G without revisiting a region
    seq = [labels[-1]]
    for lab in labels[::-1]:
        if lab != seq[-1]:
            seq.append(lab)
    assert "".join(seq) == "ABCDEFG"
    for r, (lo, hi) in b.items():
        mid = 0.5 * (lo + hi)
        assert region_of([np.cos(mid), np.sin(mid), 0.3]) == r


def test_via_points_lie_where_table_iv_needs_them():
    assert list(region_of(np.array([VIA_POINTS[2], VIA_POINTS[3]]))) == ["C", "E"]
    # crossing from A to G goes around the front through all four via-points
    p, nums = via_point_path([-0.5, 0.2, 0.1], [-0.5, -0.2, 0.1])
    assert nums == (1, 2, 3, 4)
    assert np.allclose(p, [VIA_POINTS[i] for i in nums])


def test_unknown_region_is_named():
    from iik.planning.viapoints import via_points_for

    with pytest.raises(InvalidInputError, match="region"):
        via_points_for("A", "Z")
