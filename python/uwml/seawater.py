"""The former module ``uwml.seawater``, now :mod:`uwml.sea.seawater`: its names, kept importable from here."""

# ruff: noqa: F401 (every import is a name of the former module, re-exported)

from ._checks import finite_array
from .domains import MAX_DEPTH
from .sea.seawater import Array, density_at_depth, pressure_at_depth_mpa

__all__ = ["density_at_depth", "pressure_at_depth_mpa"]
