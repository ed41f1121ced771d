"""The robot and what it computes, by the Rust core: :class:`Robot` (:mod:`uwml.robot.tree`: a
kinematic tree on a moving base, in a current), the conditions of its evaluations
(:mod:`uwml.robot.evaluation_conditions`), the base's motion (:mod:`uwml.robot.base_motion`),
the results (:mod:`uwml.robot.results`) and a reusable one for one state
(:mod:`uwml.robot.workspace`), the paper's leg as a preset
(:mod:`uwml.robot.presets`) and robots from files (:mod:`uwml.robot.files`); example robots are
:mod:`uwml.examples`'s.
"""

from .base_motion import BaseMotion
from .evaluation_conditions import Conditions
from .presets import paper_leg
from .results import BaseWrench, Jacobians, Regressors, Torques
from .tree import MAX_ROBOT_JOINTS, MAX_SEGMENTS, Robot
from .workspace import Workspace

__all__ = [
    "MAX_ROBOT_JOINTS",
    "MAX_SEGMENTS",
    "BaseMotion",
    "BaseWrench",
    "Conditions",
    "Jacobians",
    "Regressors",
    "Robot",
    "Torques",
    "Workspace",
    "paper_leg",
]
