"""What the readers of robot descriptions and hydro files share: their error, and files read
without waiting on them (uwml.descriptions, uwml.hydrofile, uwml._description_xml).

A named pipe, a socket or a device where a file should be makes a reader wait forever (a pipe
with no writer) or read forever (``/dev/zero``); only regular files are read. Messages stay short
whatever the file holds (``_checks.shown`` quotes values, :func:`clipped` cuts text).
"""

from __future__ import annotations

import os

from ._files import clipped, not_regular
from ._files import read_regular as _read_regular
from .errors import DescriptionError

__all__ = ["DescriptionError", "clipped", "not_regular", "read_regular"]


def read_regular(path: str | os.PathLike[str], what: str) -> bytes:
    """:func:`uwml._files.read_regular` with a :class:`DescriptionError`."""
    return _read_regular(path, what, DescriptionError)
