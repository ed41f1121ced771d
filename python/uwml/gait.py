"""The former module ``uwml.gait``, now :mod:`uwml.sim.gait`: its names, kept importable from here."""

# ruff: noqa: F401 (every import is a name of the former module, re-exported)

from .sim.gait import AXIS_CLEARANCE, PAPER_L2, PAPER_L3, FloatArray, Knee, WalkingGait, paper_leg_foot, paper_leg_ik

__all__ = ["WalkingGait", "paper_leg_foot", "paper_leg_ik"]
