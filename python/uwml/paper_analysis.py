"""The former module ``uwml.paper_analysis``, now :mod:`uwml.sim.paper_analysis`: its names, kept importable from here."""

# ruff: noqa: F401 (every import is a name of the former module, re-exported)

from .robot.leg import Leg
from .sim.paper_analysis import gait_like_motion, run

__all__ = ["gait_like_motion", "run"]
