"""The former module ``uwml.logs``, now :mod:`uwml.io.logs`: its names, kept importable from here."""

# ruff: noqa: F401 (every import is a name of the former module, re-exported)

from ._checks import shown
from .domains import MAX_ROBOT_JOINTS
from .io._files import not_regular
from .io.logs import (
    MAX_TIME_S,
    POLYORDER,
    UNIFORM_TOLERANCE,
    WINDOW_S,
    Array,
    Log,
    PathOrFile,
    align_logs,
    estimate_derivatives,
    read_log,
    savgol_window,
    write_log,
)

__all__ = [
    "MAX_ROBOT_JOINTS",
    "MAX_TIME_S",
    "POLYORDER",
    "UNIFORM_TOLERANCE",
    "WINDOW_S",
    "Log",
    "align_logs",
    "estimate_derivatives",
    "read_log",
    "savgol_window",
    "write_log",
]
