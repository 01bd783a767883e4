"""Hatch build hook: record, at build time, the commit a wheel is built from.

``pip install .`` builds a wheel and installs it; the installed package is no git checkout,
so the report header (:mod:`verification.provenance`) could not ask git for the commit at
run time. This hook writes ``verification/build.json`` into the wheel (and the sdist, so a
wheel built from the sdist keeps it): the commit (``git rev-parse HEAD``), whether the
tree had uncommitted changes to tracked files, the version and the build time (UTC).
Editable installs get no record: they are imported from the checkout and ask git directly.
Without git (an sdist without a record), nothing is written and the header says "unknown".
"""

from __future__ import annotations

import datetime as _dt
import json
import os
import subprocess
import tempfile

from hatchling.builders.hooks.plugin.interface import BuildHookInterface

RECORD = "verification/build.json"


def _git(args: list[str], cwd: str) -> str | None:
    try:
        out = subprocess.run(["git", *args], cwd=cwd, capture_output=True, text=True, timeout=30)
    except (OSError, subprocess.SubprocessError):
        return None
    return out.stdout.strip() if out.returncode == 0 else None


def build_record(root: str, version: str) -> dict | None:
    """The record of the checkout at ``root``, or None if it is not a git checkout."""
    commit = _git(["rev-parse", "HEAD"], root)
    if not commit:
        return None
    status = _git(["status", "--porcelain", "--untracked-files=no"], root)
    return {"commit": commit, "dirty": None if status is None else bool(status), "version": version,
            "built": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")}


class BuildRecordHook(BuildHookInterface):
    """Adds :data:`RECORD` to the wheel and the sdist (not to an editable wheel)."""

    PLUGIN_NAME = "custom"

    def initialize(self, version: str, build_data: dict) -> None:
        if version == "editable":
            return
        record = build_record(self.root, self.metadata.version)
        if record is None:  # e.g. a wheel built from an sdist: its own record (if any) is packaged as is
            return
        fd, self._tmp = tempfile.mkstemp(prefix="iik-build-", suffix=".json")
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            json.dump(record, f)
        build_data["force_include"][self._tmp] = RECORD

    def finalize(self, version: str, build_data: dict, artifact_path: str) -> None:
        tmp = getattr(self, "_tmp", None)
        if tmp and os.path.exists(tmp):
            os.unlink(tmp)
