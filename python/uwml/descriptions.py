"""The former module ``uwml.descriptions``, now :mod:`uwml.io.descriptions`: its names, kept importable from here."""

# ruff: noqa: F401 (every import is a name of the former module, re-exported)

from ._checks import shown
from .errors import DescriptionError
from .io._description_geometry import FloatArray
from .io._description_xml import MAX_DESCRIPTION_BODIES, MAX_DESCRIPTION_GEOMS, limits_exceeded, scan
from .io._files import clipped
from .io.hydrofile import HydroFile, HydroLink, read_hydro
from .io.modelfile import WATER_DENSITY_RANGE, WATER_GRAVITY_RANGE
from .model.parts import Joint, Link, Segment
from .robot.files import from_mjcf, from_mujoco, from_urdf, model_and_robot
from .robot.tree import Robot

__all__ = [
    "MAX_DESCRIPTION_BODIES",
    "MAX_DESCRIPTION_GEOMS",
    "DescriptionError",
    "HydroFile",
    "HydroLink",
    "from_mjcf",
    "from_mujoco",
    "from_urdf",
    "model_and_robot",
    "read_hydro",
]
