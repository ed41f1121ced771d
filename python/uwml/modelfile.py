"""The former module ``uwml.modelfile``, now :mod:`uwml.io.modelfile`: its names, kept importable from here."""

# ruff: noqa: F401 (every import is a name of the former module, re-exported)

from ._checks import shown
from .errors import ModelFileError
from .io._files import read_regular
from .io.modelfile import FORMAT, VERSION, WATER_DENSITY_RANGE, WATER_GRAVITY_RANGE, dumps, save
from .model.joint_losses import JointLosses
from .model.losses import Drive, OilDrag, Seal
from .model.parts import Joint, Link, Segment, Water
from .robot.files import load, loads
from .robot.tree import Robot

__all__ = ["FORMAT", "VERSION", "ModelFileError", "dumps", "load", "loads", "save"]
