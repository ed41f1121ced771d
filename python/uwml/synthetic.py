"""The former module ``uwml.synthetic``, now :mod:`uwml.sim.synthetic`: its names, kept importable from here."""

# ruff: noqa: F401 (every import is a name of the former module, re-exported)

from .io.logs import Log
from .model.losses import RPM, Drive, OilDrag, Seal
from .model.parts import Water
from .sim.synthetic import (
    CONFIGURATIONS,
    LAND_COULOMB,
    LAND_INERTIA,
    LAND_VISCOUS,
    PAPER_LIKE_ERROR,
    PAPER_LIKE_NOISE,
    PAPER_LIKE_PERIOD,
    YAW_STEP_FOOT,
    FloatArray,
    ModelDiscrepancy,
    ModelError,
    SineTrajectory,
    land_water_experiment,
    paper_like_experiment,
    three_configuration_experiment,
)

__all__ = [
    "CONFIGURATIONS",
    "LAND_COULOMB",
    "LAND_INERTIA",
    "LAND_VISCOUS",
    "PAPER_LIKE_ERROR",
    "PAPER_LIKE_NOISE",
    "PAPER_LIKE_PERIOD",
    "YAW_STEP_FOOT",
    "ModelDiscrepancy",
    "SineTrajectory",
    "land_water_experiment",
    "paper_like_experiment",
    "three_configuration_experiment",
]
