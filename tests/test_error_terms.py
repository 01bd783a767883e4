"""Errors below the CLI speak the library's terms: no ``--flag`` and no ``iik <command>`` in them.

A library error names the library argument (``allow_outside_limits``, ``port``) and carries its
remedy as data (:class:`iik.errors.Remedy`); the CLI renders the flag from it
(``tests/iik/cli/test_remedy.py``). This test reads every module of ``iik`` (without ``iik/cli``),
``hardware`` and ``verification`` and looks at the text of every error it can build: what a ``raise``
raises, every call of an error class (``...Error(...)``, ``...Fault(...)``, ``...Failed(...)``,
``...Timeout(...)``), the messages written inside error classes and ``add_note`` calls.
``test_the_scan_finds_flags_and_commands`` shows it finds both kinds in a module made to fail.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
LAYERS = ("iik", "hardware", "verification")
#: The commands of the CLI (each module of iik/cli with a NAME).
COMMANDS = tuple(sorted(
    m.group(1) for p in (ROOT / "iik" / "cli").glob("*.py")
    if (m := re.search(r'^NAME = "([a-z-]+)"', p.read_text(encoding="utf-8"), re.M))))
FLAG = re.compile(r"(?<![\w-])--[a-z][a-z-]*")
COMMAND = re.compile(r"\biik (?:" + "|".join(map(re.escape, COMMANDS)) + r")\b")
ERROR_NAME = re.compile(r"[A-Z]\w*(?:Error|Fault|Failed|Timeout|Exception)$")


def _name(node: ast.AST) -> str:
    if isinstance(node, ast.Name):
        return node.id
    if isinstance(node, ast.Attribute):
        return node.attr
    return ""


def _texts(node: ast.AST) -> list[str]:
    """The text of every string (an f-string's literal parts joined) in ``node``."""
    out = []
    for n in ast.walk(node):
        if isinstance(n, ast.JoinedStr):
            out.append("".join(v.value for v in n.values if isinstance(v, ast.Constant)))
        elif isinstance(n, ast.Constant) and isinstance(n.value, str):
            out.append(n.value)
    return out


def _is_error_class(node: ast.ClassDef) -> bool:
    return ERROR_NAME.search(node.name) is not None or any(
        ERROR_NAME.search(_name(b)) or _name(b) == "IIKError" for b in node.bases)


def _docstrings(tree: ast.AST) -> set[int]:
    ids = set()
    for n in ast.walk(tree):
        if isinstance(n, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)) and n.body:
            first = n.body[0]
            if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant):
                ids.add(id(first.value))
    return ids


def error_texts(source: str) -> list[tuple[int, str]]:
    """(line, text) of every string that can end up in an error message of ``source``."""
    tree = ast.parse(source)
    docs = _docstrings(tree)
    found: dict[int, tuple[int, str]] = {}

    def take(node: ast.AST) -> None:
        parts = {id(v) for n in ast.walk(node) if isinstance(n, ast.JoinedStr) for v in n.values}
        for n in ast.walk(node):
            if id(n) not in docs | parts and isinstance(n, (ast.JoinedStr, ast.Constant)):
                for text in _texts(n):
                    found.setdefault(id(n), (n.lineno, text))

    for n in ast.walk(tree):
        if isinstance(n, ast.Raise) and n.exc is not None:
            take(n.exc)
        elif isinstance(n, ast.Call) and (ERROR_NAME.search(_name(n.func)) or _name(n.func) == "add_note"):
            for a in [*n.args, *(k.value for k in n.keywords)]:
                take(a)
        elif isinstance(n, ast.ClassDef) and _is_error_class(n):
            for item in n.body:
                if isinstance(item, ast.FunctionDef):
                    take(item)
    return sorted(found.values())


def cli_terms(text: str) -> list[str]:
    """The flags (``--port``) and commands (``iik run``) that ``text`` names."""
    return [m.group(0) for m in FLAG.finditer(text)] + [m.group(0) for m in COMMAND.finditer(text)]


def offenders(paths) -> list[str]:
    out = []
    for path in paths:
        for line, text in error_texts(path.read_text(encoding="utf-8")):
            if terms := cli_terms(text):
                where = path.relative_to(ROOT) if path.is_relative_to(ROOT) else path
                out.append(f"{where}:{line}: {', '.join(terms)} in {text!r}")
    return out


def _library_files():
    for layer in LAYERS:
        for path in sorted((ROOT / layer).rglob("*.py")):
            if not path.is_relative_to(ROOT / "iik" / "cli"):
                yield path


def test_errors_below_the_cli_name_no_flags_and_no_commands():
    files = list(_library_files())
    assert len(files) > 100 and COMMANDS and "run" in COMMANDS
    found = offenders(files)
    assert found == [], "\n".join(found)


def test_the_scan_finds_flags_and_commands(tmp_path):
    bad = tmp_path / "bad.py"
    bad.write_text(
        "class HaltedError(Exception):\n"
        "    def __init__(self):\n"
        "        super().__init__('halted; run again with --reset')\n\n\n"
        "def f(port):\n"
        "    '''Docstrings may say --port and iik view.'''\n"
        "    err = ValueError(f'port {port} is taken: choose another with ' '--port')\n"
        "    if port:\n"
        "        raise err\n"
        "    raise check(f'see iik run {port}')\n\n\n"
        "def g(exc):\n"
        "    exc.add_note('give --arm')\n"
        "    return 'text that names --flags but is no error'\n")
    found = offenders([bad])
    assert [f.split(":")[1] for f in found] == ["3", "8", "11", "15"], found
    assert "--port" in found[1] and "iik run" in found[2]
