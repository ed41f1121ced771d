"""The sea's conditions at a joint: depth, oil temperature, and the hydrostatic pressure.

Depths are checked against the deepest ocean (:data:`MAX_DEPTH`), oil temperatures against
absolute zero, with an :class:`ExtrapolationWarning` outside the oil model's range
(:data:`OIL_TEMPERATURE_RANGE_C`). :func:`hydrostatic_pressure` is the one formula of the gauge
pressure at depth, ``ρ g z``, written in the Rust core's order (``pressure_at_depth``) so that
the pressures are the bits the core computes itself (the joint losses' pressure at depth is the
core's own); :func:`hydrostatic_pressure_mpa` is computed by it.
:mod:`uwml.sea.seawater` gives the oceanographers' TEOS-10 pressure instead.
"""

from __future__ import annotations

import math
import numbers
import warnings

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._checks import real_array as _real_array
from .._checks import to_float
from ..domains import ABSOLUTE_ZERO_C, MAX_DEPTH, MAX_PRESSURE, OIL_TEMPERATURE_RANGE_C

__all__ = [
    "ABSOLUTE_ZERO_C",
    "GRAVITY",
    "MAX_DEPTH",
    "MAX_PRESSURE_MPA",
    "OIL_TEMPERATURE_RANGE_C",
    "SEA_WATER_DENSITY",
    "ExtrapolationWarning",
    "check_depths",
    "check_temperatures",
    "hydrostatic_pressure",
    "hydrostatic_pressure_mpa",
    "positive_number",
]

FloatArray = NDArray[np.float64]

#: Default sea-water density for the hydrostatic pressure [kg/m³].
SEA_WATER_DENSITY = 1025.0
#: Default gravity for the hydrostatic pressure [m/s²].
GRAVITY = 9.81
_MPA = 1e6


#: The largest ambient (gauge) pressure taken [MPa]: the deepest ocean's 110 MPa, with margin.
MAX_PRESSURE_MPA: float = MAX_PRESSURE / _MPA
# MAX_DEPTH, ABSOLUTE_ZERO_C and OIL_TEMPERATURE_RANGE_C (outside which the losses are still
# evaluated, the exponential temperature law extrapolating, with an ExtrapolationWarning) come
# from uwml.domains.


class ExtrapolationWarning(UserWarning):
    """An input outside the range a model is meant for, though inside the physics' domain: the
    result is the model's extrapolation (e.g. an oil temperature outside
    :data:`OIL_TEMPERATURE_RANGE_C`)."""


def positive_number(value: object, name: str) -> float:
    """``value`` as a finite, positive float; else a TypeError (not a real number) or a
    ValueError, naming ``name``."""
    real = isinstance(value, numbers.Real) or (isinstance(value, np.ndarray) and value.ndim == 0 and value.dtype.kind in "fiu")
    if not real or isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name} must be a real number, got {value!r}")
    x = to_float(value)
    if not (math.isfinite(x) and x > 0.0):
        raise ValueError(f"{name} must be finite and positive, got {value!r}")
    return x


def check_depths(depth: FloatArray, name: str = "depth") -> None:
    """Every depth finite and from 0 to :data:`MAX_DEPTH`; else a ValueError naming the first."""
    flat = np.ravel(depth)
    bad = np.flatnonzero(~np.isfinite(flat) | (flat < 0.0) | (flat > MAX_DEPTH))
    if bad.size:
        where = f"{name}[{bad[0]}]" if np.ndim(depth) else name
        raise ValueError(f"{where} is {float(flat[bad[0]])!r} m: {name} must be finite and from 0 to {MAX_DEPTH:g} m (the deepest ocean)")


def check_temperatures(temperature: FloatArray, name: str = "temperature_c", stacklevel: int = 3) -> None:
    """Every temperature finite and above absolute zero (else a ValueError naming the first); an
    :class:`ExtrapolationWarning` when one is outside :data:`OIL_TEMPERATURE_RANGE_C`."""
    flat = np.ravel(temperature)
    bad = np.flatnonzero(~np.isfinite(flat) | (flat <= ABSOLUTE_ZERO_C))
    if bad.size:
        where = f"{name}[{bad[0]}]" if np.ndim(temperature) else name
        raise ValueError(f"{where} is {float(flat[bad[0]])!r} °C: {name} must be finite and above absolute zero ({ABSOLUTE_ZERO_C} °C)")
    low, high = OIL_TEMPERATURE_RANGE_C
    outside = np.flatnonzero((flat < low) | (flat > high))
    if outside.size:
        where = f"{name}[{outside[0]}]" if np.ndim(temperature) else name
        warnings.warn(
            f"{where} is {float(flat[outside[0]])!r} °C, outside the oil model's range ({low:g} to {high:g} °C, the sea's): "
            "its temperature law extrapolates there",
            ExtrapolationWarning,
            stacklevel=stacklevel,
        )


def hydrostatic_pressure(depth: FloatArray, sea_density: float, gravity: float) -> FloatArray:
    """The gauge pressure ``ρ g z`` [Pa] of a uniform sea at ``depth`` [m]: the one formula of the
    package, unchecked (its callers check their inputs). The product is taken in the Rust core's
    order (``pressure_at_depth``: ``sea_density · gravity · depth``), so that a pressure computed
    here is bit for bit the core's."""
    pressure: FloatArray = sea_density * gravity * depth
    return pressure


def hydrostatic_pressure_mpa(depth_m: ArrayLike, *, sea_density: float = SEA_WATER_DENSITY, gravity: float = GRAVITY) -> FloatArray:
    """Gauge pressure ``ρ g z`` [MPa] at depth [m] (0 to :data:`MAX_DEPTH`), the formula the core
    uses; ``sea_density`` [kg/m³] and ``gravity`` [m/s²] finite and positive, keyword-only.

    :func:`uwml.sea.seawater.pressure_at_depth_mpa` gives the oceanographers' TEOS-10 value (its second
    argument is a latitude); the two agree within the bound documented in docs/losses.md.
    """
    depth = _real_array(depth_m, "depth_m", "a real number or array")
    check_depths(depth, "depth_m")
    density = positive_number(sea_density, "sea_density")
    g = positive_number(gravity, "gravity")
    with np.errstate(over="ignore", invalid="ignore"):
        pressure = hydrostatic_pressure(depth, density, g) / _MPA
    if not np.all(pressure <= MAX_PRESSURE_MPA):
        raise ValueError(
            f"the pressure of sea_density {density:g} kg/m³ and gravity {g:g} m/s² reaches {float(np.max(pressure)):g} MPa, "
            f"beyond the deepest ocean's ({MAX_PRESSURE_MPA:g} MPa): a water far from the sea's"
        )
    return pressure
