"""What importing a module costs in a fresh interpreter: wall time and the modules it loads.

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
import {module}
seconds = time.perf_counter() - t0
print(json.dumps({{"seconds": seconds, "modules": sorted(set(sys.modules) - before)}}))
"""


@dataclass(frozen=True)
class ImportCost:
    """The cost of ``import module`` in a fresh interpreter.

    Attributes:
        module: The module imported.
        seconds: Wall time of the import statement [s] (the interpreter's start-up excluded).
        modules: Every module it loaded (names in ``sys.modules`` after, not before it).
    """

    module: str
    seconds: float
    modules: frozenset[str]

    def loads(self, top: str) -> bool:
        """Whether the import loaded the package ``top`` or any module below it."""
        return any(m == top or m.startswith(top + ".") for m in self.modules)


def import_cost(module: str, *, python: str = sys.executable, path: str | None = None,
                timeout: float = 300.0) -> ImportCost:
    """Import ``module`` in a fresh ``python`` process and measure it.

    ``path`` is put first on ``PYTHONPATH`` (measure a source tree that is not installed).
    Raises ``RuntimeError`` with the child's stderr if the import fails."""
    env = dict(os.environ)
    if path is not None:
        env["PYTHONPATH"] = os.pathsep.join(p for p in (path, env.get("PYTHONPATH")) if p)
    out = subprocess.run([python, "-c", _PROBE.format(module=module)], capture_output=True, text=True,
                         timeout=timeout, env=env)
    if out.returncode != 0:
        raise RuntimeError(f"import {module} failed: {out.stderr.strip().splitlines()[-1:]}")
    data = json.loads(out.stdout.strip().splitlines()[-1])
    return ImportCost(module, data["seconds"], frozenset(data["modules"]))
