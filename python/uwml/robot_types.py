"""The former module ``uwml.robot_types``, now :mod:`uwml.robot.results`: its names, kept importable from here."""

# ruff: noqa: F401 (every import is a name of the former module, re-exported)

from .robot.base_motion import BaseMotion
from .robot.results import (
    BaseWrench,
    EnvironmentTorques,
    FloatArray,
    HydroTorques,
    RobotEnvironment,
    RobotJacobians,
    RobotRegressors,
    RobotTorques,
)

__all__ = ["BaseMotion", "BaseWrench", "RobotEnvironment", "RobotJacobians", "RobotRegressors", "RobotTorques"]
