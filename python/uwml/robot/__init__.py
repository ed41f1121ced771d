"""The robots and what they compute, by the Rust core: :class:`Robot` (:mod:`uwml.robot.tree`: a
kinematic tree on a moving base, in a current) and :class:`Leg` (:mod:`uwml.robot.leg`: a serial
chain of revolute joints, the paper's leg), the base's motion (:mod:`uwml.robot.base_motion`),
the results (:mod:`uwml.robot.results`), robots from files (:mod:`uwml.robot.files`) and example
robots (:mod:`uwml.robot.examples`).

The package keeps the names of the former module ``uwml.robot`` (now :mod:`uwml.robot.tree`).
"""

from .._checks import check_overflow as check_overflow
from ..model.joint_losses import JointLosses as JointLosses
from ..model.joint_losses import pack_leg_losses as pack_leg_losses
from ..model.parts import FRESH_WATER as FRESH_WATER
from ..model.parts import Joint as Joint
from ..model.parts import Link as Link
from ..model.parts import Segment as Segment
from ..model.parts import Water as Water
from ..sea.conditions import loss_conditions as loss_conditions
from ._arguments import ADDED_MASS_FORMS as ADDED_MASS_FORMS
from ._arguments import one_state_losses as one_state_losses
from .base_motion import BaseMotion
from .leg import MAX_JOINTS as MAX_JOINTS
from .leg import Leg as Leg
from .results import BaseWrench, RobotEnvironment, RobotJacobians, RobotRegressors, RobotTorques
from .results import EnvironmentJacobians as EnvironmentJacobians
from .results import EnvironmentTorques as EnvironmentTorques
from .results import HydroRegressors as HydroRegressors
from .results import HydroTorques as HydroTorques
from .tree import MAX_ROBOT_JOINTS, MAX_SEGMENTS, Robot
from .tree import FloatArray as FloatArray

__all__ = [
    "MAX_ROBOT_JOINTS",
    "MAX_SEGMENTS",
    "BaseMotion",
    "BaseWrench",
    "Robot",
    "RobotEnvironment",
    "RobotJacobians",
    "RobotRegressors",
    "RobotTorques",
]
