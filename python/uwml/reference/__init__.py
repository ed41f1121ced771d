"""Independent numpy reference for the models of docs/model.md and docs/losses.md, vectorized.

This package re-derives, with numpy only and different algorithms, what the Rust core
(``uwml._core``) computes, so that tests can hold the core to it (docs/model.md section 8):

* :mod:`.chain`: a serial chain of revolute joints in still water on a fixed, upright base
  (docs/model.md sections 2-5): :func:`hydro`, :func:`regressors`, the paper's leg :func:`paper_leg`
  and the light descriptions :class:`RefJoint`, :class:`RefLink`, :class:`RefSegment`;
* :mod:`.paper_equations`: the paper's printed equations, :func:`paper_equations` (docs/model.md section 6);
* :mod:`.loss_torques`: the joint losses of an oil-filled, pressure-compensated joint
  (docs/losses.md, "The models"): :func:`smooth_sign`, :func:`oil_drag_torque`,
  :func:`seal_torque`, :func:`loss_current`, :func:`joint_loss_torques`,
  :func:`hydrostatic_pressure_mpa`;
* :mod:`.robot_hydro`: whole robots (trees of revolute and prismatic joints, a moving base with a body
  of its own, a uniform current, rectangular and circular segments; docs/model.md section 10):
  :func:`robot_hydro`, :func:`robot_added_mass_matrix`, :func:`robot_link_wrenches`.

The package imports only numpy and the standard library, so it can be loaded on its own from its
directory (``importlib.util.spec_from_file_location`` on this file with
``submodule_search_locations``), without the compiled extension. Joints, links and loss
parameters are duck-typed (see each module).
"""

# Module attributes of the former single-file reference.py that other modules and tests use,
# re-exported explicitly (``name as name``).
from ._inputs import Array as Array
from ._inputs import Vec3 as Vec3
from .chain import PAPER_D21 as PAPER_D21
from .chain import PAPER_D22 as PAPER_D22
from .chain import PAPER_D31 as PAPER_D31
from .chain import PAPER_D32 as PAPER_D32
from .chain import PAPER_L2 as PAPER_L2
from .chain import PAPER_L2C as PAPER_L2C
from .chain import PAPER_L3 as PAPER_L3
from .chain import PAPER_L3C as PAPER_L3C
from .chain import PAPER_LINK_DENSITY as PAPER_LINK_DENSITY
from .chain import PAPER_MASSES as PAPER_MASSES
from .chain import RefJoint, RefLink, RefSegment, hydro, paper_leg, regressors
from .chain import _drag_integral as _drag_integral
from .loss_torques import hydrostatic_pressure_mpa, joint_loss_torques, loss_current, oil_drag_torque, seal_torque, smooth_sign
from .paper_equations import paper_equations
from .robot_hydro import robot_added_mass_matrix, robot_hydro, robot_link_wrenches

__all__ = [
    "RefJoint",
    "RefLink",
    "RefSegment",
    "hydro",
    "hydrostatic_pressure_mpa",
    "joint_loss_torques",
    "loss_current",
    "oil_drag_torque",
    "paper_equations",
    "paper_leg",
    "regressors",
    "robot_added_mass_matrix",
    "robot_hydro",
    "robot_link_wrenches",
    "seal_torque",
    "smooth_sign",
]
