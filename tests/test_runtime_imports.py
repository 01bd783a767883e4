"""The main job (`pip install ".[verify]"` then `iik verify`) needs no test-only package.

Imports every module of the three packages and loads every registered check in a
subprocess in which the test extra's libraries (pytest, nbmake, ruff, Hypothesis) cannot be imported.
"""

import subprocess
import sys

CODE = r"""
import importlib, pkgutil, sys
for name in ("pytest", "nbmake", "ruff", "_pytest", "hypothesis"):
    sys.modules[name] = None  # any import of them now raises ImportError
import iik, verification, hardware
for pkg in (iik, verification, hardware):
    for info in pkgutil.walk_packages(pkg.__path__, pkg.__name__ + "."):
        if not info.name.endswith("__main__"):
            importlib.import_module(info.name)
import iik.cli.verify
print(len(verification.registered_checks()))
"""


def test_package_imports_without_test_extras():
    out = subprocess.run([sys.executable, "-c", CODE], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    assert int(out.stdout.split()[-1]) > 30
