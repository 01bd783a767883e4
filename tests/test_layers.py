"""Imports point down only: core < planning < hardware < verification < CLI.

Two checks per layer (see ``docs/ARCHITECTURE.md``):

* **static**: every ``import`` statement in the layer's files, including the ones
  inside functions (lazy imports), names only the layer itself, the layers below,
  the standard library and the third-party packages the layer may use;
* **at import time**: in a fresh interpreter in which the layers above and the
  libraries the layer must not use are blocked (``sys.modules[name] = None``, so
  any import of them raises ``ImportError``), every module of the layer imports.
  This also catches a forbidden library pulled in through another package.

``test_layer_check_catches_an_upward_import`` shows both checks fail on a module
that imports upward.
"""

from __future__ import annotations

import ast
import subprocess
import sys
import textwrap
from dataclasses import dataclass
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
STDLIB = set(sys.stdlib_module_names) | {"__future__"}


@dataclass(frozen=True)
class Layer:
    name: str
    package: str  # dotted package the layer's modules live in
    exclude: tuple[str, ...]  # sub-packages that belong to other layers
    own: tuple[str, ...]  # project packages it may import (itself and the layers below)
    third_party: tuple[str, ...]  # third-party top-level modules it may import


CORE_LIBS = ("numpy", "scipy", "numba")
PLANNING_LIBS = CORE_LIBS + ("pinocchio", "coal", "ompl", "toppra", "matplotlib", "mpl_toolkits", "viser",
                             "trimesh", "tomli", "tomli_w",
                             "IPython")  # the viewer's notebook display (imported lazily, in a notebook)
HARDWARE_LIBS = PLANNING_LIBS + ("can", "ruckig", "msgpack")
LAYERS = (
    Layer("core", "iik", ("iik.planning", "iik.cli"), ("iik",), CORE_LIBS),
    Layer("planning", "iik.planning", (), ("iik",), PLANNING_LIBS),
    Layer("hardware", "hardware", (), ("iik", "hardware"), HARDWARE_LIBS),
    Layer("verification", "verification", (), ("iik", "hardware", "verification"),
          HARDWARE_LIBS + ("hypothesis", "example_robot_data")),
)
#: Project packages a layer must never import, even though they share a top-level name.
FORBIDDEN_OWN = {"core": ("iik.planning", "iik.cli"), "planning": ("iik.cli",), "hardware": ("iik.cli",),
                 "verification": ("iik.cli",)}
#: Blocked at import time: the layers above and the heavy libraries the layer must not use.
BLOCKED = {
    "core": ("iik.planning", "iik.cli", "hardware", "verification", "pinocchio", "coal", "ompl", "toppra",
             "matplotlib", "viser", "can", "ruckig", "hypothesis"),
    "planning": ("iik.cli", "hardware", "verification", "can", "ruckig", "hypothesis"),
    "hardware": ("iik.cli", "verification", "hypothesis"),
    "verification": ("iik.cli", "hypothesis"),  # test-only: imported where a strategy is built
}


def _files(layer: Layer, root: Path = ROOT) -> dict[str, Path]:
    base = root.joinpath(*layer.package.split("."))
    out = {}
    for path in sorted(base.rglob("*.py")):
        rel = path.relative_to(root).with_suffix("")
        parts = rel.parts[:-1] if rel.name == "__init__" else rel.parts
        mod = ".".join(parts)
        if not any(mod == x or mod.startswith(x + ".") for x in layer.exclude):
            out[mod] = path
    return out


def _imports(path: Path, module: str) -> list[tuple[int, str]]:
    """(line, absolute module name) of every import statement in the file."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    pkg = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [(node.lineno, a.name) for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = pkg.split(".")[: len(pkg.split(".")) - node.level + 1]
                name = ".".join(base + ([node.module] if node.module else []))
                names = [name] if node.module else [f"{name}.{a.name}" for a in node.names]
            else:
                names = [node.module] + [f"{node.module}.{a.name}" for a in node.names]
            found += [(node.lineno, n) for n in names]
    return found


def static_violations(layer: Layer, files: dict[str, Path]) -> list[str]:
    bad = []
    for mod, path in files.items():
        for line, name in _imports(path, mod):
            top = name.split(".")[0]
            if top in STDLIB or top in layer.third_party:
                continue
            forbidden = any(name == f or name.startswith(f + ".") for f in FORBIDDEN_OWN[layer.name])
            if top in layer.own and not forbidden:
                continue
            bad.append(f"{path.relative_to(ROOT) if path.is_relative_to(ROOT) else path}:{line}: "
                       f"{layer.name} imports {name}")
    return bad


RUNTIME = textwrap.dedent("""
    import importlib, sys
    blocked, modules = sys.argv[1].split(","), sys.argv[2].split(",")
    for name in blocked:
        sys.modules[name] = None  # importing it (or below it) now raises ImportError
    bad = []
    for mod in modules:
        try:
            importlib.import_module(mod)
        except ImportError as exc:
            bad.append(f"{mod}: {exc}")
    print("\\n".join(bad))
""")


def runtime_violations(blocked, modules, *, pythonpath: Path | None = None) -> list[str]:
    env = None
    if pythonpath is not None:
        import os

        env = dict(os.environ, PYTHONPATH=f"{pythonpath}{os.pathsep}{os.environ.get('PYTHONPATH', '')}")
    out = subprocess.run([sys.executable, "-c", RUNTIME, ",".join(blocked), ",".join(modules)],
                         capture_output=True, text=True, timeout=300, env=env)
    assert out.returncode == 0, out.stderr
    return [line for line in out.stdout.splitlines() if line]


@pytest.mark.parametrize("layer", LAYERS, ids=lambda layer: layer.name)
def test_imports_point_down(layer):
    files = _files(layer)
    assert files, f"no modules found for layer {layer.name}"
    assert static_violations(layer, files) == []
    assert runtime_violations(BLOCKED[layer.name], [m for m in files if not m.endswith("__main__")]) == []


def test_cli_modules_are_thin():
    """The CLI only wires: no command module is longer than about 100 lines."""
    long = {p.name: n for p in (ROOT / "iik" / "cli").glob("*.py")
            if (n := len(p.read_text(encoding="utf-8").splitlines())) > 110}
    assert long == {}


def test_notebooks_and_benchmarks_do_not_import_the_cli():
    users = [p for folder in ("notebooks", "benchmarks") for p in (ROOT / folder).rglob("*")
             if p.suffix in (".py", ".ipynb") and "iik.cli" in p.read_text(encoding="utf-8")]
    assert users == []


def test_layer_check_catches_an_upward_import(tmp_path):
    """A core module that imports hardware (lazily) and coal (at import time) is caught by both checks."""
    pkg = tmp_path / "fakecore"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "bad.py").write_text("import coal\n\n\ndef f():\n    from hardware import PowerCubeArm\n")
    layer = Layer("core", "fakecore", (), ("fakecore",), CORE_LIBS)
    files = {"fakecore": pkg / "__init__.py", "fakecore.bad": pkg / "bad.py"}
    static = static_violations(layer, files)
    assert any("imports coal" in s for s in static) and any("imports hardware" in s for s in static)
    assert runtime_violations(BLOCKED["core"], ["fakecore.bad"], pythonpath=tmp_path) != []
