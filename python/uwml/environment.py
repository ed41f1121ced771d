"""The former module ``uwml.environment``, now :mod:`uwml.sea.conditions`: its names, kept importable from here."""

# ruff: noqa: F401 (every import is a name of the former module, re-exported)

from ._checks import check_overflow, to_float
from .domains import ABSOLUTE_ZERO_C, MAX_DEPTH, MAX_PRESSURE, OIL_TEMPERATURE_RANGE_C
from .model.joint_losses import JointLosses, LossTorques, pack_leg_losses
from .model.losses import Drive, OilDrag, Seal
from .robot._arguments import one_state_losses
from .robot.results import EnvironmentTorques
from .sea.conditions import (
    MAX_PRESSURE_MPA,
    SEA_WATER_DENSITY,
    ExtrapolationWarning,
    FloatArray,
    check_depths,
    check_temperatures,
    hydrostatic_pressure_mpa,
    loss_conditions,
)

__all__ = [
    "ABSOLUTE_ZERO_C",
    "MAX_DEPTH",
    "OIL_TEMPERATURE_RANGE_C",
    "SEA_WATER_DENSITY",
    "EnvironmentTorques",
    "ExtrapolationWarning",
    "JointLosses",
    "LossTorques",
    "hydrostatic_pressure_mpa",
]
