"""The robots and what they compute, by the Rust core: :class:`Robot` (:mod:`uwml.robot.tree`: a
kinematic tree on a moving base, in a current) and :class:`Leg` (:mod:`uwml.robot.leg`: a serial
chain of revolute joints, the paper's leg), the base's motion (:mod:`uwml.robot.base_motion`),
the results (:mod:`uwml.robot.results`), robots from files (:mod:`uwml.robot.files`) and example
robots (:mod:`uwml.robot.examples`).
"""

from .base_motion import BaseMotion
from .leg import MAX_JOINTS, Leg
from .results import (
    BaseWrench,
    EnvironmentJacobians,
    EnvironmentTorques,
    HydroRegressors,
    HydroTorques,
    RobotEnvironment,
    RobotJacobians,
    RobotRegressors,
    RobotTorques,
)
from .tree import MAX_ROBOT_JOINTS, MAX_SEGMENTS, Robot

__all__ = [
    "MAX_JOINTS",
    "MAX_ROBOT_JOINTS",
    "MAX_SEGMENTS",
    "BaseMotion",
    "BaseWrench",
    "EnvironmentJacobians",
    "EnvironmentTorques",
    "HydroRegressors",
    "HydroTorques",
    "Leg",
    "Robot",
    "RobotEnvironment",
    "RobotJacobians",
    "RobotRegressors",
    "RobotTorques",
]
