"""The viewer's first impression (issue 20, item 13): what a user sees before touching anything.

Browser tests wait on a condition (what the page shows, what the server saw), never a fixed
time. Set ``IIK_SCREENSHOTS=DIR`` to keep the screenshots.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest

import iik
from iik.planning.viewer import PlanScene, PoseView, plan_for_view, serve
from iik.planning.viewer.environment import VIEW_PRESETS, framing, legend_html
from iik.planning.viewer.session import open_server
from verification.testing.polling import wait_until

from .conftest import canvas_rect, hue_mask, project, screenshot, wait_for_scene

ARM = iik.THESIS_ARM
BLUE = (205.0, 240.0)  # the arm (style.ARM, hue 222 deg), shaded


def _keep(img: np.ndarray, name: str) -> None:
    folder = os.environ.get("IIK_SCREENSHOTS")
    if folder:
        import matplotlib.image as mpimg

        Path(folder).mkdir(parents=True, exist_ok=True)
        mpimg.imsave(Path(folder) / name, np.clip(img, 0, 1))


@pytest.fixture(scope="module")
def plan_j():
    return plan_for_view("j")


def _arm_far_end(q) -> np.ndarray:
    """Joint-5 origin and the tool point at ``q`` [m]: far from the base, so a heap of shapes at the
    origin cannot be mistaken for them."""
    return iik.joint_frames(np.asarray(q).reshape(1, 6), ARM)[0, -2:, :3, 3]


def test_a_live_plan_opens_with_the_arm_posed_at_t0(browser, plan_j):
    """No slider touched: the arm's far end is drawn where fk(q(t = 0)) puts it."""
    view = PlanScene(plan_j)
    live = serve(view, host="127.0.0.1", port=0)
    try:
        browser.get(live.url)
        wait_for_scene(browser)
        rect = canvas_rect(browser)
        eye, target, fov = view.camera
        uv = project(_arm_far_end(plan_j.q[0]), eye, target, fov_deg=fov, rect=rect)
        x0, y0 = (int(v) for v in uv.min(axis=0) - 30)
        x1, y1 = (int(v) for v in uv.max(axis=0) + 30)

        def blue_at_far_end() -> int:
            return int(hue_mask(screenshot(browser), *BLUE)[max(y0, 0):y1, max(x0, 0):x1].sum())

        assert wait_until(lambda: blue_at_far_end() > 150, 60.0, 0.5), "the arm is not posed at t = 0"
        assert live.time_slider.value == pytest.approx(float(plan_j.t[0]))  # nobody moved the slider
        _keep(screenshot(browser), "live_j_first_load.png")
    finally:
        live.stop()


def test_the_clearance_panel_plots_the_motion_and_jumps_to_its_minimum(browser, plan_j):
    from selenium.webdriver.common.by import By

    view = PlanScene(plan_j)
    k = view.least
    n = view.clearance[k]
    text = view.clearance_summary()
    assert f"{n.distance * 1000:.1f} mm** at t = {plan_j.t[k]:.2f} s" in text
    assert f"{plan_j.certified_clearance * 1000:.1f} mm" in text and n.link in text
    assert n.distance == min(m.distance for m in view.clearance)
    assert plan_j.certified_clearance <= n.distance + 1e-9  # a lower bound is below what is seen
    live = serve(view, host="127.0.0.1", port=0)
    try:
        browser.get(live.url)
        wait_for_scene(browser)
        assert wait_until(lambda: browser.find_elements(By.CSS_SELECTOR, ".uplot canvas"), 30.0, 0.2), \
            "no clearance plot in the panel"
        plot = browser.find_elements(By.CSS_SELECTOR, ".uplot")[0]
        browser.execute_script("arguments[0].scrollIntoView({block: 'center'});", plot)
        assert "whole-arm clearance vs time" in plot.text
        buttons = [b for b in browser.find_elements(By.TAG_NAME, "button") if "minimum clearance" in b.text]
        assert len(buttons) == 1
        _keep(screenshot(browser), "live_j_clearance_plot.png")
        buttons[0].click()
        assert wait_until(lambda: abs(live.time_slider.value - plan_j.t[k]) < 1e-6, 20.0, 0.1), \
            live.time_slider.value
    finally:
        live.stop()


def test_view_presets_move_the_browsers_camera(browser, plan_j):
    from selenium.webdriver.common.by import By

    view = PlanScene(plan_j)
    live = serve(view, host="127.0.0.1", port=0)
    try:
        browser.get(live.url)
        wait_for_scene(browser)
        assert wait_until(lambda: len(live.server.get_clients()) == 1, 20.0, 0.1)
        client = next(iter(live.server.get_clients().values()))
        for preset in ("Top", "Front", "Side"):
            browser.find_element(By.XPATH, f"//button[normalize-space()='{preset}']").click()
            az, el = VIEW_PRESETS[preset.lower()]
            want = np.array([np.cos(np.radians(el)) * np.cos(np.radians(az)),
                             np.cos(np.radians(el)) * np.sin(np.radians(az)), np.sin(np.radians(el))])

            def looking_from_there(want=want) -> bool:
                d = np.asarray(client.camera.position) - np.asarray(client.camera.look_at)
                return float(d @ want / np.linalg.norm(d)) > 0.999

            assert wait_until(looking_from_there, 20.0, 0.1), (preset, client.camera.position)
    finally:
        live.stop()


def test_framing_holds_every_point_in_view():
    pts = np.random.default_rng(0).uniform(-0.5, 0.8, (50, 3))
    for preset in VIEW_PRESETS:
        eye, target = framing(pts, 50.0, preset)
        uv = project(pts, eye, target, fov_deg=50.0, rect=(0, 0, 1600, 1000))
        assert np.all((uv >= 0) & (uv <= [1600, 1000])), preset


def test_pose_mode_draws_the_target_frame_even_when_unreachable_and_colours_each_solution():
    server = open_server("127.0.0.1", 0)
    try:
        far = PoseView(iik.pose_from_euler([1.5, 0.0, 0.3], 0.0, 1.0, 0.0), arm=ARM)
        far.build(server)
        assert far.result.count == 0 and "unreachable" in far.target_label.text
        pv = PoseView(iik.pose_from_euler([0.4, 0.3, 0.2], np.pi, np.radians(120), 0.0), arm=ARM)
        pv.build(server)
        n = pv.result.count
        assert n >= 2 and pv.target_label.text == "target"
        assert len({b.colour for b in pv.bodies[:n]}) == n  # one colour each
        pv.toggles[1].value = False  # the toggle hides that solution alone
        assert wait_until(lambda: not pv.bodies[1].visible, 5.0, 0.05) and pv.bodies[0].visible
    finally:
        server.stop()


def test_q_mode_has_joint_sliders_that_move_the_arm():
    server = open_server("127.0.0.1", 0)
    try:
        pv = PoseView(q=[0.3, -0.5, 0.4, 0.8, 0.2, 0.0], arm=ARM)
        pv.build(server)
        assert [s.label for s in pv.sliders] == [f"q{j}" for j in range(1, 7)]
        assert [s.min for s in pv.sliders] == pytest.approx(np.degrees(ARM.q_min), abs=0.1)
        pv.sliders[0].value = 20.0
        assert wait_until(lambda: abs(pv.given[0] - np.radians(20.0)) < 1e-9, 5.0, 0.05)
        assert np.allclose(pv.bodies[0].q, pv.given) and np.allclose(pv.T, iik.fk(pv.given, ARM))
    finally:
        server.stop()


def test_the_legend_names_each_arm_drawn():
    html = legend_html((("commanded target", (1, 2, 3)), ("measured arm (PCube_getPos)", (4, 5, 6))))
    assert "measured arm (PCube_getPos)" in html and "rgb(4, 5, 6)" in html
    assert "arm (URDF collision shapes)" not in html and "arm (URDF collision shapes)" in legend_html()
