"""The former module ``uwml.mujoco``, now :mod:`uwml.sim.mujoco`: its names, kept importable from here."""

# ruff: noqa: F401 (every import is a name of the former module, re-exported)

from ._checks import shown
from .model.joint_losses import JointLosses, pack_leg_losses
from .model.parts import Water
from .robot.base_motion import BaseMotion
from .robot.results import BaseWrench, RobotEnvironment
from .robot.tree import Robot
from .sea.conditions import check_depths, check_temperatures
from .sim.mujoco import INTEGRATORS, NOSLIP_ITERATIONS, NOSLIP_TOLERANCE, SCHEMES, FloatArray, Simulation, mjcf_of

__all__ = ["SCHEMES", "Simulation", "mjcf_of"]
