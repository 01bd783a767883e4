"""Arms are data: below the CLI no function quietly falls back on the thesis arm.

A static scan (AST) of every module of ``iik`` (without ``iik.cli``, the one place that picks
the default arm) and of ``hardware``:

* no parameter of any function or method, and no field of any class, has a default that names
  the thesis arm (``THESIS_ARM``, ``thesis_arm(...)``, ``arms.get("thesis")``, ``resolve("thesis")``);
* no function body names the thesis arm at all (so an ``arm=None`` cannot be turned into it),
  except the registry that defines the shipped arms and the model loader that maps the thesis
  arm to its shipped URDF file (:data:`ALLOWED`). Module-level thesis facts (e.g.
  ``iik.singularities.TABLE_VII``, computed once for the thesis arm) are not functions.

The tests below the scan show it catches each form it forbids. The dynamic counterpart (an arm
other than the thesis arm carried through plan -> run -> analyse -> view) is
``tests/test_arm_end_to_end.py``.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
#: Functions that may name the thesis arm: (file relative to the root, function name).
ALLOWED = {
    ("iik/arms.py", "_shipped"),  # the registry: "thesis" -> THESIS_ARM
    ("iik/planning/robot_model.py", "_cached_model"),  # the thesis arm's shipped URDF file
}


def _names_thesis(node: ast.AST) -> bool:
    """Does the expression name the thesis arm?"""
    for n in ast.walk(node):
        if isinstance(n, ast.Name) and n.id in ("THESIS_ARM", "thesis_arm"):
            return True
        if isinstance(n, ast.Attribute) and n.attr in ("THESIS_ARM", "thesis_arm"):
            return True
        first = n.args[0] if isinstance(n, ast.Call) and n.args else None
        if isinstance(first, ast.Constant) and first.value == "thesis":
            f = n.func  # arms.get("thesis"), iik.arms.resolve("thesis"), get("thesis")
            if (isinstance(f, ast.Name) and f.id in ("get", "resolve")) or (
                    isinstance(f, ast.Attribute) and f.attr in ("get", "resolve")
                    and "arms" in ast.unparse(f.value).split(".")):
                return True
    return False


def offences(source: str, rel: str) -> list[str]:
    """Every default naming the thesis arm, and every function body naming it, in ``source``."""
    tree = ast.parse(source)
    out = []
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
            args = node.args
            defaults = list(args.defaults) + [d for d in args.kw_defaults if d is not None]
            name = getattr(node, "name", "<lambda>")
            if any(_names_thesis(d) for d in defaults):
                out.append(f"{rel}:{node.lineno} {name}(): a parameter defaults to the thesis arm")
            body = node.body if isinstance(node.body, list) else [node.body]
            if (rel, name) not in ALLOWED and any(_names_thesis(s) for s in body):
                out.append(f"{rel}:{node.lineno} {name}(): the body names the thesis arm")
        elif isinstance(node, ast.ClassDef):
            for st in node.body:
                if isinstance(st, ast.AnnAssign) and st.value is not None and _names_thesis(st.value):
                    field = f"{node.name}.{ast.unparse(st.target)}"
                    out.append(f"{rel}:{st.lineno} {field}: a field defaults to the thesis arm")
    return out


def _files() -> list[Path]:
    core = [p for p in sorted((ROOT / "iik").rglob("*.py")) if not p.is_relative_to(ROOT / "iik" / "cli")]
    return core + sorted((ROOT / "hardware").rglob("*.py"))


def test_no_function_below_the_cli_defaults_to_the_thesis_arm():
    found = []
    files = _files()
    assert any(p.name == "pipeline.py" for p in files) and not any("/cli/" in p.as_posix() for p in files)
    for path in files:
        rel = path.relative_to(ROOT).as_posix()
        found += offences(path.read_text(encoding="utf-8"), rel)
    assert not found, "\n".join(found)


@pytest.mark.parametrize("source", [
    "def f(q, arm=THESIS_ARM): pass",
    "def f(q, *, arm: Arm = iik.THESIS_ARM): pass",
    "def f(q, arm=None):\n    arm = arm or THESIS_ARM",
    "def f(q, arm=None):\n    if arm is None:\n        arm = arms.get('thesis')",
    "class C:\n    arm: Arm = THESIS_ARM",
    "def f(q, arm=thesis_arm(0.3, 0.1, 0.3, 0.2, 0.2)): pass",
    "class C:\n    def __init__(self, arm=None):\n        self.arm = resolve('thesis') if arm is None else 0",
])
def test_the_scan_catches_each_form(source):
    assert offences(source, "x.py")


def test_the_scan_passes_a_required_arm_and_a_module_level_thesis_fact():
    src = ("TABLE = build(THESIS_ARM)\n"
           "def f(q, arm): return fk(q, arm)\n"
           "def g(q, *, arm=None):\n    return arm if arm is not None else q.arm\n")
    assert offences(src, "x.py") == []
