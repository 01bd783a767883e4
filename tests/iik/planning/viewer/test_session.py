"""Serving and exporting: localhost by default, a clear error for a taken port, no half-written export."""

import os
import signal
import socket
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import iik
from iik import THESIS_ARM
from iik.cli import main
from iik.planning.viewer import (
    ExportError,
    PortInUseError,
    PoseView,
    ViewerError,
    export,
    inline,
    serve,
    show,
)
from iik.planning.viewer.motion import Motion, MotionView, Track
from iik.planning.viewer.session import ViewOptions


@pytest.fixture(scope="module")
def pose_view():
    return PoseView(q=[0.3, -0.5, 0.4, 0.8, 0.2, 0.0], arm=THESIS_ARM)


def test_serves_on_localhost_by_default(pose_view):
    live = serve(pose_view, port=0)
    try:
        assert live.url.startswith("http://127.0.0.1:")
        host = live.server.get_host()
        assert host == "127.0.0.1"
        with socket.create_connection(("127.0.0.1", live.server.get_port()), timeout=2):
            pass
    finally:
        live.stop()


def test_a_taken_port_is_an_error_naming_it(pose_view):
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        s.listen()
        port = s.getsockname()[1]
        with pytest.raises(PortInUseError, match=f"port {port}") as err:
            serve(pose_view, port=port)
        assert err.value.port == port and isinstance(err.value, OSError)


def test_export_writes_one_page_with_the_recording(pose_view, tmp_path):
    res = export(pose_view, tmp_path / "out")
    page = (tmp_path / "out" / "index.html").read_text(encoding="utf-8")
    assert "__VISER_EMBED_DATA__" in page
    assert res.size == (tmp_path / "out" / "index.html").stat().st_size and res.frames == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]  # no temporary folder left behind
    mask = os.umask(0)
    os.umask(mask)
    assert (tmp_path / "out").stat().st_mode & 0o777 == 0o777 & ~mask


def test_export_refuses_a_non_empty_folder_and_changes_nothing(pose_view, tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / "keep.txt").write_text("mine")
    with pytest.raises(ExportError, match="not empty"):
        export(pose_view, out)
    assert [p.name for p in out.iterdir()] == ["keep.txt"]
    export(pose_view, out, force=True)
    assert [p.name for p in out.iterdir()] == ["index.html"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]


def test_a_failed_export_leaves_nothing(tmp_path):
    class Broken:
        title = "broken"

        def build(self, server):
            raise RuntimeError("boom")

    with pytest.raises(RuntimeError):
        export(Broken(), tmp_path / "out")
    assert list(tmp_path.iterdir()) == []


INTERRUPTED_EXPORT = textwrap.dedent("""
    import os, pathlib, signal, sys, time
    from iik.cli import main
    real = pathlib.Path.write_text
    def write_text(self, text, *args, **kwargs):  # SIGTERM half-way through the page
        if self.name == "index.html":
            real(self, text[: len(text) // 2], *args, **kwargs)
            os.kill(os.getpid(), signal.SIGTERM)
            time.sleep(30)
        return real(self, text, *args, **kwargs)
    pathlib.Path.write_text = write_text
    sys.exit(main(["view", "--q", "0.3", "0", "0", "0", "0", "0", "--export", sys.argv[1], "--force"]))
""")


def test_sigterm_while_exporting_leaves_the_previous_page_and_no_temporary(tmp_path):
    out = tmp_path / "v"
    assert main(["view", "--q", "0", "0", "0", "0", "0", "0", "--export", str(out)]) == 0
    before = (out / "index.html").read_bytes()
    res = subprocess.run([sys.executable, "-c", INTERRUPTED_EXPORT, str(out)], capture_output=True, text=True,
                         timeout=300)
    assert res.returncode == 128 + signal.SIGTERM, res.stderr
    assert "iik view: interrupted by SIGTERM" in res.stderr
    assert [p.name for p in out.iterdir()] == ["index.html"] and (out / "index.html").read_bytes() == before
    assert [p.name for p in tmp_path.iterdir()] == ["v"]


def test_an_animation_is_recorded_frame_by_frame(tmp_path):
    t = np.linspace(0.0, 2.0, 201)
    q = np.outer(t / 2.0, [1.0, -0.5, 0.5, 0.3, 0.2, 0.1])
    motion = Motion("m", t, (Track("a", q, (40, 90, 200)),), THESIS_ARM)
    res = export(MotionView(motion), tmp_path / "m", fps=25)
    assert res.frames == 51  # every 4th of 201 samples at 100 Hz, last kept


def test_interactive_ik_cannot_be_exported(tmp_path):
    view = PoseView(iik.fk(np.zeros(6), THESIS_ARM), interactive=True, arm=THESIS_ARM)
    with pytest.raises(ViewerError, match="live server"):
        show(view, ViewOptions(export=tmp_path / "x"))
    assert not (tmp_path / "x").exists()


def test_inline_embeds_the_recorded_page_in_an_iframe(pose_view, capsys):
    import html

    shown = inline(pose_view, height=300)
    assert shown.data.startswith('<div><iframe srcdoc="') and 'height="300"' in shown.data
    page = html.unescape(shown.data.split('srcdoc="', 1)[1].split('" width=', 1)[0])
    assert "__VISER_EMBED_DATA__" in page and page.lstrip().lower().startswith("<!doctype html")
    assert capsys.readouterr().out == ""  # viser's banner is not printed
