"""The former module ``uwml.hydrofile``, now :mod:`uwml.io.hydrofile`: its names, kept importable from here."""

# ruff: noqa: F401 (every import is a name of the former module, re-exported)

from ._checks import shown
from .domains import MAX_COEFFICIENT, MAX_LENGTH, MAX_VOLUME
from .errors import DescriptionError
from .io._description_io import read_regular
from .io._files import clipped
from .io.hydrofile import HydroFile, HydroLink, read_hydro
from .io.modelfile import WATER_DENSITY_RANGE, WATER_GRAVITY_RANGE
from .model.joint_losses import JointLosses
from .model.parts import Segment, Water
from .robot.tree import MAX_SEGMENTS

__all__ = ["WATER_DENSITY_RANGE", "WATER_GRAVITY_RANGE", "DescriptionError", "HydroFile", "HydroLink", "read_hydro"]
