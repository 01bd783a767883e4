"""What an import statement costs in a fresh interpreter: wall time and the modules it loads.

Used by ``tests/test_import_cost.py`` (which asserts on the modules, never on the time) and
``benchmarks/bench_imports.py`` (which prints median times against a baseline measured in the
same run).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from dataclasses import dataclass

__all__ = ["ImportCost", "import_cost"]

#: Run in the fresh interpreter: the modules already loaded at start-up, then the timed import.
_PROBE = """
import json, sys, time
before = set(sys.modules)
t0 = time.perf_counter()
{statement}
seconds = time.perf_counter() - t0
print(json.dumps({{"seconds": seconds, "modules": sorted(set(sys.modules) - before)}}))
"""


@dataclass(frozen=True)
class ImportCost:
    """The cost of an import statement in a fresh interpreter.

    Attributes:
        statement: The statement (``"import iik"``, ``"from iik import solve"``).
        seconds: Its wall time [s] (the interpreter's start-up excluded).
        modules: Every module it loaded (names in ``sys.modules`` after, not before it).
    """

    statement: str
    seconds: float
    modules: frozenset[str]

    def loads(self, top: str) -> bool:
        """Whether the import loaded the package ``top`` or any module below it."""
        return any(m == top or m.startswith(top + ".") for m in self.modules)


def import_cost(statement: str, *, python: str = sys.executable, path: str | None = None,
                timeout: float = 300.0) -> ImportCost:
    """Run the import ``statement`` in a fresh ``python`` process and measure it.

    ``path`` is put first on ``PYTHONPATH`` and made the working directory (``python -c`` puts the
    working directory first on ``sys.path``), to measure a source tree that is not installed.
    Raises ``RuntimeError`` with the last line of the child's stderr if the statement fails."""
    env = dict(os.environ)
    if path is not None:
        env["PYTHONPATH"] = os.pathsep.join(p for p in (path, env.get("PYTHONPATH")) if p)
    out = subprocess.run([python, "-c", _PROBE.format(statement=statement)], capture_output=True, text=True,
                         timeout=timeout, env=env, cwd=path)
    if out.returncode != 0:
        raise RuntimeError(f"{statement}: {out.stderr.strip().splitlines()[-1:]}")
    data = json.loads(out.stdout.strip().splitlines()[-1])
    return ImportCost(statement, data["seconds"], frozenset(data["modules"]))
