"""The former module ``uwml.oil``, now :mod:`uwml.sea.oil`: its names, kept importable from here."""

# ruff: noqa: F401 (every import is a name of the former module, re-exported)

from ._checks import finite_array
from .sea.oil import ISO_VG32, OILS, Array, OilViscosity, barus_factor, drag_temperature_sensitivity

__all__ = ["ISO_VG32", "OILS", "OilViscosity", "barus_factor", "drag_temperature_sensitivity"]
