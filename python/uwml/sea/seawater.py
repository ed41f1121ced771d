"""Sea pressure and sea-water density at depth, by TEOS-10 (the ``gsw`` package).

The Rust core takes the pressure of a uniform sea, ``p = ρ g z`` (ρ = 1025 kg/m³ by default;
:func:`uwml.sea.conditions.hydrostatic_pressure_mpa`). This module gives the oceanographers'
standard instead: ``gsw.p_from_z`` integrates the TEOS-10 density of a standard ocean
(absolute salinity 35.16504 g/kg, conservative temperature 0 °C) under latitude-dependent
gravity. The uniform sea underestimates it by at most 0.77 % down to 1000 m and 1.92 % down to
6000 m (at the poles; 0.24 % and 1.40 % at the equator): docs/losses.md gives the measured
table.

Pressures here are *sea* (gauge) pressures, absolute pressure less one standard atmosphere
(101 325 Pa), which is what a pressure-compensated joint sees across its seal.
"""

from __future__ import annotations

import gsw
import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._checks import finite_array
from ..domains import MAX_DEPTH

__all__ = ["density_at_depth", "pressure_at_depth_mpa"]

Array = NDArray[np.float64]

#: MPa per dbar.
_MPA_PER_DBAR = 0.01


def _depth_and_latitude(depth_m: ArrayLike, latitude_deg: ArrayLike) -> tuple[Array, Array]:
    depth = finite_array(depth_m, "depth_m")
    if np.any(depth < 0.0):
        raise ValueError(f"depth_m must be >= 0 (metres below the surface), got minimum {depth.min()}")
    if np.any(depth > MAX_DEPTH):
        raise ValueError(f"depth_m must be at most {MAX_DEPTH:g} m (the deepest ocean), got maximum {depth.max()}")
    latitude = finite_array(latitude_deg, "latitude_deg")
    if np.any(np.abs(latitude) > 90.0):
        raise ValueError(f"latitude_deg must lie in [-90, 90], got {latitude[np.abs(latitude) > 90.0].flat[0]}")
    return depth, latitude


def pressure_at_depth_mpa(depth_m: ArrayLike, latitude_deg: ArrayLike = 0.0) -> Array:
    """Sea (gauge) pressure at a depth, by TEOS-10: ``gsw.p_from_z(−depth, latitude)`` [MPa].

    Parameters
    ----------
    depth_m : array_like
        Depth below the sea surface [m], ≥ 0.
    latitude_deg : array_like
        Latitude [degrees], in [−90, 90]; gravity grows toward the poles.

    Returns
    -------
    ndarray
        Sea pressure [MPa] (1 dbar = 0.01 MPa), the broadcast shape of the inputs; 0 at the
        surface.

    Raises
    ------
    ValueError
        If a depth is negative or beyond 11000 m, a latitude outside [−90, 90], or an input not
        finite.
    """
    depth, latitude = _depth_and_latitude(depth_m, latitude_deg)
    return np.asarray(gsw.p_from_z(-depth, latitude), dtype=np.float64) * _MPA_PER_DBAR


def density_at_depth(
    depth_m: ArrayLike,
    latitude_deg: ArrayLike = 0.0,
    absolute_salinity: ArrayLike = 35.16504,
    conservative_temperature: ArrayLike = 2.0,
) -> Array:
    """In-situ sea-water density at a depth, by TEOS-10: ``gsw.rho(SA, CT, p)`` [kg/m³].

    The pressure is :func:`pressure_at_depth_mpa` at that depth and latitude (the standard
    ocean's); the water itself has the given salinity and temperature.

    Parameters
    ----------
    depth_m : array_like
        Depth below the sea surface [m], ≥ 0.
    latitude_deg : array_like
        Latitude [degrees], in [−90, 90].
    absolute_salinity : array_like
        Absolute salinity SA [g/kg], ≥ 0 (standard sea water: 35.16504).
    conservative_temperature : array_like
        Conservative temperature CT [°C] (the deep ocean: about 2).

    Returns
    -------
    ndarray
        Density [kg/m³], the broadcast shape of the inputs (about 1028 at the surface and 1032
        at 1000 m for the defaults).

    Raises
    ------
    ValueError
        If a depth is negative or beyond 11000 m, a latitude outside [−90, 90], a salinity
        outside 0 to 120 g/kg, a temperature outside −5 to 95 °C, or an input not finite.
    """
    depth, latitude = _depth_and_latitude(depth_m, latitude_deg)
    salinity = finite_array(absolute_salinity, "absolute_salinity")
    if np.any(salinity < 0.0) or np.any(salinity > 120.0):
        raise ValueError(f"absolute_salinity must be from 0 to 120 g/kg (TEOS-10's range), got {salinity.min()} to {salinity.max()}")
    temperature = finite_array(conservative_temperature, "conservative_temperature")
    if np.any(temperature < -5.0) or np.any(temperature > 95.0):
        raise ValueError(
            f"conservative_temperature must be from -5 to 95 °C (liquid sea water, TEOS-10's range), got {temperature.min()} to {temperature.max()}"
        )
    pressure_dbar = pressure_at_depth_mpa(depth, latitude) / _MPA_PER_DBAR
    return np.asarray(gsw.rho(salinity, temperature, pressure_dbar), dtype=np.float64)
