"""The former module ``uwml.examples``, now :mod:`uwml.robot.examples`: its names, kept importable from here."""

# ruff: noqa: F401 (every import is a name of the former module, re-exported)

from .model.parts import Joint, Link, Segment
from .robot.examples import arm_on_rov
from .robot.tree import Robot

__all__ = ["arm_on_rov"]
