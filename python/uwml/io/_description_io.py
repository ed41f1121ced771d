"""What the readers of robot descriptions and hydro files share: their error, and files read
without waiting on them (uwml.io.descriptions, uwml.io.hydrofile, uwml.io._description_xml).

A named pipe, a socket or a device where a file should be makes a reader wait forever (a pipe
with no writer) or read forever (``/dev/zero``); only regular files are read. Messages stay short
whatever the file holds (``_checks.shown`` quotes values, :func:`clipped` cuts text).
"""

from __future__ import annotations

import os

from .._checks import shown
from ..errors import DescriptionError
from ._file_access import clipped, not_regular
from ._file_access import read_regular as _read_regular

__all__ = ["DescriptionError", "clipped", "not_regular", "quoted", "read_regular"]


def read_regular(path: str | os.PathLike[str], what: str) -> bytes:
    """:func:`uwml.io._file_access.read_regular` with a :class:`DescriptionError`."""
    return _read_regular(path, what, DescriptionError)


def quoted(name: str) -> str:
    """``name`` in quotes for a message, or shown short (:func:`uwml._checks.shown`) if it is long or odd."""
    return f"'{name}'" if len(name) <= 60 and name.isprintable() and "'" not in name else shown(name, 40)
