"""Ray, the optional extra for work beyond one process (docs/scale.md): a session that uses the
Ray this process has initialized, else connects to a cluster's address, else starts a local Ray
for the work and stops it after.

A local Ray started here ends with this process even if it is killed (SIGKILL, out of memory):
Ray ends its GCS and raylet with their parent, but not the raylet's agents, so a watchdog
(:mod:`uwml._watchdog`, a small process of its own, POSIX) waits on a pipe from this process
and, when the pipe closes, kills what remains of that Ray.
"""

from __future__ import annotations

import os
import secrets
import subprocess
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

__all__ = ["ray_session"]


@contextmanager
def ray_session(address: str | None = None, workers: int | None = None) -> Iterator[Any]:
    """The ``ray`` module, initialized (module docstring); ``workers``: a local Ray's CPUs
    (default all)."""
    try:
        import ray
    except ImportError:
        raise ImportError('this runs on Ray: pip install "uwml[ray]"') from None
    started = not ray.is_initialized()
    watchdog = None
    if started:
        options: dict[str, Any] = {"include_dashboard": False, "logging_level": "ERROR", "log_to_driver": False}
        if address is not None:
            ray.init(address=address, **options)
        else:
            watchdog = _init_watched(ray, num_cpus=workers or os.cpu_count() or 1, **options)
    try:
        yield ray
    finally:
        if started:
            ray.shutdown()
        if watchdog is not None:
            _release(watchdog)


def _init_watched(ray: Any, **options: Any) -> subprocess.Popen[bytes] | None:
    """``ray.init(**options)`` for a local Ray, its processes marked for a watchdog started
    first (module docstring); the watchdog (None where there is none: Windows, where Ray ties
    its processes to the driver itself)."""
    if sys.platform == "win32":
        ray.init(**options)
        return None
    from ._watchdog import VARIABLE

    token = secrets.token_hex(8)
    watchdog = subprocess.Popen(
        [sys.executable, "-I", str(Path(__file__).with_name("_watchdog.py")), token],
        stdin=subprocess.PIPE, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True,
    )  # fmt: skip
    previous = os.environ.get(VARIABLE)
    os.environ[VARIABLE] = token  # inherited by the processes ray.init starts, and theirs
    try:
        ray.init(**options)
    except BaseException:
        _release(watchdog)
        raise
    finally:
        if previous is None:
            del os.environ[VARIABLE]
        else:
            os.environ[VARIABLE] = previous
    try:  # Ray is up: the watchdog notes its processes, then waits for the pipe to close
        assert watchdog.stdin is not None
        watchdog.stdin.write(b"up\n")
        watchdog.stdin.flush()
    except OSError:  # the watchdog is gone: Ray runs unwatched, as without uwml
        pass
    return watchdog


def _release(watchdog: subprocess.Popen[bytes]) -> None:
    """Closes the watchdog's pipe (it kills what is left of its Ray, then exits) and reaps it."""
    if watchdog.stdin is not None:
        watchdog.stdin.close()
    try:
        watchdog.wait(timeout=30)
    except subprocess.TimeoutExpired:
        pass
