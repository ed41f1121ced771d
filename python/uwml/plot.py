"""The former module ``uwml.plot``, now :mod:`uwml.viz.plot`: its names, kept importable from here."""

# ruff: noqa: F401 (every import is a name of the former module, re-exported)

from .fit.hydro import HydroFit
from .fit.results import LossFit
from .model.losses import RPM, Drive, OilDrag, Seal
from .viz.plot import efficiency_map, fit_plot, hydro_fit_plot, loss_maps

__all__ = ["efficiency_map", "fit_plot", "hydro_fit_plot", "loss_maps"]
