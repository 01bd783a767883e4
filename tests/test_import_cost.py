"""Importing a module loads only what it uses; a missing extra is one line naming it.

Each entry point is imported in a fresh interpreter (:func:`verification.testing.imports.import_cost`)
and the test asserts on the modules it loads, never on the time (a timed test fails under load);
the times are printed (``pytest tests/test_import_cost.py -s -p no:xdist``) and measured properly
by ``benchmarks/bench_imports.py``. Missing extras are simulated by blocking their modules
(``sys.modules[name] = None``) in a fresh interpreter.
"""

from __future__ import annotations

import importlib
import subprocess
import sys
import textwrap
import types
from pathlib import Path

import pytest

from iik.extras import EXTRAS
from verification.testing.imports import import_cost

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[1]
OPTIONAL = ("pinocchio", "coal", "ompl", "toppra", "matplotlib", "viser", "trimesh", "can", "ruckig",
            "hypothesis")

#: import statement -> (libraries it must not load, one it must load or None)
CASES = {
    "import iik": (OPTIONAL + ("numpy", "numba", "scipy", "iik.ik", "iik.planning"), None),
    "import iik.ik": (OPTIONAL + ("numpy", "iik.planning"), None),
    "from iik import solve": (OPTIONAL + ("iik.planning",), "numpy"),
    "import hardware.protocol": (tuple(m for m in OPTIONAL if m != "can") + ("numba", "iik.planning"), "can"),
    "import iik.planning": (OPTIONAL, None),
    "import iik.planning.viewer": (OPTIONAL, None),
    "import verification": (OPTIONAL + ("pytest",), None),
    "from verification import verify": (("hypothesis", "pytest"), None),
}


@pytest.mark.parametrize("statement", list(CASES))
def test_import_loads_only_what_it_uses(statement):
    forbidden, needed = CASES[statement]
    cost = import_cost(statement)
    print(f"{statement}: {cost.seconds:.3f} s, {len(cost.modules)} modules")
    assert [m for m in forbidden if cost.loads(m)] == []
    assert needed is None or cost.loads(needed)  # the probe sees what an import loads


def test_a_name_is_imported_when_first_used():
    cost = import_cost("import iik; iik.fk")
    assert cost.loads("iik.kinematics") and not cost.loads("iik.ik") and not cost.loads("pinocchio")


BLOCKED_RUN = textwrap.dedent("""
    import sys
    for name in sys.argv[1].split(","):
        sys.modules[name] = None  # as if not installed
    exec(sys.argv[2])
""")


def _run_blocked(blocked, code):
    return subprocess.run([sys.executable, "-c", BLOCKED_RUN, ",".join(blocked), code], capture_output=True,
                          text=True, timeout=300)


@pytest.mark.parametrize("package, extra, blocked", [
    ("iik.planning", "planning", ("ompl", "toppra")),
    ("iik.planning.viewer", "viewer", ("viser",)),
    ("hardware", "hardware", ("can", "ruckig")),
    ("verification", "verify", ("viser",)),
])
def test_a_missing_extra_is_one_line_naming_it(package, extra, blocked):
    out = _run_blocked(blocked, f"""
try:
    import {package}
except ImportError as exc:
    print(type(exc).__name__, exc.name, exc.extra, str(exc), sep="|")
""")
    assert out.returncode == 0, out.stderr
    kind, name, said_extra, message = out.stdout.strip().split("|")
    assert (kind, name, said_extra) == ("MissingExtraError", blocked[0], extra)
    assert "\n" not in message and f"pip install 'iik[{extra}]'" in message
    assert message.startswith(f"{package} needs the '{extra}' extra (missing: {', '.join(blocked)})")


@pytest.mark.parametrize("argv, blocked, needs", [
    (["plan", "j"], ("ompl",), "iik.planning needs the 'planning' extra"),
    (["view", "--q", "0", "0", "0", "0", "0", "0"], ("ompl", "viser"), "iik view needs the 'viewer' extra"),
    (["run", "j"], ("can",), "hardware needs the 'hardware' extra"),
    (["verify", "--quick"], ("viser",), "verification needs the 'verify' extra"),
])
def test_the_cli_prints_a_missing_extra_as_one_line_and_exits_2(argv, blocked, needs):
    out = _run_blocked(blocked, f"from iik.cli import main; sys.exit(main({argv!r}))")
    assert out.returncode == 2
    assert out.stderr.count("\n") == 1
    assert out.stderr.startswith(f"iik {argv[0]}: error: MissingExtraError: {needs}")


def test_a_trajectory_file_or_the_demo_runs_without_the_planning_extra():
    """``hardware`` needs only its own extra for a trajectory file or the demo (the safety numbers live
    in ``iik.safety``); a scenario run names the 'planning' extra it needs."""
    planning_only = tuple(m for m in EXTRAS["planning"] if m not in EXTRAS["hardware"])
    out = _run_blocked(planning_only + ("iik.planning", "pinocchio", "viser"), """
import iik.arms
from hardware.bus import BusConfig
from hardware.runner import RunOptions, run
from hardware.sources import demo_trajectory, scenario_trajectory
arm = iik.arms.get("thesis")
RunOptions(), BusConfig.simulated()
print(len(demo_trajectory(arm).validate()) > 2)
try:
    scenario_trajectory("j")
except ImportError as exc:
    print(type(exc).__name__, exc.extra, str(exc), sep="|")
""")
    assert out.returncode == 0, out.stderr
    ok, error = out.stdout.strip().splitlines()
    assert ok == "True" and "coal" in planning_only
    assert error.startswith("MissingExtraError|planning|a scenario run "
                            "(hardware.sources.scenario_trajectory) needs the 'planning' extra")


def test_the_core_solves_without_any_extra():
    """``iik.solve`` and ``iik.fk`` with every optional library missing (core only), on an arm read
    from its URDF (the registry's CRX-10iA)."""
    out = _run_blocked(OPTIONAL, "import numpy as np, iik; q = np.full(6, 0.3); "
                                 "arm = iik.arms.get('crx10ia'); r = iik.solve(iik.fk(q, arm), arm); "
                                 "print(min(np.abs(r.q - q).max(axis=1)))")
    assert out.returncode == 0, out.stderr
    assert float(out.stdout.split()[-1]) < 1e-9


def test_hypothesis_is_needed_only_to_build_a_strategy():
    """``iik verify`` imports no Hypothesis (``tests/test_runtime_imports.py`` blocks it); the strategies
    say which extra they need."""
    out = _run_blocked(("hypothesis",), """
from verification.testing.strategies import joint_vectors, sample_joints
import numpy as np
assert sample_joints(np.random.default_rng(0), 3).shape == (3, 6)
try:
    joint_vectors()
except ImportError as exc:
    print(exc)
""")
    assert out.returncode == 0, out.stderr
    assert "needs the 'test' extra (missing: hypothesis)" in out.stdout


PACKAGES = ("iik", "iik.ik", "iik.planning", "iik.planning.viewer", "hardware", "verification")


@pytest.mark.parametrize("name", PACKAGES)
def test_lazy_exports_are_the_packages_all(name):
    """Every name of ``__all__`` resolves, ``dir()`` lists it, and nothing else is re-exported."""
    package = importlib.import_module(name)
    unresolved = [n for n in package.__all__ if getattr(package, n, None) is None]
    assert unresolved == []
    assert set(package.__all__) <= set(dir(package))
    helpers = {"lazy_exports", "require"}
    beyond_all = [n for n in dir(package) if not n.startswith("_") and n not in package.__all__
                  and n not in helpers and not isinstance(getattr(package, n), types.ModuleType)]
    assert beyond_all == []
    with pytest.raises(AttributeError, match="no attribute 'not_a_name'"):
        package.not_a_name  # noqa: B018


def test_a_name_shared_with_its_module_stays_the_name():
    """``iik.dexterity`` is the function even after ``iik/dexterity.py`` is imported on its own."""
    code = ("import iik, iik.dexterity, iik.ik.solve, verification.self_test, verification as v; "
            "print(callable(iik.dexterity), callable(iik.ik.solve), callable(v.self_test))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split() == ["True", "True", "True"]


def test_extras_are_declared_in_pyproject():
    declared = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    extras = declared["optional-dependencies"]
    assert set(EXTRAS) <= set(extras)
    core = [d.split(">")[0] for d in declared["dependencies"]]
    assert not set(core) & {"hypothesis", "viser", "ompl", "toppra", "matplotlib", "python-can"}, core
