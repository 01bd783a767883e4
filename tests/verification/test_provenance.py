"""The report header's version and commit, from a checkout and from a non-editable install."""

import json
import subprocess
import sys
import zipfile
from importlib import metadata
from pathlib import Path

import pytest

from verification.provenance import provenance

ROOT = Path(__file__).resolve().parents[2]  # the checkout the tests come from


def _git(*args, cwd=ROOT) -> str:
    return subprocess.run(["git", *args], cwd=cwd, capture_output=True, text=True, check=True).stdout.strip()


def _head() -> str:
    try:
        return _git("rev-parse", "HEAD")
    except (OSError, subprocess.CalledProcessError):
        pytest.skip("the tests do not run from a git checkout")


SHOW = "import json, verification, verification.provenance as p; " \
       "print(json.dumps({**p.provenance(0, True).as_dict(), 'file': verification.__file__}))"


def _provenance_in(site: Path) -> dict:
    """The header as a fresh interpreter importing ``verification`` from ``site`` computes it."""
    out = subprocess.run([sys.executable, "-c", SHOW], cwd=site, capture_output=True, text=True, timeout=120,
                         env={"PYTHONPATH": str(site), "PATH": "/usr/bin:/bin"})
    assert out.returncode == 0, out.stderr
    doc = json.loads(out.stdout)
    assert Path(doc["file"]).resolve().is_relative_to(site.resolve())  # not the checkout's copy
    return doc


@pytest.fixture(scope="module")
def wheel(tmp_path_factory) -> Path:
    """A wheel built from this checkout as `pip install .` builds it."""
    _head()
    out = tmp_path_factory.mktemp("wheel")
    res = subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(out), str(ROOT)],
                         capture_output=True, text=True, timeout=600)
    assert res.returncode == 0, res.stderr
    (whl,) = out.glob("iik-*.whl")
    return whl


def _install(whl: Path, site: Path) -> Path:
    with zipfile.ZipFile(whl) as z:  # what pip install does with a pure-Python wheel
        z.extractall(site)
    return site


def test_the_header_of_this_run_names_the_commit_the_tests_come_from():
    """Editable (git at run time) or installed by CI's `pip install .` (the build record): the same commit."""
    p = provenance(0, True)
    assert p.commit == _head() and p.version == metadata.version("iik")
    assert p.commit_from == "git checkout" or p.commit_from.startswith("build record (built ")


def test_a_non_editable_install_reports_the_commit_recorded_at_build_time(wheel, tmp_path):
    with zipfile.ZipFile(wheel) as z:
        record = json.loads(z.read("verification/build.json"))
    assert record["commit"] == _head() and record["version"] == metadata.version("iik")
    doc = _provenance_in(_install(wheel, tmp_path / "site"))
    assert doc["commit"] == _head() and doc["commit_from"] == f"build record (built {record['built']})"
    assert doc["version"] == metadata.version("iik") and doc["dirty"] is record["dirty"]


def test_a_repository_enclosing_the_install_is_not_taken_for_its_source(wheel, tmp_path):
    """A .venv inside some other clone: its HEAD is not what was built."""
    repo = tmp_path / "other"
    repo.mkdir()
    _git("init", "-q", cwd=repo)
    _git("-c", "user.name=t", "-c", "user.email=t@t", "commit", "-q", "--allow-empty", "-m", "unrelated",
         cwd=repo)
    other = _git("rev-parse", "HEAD", cwd=repo)
    doc = _provenance_in(_install(wheel, repo / ".venv" / "site-packages"))
    assert doc["commit"] == _head() != other and doc["commit_from"].startswith("build record")


def test_without_checkout_or_record_the_commit_is_unknown_and_says_why(wheel, tmp_path):
    site = _install(wheel, tmp_path / "site")
    (site / "verification" / "build.json").unlink()
    doc = _provenance_in(site)
    assert doc["commit"].startswith("unknown (not a git checkout") and doc["commit_from"] == "unknown"
    assert doc["dirty"] is None
