"""The former module ``uwml.describe``, now :mod:`uwml.viz.describe`: its names, kept importable from here."""

# ruff: noqa: F401 (every import is a name of the former module, re-exported)

from .model.parts import Link, Segment, Water
from .robot.tree import Robot
from .viz.describe import describe, draw, frame_origins

__all__ = ["describe", "draw", "frame_origins"]
