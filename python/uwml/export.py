"""The former module ``uwml.export``, now :mod:`uwml.io.export`: its names, kept importable from here."""

# ruff: noqa: F401 (every import is a name of the former module, re-exported)

from ._checks import shown
from .io.export import PRECISIONS, to_c, to_rust
from .model.parts import Link, Segment
from .robot.tree import Robot

__all__ = ["to_c", "to_rust"]
