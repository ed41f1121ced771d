"""The former module ``uwml.losses``, now :mod:`uwml.model.losses`: its names, kept importable from here."""

# ruff: noqa: F401 (every import is a name of the former module, re-exported)

from ._checks import to_float
from .model.losses import RPM, Drive, OilDrag, Seal, rad_s_to_rpm, rpm_to_rad_s

__all__ = ["RPM", "Drive", "OilDrag", "Seal", "rad_s_to_rpm", "rpm_to_rad_s"]
