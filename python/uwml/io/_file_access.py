"""Reading a user's file without waiting on it, and writing one whole or not at all: model files,
descriptions, hydro files and logs.

A named pipe, a socket or a device where a file should be makes a reader wait forever (a pipe
with no writer) or read forever (``/dev/zero``); only regular files are read. A path is checked
without opening it (:func:`not_regular`), or opened without blocking and checked on the open file
(:func:`read_regular`).
"""

from __future__ import annotations

import os
import secrets
import stat
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import BinaryIO

__all__ = ["atomic_file", "clipped", "not_regular", "read_regular", "write_atomically"]


def clipped(text: str, limit: int = 160) -> str:
    """``text`` cut to ``limit`` characters (saying how long it was), whitespace runs as one space."""
    text = " ".join(text.split())
    return text if len(text) <= limit else f"{text[:limit]}... ({len(text)} characters)"


def _kind(mode: int) -> str:
    if stat.S_ISDIR(mode):
        return "is a directory"
    what = (
        "a named pipe"
        if stat.S_ISFIFO(mode)
        else "a socket"
        if stat.S_ISSOCK(mode)
        else "a device"
        if stat.S_ISCHR(mode) or stat.S_ISBLK(mode)
        else "special"
    )
    return f"is not a regular file ({what})"


def not_regular(path: str | os.PathLike[str]) -> str | None:
    """Why the existing ``path`` cannot be read as a file (``"is a directory"``, ``"is not a
    regular file (a named pipe)"``), or None if it is a regular file or does not exist. Follows
    symbolic links; never opens the path."""
    try:
        mode = os.stat(path).st_mode
    except (OSError, ValueError):
        return None
    return None if stat.S_ISREG(mode) else _kind(mode)


def read_regular(path: str | os.PathLike[str], what: str, error: type[ValueError] = ValueError) -> bytes:
    """The bytes of the regular file ``path``, or an ``error`` ``"{path}: the {what} cannot be
    read: ..."`` (no such file, a directory, a named pipe or device, no permission). Opened
    without blocking and checked on the open file, so a pipe is refused, not waited on."""
    source = str(path)
    prefix = f"{source}: the {what} cannot be read"
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0)
    try:
        fd = os.open(path, flags)
    except FileNotFoundError:
        raise error(f"{prefix}: no such file") from None
    except (OSError, ValueError) as exc:  # ValueError: a NUL in the path
        reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)
        raise error(f"{prefix}: {clipped(reason).lower()}") from None
    try:
        mode = os.fstat(fd).st_mode
        if not stat.S_ISREG(mode):
            raise error(f"{prefix}: it {_kind(mode)}; uwml reads regular files only")
        with os.fdopen(fd, "rb", closefd=False) as handle:
            return handle.read()
    except OSError as exc:
        raise error(f"{prefix}: {clipped(exc.strerror or str(exc)).lower()}") from None
    finally:
        os.close(fd)


def write_atomically(path: str | os.PathLike[str], data: bytes) -> None:
    """Writes ``data`` to ``path``, whole or not at all (:func:`atomic_file`)."""
    with atomic_file(path) as handle:
        handle.write(data)


@contextmanager
def atomic_file(path: str | os.PathLike[str]) -> Iterator[BinaryIO]:
    """A binary file to write ``path`` through, whole or not at all: a temporary file in the same
    folder, synced and renamed over ``path`` when the block ends; on any failure the temporary
    file is removed and an existing file at ``path`` is left as it was. What is written streams
    to the disk (a large log is never held in memory twice)."""
    target = Path(os.path.realpath(path))  # through a symbolic link: replace the file it points to
    temporary = target.with_name(f".{target.name}.{secrets.token_hex(8)}.tmp")
    # Created with mode 0o666 (less the umask) like any new file; an existing file keeps its mode.
    fd = os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_BINARY", 0), 0o666)
    try:
        with os.fdopen(fd, "wb") as handle:
            yield handle
            handle.flush()
            os.fsync(handle.fileno())
        if target.is_file():
            os.chmod(temporary, target.stat().st_mode & 0o7777)
        os.replace(temporary, target)
    except BaseException:
        temporary.unlink(missing_ok=True)
        raise
    _sync_folder(target.parent)


def _sync_folder(folder: Path) -> None:
    """Makes a rename in ``folder`` durable where the system allows it (POSIX; a no-op elsewhere)."""
    try:
        fd = os.open(folder, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0))
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)
