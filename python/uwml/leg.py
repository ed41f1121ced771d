"""The former module ``uwml.leg``, now :mod:`uwml.robot.leg`: its names, kept importable from here."""

# ruff: noqa: F401 (every import is a name of the former module, re-exported)

from ._checks import check_overflow
from .model.joint_losses import JointLosses, pack_leg_losses
from .model.parts import FRESH_WATER, SEA_WATER, Joint, Link, Segment, Water
from .robot._arguments import one_state_losses
from .robot.leg import MAX_JOINTS, FloatArray, Leg
from .robot.results import EnvironmentJacobians, EnvironmentTorques, HydroRegressors, HydroTorques
from .sea.conditions import SEA_WATER_DENSITY, loss_conditions

__all__ = ["MAX_JOINTS", "EnvironmentJacobians", "HydroRegressors", "HydroTorques", "Leg"]
