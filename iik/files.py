"""Files the product writes and reads: an output appears whole or not at all, and no read
takes more than its limit.

**Writing** (:class:`AtomicOutput`, :func:`atomic_output`). Every output -- the report
folder of ``iik verify``, the folder of ``iik plan --out``, the page of ``iik view
--export``, a run log and its figures, a URDF or scenario file -- is written into a
temporary sibling of its target (``.partial-XXXXXXXX-NAME`` in the same folder, so the
final move is a rename on one file system) and moved into place only when complete. An
existing file is replaced by one ``os.replace``; an existing folder is renamed aside and
the new one renamed in, with Ctrl-C, SIGTERM and SIGHUP held between the two renames
(:func:`iik.signals.signals_deferred`), then the old one is removed. An error, Ctrl-C,
SIGTERM or SIGHUP before that (inside :func:`atomic_output` the last two are turned into
:class:`iik.signals.StopSignal`) discards the temporary and leaves the target as it was:
the previous output intact, nothing mixed. (A process killed outright, SIGKILL or a power
cut, leaves its ``.partial-*`` sibling behind, and the target still as it was.)

A folder is only replaced if it holds nothing but what the writer writes (``owns``), so
``--out .`` cannot wipe a working directory.

**Reading** (:func:`read_bytes`, :func:`read_text`). Every file the product reads (scenario
TOML, trajectory CSV, run logs, URDF, report JSON) is opened without blocking, must be a
regular file (a device such as ``/dev/zero``, a FIFO or a folder is refused at once), and
is read in chunks that stop as soon as the caller's documented limit is passed -- a limit
on the bytes actually read, not on the size ``stat`` reports (which is 0 for ``/proc``
files and meaningless for devices).

Both raise :class:`iik.errors.FileError` naming the argument and the path.
"""

from __future__ import annotations

import contextlib
import os
import secrets
import shutil
import stat
from collections.abc import Collection, Iterator
from pathlib import Path

from .errors import FileError
from .signals import signals_deferred, stop_on_signals

__all__ = ["AtomicOutput", "atomic_output", "check_output", "write_text", "read_bytes", "read_text",
           "PARTIAL_PREFIX"]

#: Name prefix of the temporary sibling an output is written into.
PARTIAL_PREFIX = ".partial-"

_CHUNK = 1 << 20


def _kind(mode: int) -> str:
    for test, name in ((stat.S_ISDIR, "a folder"), (stat.S_ISCHR, "a character device"),
                       (stat.S_ISBLK, "a block device"), (stat.S_ISFIFO, "a FIFO (named pipe)"),
                       (stat.S_ISSOCK, "a socket")):
        if test(mode):
            return name
    return "not a regular file"


def _size(limit: int) -> str:
    return f"{limit / 1e6:g} MB" if limit >= 1_000_000 else f"{limit} bytes"


def read_bytes(path, argument: str, *, limit: int, what: str = "a file") -> bytes:
    """The contents of the regular file ``path``, at most ``limit`` bytes.

    Args:
        path: The file (str or path-like).
        argument: The argument that named it, for the error (e.g. ``"trajectory"``).
        limit: Largest size accepted [bytes]; reading stops once it is passed.
        what: What the file is, for the size error (e.g. ``"a scenario file"``).

    Raises:
        FileError: missing or unreadable, not a regular file, or more than ``limit`` bytes.
    """
    p = os.fspath(path)
    try:  # O_NONBLOCK: opening a FIFO without a writer returns at once (and is refused below)
        fd = os.open(p, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0))
    except FileNotFoundError:
        raise FileError(argument, f"cannot read {p}: no such file", p) from None
    except OSError as exc:
        raise FileError(argument, f"cannot read {p}: {exc.strerror or exc}", p) from None
    try:
        mode = os.fstat(fd).st_mode
        if not stat.S_ISREG(mode):
            raise FileError(argument, f"cannot read {p}: it is {_kind(mode)}, not a regular file", p)
        chunks, total = [], 0
        while chunk := os.read(fd, min(_CHUNK, limit + 1 - total)):
            chunks.append(chunk)
            total += len(chunk)
            if total > limit:
                raise FileError(argument, f"cannot read {p}: more than {_size(limit)}, the limit of {what}",
                                p)
        return b"".join(chunks)
    except OSError as exc:
        if isinstance(exc, FileError):
            raise
        raise FileError(argument, f"cannot read {p}: {exc.strerror or exc}", p) from None
    finally:
        os.close(fd)


def read_text(path, argument: str, *, limit: int, what: str = "a file", encoding: str = "utf-8") -> str:
    """:func:`read_bytes` decoded (``"utf-8-sig"`` also drops a byte-order mark).

    Raises:
        FileError: as :func:`read_bytes`, or the bytes are not text in ``encoding``.
    """
    data = read_bytes(path, argument, limit=limit, what=what)
    try:
        return data.decode(encoding)
    except UnicodeDecodeError as exc:
        raise FileError(argument, f"cannot read {os.fspath(path)}: not UTF-8 text (byte "
                                  f"0x{data[exc.start]:02x} at offset {exc.start})", path) from None


def check_output(target, argument: str, *, folder: bool, owns: Collection[str] | None = ()) -> Path:
    """Refuse, before any work, an output ``target`` that :class:`AtomicOutput` would refuse.

    Args:
        target: The output file or folder.
        argument: The argument that named it (e.g. ``"out"``).
        folder: The output is a folder (else a file).
        owns: For a folder: the names the writer writes; an existing folder holding anything
            else is refused. ``()``: only an empty folder may be replaced; ``None``: any
            (the caller was told to, e.g. ``--force``).

    Returns:
        ``target`` as a :class:`~pathlib.Path`.

    Raises:
        FileError: a file where a folder goes (or the reverse), or a folder holding other things.
    """
    t = Path(target)
    if str(t) in ("", ".", "..") or t.name in ("", ".", ".."):
        raise FileError(argument, f"{str(target)!r} names no {'folder' if folder else 'file'} to write "
                                  "(give a new name, e.g. out/NAME)", target)
    if folder and t.exists() and not t.is_dir():
        raise FileError(argument, f"{t} is a file, not a folder", target)
    if not folder and t.exists() and not t.is_file():  # never replace a folder, a device, a FIFO...
        raise FileError(argument, f"{t} is {_kind(t.stat().st_mode)}, not a file to write", target)
    if folder and owns is not None and t.is_dir():
        other = sorted(e.name for e in t.iterdir() if e.name not in owns)
        if other:
            shown = ", ".join(other[:5]) + (", ..." if len(other) > 5 else "")
            raise FileError(argument, f"{t} holds other things ({shown}); it would be replaced as a whole: "
                                      "give a new or empty folder", target)
    return t


class AtomicOutput:
    """One output being written: :attr:`path` is a fresh temporary sibling of :attr:`target`;
    :meth:`commit` moves it into place, :meth:`discard` removes it (the target untouched).

    Args:
        target: The output file or folder.
        argument: The argument that named it (for errors).
        folder: The output is a folder (:attr:`path` is then an empty folder), else a file
            (:attr:`path` is then an empty file).
        owns: See :func:`check_output`.

    Raises:
        FileError: see :func:`check_output`; or the temporary cannot be created.
    """

    def __init__(self, target, argument: str, *, folder: bool, owns: Collection[str] | None = ()):
        self.target = check_output(target, argument, folder=folder, owns=owns)
        self.argument, self.folder, self.owns = argument, folder, owns
        parent = self.target.parent
        name = f"{PARTIAL_PREFIX}{secrets.token_hex(4)}-{self.target.name}"
        try:
            parent.mkdir(parents=True, exist_ok=True)
            self.path = parent / name
            if folder:
                self.path.mkdir()
            else:
                self.path.touch(exist_ok=False)
            mask = os.umask(0)
            os.umask(mask)
            self.path.chmod((0o777 if folder else 0o666) & ~mask)
        except OSError as exc:
            raise FileError(argument, f"cannot write {self.target}: {exc.strerror or exc}", target) from None
        self.done = False

    def commit(self) -> Path:
        """Move the finished temporary into place, replacing the target; returns the target."""
        check_output(self.target, self.argument, folder=self.folder, owns=self.owns)  # it may have changed
        old = self.target.with_name(f"{PARTIAL_PREFIX}{secrets.token_hex(4)}-old-{self.target.name}")
        try:
            with signals_deferred():  # nothing between the two renames
                if self.folder and self.target.is_dir():
                    os.replace(self.target, old)
                    try:
                        os.replace(self.path, self.target)
                    except OSError:
                        os.replace(old, self.target)
                        raise
                else:
                    os.replace(self.path, self.target)
                self.done = True
        except OSError as exc:
            self.discard()
            raise FileError(self.argument, f"cannot write {self.target}: {exc.strerror or exc}",
                            self.target) from None
        finally:
            if old.exists():
                shutil.rmtree(old, ignore_errors=True)
        return self.target

    def discard(self) -> None:
        """Remove the temporary (the target stays as it was)."""
        if self.done:
            return
        self.done = True
        if self.path.is_dir():
            shutil.rmtree(self.path, ignore_errors=True)
        else:
            with contextlib.suppress(FileNotFoundError):
                self.path.unlink()

    def final(self, path) -> Path:
        """Where ``path`` (inside the temporary) will be once committed."""
        return self.target / Path(path).relative_to(self.path) if self.folder else self.target


@contextlib.contextmanager
def atomic_output(target, argument: str, *, folder: bool, owns: Collection[str] | None = ()
                  ) -> Iterator[AtomicOutput]:
    """Write an output whole or not at all (module docstring): yields the :class:`AtomicOutput`
    (write into its ``.path``); committed when the block ends normally, discarded when it
    raises. SIGTERM and SIGHUP inside the block raise :class:`iik.signals.StopSignal`."""
    out = AtomicOutput(target, argument, folder=folder, owns=owns)
    try:
        with stop_on_signals():
            yield out
            out.commit()
    except BaseException:
        out.discard()  # (nothing to do once committed)
        raise


def write_text(target, argument: str, text: str, *, encoding: str = "utf-8") -> Path:
    """Write the file ``target`` whole or not at all (:func:`atomic_output`); returns it.

    Raises:
        FileError: ``target`` is a folder or cannot be written.
    """
    with atomic_output(target, argument, folder=False) as out:
        try:
            out.path.write_text(text, encoding=encoding)
        except OSError as exc:
            raise FileError(argument, f"cannot write {target}: {exc.strerror or exc}", target) from None
    return out.target
