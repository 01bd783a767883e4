"""Where a report came from: version, commit, package versions, seeds and machine (the report header).

The commit is read where it can be trusted:

* imported from a source checkout (an editable install, or the repository itself): ``git
  rev-parse HEAD`` and ``git status`` of that checkout, at run time;
* imported from an installed wheel (``pip install .``): the record the build wrote into the
  wheel, :data:`BUILD_RECORD` (``hatch_build.py``: the commit and whether the tree had
  uncommitted changes when the wheel was built). A git repository that merely encloses the
  installation (a ``.venv`` inside a clone) is not asked: its HEAD need not be what was built;
* neither: ``"unknown ..."``, saying why.
"""

from __future__ import annotations

import datetime as _dt
import json
import os
import platform
import subprocess
import sys
from dataclasses import asdict, dataclass, field
from importlib import metadata
from pathlib import Path

from iik.errors import FileError
from iik.files import read_text

__all__ = ["Provenance", "provenance", "PACKAGES", "BUILD_RECORD"]

#: The build record of an installed wheel (written at build time by ``hatch_build.py``; absent in
#: a source checkout).
BUILD_RECORD = Path(__file__).with_name("build.json")

#: Distributions whose versions a verdict can depend on.
PACKAGES = (
    "iik",
    "numpy",
    "scipy",
    "pin",
    "coal",
    "example-robot-data",
    "python-can",
    "toppra",
    "ompl",
    "ruckig",
    "matplotlib",
)


@dataclass(frozen=True)
class Provenance:
    """The report header.

    Attributes:
        commit: The commit the code came from (module docstring), or ``"unknown (...)"``.
        dirty: Uncommitted changes in that checkout, at run time or at build time (None if unknown).
        versions: Installed version per distribution of :data:`PACKAGES`.
        seed: The seed every check's random samples derive from.
        quick: Quick mode (small samples).
        python: Python version.
        machine: Platform, processor and logical CPU count.
        created: UTC time the report was written (ISO 8601).
        version: The version of this distribution (``iik``).
        commit_from: Where :attr:`commit` was read: ``"git checkout"``, ``"build record (built
            <time>)"`` or ``"unknown"``.
        only: The selection of a partial run (``iik verify --only``), or None (every check ran).
    """

    commit: str
    dirty: bool | None
    versions: dict = field(default_factory=dict)
    seed: int = 0
    quick: bool = False
    python: str = ""
    machine: dict = field(default_factory=dict)
    created: str = ""
    version: str = ""
    commit_from: str = "unknown"
    only: list | None = None

    def as_dict(self) -> dict:
        return asdict(self)


def _git(args: list[str], cwd: Path) -> str | None:
    try:
        out = subprocess.run(["git", *args], cwd=cwd, capture_output=True, text=True, timeout=10)
    except (OSError, subprocess.SubprocessError):
        return None
    return out.stdout.strip() if out.returncode == 0 else None


def _version(dist: str) -> str:
    try:
        return metadata.version(dist)
    except metadata.PackageNotFoundError:
        return "not installed"


def _build_record() -> dict | None:
    try:
        rec = json.loads(read_text(BUILD_RECORD, "build record", limit=100_000))
    except (FileError, ValueError):
        return None
    return rec if isinstance(rec, dict) and isinstance(rec.get("commit"), str) else None


def _commit() -> tuple[str, bool | None, str]:
    """``(commit, dirty, where from)`` (module docstring)."""
    here = Path(__file__).resolve()
    root = here.parent.parent
    tracked = _git(["ls-files", "--error-unmatch", str(here.relative_to(root))], root) is not None
    if tracked:  # imported from a checkout, not from an installation a repository happens to enclose
        commit = _git(["rev-parse", "HEAD"], root)
        status = _git(["status", "--porcelain", "--untracked-files=no"], root) if commit else None
        if commit:
            return commit, None if status is None else bool(status), "git checkout"
    rec = _build_record()
    if rec is not None:
        dirty = rec.get("dirty")
        built = f"build record (built {rec.get('built')})"
        return rec["commit"], dirty if isinstance(dirty, bool) else None, built
    return "unknown (not a git checkout, and built without a build record)", None, "unknown"


def provenance(seed: int, quick: bool, only=None) -> Provenance:
    """Collect the header for a run with ``seed`` and ``quick`` (and the selection ``only`` of a
    partial run)."""
    commit, dirty, commit_from = _commit()
    return Provenance(
        commit=commit,
        dirty=dirty,
        version=_version("iik"),
        commit_from=commit_from,
        only=None if not only else [str(s) for s in only],
        versions={p: _version(p) for p in PACKAGES},
        seed=int(seed),
        quick=bool(quick),
        python=sys.version.split()[0],
        machine={
            "platform": platform.platform(),
            "processor": platform.processor() or platform.machine(),
            "cpus": os.cpu_count(),
        },
        created=_dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
    )
