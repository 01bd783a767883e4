"""A real headless Chromium for the viewer's browser tests (skipped with one line when there is none).

Chromium and its driver come from Debian (``chromium``, ``chromium-driver``; ``.ci/run``
installs them); Selenium drives it through ``/usr/bin/chromedriver``. Nothing is
downloaded: the flags keep Chromium off the network.
"""

from __future__ import annotations

import io
import os
import shutil
import tempfile
import time

import numpy as np
import pytest

CHROMIUM = os.environ.get("IIK_CHROMIUM", "/usr/bin/chromium")
CHROMEDRIVER = os.environ.get("IIK_CHROMEDRIVER", "/usr/bin/chromedriver")
WINDOW = (1280, 800)
FLAGS = ("--headless=new", "--no-sandbox", "--disable-gpu", "--enable-unsafe-swiftshader", "--disable-quic",
         "--no-first-run", "--disable-background-networking", "--disable-component-update", "--disable-sync",
         f"--window-size={WINDOW[0]},{WINDOW[1]}")


def _why_no_browser() -> str:
    try:
        import selenium  # noqa: F401
    except ImportError:
        return "selenium is not installed (pip install '.[test]')"
    for exe in (CHROMIUM, CHROMEDRIVER):
        if not (os.path.isfile(exe) and os.access(exe, os.X_OK)):
            return f"no {exe} (apt-get install chromium chromium-driver; .ci/run does)"
    return ""


@pytest.fixture(scope="module")
def browser():
    """A Selenium Chrome driver on Debian's headless Chromium, with a fresh profile."""
    why = _why_no_browser()
    if why:
        pytest.skip(f"browser tests skipped: {why}")
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    profile = tempfile.mkdtemp(prefix="iik-chromium-")
    opts = webdriver.ChromeOptions()
    opts.binary_location = CHROMIUM
    for flag in (*FLAGS, f"--user-data-dir={profile}"):
        opts.add_argument(flag)
    driver = webdriver.Chrome(service=Service(CHROMEDRIVER), options=opts)
    yield driver
    driver.quit()
    shutil.rmtree(profile, ignore_errors=True)


def screenshot(driver) -> np.ndarray:
    """The viewport as an (h, w, 3) float RGB array in 0..1."""
    import matplotlib.image as mpimg

    return mpimg.imread(io.BytesIO(driver.get_screenshot_as_png()), format="png")[..., :3]


def canvas_rect(driver) -> tuple[float, float, float, float]:
    """(left, top, width, height) of the 3D canvas in CSS pixels (= screenshot pixels here)."""
    r = driver.execute_script(
        "const c = [...document.querySelectorAll('canvas')].sort((a, b) => "
        "b.clientWidth * b.clientHeight - a.clientWidth * a.clientHeight)[0];"
        "if (!c) return null; const r = c.getBoundingClientRect();"
        "return [r.left, r.top, r.width, r.height];")
    return tuple(r) if r else (0.0, 0.0, 0.0, 0.0)


def wait_for_scene(driver, *, timeout: float = 120.0, until=None) -> np.ndarray:
    """Wait until the canvas draws a scene that has stopped fading in (and, with ``until``, whose
    screenshot satisfies ``until(img)``: on a loaded machine the meshes can arrive after the
    grid has settled); return a screenshot.

    The scene counts as drawn when the image is not uniform; it has settled when the
    spread of its pixel values changes by less than 10 % between two screenshots
    (the arm may still be moving: that changes the spread far less).
    """
    end = time.monotonic() + timeout
    last = None
    while time.monotonic() < end:
        w, h = canvas_rect(driver)[2:]
        img = screenshot(driver) if w > 100 and h > 100 else None
        spread = float(img.std()) if img is not None else 0.0
        settled = spread > 0.02 and last is not None and abs(spread - last) < 0.1 * last
        if settled and (until is None or until(img)):
            return img
        last = spread if spread > 0.02 else None
        time.sleep(0.5)
    raise AssertionError("the 3D scene did not appear" + ("" if until is None else " (or not as awaited)"))


def hue_mask(img: np.ndarray, lo: float, hi: float, *, min_sat: float = 0.45,
             min_val: float = 0.2) -> np.ndarray:
    """Pixels whose hue [deg] is in [lo, hi] (wrapping when lo > hi) and that are saturated enough."""
    from matplotlib.colors import rgb_to_hsv

    hsv = rgb_to_hsv(np.clip(img, 0, 1))
    h = hsv[..., 0] * 360
    inside = (h >= lo) & (h <= hi) if lo <= hi else (h >= lo) | (h <= hi)
    return inside & (hsv[..., 1] >= min_sat) & (hsv[..., 2] >= min_val)


def project(points, eye, target, *, fov_deg: float, rect) -> np.ndarray:
    """Pinhole projection (three.js camera, vertical ``fov_deg``, z up) of (n, 3) points to pixels."""
    left, top, w, h = rect
    eye, target = np.asarray(eye, float), np.asarray(target, float)
    fwd = (target - eye) / np.linalg.norm(target - eye)
    right = np.cross(fwd, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    d = np.asarray(points, float).reshape(-1, 3) - eye
    x, y, z = d @ right, d @ up, d @ fwd
    f = (h / 2) / np.tan(np.radians(fov_deg) / 2)
    return np.column_stack([left + w / 2 + f * x / z, top + h / 2 - f * y / z])
