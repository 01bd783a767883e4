"""One home per concept: angles are wrapped by ``iik.ik.angles.wrap_angle`` (one convention, (-pi, pi]).

Reads the library's and the benchmarks' code for a hand-written wrap (``(x + pi) % 2pi - pi``,
``pi - (pi - x) % 2pi``, ``np.mod(... pi ...)``, ``math.remainder``, ``angle(exp(1j x))``).
The compiled kernel compiles :func:`iik.ik.angles.wrap` from its source; no other file may add one.
"""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
HOME = "iik/ik/angles.py"
PI = r"(?:np|math)\.pi"
TURN = rf"\(?(?:2 *\* *{PI}|_?TWO_PI|(?:np|math)\.tau)\)?"
WRAP = re.compile(rf"\+ *{PI}\)? *% *{TURN}|{PI} *- *\(*(?:np\.mod\(|{PI} *- )|np\.mod\([^)]*{PI}"
                  rf"|math\.remainder\(|np\.angle\(np\.exp\(")


def wraps(paths, root: Path = ROOT) -> dict[str, list[int]]:
    """File (relative to ``root``) -> lines holding a hand-written angle wrap."""
    found: dict[str, list[int]] = {}
    for path in paths:
        for i, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            if WRAP.search(line.split("#")[0]):
                found.setdefault(str(path.relative_to(root)), []).append(i)
    return found


def test_angles_are_wrapped_in_one_place():
    files = [p for d in ("iik", "hardware", "verification", "benchmarks") for p in (ROOT / d).rglob("*.py")]
    found = wraps(files)
    assert HOME in found, "the scan no longer sees the one wrap"
    assert set(found) - {HOME} == set(), found


def test_the_kernel_compiles_the_one_wrap():
    """The kernel's wrap is :func:`iik.ik.angles.wrap` compiled, and it agrees with the array form
    on the edges of the convention (+-pi, +-3 pi, multiples of 2 pi, huge angles, neighbours)."""
    import numpy as np

    from iik.ik import angles, kernel

    assert kernel.wrap.py_func is angles.wrap
    edges = np.array([0.0, np.pi, -np.pi, 3 * np.pi, -3 * np.pi, 2 * np.pi, -2 * np.pi, 1e6, -1e6, 1e300])
    xs = np.concatenate([edges, np.nextafter(edges, np.inf), np.nextafter(edges, -np.inf),
                         np.random.default_rng(0).uniform(-20, 20, 200)])
    compiled = np.array([kernel.wrap(x) for x in xs])
    plain = np.array([angles.wrap(x) for x in xs])
    assert np.array_equal(compiled, plain)
    assert np.all((plain > -np.pi) & (plain <= np.pi))
    assert np.array_equal(plain, angles.wrap_angle(xs))
    inside = xs[(xs > -np.pi) & (xs <= np.pi)]
    assert np.array_equal(angles.wrap_angle(inside), inside)  # nothing moves that need not


def test_the_scan_sees_each_form(tmp_path):
    forms = ["d = (a - b + np.pi) % (2 * np.pi) - np.pi", "return math.pi - (math.pi - x) % _TWO_PI",
             "np.mod(q - p + np.pi, 2 * np.pi)", "abs(math.remainder(t, 2 * math.pi))",
             "np.angle(np.exp(1j * d))", "return np.pi - np.mod(np.pi - x, _TWO_PI)"]
    paths = []
    for k, line in enumerate(forms + ["x = (a - lo) % (2 * np.pi)  # a forward distance, no wrap"]):
        paths.append(tmp_path / f"f{k}.py")
        paths[-1].write_text(line + "\n")
    assert set(wraps(paths, tmp_path)) == {f"f{k}.py" for k in range(len(forms))}
