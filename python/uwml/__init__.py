"""uwml: what the deep sea does to each joint of an underwater robot.

Drag, added mass and buoyancy on the links of a serial chain or a whole robot on a moving base
in a current (strip theory, Morison), with the wrench on the base, and the
oil-viscous and dynamic-seal losses inside oil-filled, pressure-compensated joints, computed
exactly by a no_std Rust core and exposed over numpy arrays. Sign convention: every torque is
the generalized force exerted by the environment on the joint, in the joint's positive
direction (so drag opposes motion and the motor must supply ``-total`` on top of the land
torque).

The package, one idea per subpackage, each importing only those before it: :mod:`uwml.sea` (the
sea's conditions at a joint: depth, temperature, hydrostatic pressure; sea water, oil),
:mod:`uwml.model` (joints, links, segments, the water; the joint losses), :mod:`uwml.io` (model
files, robot descriptions, hydro files, exported code, logs), :mod:`uwml.robot` (:class:`Robot`,
:class:`Conditions`, the results, the paper's leg :func:`paper_leg`), then :mod:`uwml.fit` (identification), :mod:`uwml.viz` (figures,
descriptions), :mod:`uwml.sim` (MuJoCo with uwml's forces, prescribed motion, replay, control),
:mod:`uwml.paper` (the paper's gait, synthetic experiments, analysis and control study),
:mod:`uwml.study` (scenarios over grids of parameters, on Ray) and the command line
(:mod:`uwml.cli`). Below them, the modules every layer may use: :mod:`uwml.errors`,
:mod:`uwml.domains` and :mod:`uwml.plausibility`. :mod:`uwml.reference` is the independent numpy
reference (tests and checks); this module is the front door: the names most users need.
"""

from .errors import DescriptionError, ModelError, ModelFileError, UwmlError
from .io.export import get_include
from .io.logs import Log, read_log, write_log
from .model.joint_losses import JointLosses, LossTorques
from .model.losses import Drive, OilDrag, Seal
from .model.lumped import LumpedModel
from .model.parts import Joint, Link, Segment, Water
from .model.thrusters import ThrustCurve, Thruster
from .paper.gait import WalkingGait, paper_leg_foot, paper_leg_ik
from .plausibility import DescriptionWarning, PlausibilityWarning
from .robot.base_motion import BaseMotion
from .robot.evaluation_conditions import Conditions
from .robot.presets import paper_leg
from .robot.results import BaseWrench, Jacobians, Regressors, Torques
from .robot.tree import MAX_LUMPED_BODIES, MAX_ROBOT_JOINTS, MAX_SEGMENTS, Robot
from .robot.workspace import Workspace
from .sea.conditions import ExtrapolationWarning, hydrostatic_pressure_mpa

__all__ = [
    "MAX_LUMPED_BODIES",
    "MAX_ROBOT_JOINTS",
    "MAX_SEGMENTS",
    "BaseMotion",
    "BaseWrench",
    "Conditions",
    "DescriptionError",
    "DescriptionWarning",
    "Drive",
    "ExtrapolationWarning",
    "Jacobians",
    "Joint",
    "JointLosses",
    "Link",
    "Log",
    "LossTorques",
    "LumpedModel",
    "ModelError",
    "ModelFileError",
    "OilDrag",
    "PlausibilityWarning",
    "Regressors",
    "Robot",
    "Seal",
    "Segment",
    "ThrustCurve",
    "Thruster",
    "Torques",
    "UwmlError",
    "WalkingGait",
    "Water",
    "Workspace",
    "get_include",
    "hydrostatic_pressure_mpa",
    "paper_leg",
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
