"""uwml: what the deep sea does to each joint of an underwater robot.

Drag, added mass and buoyancy on the links of a serial chain or a whole robot on a moving base
in a current (strip theory, Morison), with the wrench on the base, and the
oil-viscous and dynamic-seal losses inside oil-filled, pressure-compensated joints, computed
exactly by a no_std Rust core and exposed over numpy arrays. Sign convention: every torque is
the generalized force exerted by the environment on the joint, in the joint's positive
direction (so drag opposes motion and the motor must supply ``-total`` on top of the land
torque).
"""

from .environment import EnvironmentTorques, ExtrapolationWarning, JointLosses, LossTorques, hydrostatic_pressure_mpa
from .errors import DescriptionError, ModelError, ModelFileError, UwmlError
from .gait import WalkingGait, paper_leg_foot, paper_leg_ik
from .leg import MAX_JOINTS, EnvironmentJacobians, HydroRegressors, HydroTorques, Leg
from .logs import Log, read_log, write_log
from .losses import Drive, OilDrag, Seal
from .model import Joint, Link, Segment, Water
from .robot import (
    MAX_ROBOT_JOINTS,
    MAX_SEGMENTS,
    BaseMotion,
    BaseWrench,
    Robot,
    RobotEnvironment,
    RobotJacobians,
    RobotRegressors,
    RobotTorques,
)

__all__ = [
    "MAX_JOINTS",
    "MAX_ROBOT_JOINTS",
    "MAX_SEGMENTS",
    "BaseMotion",
    "BaseWrench",
    "DescriptionError",
    "Drive",
    "EnvironmentJacobians",
    "EnvironmentTorques",
    "ExtrapolationWarning",
    "HydroRegressors",
    "HydroTorques",
    "Joint",
    "JointLosses",
    "Leg",
    "Link",
    "Log",
    "LossTorques",
    "ModelError",
    "ModelFileError",
    "OilDrag",
    "Robot",
    "RobotEnvironment",
    "RobotJacobians",
    "RobotRegressors",
    "RobotTorques",
    "Seal",
    "Segment",
    "UwmlError",
    "WalkingGait",
    "Water",
    "hydrostatic_pressure_mpa",
    "paper_leg_foot",
    "paper_leg_ik",
    "read_log",
    "write_log",
]
__version__ = "0.1.0"


def __getattr__(name: str) -> object:
    """``uwml.reference`` after a bare ``import uwml``: the numpy reference is imported on first
    use, not with the package (it is for tests and checks, and takes a while to import)."""
    if name == "reference":
        import importlib

        return importlib.import_module(".reference", __name__)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
