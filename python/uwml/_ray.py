"""Ray, the optional extra for work beyond one process (docs/scale.md): a session that uses the
Ray this process has initialized, else connects to a cluster's address, else starts a local Ray
for the work and stops it after."""

from __future__ import annotations

import os
from collections.abc import Iterator
from contextlib import contextmanager
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
    if started:
        options: dict[str, Any] = {"include_dashboard": False, "logging_level": "ERROR", "log_to_driver": False}
        if address is not None:
            ray.init(address=address, **options)
        else:
            ray.init(num_cpus=workers or os.cpu_count() or 1, **options)
    try:
        yield ray
    finally:
        if started:
            ray.shutdown()
