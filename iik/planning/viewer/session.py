"""Serve a view live (localhost by default) or export it as a page that opens from disk.

A *view* is anything with ``title`` and ``build(server) -> Animation | None``
(:class:`iik.planning.viewer.pose.PoseView`, :class:`~iik.planning.viewer.playback.MotionView`, ...).

* :func:`serve` starts a :class:`viser.ViserServer` on ``host:port`` (127.0.0.1
  unless told otherwise), builds the view and, for an animation, adds a time
  slider with play/pause; it fails with :class:`PortInUseError` naming the port
  instead of silently moving to another one.
* :func:`export` builds the view on a private server on a free loopback port,
  records the scene and every animation frame with viser's scene serializer and
  writes ``index.html``: viser's built client with the recording embedded, which
  a browser plays from disk with no server and no network (viser's own playback
  bar gives play/pause and the time slider). The folder appears complete or not
  at all.
"""

from __future__ import annotations

import contextlib
import errno
import io
import signal
import socket
import threading
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Protocol

import numpy as np
import viser

from iik.errors import FileError, Remedy
from iik.files import atomic_output, check_output

from ..errors import ExportError, PortInUseError, ViewRequestError
from .environment import configure_server

__all__ = ["Animation", "View", "ViewOptions", "LiveView", "ExportResult", "open_server", "serve", "record",
           "export", "inline", "present"]

EXPORT_FILE = "index.html"


@dataclass(frozen=True)
class Animation:
    """Frames of a view: ``show(i)`` puts the scene at frame ``i`` (time ``times[i]`` [s]).

    Attributes:
        times: (k,) increasing frame times [s].
        show: Callback placing every moving node at frame ``i``.
        marks: ``(time [s], label)`` pairs marked on the live time slider (e.g. IK branch switches).
        status: Optional callback giving a Markdown status line for frame ``i`` (live panel).
        jumps: ``(button label, time [s])`` pairs: a live-panel button per pair moves the time slider
            there (e.g. to the minimum clearance).
    """

    times: np.ndarray
    show: Callable[[int], None]
    marks: tuple[tuple[float, str], ...] = ()
    status: Callable[[int], str] | None = None
    jumps: tuple[tuple[str, float], ...] = ()

    def frame_at(self, t: float) -> int:
        """Index of the last frame at or before ``t`` [s]."""
        return int(np.clip(np.searchsorted(self.times, t + 1e-9, side="right") - 1, 0, len(self.times) - 1))

    @property
    def duration(self) -> float:
        return float(self.times[-1] - self.times[0]) if len(self.times) else 0.0


class View(Protocol):
    """What :func:`serve` and :func:`export` draw."""

    title: str

    def build(self, server: viser.ViserServer) -> Animation | None: ...


@dataclass(frozen=True)
class ViewOptions:
    """How to present a view.

    Attributes:
        host: Interface to listen on (127.0.0.1: this machine only).
        port: TCP port (0: any free port).
        export: Write an offline page into this folder instead of serving.
        force: Replace a non-empty export folder.
        fps: Frames per second of an exported animation [1/s].
    """

    host: str = "127.0.0.1"
    port: int = 8080
    export: Path | None = None
    force: bool = False
    fps: float = 25.0


@dataclass
class LiveView:
    """A running viewer. ``stop()`` ends it; ``serve_forever()`` blocks until Ctrl-C."""

    server: viser.ViserServer
    url: str
    animation: Animation | None
    time_slider: object | None = None
    _stop: threading.Event = field(default_factory=threading.Event)
    _closed: threading.Lock = field(default_factory=threading.Lock)

    def serve_forever(self) -> None:
        """Block until Ctrl-C (SIGINT) or :meth:`stop`, then stop the server."""
        previous = None
        if threading.current_thread() is threading.main_thread():
            previous = signal.signal(signal.SIGINT, lambda *_: self._stop.set())
        try:
            while not self._stop.wait(0.5):
                pass
        finally:
            if previous is not None:
                signal.signal(signal.SIGINT, previous)
            self.stop()

    def stop(self) -> None:
        """Stop serving (idempotent)."""
        self._stop.set()
        if self._closed.acquire(blocking=False):
            with contextlib.redirect_stdout(io.StringIO()):
                self.server.stop()


@dataclass(frozen=True)
class ExportResult:
    """An offline page: ``path / "index.html"``, its ``size`` [bytes], ``frames`` and build ``seconds``."""

    path: Path
    size: int
    frames: int
    seconds: float


def _check_port(host: str, port: int) -> None:
    """Bind ``host:port`` once: a host that is no address of this machine is a bad ``host``
    (:class:`ViewRequestError`), a taken or forbidden port a :class:`PortInUseError`."""
    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    with socket.socket(family, socket.SOCK_STREAM) as s:
        s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            s.bind((host, port))
        except socket.gaierror as exc:  # not an address nor a name that resolves (999.1.1.1)
            raise ViewRequestError("host", f"bad host {host!r}: not an address or host name "
                                           f"({exc.strerror}); e.g. 127.0.0.1 (this machine only), 0.0.0.0 "
                                           "(every interface)") from None
        except OSError as exc:
            if exc.errno == errno.EADDRNOTAVAIL:  # a valid address of another machine (8.8.8.8)
                raise ViewRequestError("host", f"bad host {host!r}: not an address of this machine "
                                               f"({exc.strerror}); e.g. 127.0.0.1, 0.0.0.0") from None
            detail = "address in use" if exc.errno == errno.EADDRINUSE else exc.strerror or str(exc)
            raise PortInUseError(host, port, detail) from None


def open_server(host: str, port: int) -> viser.ViserServer:
    """A quiet :class:`viser.ViserServer` on exactly ``host:port`` (0: any free port).

    Raises:
        ViewRequestError: ``host`` is not an address of this machine; ``port`` is no TCP port.
        PortInUseError: the port is taken (viser itself would silently move to the next one).
    """
    if isinstance(port, bool) or not isinstance(port, int) or not 0 <= port <= 65535:
        raise ViewRequestError("port", f"{port!r} is not a TCP port (0..65535; 0: any free port)")
    _check_port(host, port)
    with contextlib.redirect_stdout(io.StringIO()):  # viser prints its own banner; we print the URL
        server = viser.ViserServer(host=host, port=port, verbose=False)
    if port and server.get_port() != port:  # viser moves to the next port when one is taken
        with contextlib.redirect_stdout(io.StringIO()):
            server.stop()
        raise PortInUseError(host, port, "taken while starting")
    return server


def _add_jump(gui, label: str, t: float, slider) -> None:
    """A button that moves the time slider to ``t`` [s] (its update shows that frame)."""
    button = gui.add_button(label, icon=viser.Icon.TARGET)

    @button.on_click
    def _(_event) -> None:
        slider.value = t


def _add_player(server: viser.ViserServer, anim: Animation) -> object:
    """Time slider (with marks), play/pause and a status line in the live panel."""
    gui = server.gui
    t0, t1 = float(anim.times[0]), float(anim.times[-1])
    step = max(round(float(np.min(np.diff(anim.times))), 3), 1e-3) if len(anim.times) > 1 else 1.0
    t1 = round(t1, 3)
    marks = tuple((round(t, 3), lab) for t, lab in anim.marks) or None
    slider = gui.add_slider("time [s]", min=t0, max=max(t1, t0 + step), step=step, initial_value=t0,
                            marks=marks)
    play = gui.add_button("Play", icon=viser.Icon.PLAYER_PLAY)
    status = gui.add_markdown(anim.status(0) if anim.status else "")
    playing = threading.Event()

    @slider.on_update
    def _(_event) -> None:
        i = anim.frame_at(slider.value)
        anim.show(i)
        if anim.status:
            status.content = anim.status(i)

    for label, t_jump in anim.jumps:
        _add_jump(gui, label, min(max(float(t_jump), t0), t1), slider)

    @play.on_click
    def _(_event) -> None:
        if playing.is_set():
            playing.clear()
        else:
            if slider.value >= t1:
                slider.value = t0
            playing.set()
        play.label = "Pause" if playing.is_set() else "Play"
        play.icon = viser.Icon.PLAYER_PAUSE if playing.is_set() else viser.Icon.PLAYER_PLAY

    def _run() -> None:
        last = time.perf_counter()
        while True:
            time.sleep(1 / 30)
            now = time.perf_counter()
            if playing.is_set():
                t = min(slider.value + (now - last), t1)
                slider.value = t
                if t >= t1:
                    playing.clear()
                    play.label, play.icon = "Play", viser.Icon.PLAYER_PLAY
            last = now

    threading.Thread(target=_run, daemon=True, name="iik-view-player").start()
    return slider


def serve(view: View, *, host: str = "127.0.0.1", port: int = 8080) -> LiveView:
    """Start the live viewer for ``view`` and return at once (the server runs in threads)."""
    server = open_server(host, port)
    try:
        configure_server(server, view.title)
        anim = view.build(server)
        if anim is not None and len(anim.times):
            anim.show(0)  # the arm posed at t = 0 on first load, not a heap of shapes at the origin
        slider = _add_player(server, anim) if anim is not None and len(anim.times) > 1 else None
    except BaseException:
        with contextlib.redirect_stdout(io.StringIO()):
            server.stop()
        raise
    shown = "127.0.0.1" if host in ("", "0.0.0.0") else host
    shown = f"[{shown}]" if ":" in shown else shown
    url = f"http://{shown}:{server.get_port()}/"
    return LiveView(server=server, url=url, animation=anim, time_slider=slider)


def _frames(anim: Animation, fps: float) -> Sequence[int]:
    """Every n-th frame so the export has at most about ``fps`` frames per second (last frame kept)."""
    k = len(anim.times)
    dt = float(np.median(np.diff(anim.times))) if k > 1 else 1.0
    stride = max(1, int(round(1.0 / (fps * dt)))) if dt > 0 else 1
    keep = list(range(0, k, stride))
    if keep[-1] != k - 1:
        keep.append(k - 1)
    return keep


@contextlib.contextmanager
def _export_errors(directory: Path, force: bool) -> Iterator[None]:
    """Refuse a non-empty folder without ``force``; :class:`iik.errors.FileError` as :class:`ExportError`."""
    if directory.is_dir() and any(directory.iterdir()) and not force:
        raise ExportError(directory, "folder is not empty",
                          Remedy("use {} to replace its contents", "force", True))
    try:
        yield
    except FileError as exc:
        raise ExportError(directory, exc.reason) from None


def record(view: View, *, fps: float = 25.0) -> tuple[str, int]:
    """Build ``view`` on a private loopback server and record it: ``(self-contained HTML page, frames)``."""
    if not np.isfinite(fps) or fps <= 0:
        raise ViewRequestError("fps", f"must be a positive number of frames per second, got {fps!r}")
    server = open_server("127.0.0.1", 0)
    try:
        configure_server(server, view.title)
        anim = view.build(server)
        frames = _frames(anim, fps) if anim is not None and len(anim.times) else [0]
        if anim is not None and len(anim.times):
            anim.show(frames[0])
        recorder = server.get_scene_serializer()
        if anim is not None and len(anim.times) > 1:
            for a, b in zip(frames[:-1], frames[1:], strict=True):
                recorder.insert_sleep(float(anim.times[b] - anim.times[a]))
                anim.show(b)
            recorder.insert_sleep(1.0)  # hold the last frame before the loop restarts
        return recorder.as_html(), len(frames)
    finally:
        with contextlib.redirect_stdout(io.StringIO()):
            server.stop()


def export(view: View, directory: Path | str, *, force: bool = False, fps: float = 25.0) -> ExportResult:
    """Write ``directory/index.html``: the view and its animation, playable from disk offline.

    The folder is written whole or not at all (:func:`iik.files.atomic_output`): an error or an
    interrupt (Ctrl-C, SIGTERM, SIGHUP) leaves ``directory`` as it was.

    Raises:
        ExportError: ``directory`` is not empty (without ``force``), is a file, or cannot be written.
    """
    t_start = time.perf_counter()
    directory, owns = Path(directory), None if force else ()
    with _export_errors(directory, force):
        check_output(directory, "export", folder=True, owns=owns)  # before the work
        with atomic_output(directory, "export", folder=True, owns=owns) as out:
            page, frames = record(view, fps=fps)
            try:
                (out.path / EXPORT_FILE).write_text(page, encoding="utf-8")
            except OSError as exc:
                raise ExportError(directory, f"cannot write the export ({exc.strerror or exc})") from None
    size = sum(f.stat().st_size for f in directory.rglob("*") if f.is_file())
    return ExportResult(path=directory, size=size, frames=frames, seconds=time.perf_counter() - t_start)


def inline(view: View, *, height: int = 420, fps: float = 25.0):
    """The recorded view as an ``IPython.display.HTML`` iframe for a notebook (no server stays up).

    viser's own messages (its banner, "Server stopped"), which its console shows as notebook
    displays rather than on stdout, are kept out of the cell.
    """
    import html

    from IPython.display import HTML
    from IPython.utils.capture import capture_output

    with capture_output():
        page, _ = record(view, fps=fps)
    return HTML(f'<div><iframe srcdoc="{html.escape(page, quote=True)}" width="100%" height="{int(height)}" '
                'style="border:1px solid #ddd"></iframe></div>')


def present(view: View, options: ViewOptions = ViewOptions()) -> LiveView | ExportResult:
    """:func:`export` when ``options.export`` is set, else :func:`serve`."""
    if options.export is not None:
        return export(view, options.export, force=options.force, fps=options.fps)
    if not options.host:
        raise ViewRequestError("host", "empty (127.0.0.1: this machine only)")
    return serve(view, host=options.host, port=options.port)
