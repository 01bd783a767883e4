"""Lazy re-exports for the packages' ``__init__`` (PEP 562): a name is imported when first used.

``import iik`` then loads only its ``__init__``; ``iik.solve`` imports :mod:`iik.ik` on first
access and binds the result in the package, so later accesses are plain attribute look-ups.
Usage, in a package's ``__init__``::

    __getattr__, __dir__ = lazy_exports(__name__, {".arm": ("Arm", "THESIS_ARM"), ...})
    __all__ = ["Arm", "THESIS_ARM", ...]
"""

from __future__ import annotations

import importlib
import importlib.util
import sys
import types
from collections.abc import Callable, Mapping

__all__ = ["lazy_exports"]


def lazy_exports(package: str, exports: Mapping[str, tuple[str, ...]]
                 ) -> tuple[Callable[[str], object], Callable[[], list[str]]]:
    """``(__getattr__, __dir__)`` of ``package``, re-exporting ``exports``: a module relative to
    the package (``".arm"``) -> the names taken from it (the package's ``__all__``, which
    ``tests/test_import_cost.py`` holds equal to them).

    ``__getattr__`` also imports the package's submodules (``iik.rotations`` after ``import iik``).
    A name taken from the submodule of the same name (the function ``iik.dexterity`` from
    ``iik/dexterity.py``) stays that name when the submodule is imported: the import system binds
    a submodule on its package, which would otherwise replace the function by the module.
    """
    source = {name: module for module, names in exports.items() for name in names}
    namespace = vars(sys.modules[package])

    def __getattr__(name: str):
        if name in source:
            value = getattr(importlib.import_module(source[name], package), name)
        elif not name.startswith("__") and importlib.util.find_spec(f"{package}.{name}") is not None:
            value = importlib.import_module(f"{package}.{name}")
        else:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        namespace[name] = value
        return value

    def __dir__() -> list[str]:
        return sorted(set(namespace) | set(source))

    class Package(types.ModuleType):
        def __setattr__(self, name: str, value: object) -> None:
            if isinstance(value, types.ModuleType) and source.get(name) == f".{name}":
                value = getattr(value, name)  # iik.dexterity: the function, not its module
            super().__setattr__(name, value)

    sys.modules[package].__class__ = Package
    return __getattr__, __dir__
