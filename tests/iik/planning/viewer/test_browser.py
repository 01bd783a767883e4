"""The viewer in a real headless Chromium: an exported plan opened from disk, and the live server.

Set ``IIK_SCREENSHOTS=DIR`` to keep the screenshots.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest
from matplotlib.colors import rgb_to_hsv

import iik
from iik import THESIS_ARM
from iik.planning import PlanOptions
from iik.planning.viewer import PlanScene, PoseView, export, plan_for_view, serve
from iik.planning.viewer.environment import view_top
from verification.testing.polling import wait_until

from .conftest import canvas_rect, hue_mask, project, screenshot, wait_for_scene

BLUE = (205.0, 240.0)  # the arm (style.ARM, hue 222 deg), shaded
RED = (348.0, 10.0)  # obstacles (style.OBSTACLE, hue 2 deg)


def _keep(img: np.ndarray, name: str) -> None:
    folder = os.environ.get("IIK_SCREENSHOTS")
    if folder:
        import matplotlib.image as mpimg

        Path(folder).mkdir(parents=True, exist_ok=True)
        mpimg.imsave(Path(folder) / name, np.clip(img, 0, 1))


def _box(uv: np.ndarray, pad: float) -> tuple[float, float, float, float]:
    return uv[:, 0].min() - pad, uv[:, 1].min() - pad, uv[:, 0].max() + pad, uv[:, 1].max() + pad


def _inside(mask: np.ndarray, box) -> float:
    """Fraction of the mask's pixels inside the box (x0, y0, x1, y1)."""
    ys, xs = np.nonzero(mask)
    if len(xs) == 0:
        return 0.0
    x0, y0, x1, y1 = box
    return float(np.mean((xs >= x0) & (xs <= x1) & (ys >= y0) & (ys <= y1)))


def _in_canvas(mask: np.ndarray, rect) -> np.ndarray:
    """The mask without the page around the 3D canvas (panel, playback bar)."""
    left, top, w, h = (int(round(v)) for v in rect)
    out = np.zeros_like(mask)
    out[top:top + h, left:left + w] = mask[top:top + h, left:left + w]
    return out


def _arm_points(q: np.ndarray) -> np.ndarray:
    """Joint-frame origins and the tool point of every configuration [m]."""
    return iik.joint_frames(np.asarray(q).reshape(-1, 6), THESIS_ARM)[:, :, :3, 3].reshape(-1, 3)


def _open_export(browser, view, folder: Path, shot: str, until=None) -> tuple[np.ndarray, tuple]:
    """Export ``view`` into ``folder``, open it from disk, wait for the scene (and ``until(img)``,
    :func:`wait_for_scene`): (screenshot, canvas rect)."""
    res = export(view, folder)
    browser.get((res.path / "index.html").resolve().as_uri())
    img = wait_for_scene(browser, until=until)
    _keep(img, shot)
    return img, canvas_rect(browser)


@pytest.fixture(scope="module")
def plan_j():
    return plan_for_view("j")


def test_exported_plan_opens_from_disk_and_draws_arm_and_obstacle(browser, plan_j, tmp_path):
    view = PlanScene(plan_j)
    def drawn(img):  # the obstacle's and the arm's colours on screen (meshes arrive after the grid)
        r = canvas_rect(browser)
        return _in_canvas(hue_mask(img, *RED), r).sum() > 300 and _in_canvas(hue_mask(img, *BLUE), r).any()

    img, rect = _open_export(browser, view, tmp_path / "j", "exported_j_from_disk.png", until=drawn)
    eye, target, fov = view.camera

    assert img.std() > 0.05, "blank page"
    # Nothing but the file itself and inline data/blob resources was loaded: no server, no network.
    urls = browser.execute_script("return performance.getEntriesByType('resource').map(e => e.name)")
    assert all(u.split(":", 1)[0] in ("file", "data", "blob") for u in urls), urls

    red = _in_canvas(hue_mask(img, *RED), rect)
    cabinet = next(b for b in plan_j.obstacles if b.name == "cabinet")
    assert red.sum() > 300, "no obstacle colour on screen"
    assert _inside(red, _box(project(cabinet.corners, eye, target, fov_deg=fov, rect=rect), 15)) > 0.9

    blue = _in_canvas(hue_mask(img, *BLUE), rect)
    arm_box = _box(project(_arm_points(plan_j.q), eye, target, fov_deg=fov, rect=rect), 40)
    assert blue.sum() > 300, "no arm colour on screen"
    assert _inside(blue, arm_box) > 0.9
    # The two colours are drawn in different places (not one blended blob).
    assert _inside(red, arm_box) < 1.0 or _inside(blue, _box(project(cabinet.corners, eye, target,
                                                                        fov_deg=fov, rect=rect), 0)) < 0.5


def test_exported_pose_shows_every_solution(browser, tmp_path):
    T = iik.pose_from_euler([0.4, 0.3, 0.2], np.pi, np.radians(120), 0.0)
    view = PoseView(T, arm=THESIS_ARM)
    assert view.result.count >= 2
    def blue(img):
        return _in_canvas(hue_mask(img, *BLUE, min_sat=0.25), canvas_rect(browser))

    img, rect = _open_export(browser, view, tmp_path / "pose", "pose_all_solutions.png",
                             until=lambda img: blue(img).sum() > 300)  # (times out, failing, if never)
    assert blue(img).sum() > 300


def test_exported_failed_plan_shows_the_arm_and_its_attempt_log(browser, tmp_path):
    """A failed plan opened from disk: the arm at the start pose and the caption (verdict, attempts)."""
    plan = plan_for_view("a", PlanOptions(fallbacks=False, timing=False))
    assert not plan.success and plan.attempts
    view = PlanScene(plan)
    img, rect = _open_export(browser, view, tmp_path / "a", "exported_failed_plan_a.png")
    eye, target, fov = view.camera
    arm_box = _box(project(_arm_points(plan.q), eye, target, fov_deg=fov, rect=rect), 40)
    u, v = project(view_top(eye, target, fov), eye, target, fov_deg=fov, rect=rect)[0]

    def arm_and_caption(img: np.ndarray) -> tuple[float, int]:
        """Share of the arm's colour inside the start pose's box; dark grey caption pixels below the top
        centre. Chromium's software renderer draws the caption's strokes at a value of 0.2 .. 0.5 from
        one page load to the next (measured: 151 .. 1393 pixels below 0.35, 1641 .. 3744 below 0.5);
        the scene without text gives under 10 grey pixels below 0.5 in a band of this size."""
        band = img[int(v):int(v) + 12 * len(view.caption.splitlines()), int(u) - 250:int(u) + 250]
        hsv = rgb_to_hsv(np.clip(band, 0, 1))
        return _inside(_in_canvas(hue_mask(img, *BLUE), rect), arm_box), int(
            ((hsv[..., 2] < 0.5) & (hsv[..., 1] < 0.3)).sum())

    # The page plays its recording: wait until the arm stands at the start pose (a condition, not a time).
    seen = [arm_and_caption(img)]

    def settled() -> bool:
        seen[0] = arm_and_caption(screenshot(browser))
        return seen[0][0] > 0.9 and seen[0][1] > 300

    wait_until(settled, 90.0, 0.5)
    seen = seen[0]
    assert seen[0] > 0.9, f"the arm is not at the start pose ({seen[0]:.2f} of its pixels in its box)"
    # The caption hangs from the top centre of the view: dark text on the white page above the scene.
    assert seen[1] > 300, "no caption text below the top centre of the view"


def test_a_q_outside_the_limits_is_drawn_red(browser, tmp_path):
    """The links moved by a joint outside Table I are red; the same pose with that joint inside is not."""
    counts = {}
    for name, q4 in (("outside", 2.6), ("inside", 2.0)):
        view = PoseView(q=[0.3, -0.5, 0.4, q4, 0.2, 0.0], arm=THESIS_ARM)
        assert bool(view.warnings) == (name == "outside")
        img, rect = _open_export(browser, view, tmp_path / name, f"pose_q4_{name}_limits.png")
        counts[name] = 0

        def coloured(name=name, rect=rect) -> bool:
            """The colours arrive after the shapes: the arm's blue shows once they have."""
            img = screenshot(browser)
            counts[name] = max(counts[name], int(_in_canvas(hue_mask(img, *RED, min_sat=0.6), rect).sum()))
            blue = int(_in_canvas(hue_mask(img, *BLUE), rect).sum())
            return blue > 300 and (name == "inside" or counts[name] > 400)

        assert wait_until(coloured, 90.0, 0.5), (name, counts)
    assert counts["outside"] > 400 and counts["outside"] > 5 * counts["inside"], counts


def _thumb(browser):
    from selenium.webdriver.common.by import By

    sliders = browser.find_elements(By.CSS_SELECTOR, "[role=slider]")
    assert len(sliders) == 1, "expected one time slider in the panel"
    return sliders[0]


def test_live_time_slider_moves_the_arm(browser, plan_j):
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.keys import Keys

    view = PlanScene(plan_j)
    live = serve(view, host="127.0.0.1", port=0)
    try:
        assert live.url.startswith("http://127.0.0.1:")
        browser.get(live.url)
        wait_for_scene(browser)
        rect = canvas_rect(browser)
        eye, target, fov = view.camera
        region = _box(project(_arm_points(plan_j.q[[0, -1]]), eye, target, fov_deg=fov, rect=rect), 30)
        x0, y0, x1, y1 = (int(max(v, 0)) for v in region)
        # (on a loaded machine the arm's meshes can arrive after the grid has settled: wait for them)
        before = wait_for_scene(browser, until=lambda img: hue_mask(img, *BLUE)[y0:y1, x0:x1].sum() > 100)
        slider = live.time_slider
        t_end = slider.max

        thumb = _thumb(browser)
        thumb.click()
        thumb.send_keys(Keys.END)
        moved = wait_until(lambda: abs(slider.value - t_end) < 1e-9, 30.0, 0.1)
        assert moved, "the server never saw the slider move"
        blue0 = hue_mask(before, *BLUE)[y0:y1, x0:x1]  # not the panel's button
        c0 = np.argwhere(blue0).mean(axis=0)
        shot = [before]

        def arm_moved() -> bool:
            shot[0] = screenshot(browser)
            blue1 = hue_mask(shot[0], *BLUE)[y0:y1, x0:x1]
            return blue1.sum() > 100 and np.hypot(*(np.argwhere(blue1).mean(axis=0) - c0)) > 10

        assert wait_until(arm_moved, 60.0, 0.25), "the arm's pixels did not move"
        after = shot[0]
        changed = np.abs(after - before)[y0:y1, x0:x1].max(axis=2) > 0.15
        assert changed.mean() > 0.01, "the arm did not move on screen"

        # Drag the thumb back to mid-track: the scene shows the motion half-way, with its clearance label.
        track = thumb.find_element("xpath", "..")
        drag = ActionChains(browser).click_and_hold(thumb).move_by_offset(-track.size["width"] // 2, 0)
        drag.release().perform()
        assert wait_until(lambda: 0.2 * t_end < slider.value < 0.8 * t_end, 30.0, 0.1), slider.value
        wait_until(lambda: np.abs(screenshot(browser) - after)[y0:y1, x0:x1].max() > 0.15, 60.0, 0.25)
        _keep(screenshot(browser), "live_j_mid_motion.png")
    finally:
        live.stop()
