"""The former module ``uwml.simulate``, now :mod:`uwml.sim.studies`: its names, kept importable from here."""

# ruff: noqa: F401 (every import is a name of the former module, re-exported)

from .model.joint_losses import JointLosses
from .model.parts import Water
from .robot.base_motion import BaseMotion
from .robot.leg import Leg
from .robot.tree import Robot
from .sim.studies import (
    CONTROLLERS,
    DEPTHS,
    MAX_CYCLES,
    PD_HZ,
    ROV_CURRENT,
    SEA,
    SEA_VISCOSITY,
    TEMPERATURE_C,
    TIMESTEP,
    Drift,
    FloatArray,
    FluidComparison,
    Run,
    fluid_models,
    leg_model,
    rov_drift,
    run,
    study,
    write_report,
)
from .study.paper import command
from .study.runner import progress_bar

__all__ = [
    "CONTROLLERS",
    "DEPTHS",
    "MAX_CYCLES",
    "Drift",
    "FluidComparison",
    "Run",
    "fluid_models",
    "leg_model",
    "rov_drift",
    "run",
    "study",
]
