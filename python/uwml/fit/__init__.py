"""Identification: the joint losses from the three-configuration current experiment, and the
hydrodynamic coefficients Cd and Cm from the land/water experiment (:func:`hydro_coefficients`,
section "Hydrodynamic coefficients" below).

docs/losses.md, "Identification from the three-configuration experiment", and the paper's
Section IV: the motor current of a joint is measured with the housing dry and no seal (``dry``),
oil-filled without the seal (``oil``) and oil-filled with the seal (``oil_seal``), at several
output speeds and pressures. The differences isolate the
two losses, ``ΔI_oil(ω, p) = I_oil − I_dry(ω)`` and ``ΔI_seal(ω, p) = I_oil_seal − I_oil``;
:func:`oil_drag` and :func:`seal` fit :class:`uwml.model.losses.OilDrag` and :class:`uwml.model.losses.Seal`
to them and return a result in the lmfit style (:class:`LossFit`).

CSV format
----------
One header row, then one row per measurement (repeats allowed, in any order, extra columns
ignored). Rows are numbered as in a spreadsheet: the header is row 1.

=================  ========  ==========================================================
column             required  meaning
=================  ========  ==========================================================
``configuration``  yes       ``dry``, ``oil`` or ``oil_seal``
``speed_rpm``      yes       output speed [r/min], ≥ 0
``pressure_mpa``   yes       ambient (gauge) pressure [MPa], ≥ 0; ignored for ``dry``
``current_a``      yes       motor current [A] (mean over the steady part of the run)
``startup``        no        1 for the current peak at breakaway from rest, else 0
                             (default 0)
``temperature_c``  no        oil temperature of the run (its set point) [°C]; rows
                             are grouped by equal values
=================  ========  ==========================================================

Every ``oil`` row (steady) needs ``dry`` rows at the same speed; every ``oil_seal`` row needs
``oil`` rows at the same speed, pressure and temperature (start-up rows: at the same pressure
and temperature). Start-up rows are evaluated at ``ω → 0⁺`` (their speed is not used): there
the seal's friction is its breakaway level ``S(p)`` and the oil's drag is 0, so start-up rows
of ``oil_seal`` minus ``oil`` measure ``S(p)`` and the oil fit does not use start-up rows.

How the fits work
-----------------
Rows are averaged per group (configuration, speed, pressure, temperature; ``dry`` per speed
only). The standard error of a group mean is ``s/√n`` with ``s`` the within-group standard
deviation pooled over all groups of the same configuration and kind (steady or start-up): a
standard deviation from three to five repeats is itself uncertain by 35-50 %, and weighting
each point by its own would favour the points whose noise happened to be small. Without any
repeats (or with exactly repeated currents) the points get unit weights and the covariance is
scaled by the reduced χ².

* :func:`oil_drag`: ``T_oil = K_t ΔI_oil`` [N·m at the motor shaft] at motor speed ``N ω``.
  One ``dry`` mean is subtracted from every oil point at its speed, so those differences are
  correlated; the fit is generalized least squares with that covariance. Start: the log-linear
  fit of ``ln T = ln K_oil + n ln ω_m + a_p (p − p_ref) − a_T (θ − θ_ref)``; then
  ``scipy.optimize.least_squares`` (trust region, bounds ``K_oil ≥ 0``, ``1 ≤ n ≤ 2``,
  ``a_p, a_T ≥ 0``). ``a_T`` is fitted only where the temperature varies.
* :func:`seal`: ``T_seal = N η K_t ΔI_seal`` [N·m at the output]. For a given ω_s the six
  level parameters are linear (fitted as ``C0, C1, S0 − C0, S1 − C1, D0, D1 ≥ 0`` by bounded
  linear least squares, so that ``S ≥ C ≥ 0`` and ``D ≥ 0`` hold); ω_s comes from a 1-D search
  of the profile χ² over ``log ω_s`` (a log grid, then ``scipy.optimize.minimize_scalar``,
  bounded); a final ``least_squares`` over all seven gives the covariance.

Steady rows use the hard sign (ε = 0): the data are at steady, known-sign speeds.

Hydrodynamic coefficients
-------------------------
:func:`hydro_coefficients` fits docs/model.md section 4, ``−Δτ_motor − τ_buoy = Cd R_d + Cm R_m``
with ``Δτ_motor = τ_water − τ_land`` from a log of :mod:`uwml.io.logs`, on the selected joints
(default joint index 0, the paper's joint 1, hip yaw, whose vertical axis gravity and
buoyancy do not act about), of any :class:`uwml.Robot` (default :func:`uwml.paper_leg`; a tree,
from a URDF, MJCF or model file) on a fixed base, with the core's regressors summed per body.
``per="link"`` gives one Cd and one Cm per body (``cd_<link name>``, ``cd_link<l>`` for an
unnamed link ``l``, 0-based; ``cd_base`` for the base's own segments, dropped on a fixed base),
``per="direction"`` one per body and normal direction (``cd_link<l>_n<k>``, ``k`` the
segment's normal, as in :attr:`uwml.Segment.normals`; a circular segment counts in ``n0``);
columns that are zero on every selected sample (a link without a segment, a direction that
never moves) are dropped and named in ``message`` and ``dropped``.

Weights: each joint ``j`` gets ``1/σ_j²``. Given ``sigma`` (the standard error of ``−Δτ``, a
scalar or one per selected joint [N·m]), those are used and the covariance is scaled by the
reduced χ² only if ``scale_covar``. Otherwise σ_j is estimated from the residuals of an
unweighted first pass (their root mean square; for ``robust=True`` their scaled median
absolute deviation ``1.4826 · MAD``), and the covariance is always scaled by the reduced χ².
``robust=True`` minimizes Huber's loss of the weighted residuals with ``HUBER_SCALE = 1.345``
standard errors (95 % efficiency for Gaussian noise; residuals larger than that count
linearly), by iteratively reweighted least squares (the loss is convex: the minimum is the one
``scipy.optimize.least_squares(loss="huber", f_scale=HUBER_SCALE)`` finds, which a test
checks), twice, re-estimating σ_j from the first Huber fit's residuals; its covariance is Huber's asymptotic estimate (*Robust
Statistics*, 1981, ch. 7) with his small-sample correction K,
``K² [Σψ²/(n−p)] / [mean ψ']² (XᵀWX)⁻¹``, ``K = 1 + (p/n) var(ψ')/mean(ψ')²``.

Logs of any length: the Rust core assembles the problem (regressors and target of each
selected joint) chunk by chunk (``CHUNK_SAMPLES`` samples) in one pass over the log, and the fit
accumulates the normal equations ``XᵀX``, ``Xᵀy`` per joint, so the design is never held whole
(it is kept for the robust fit's later passes only while it takes less than ``cache_bytes``).
The normal equations are solved with their columns scaled to unit norm; fitted values come
from the torques at the fitted coefficients (linearity), at a third of the regressors' cost.
The result's per-point arrays (data, fit, residuals, σ, time, joint) are what grows with the
log: about 6 floats per fitted point. Measured on 10 million samples:
``python benches/large_log.py --fit-settings 1e7`` (docs/identification.md).

With estimated σ_j the reduced χ² is 1 by construction (for ``robust=False``); it says
something about the model only with a known ``sigma`` (the paper's 2.425 is of that kind).

Without a land run
------------------
:func:`hydro_from_water_logs` fits Cd, Cm and the joints' loss levels to logs of the water run
alone, the description's rigid-body inverse dynamics standing in for the land run
(:mod:`uwml.fit.water_only`); :func:`hull_from_free_running` fits a vehicle's lumped model (and
its buoyancy) to logs of it running free on its thrusters (:mod:`uwml.fit.free_running`).

By output error
---------------
:func:`uwml.sim.free_floating.vehicle_from_trials` fits chosen entries of a vehicle's hull and
its trim (:data:`VEHICLE_PARAMETERS`) to trials of it floating with the thrusters off while its
arm moves, each residual a replay; it lives with the simulation it needs (a layer above this
one), its least squares, statistics and result (:class:`VehicleFit`) here
(:mod:`uwml.fit.output_error`, :mod:`uwml.fit.vehicle_parameters`).
"""

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from .design import CHUNK_SAMPLES, DESIGN_CACHE_BYTES
    from .fit_results import FitResult, LossFit, OilDragFit, SealFit
    from .free_running import HullFit, hull_from_free_running
    from .hydro import HUBER_SCALE, HydroFit, LogDiagnostics, hydro_coefficients
    from .loss_data import CONFIGURATIONS, read_loss_csv, validate_loss_data, write_loss_csv
    from .loss_fits import oil_drag, seal
    from .output_error import TrialRMS, VehicleFit
    from .vehicle_parameters import VEHICLE_PARAMETERS
    from .water_only import WaterOnlyFit, hydro_from_water_logs

#: Where each name is defined. The package imports its modules on first use (PEP 562): they
#: import scipy, which takes longer than the command line may (``uwml --help``; a submodule's
#: constants, the fits' term names, come without them).
_DEFINED_IN = {
    "CHUNK_SAMPLES": "design",
    "DESIGN_CACHE_BYTES": "design",
    "FitResult": "fit_results",
    "LossFit": "fit_results",
    "OilDragFit": "fit_results",
    "SealFit": "fit_results",
    "HullFit": "free_running",
    "hull_from_free_running": "free_running",
    "HUBER_SCALE": "hydro",
    "HydroFit": "hydro",
    "LogDiagnostics": "hydro",
    "hydro_coefficients": "hydro",
    "CONFIGURATIONS": "loss_data",
    "read_loss_csv": "loss_data",
    "validate_loss_data": "loss_data",
    "write_loss_csv": "loss_data",
    "oil_drag": "loss_fits",
    "seal": "loss_fits",
    "TrialRMS": "output_error",
    "VehicleFit": "output_error",
    "VEHICLE_PARAMETERS": "vehicle_parameters",
    "WaterOnlyFit": "water_only",
    "hydro_from_water_logs": "water_only",
}


def __getattr__(name: str) -> Any:
    module = _DEFINED_IN.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(f".{module}", __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted([*globals(), *_DEFINED_IN])


__all__ = [
    "CHUNK_SAMPLES",
    "CONFIGURATIONS",
    "DESIGN_CACHE_BYTES",
    "HUBER_SCALE",
    "VEHICLE_PARAMETERS",
    "FitResult",
    "HullFit",
    "HydroFit",
    "LogDiagnostics",
    "LossFit",
    "OilDragFit",
    "SealFit",
    "TrialRMS",
    "VehicleFit",
    "WaterOnlyFit",
    "hull_from_free_running",
    "hydro_coefficients",
    "hydro_from_water_logs",
    "oil_drag",
    "read_loss_csv",
    "seal",
    "validate_loss_data",
    "write_loss_csv",
]
