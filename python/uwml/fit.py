"""Identification: the joint losses from the three-configuration current experiment, and the
hydrodynamic coefficients Cd and Cm from the land/water experiment (:func:`hydro_coefficients`,
section "Hydrodynamic coefficients" below).

MODEL.md section 7 and the paper's Section IV: the motor current of a joint is measured with
the housing dry and no seal (``dry``), oil-filled without the seal (``oil``) and oil-filled with
the seal (``oil_seal``), at several output speeds and pressures. The differences isolate the
two losses, ``ΔI_oil(ω, p) = I_oil − I_dry(ω)`` and ``ΔI_seal(ω, p) = I_oil_seal − I_oil``;
:func:`oil_drag` and :func:`seal` fit :class:`uwml.losses.OilDrag` and :class:`uwml.losses.Seal`
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
:func:`hydro_coefficients` fits MODEL.md section 4, ``−Δτ_motor − τ_buoy = Cd R_d + Cm R_m``
with ``Δτ_motor = τ_water − τ_land`` from a log of :mod:`uwml.logs`, on the selected joints
(default joint index 0, the paper's joint 1, hip yaw, whose vertical axis gravity and
buoyancy do not act about). ``per="link"`` gives one Cd and one Cm per link (``cd_link<l>``,
``cm_link<l>``, ``l`` the 0-based link index), ``per="direction"`` one per link and normal
direction (``cd_link<l>_n<k>``, ``k`` as in :meth:`uwml.Leg.hydro`); columns that are zero on
every selected sample (a link without a segment, a direction that never moves) are dropped and
named in ``message`` and ``dropped``.

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
``python benches/large_log.py`` (docs/identification.md).

With estimated σ_j the reduced χ² is 1 by construction (for ``robust=False``); it says
something about the model only with a known ``sigma`` (the paper's 2.425 is of that kind).
"""

from __future__ import annotations

import csv
import math
import os
from abc import ABC, abstractmethod
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from typing import IO, TYPE_CHECKING, Any, Literal

import numpy as np
import scipy.linalg
import scipy.optimize
import scipy.stats
from numpy.typing import ArrayLike, NDArray

from . import reference
from ._checks import read_csv_columns
from .logs import Log, align_logs, read_log
from .losses import RPM, Drive, OilDrag, Seal
from .model import Water

if TYPE_CHECKING:
    from .leg import Leg

__all__ = [
    "CONFIGURATIONS",
    "HUBER_SCALE",
    "FitResult",
    "HydroFit",
    "LossFit",
    "OilDragFit",
    "SealFit",
    "hydro_coefficients",
    "oil_drag",
    "read_loss_csv",
    "seal",
    "validate_loss_data",
    "write_loss_csv",
]

Array = NDArray[np.float64]
Columns = dict[str, NDArray]
PathOrFile = str | os.PathLike[str] | IO[str]

#: Valid values of the ``configuration`` column.
CONFIGURATIONS = ("dry", "oil", "oil_seal")
_REQUIRED = ("configuration", "speed_rpm", "pressure_mpa", "current_a")
_OPTIONAL = ("startup", "temperature_c")
#: The temperature of data without a ``temperature_c`` column, unless told otherwise [°C].
_DEFAULT_TEMPERATURE_C = 20.0
#: Correlations below this are left out of :meth:`LossFit.fit_report`.
_MIN_CORRELATION = 0.1
#: Relative singular value below which the Jacobian is taken as rank-deficient.
_RANK_TOLERANCE = 1e-10
#: The default drive (the paper's hip-roll joint, illustrative K_t and η).
_DRIVE = Drive()


# --------------------------------------------------------------------------------------------
# Data: reading, validating, writing
# --------------------------------------------------------------------------------------------


def _cell_number(value: Any, row: int, column: str) -> float:
    try:
        x = float(value.strip() if isinstance(value, str) else value)
    except (TypeError, ValueError):
        raise ValueError(f"row {row}, column {column!r}: expected a number, got {value!r}") from None
    if not math.isfinite(x):
        raise ValueError(f"row {row}, column {column!r}: expected a finite number, got {value!r}")
    return x


def _key_text(speed_rpm: float | None, pressure_mpa: float | None, temperature_c: float | None) -> str:
    parts = [] if speed_rpm is None else [f"{speed_rpm:g} r/min"]
    parts += [] if pressure_mpa is None else [f"{pressure_mpa:g} MPa"]
    parts += [] if temperature_c is None else [f"{temperature_c:g} °C"]
    return ", ".join(parts)


def validate_loss_data(columns: Mapping[str, ArrayLike]) -> Columns:
    """Check loss-experiment columns and return them as numpy arrays.

    Parameters
    ----------
    columns : mapping of str to array_like
        The columns of the CSV format (module docstring), of equal length; values may be
        numbers or their text. Extra columns are ignored.

    Returns
    -------
    dict of ndarray
        ``configuration`` (str), ``speed_rpm``, ``pressure_mpa``, ``current_a`` (float),
        ``startup`` (int, 0 or 1) and, if given, ``temperature_c`` (float).

    Raises
    ------
    ValueError
        Naming the row (the header is row 1) and the column: a missing column, columns of
        unequal length, no data rows, an unknown configuration, a speed or pressure that is not
        a number or negative, a current or temperature that is not a finite number, a start-up
        flag other than 0 or 1, or a configuration without the one it is compared with (``oil``
        without ``dry`` at its speed, ``oil_seal`` without ``oil`` at its speed, pressure and
        temperature).
    """
    for name in _REQUIRED:
        if name not in columns:
            raise ValueError(f"row 1 (header), column {name!r}: missing column (required: {', '.join(_REQUIRED)})")
    present = [name for name in (*_REQUIRED, *_OPTIONAL) if name in columns]
    cells = {name: list(np.asarray(columns[name], dtype=object).ravel()) for name in present}
    n_rows = len(cells["configuration"])
    for name in present:
        if len(cells[name]) != n_rows:
            raise ValueError(f"row {min(n_rows, len(cells[name])) + 2}, column {name!r}: has {len(cells[name])} values, expected {n_rows}")
    if n_rows == 0:
        raise ValueError("row 2, column 'configuration': no data rows")

    configuration, speed, pressure, current, startup = [], [], [], [], []
    temperature: list[float] | None = [] if "temperature_c" in cells else None
    for i in range(n_rows):
        row = i + 2
        value = cells["configuration"][i]
        text = value.strip() if isinstance(value, str) else value
        if text not in CONFIGURATIONS:
            raise ValueError(
                f"row {row}, column 'configuration': unknown configuration {value!r} (expected one of {', '.join(CONFIGURATIONS)})"
            )
        configuration.append(text)
        for name, values in (("speed_rpm", speed), ("pressure_mpa", pressure)):
            x = _cell_number(cells[name][i], row, name)
            if x < 0.0:
                raise ValueError(f"row {row}, column {name!r}: must be >= 0, got {cells[name][i]!r}")
            values.append(x)
        current.append(_cell_number(cells["current_a"][i], row, "current_a"))
        if "startup" in cells:
            flag = _cell_number(cells["startup"][i], row, "startup")
            if flag not in (0.0, 1.0):
                raise ValueError(f"row {row}, column 'startup': expected 0 or 1, got {cells['startup'][i]!r}")
            startup.append(int(flag))
        else:
            startup.append(0)
        if temperature is not None:
            theta = _cell_number(cells["temperature_c"][i], row, "temperature_c")
            if theta <= -273.15:
                raise ValueError(f"row {row}, column 'temperature_c': must be above -273.15 °C, got {cells['temperature_c'][i]!r}")
            temperature.append(theta)

    data: Columns = {
        "configuration": np.array(configuration, dtype=str),
        "speed_rpm": np.array(speed),
        "pressure_mpa": np.array(pressure),
        "current_a": np.array(current),
        "startup": np.array(startup, dtype=np.int64),
    }
    if temperature is not None:
        data["temperature_c"] = np.array(temperature)
    _check_pairs(data)
    return data


def _check_pairs(data: Columns) -> None:
    """Every ``oil`` row has ``dry`` rows at its speed, every ``oil_seal`` row ``oil`` rows."""
    theta = data.get("temperature_c")
    keys = []
    for i, configuration in enumerate(data["configuration"]):
        t = None if theta is None else float(theta[i])
        s, p = float(data["speed_rpm"][i]), float(data["pressure_mpa"][i])
        keys.append((str(configuration), bool(data["startup"][i]), s, p, t))
    dry_speeds = {s for c, start, s, _, _ in keys if c == "dry" and not start}
    oil_steady = {(s, p, t) for c, start, s, p, t in keys if c == "oil" and not start}
    oil_startup = {(p, t) for c, start, _, p, t in keys if c == "oil" and start}
    for i, (c, start, s, p, t) in enumerate(keys):
        row = i + 2
        if c == "oil" and not start and s not in dry_speeds:
            raise ValueError(
                f"row {row}, column 'configuration': 'oil' at {_key_text(s, None, None)} needs 'dry' rows at the same speed; there are none"
            )
        if c == "oil_seal" and not start and (s, p, t) not in oil_steady:
            raise ValueError(
                f"row {row}, column 'configuration': 'oil_seal' at {_key_text(s, p, t)} needs 'oil' rows at the same point; there are none"
            )
        if c == "oil_seal" and start and (p, t) not in oil_startup:
            raise ValueError(
                f"row {row}, column 'configuration': start-up 'oil_seal' at {_key_text(None, p, t)} needs start-up 'oil' rows there; there are none"
            )


def read_loss_csv(path_or_file: PathOrFile) -> Columns:
    """Read and check a loss-experiment CSV file (format in the module docstring).

    Parameters
    ----------
    path_or_file : str, path or text file
        The file, or an open text stream.

    Returns
    -------
    dict of ndarray
        The checked columns (:func:`validate_loss_data`).

    Raises
    ------
    ValueError
        Naming the row (header = row 1) and column of the first problem; also for an empty file
        or a row with fewer cells than the header.
    """
    return validate_loss_data(read_csv_columns(path_or_file, "", _REQUIRED[0]))


def write_loss_csv(data: Mapping[str, ArrayLike], path_or_file: PathOrFile) -> None:
    """Write loss-experiment columns as CSV (format in the module docstring), after checking them.

    Numbers are written in their shortest round-trip form, so :func:`read_loss_csv` gives the
    same values back.

    Raises
    ------
    ValueError
        As :func:`validate_loss_data`.
    """
    checked = validate_loss_data(data)
    if isinstance(path_or_file, str | os.PathLike):
        with open(path_or_file, "w", newline="", encoding="utf-8") as handle:
            write_loss_csv(checked, handle)
        return
    names = [name for name in (*_REQUIRED, *_OPTIONAL) if name in checked]
    writer = csv.writer(path_or_file, lineterminator="\n")
    writer.writerow(names)
    for i in range(len(checked["configuration"])):
        writer.writerow(
            [str(checked[name][i]) if name in ("configuration", "startup") else repr(float(checked[name][i])) for name in names]
        )


def _load(data_or_path: Mapping[str, ArrayLike] | PathOrFile) -> Columns:
    if isinstance(data_or_path, Mapping):
        return validate_loss_data(data_or_path)
    return read_loss_csv(data_or_path)


# --------------------------------------------------------------------------------------------
# Group means and their standard errors
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class _Groups:
    """Means of the rows of one configuration and kind, per key, with their standard errors."""

    keys: list[tuple[float, ...]]
    mean: Array
    stderr: Array
    #: Whether the standard errors come from repeats (False: no repeats anywhere, unit σ).
    known: bool


def _groups(pools: list[tuple[Array, list[tuple[float, ...]]]]) -> list[_Groups]:
    """Group means of several pools (values, row keys), each pool's variance pooled over its groups.

    A pool without repeats (or without scatter) borrows the variance pooled over all pools;
    without any repeats (or exact repeats everywhere) the standard errors are 1 and ``known`` is
    False.
    """
    summaries = []
    total_ss, total_dof = 0.0, 0
    for values, row_keys in pools:
        keys = sorted(set(row_keys))
        index = {key: k for k, key in enumerate(keys)}
        labels = np.array([index[key] for key in row_keys], dtype=np.int64)
        count = np.bincount(labels, minlength=len(keys)).astype(np.float64)
        mean = np.bincount(labels, weights=values, minlength=len(keys)) / count
        ss = float(np.sum((values - mean[labels]) ** 2))
        dof = int(len(values) - len(keys))
        summaries.append((keys, mean, count, ss, dof))
        total_ss, total_dof = total_ss + ss, total_dof + dof
    result = []
    for keys, mean, count, ss, dof in summaries:
        if dof > 0 and ss > 0.0:
            variance, known = ss / dof, True
        elif total_dof > 0 and total_ss > 0.0:
            variance, known = total_ss / total_dof, True
        else:
            variance, known = 1.0, False
        result.append(_Groups(keys, mean, np.sqrt(variance / count), known))
    return result


def _temperatures(data: Columns, default_c: float) -> Array:
    theta = data.get("temperature_c")
    return np.full(len(data["configuration"]), default_c) if theta is None else theta


def _select(data: Columns, configuration: str, startup: bool) -> NDArray[np.bool_]:
    return (data["configuration"] == configuration) & (data["startup"] == int(startup))


# --------------------------------------------------------------------------------------------
# Results
# --------------------------------------------------------------------------------------------


def _json_float(x: float | None) -> float | None:
    return None if x is None or not math.isfinite(x) else float(x)


@dataclass(frozen=True, eq=False, kw_only=True)
class FitResult:
    """A fit's result, in the style of lmfit's ``MinimizerResult`` / ``ModelResult``: the part
    shared by the loss fits (:class:`LossFit`) and the hydrodynamic fit
    (:class:`HydroFit`): parameters, uncertainties, statistics, report and JSON summary.
    """

    #: Fitted (and held) parameters, name → value, in the order of the model's fields.
    params: dict[str, float]
    #: Standard errors of the fitted parameters (None for held ones, or without error bars).
    stderr: dict[str, float | None]
    #: Names of the fitted parameters, the order of ``covar``.
    var_names: tuple[str, ...]
    #: Values held fixed, name → value.
    fixed: dict[str, float]
    #: Starting values of the fitted parameters (empty for a direct linear solve).
    init_values: dict[str, float]
    #: Covariance of the fitted parameters (None without error bars).
    covar: Array | None
    #: Correlations between fitted parameters, name → name → value (empty without error bars).
    correl: dict[str, dict[str, float]]
    ndata: int
    nvarys: int
    nfree: int
    #: Weighted (generalized) sum of squared residuals.
    chisqr: float
    redchi: float
    #: Coefficient of determination (COD), weighted: ``1 − χ² / weighted total sum of squares``.
    rsquared: float
    aic: float
    bic: float
    #: Weighted (whitened) residuals, ``L⁻¹ (best_fit − data)`` with ``L Lᵀ`` the data covariance.
    residual: Array
    #: The model at the data points.
    best_fit: Array
    #: The fitted data.
    data: Array
    #: Their standard errors.
    sigma: Array
    success: bool
    message: str
    #: False when the uncertainties could not be estimated (singular Jacobian, no free dof).
    errorbars: bool
    nfev: int
    #: Unit of ``data`` and ``best_fit``.
    unit: str = "N·m"
    method: str = "least_squares"

    def conf_int(self, level: float = 0.95) -> dict[str, tuple[float, float]]:
        """Confidence intervals ``value ± t(level, nfree) · stderr`` of the fitted parameters.

        Raises
        ------
        ValueError
            If the fit has no error bars or ``level`` is not in (0, 1).
        """
        if not 0.0 < level < 1.0:
            raise ValueError(f"level must lie in (0, 1), got {level}")
        if not self.errorbars:
            raise ValueError("the fit has no error bars")
        t = float(scipy.stats.t.ppf(0.5 + 0.5 * level, self.nfree))
        return {name: (self.params[name] - t * self.stderr[name], self.params[name] + t * self.stderr[name]) for name in self.var_names}  # type: ignore[operator]

    def _report_statistics(self) -> list[str]:
        """Extra lines for the ``[[Fit Statistics]]`` block."""
        return []

    def fit_report(self, min_correl: float = _MIN_CORRELATION) -> str:
        """A readable report, as lmfit's: statistics, ``value +/- stderr (pct)``, correlations."""
        lines = [
            "[[Fit Statistics]]",
            f"    # fitting method   = {self.method}",
            f"    # function evals   = {self.nfev}",
            f"    # data points      = {self.ndata}",
            f"    # variables        = {self.nvarys}",
            f"    chi-square         = {self.chisqr:.7g}",
            f"    reduced chi-square = {self.redchi:.7g}",
            f"    Akaike info crit   = {self.aic:.7g}",
            f"    Bayesian info crit = {self.bic:.7g}",
            f"    R-squared (COD)    = {self.rsquared:.7g}",
            f"    data unit          = {self.unit}",
            *self._report_statistics(),
        ]
        if not self.success:
            lines.append(f"##  Warning: the fit did not converge: {self.message}")
        if not self.errorbars:
            lines.append("##  Warning: uncertainties could not be estimated")
        lines.append("[[Variables]]")
        width = max(len(name) for name in self.params) + 1
        for name, value in self.params.items():
            label = f"{name}:".ljust(width)
            if name in self.fixed:
                lines.append(f"    {label} {value:.7g} (fixed)")
                continue
            error = self.stderr[name]
            if error is None:
                text = f"{value:.7g} +/- None"
            else:
                pct = f"({100.0 * abs(error / value):.2f}%)" if value != 0.0 else "(inf%)"
                text = f"{value:.7g} +/- {error:.7g} {pct}"
            init = f" (init = {self.init_values[name]:.7g})" if name in self.init_values else ""
            lines.append(f"    {label} {text}{init}")
        pairs = sorted(
            ((a, b, c) for a, row in self.correl.items() for b, c in row.items() if a < b and abs(c) >= min_correl),
            key=lambda item: -abs(item[2]),
        )
        if pairs:
            lines.append(f"[[Correlations]] (unreported correlations are < {min_correl:.3f})")
            lines += [f"    C({a}, {b}) = {c:+.4f}" for a, b, c in pairs]
        return "\n".join(lines)

    def _summary_head(self) -> dict[str, Any]:
        """Keys put first in :meth:`summary`."""
        return {}

    def _point_coordinates(self) -> dict[str, list[Any]]:
        """Where each data point was taken, for :meth:`summary` (JSON-safe lists)."""
        return {}

    def _summary_tail(self) -> dict[str, Any]:
        """Keys put last in :meth:`summary`: the data points, their coordinates first."""
        return {
            "points": {
                **self._point_coordinates(),
                "data": [_json_float(x) for x in self.data],
                "sigma": [_json_float(x) for x in self.sigma],
                "best_fit": [_json_float(x) for x in self.best_fit],
                "residual": [_json_float(x) for x in self.residual],
            },
        }

    def summary(self) -> dict[str, Any]:
        """The result as a JSON-safe dict (numbers, strings, None, lists, dicts; no NaN)."""
        return {
            **self._summary_head(),
            "method": self.method,
            "success": bool(self.success),
            "message": self.message,
            "errorbars": bool(self.errorbars),
            "unit": self.unit,
            "params": {name: _json_float(value) for name, value in self.params.items()},
            "stderr": {name: _json_float(value) for name, value in self.stderr.items()},
            "fixed": {name: _json_float(value) for name, value in self.fixed.items()},
            "init_values": {name: _json_float(value) for name, value in self.init_values.items()},
            "var_names": list(self.var_names),
            "covar": None if self.covar is None else [[_json_float(x) for x in row] for row in self.covar],
            "correl": {a: {b: _json_float(c) for b, c in row.items()} for a, row in self.correl.items()},
            "ndata": int(self.ndata),
            "nvarys": int(self.nvarys),
            "nfree": int(self.nfree),
            "nfev": int(self.nfev),
            "chisqr": _json_float(self.chisqr),
            "redchi": _json_float(self.redchi),
            "rsquared": _json_float(self.rsquared),
            "aic": _json_float(self.aic),
            "bic": _json_float(self.bic),
            **self._summary_tail(),
        }


@dataclass(frozen=True, eq=False, kw_only=True)
class LossFit(FitResult, ABC):
    """Result of a loss fit, in the style of lmfit's ``MinimizerResult`` / ``ModelResult``.

    Parameters are in the units of :mod:`uwml.losses`; ``data``, ``sigma`` and ``best_fit`` are
    torques (``unit``): the oil fit's at the motor shaft, the seal fit's at the joint output.
    ``data`` are the fitted loss torques (differences of group means), ``sigma`` their standard
    errors.
    """

    #: Output speed [rad/s], pressure [MPa], temperature [°C] and start-up flag of each point.
    speed: Array
    pressure_mpa: Array
    temperature_c: Array
    startup: NDArray[np.bool_]
    #: The drive used to turn currents into torques.
    drive: Drive

    @property
    @abstractmethod
    def model(self) -> OilDrag | Seal:
        """The fitted loss model."""

    @abstractmethod
    def eval(self, speed: ArrayLike, pressure_mpa: ArrayLike, temperature_c: ArrayLike = 20.0) -> Array:
        """The fitted loss torque (in ``unit``) at output speed ``speed`` [rad/s], pressure [MPa]
        and temperature [°C]."""

    def _summary_head(self) -> dict[str, Any]:
        return {"model": type(self.model).__name__}

    def _point_coordinates(self) -> dict[str, list[Any]]:
        return {
            "speed": [_json_float(x) for x in self.speed],
            "pressure_mpa": [_json_float(x) for x in self.pressure_mpa],
            "temperature_c": [_json_float(x) for x in self.temperature_c],
            "startup": [bool(x) for x in self.startup],
        }


@dataclass(frozen=True, eq=False)
class OilDragFit(LossFit):
    """Result of :func:`oil_drag`; ``model`` is the fitted :class:`uwml.losses.OilDrag`."""

    @property
    def model(self) -> OilDrag:
        """The fitted :class:`uwml.losses.OilDrag`."""
        return OilDrag(**self.params)

    def eval(self, speed: ArrayLike, pressure_mpa: ArrayLike, temperature_c: ArrayLike = 20.0) -> Array:
        """``T_oil`` [N·m at the motor shaft] at output speed ``speed`` [rad/s] (motor speed N ω)."""
        return reference.oil_drag_torque(self.model, self.drive.ratio * np.asarray(speed, dtype=np.float64), pressure_mpa, temperature_c)


@dataclass(frozen=True, eq=False)
class SealFit(LossFit):
    """Result of :func:`seal`; ``model`` is the fitted :class:`uwml.losses.Seal`."""

    @property
    def model(self) -> Seal:
        """The fitted :class:`uwml.losses.Seal`."""
        return Seal(**self.params)

    def eval(self, speed: ArrayLike, pressure_mpa: ArrayLike, temperature_c: ArrayLike = 20.0) -> Array:
        """``T_seal`` [N·m at the output] at output speed ``speed`` [rad/s] (temperature unused)."""
        return reference.seal_torque(self.model, speed, pressure_mpa)


# --------------------------------------------------------------------------------------------
# The generalized least-squares engine
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class _Points:
    """Loss torques to fit: values, covariance (as its Cholesky factor) and coordinates."""

    data: Array
    cholesky: Array
    speed: Array
    pressure_mpa: Array
    temperature_c: Array
    startup: NDArray[np.bool_]
    #: Whether the covariance comes from repeats (else unit σ, covariance scaled by χ²_red).
    known: bool

    @property
    def sigma(self) -> Array:
        """Standard errors of the points, ``sqrt(diag(L Lᵀ))``."""
        return np.sqrt(np.sum(self.cholesky**2, axis=1))

    def whiten(self, x: Array) -> Array:
        """``L⁻¹ x``: uncorrelated, unit-variance residuals from raw ones."""
        return scipy.linalg.solve_triangular(self.cholesky, x, lower=True)


@dataclass(frozen=True)
class _Solution:
    x: Array
    init: Array
    #: The whitened Jacobian, or None where only its Gram matrix ``JᵀJ`` is kept (streamed fits).
    jacobian: Array | None
    residual: Array
    success: bool
    message: str
    nfev: int
    gram: Array | None = None

    def normal_matrix(self) -> Array:
        """``JᵀJ``."""
        if self.gram is not None:
            return self.gram
        assert self.jacobian is not None
        return self.jacobian.T @ self.jacobian

    def singular_values(self) -> Array:
        """Singular values of the whitened Jacobian, largest first (from ``JᵀJ`` if that is all
        there is: exact down to about 1e-8 of the largest, far below the rank tolerance's use)."""
        if self.jacobian is not None:
            return np.linalg.svd(self.jacobian, compute_uv=False)
        return np.sqrt(np.clip(np.linalg.eigvalsh(self.normal_matrix())[::-1], 0.0, None))

    def rank_tolerance(self) -> float:
        """The smallest singular value, relative to the largest, that counts as non-zero: from
        ``JᵀJ``, rounding alone leaves singular values near ``sqrt(ε)`` of the largest."""
        if self.jacobian is not None:
            return _RANK_TOLERANCE
        return max(_RANK_TOLERANCE, math.sqrt(64.0 * np.finfo(float).eps * max(len(self.x), 1)))


def _statistics(
    points: _Points, best_fit: Array, solution: _Solution, names: tuple[str, ...], transform: Array, scale_covar: bool
) -> dict[str, Any]:
    """lmfit's statistics and the covariance of ``transform @ x`` (the reported parameters)."""
    stats = _fit_statistics(points.data, points.whiten, points.known, best_fit, solution, names, transform, scale_covar)
    return stats | {
        "sigma": points.sigma,
        "speed": points.speed,
        "pressure_mpa": points.pressure_mpa,
        "temperature_c": points.temperature_c,
        "startup": points.startup,
    }


def _fit_statistics(
    data: Array,
    whiten: Callable[[Array], Array],
    known: bool,
    best_fit: Array,
    solution: _Solution,
    names: tuple[str, ...],
    transform: Array,
    scale_covar: bool,
) -> dict[str, Any]:
    """lmfit's statistics of a fit to ``data`` whose errors are whitened by ``whiten`` (``L⁻¹``),
    and the covariance of ``transform @ x``; ``known``: whether the data's covariance is known
    (else it is scaled by the reduced χ² whatever ``scale_covar`` says)."""
    ndata, nvarys = len(data), len(names)
    nfree = ndata - nvarys
    chisqr = float(solution.residual @ solution.residual)
    redchi = chisqr / nfree if nfree > 0 else math.nan
    ones, z = whiten(np.ones(ndata)), whiten(data)
    centred = z - ones * (ones @ z) / (ones @ ones)
    total = float(centred @ centred)
    neg2_log_likelihood = ndata * math.log(max(chisqr, np.finfo(float).tiny) / ndata)
    covar, message = None, solution.message
    singular = solution.singular_values()
    gram = solution.normal_matrix()
    if nfree <= 0:
        message += "; no degrees of freedom left for uncertainties"
    elif singular.size < nvarys or singular[-1] <= solution.rank_tolerance() * singular[0]:
        weakest = names[int(np.argmin(np.diag(gram)))]
        message += f"; the data do not determine every parameter (singular Jacobian; least sensitive: {weakest})"
    else:
        covar = np.linalg.inv(gram)
        if scale_covar or not known:
            covar = covar * redchi
        covar = transform @ covar @ transform.T
    return {
        **_uncertainties(covar, names),
        "ndata": ndata,
        "nvarys": nvarys,
        "nfree": nfree,
        "chisqr": chisqr,
        "redchi": redchi,
        "rsquared": 1.0 - chisqr / total if total > 0.0 else math.nan,
        "aic": neg2_log_likelihood + 2.0 * nvarys,
        "bic": neg2_log_likelihood + math.log(ndata) * nvarys,
        "residual": solution.residual,
        "best_fit": best_fit,
        "data": data,
        "success": solution.success,
        "message": message,
        "nfev": solution.nfev,
    }


def _uncertainties(covar: Array | None, names: tuple[str, ...]) -> dict[str, Any]:
    """``covar`` (None if not finite or with a negative variance), ``stderr``, ``correl`` and
    ``errorbars`` of the parameters ``names``."""
    errorbars = covar is not None and bool(np.all(np.isfinite(covar)) and np.all(np.diag(covar) >= 0.0))
    covar = covar if errorbars else None
    stderr = dict.fromkeys(names, None) if covar is None else dict(zip(names, np.sqrt(np.diag(covar)).tolist(), strict=True))
    correl: dict[str, dict[str, float]] = {}
    if covar is not None:
        d = np.sqrt(np.diag(covar))
        with np.errstate(divide="ignore", invalid="ignore"):
            r = covar / np.outer(d, d)
        correl = {a: {b: float(r[i, j]) for j, b in enumerate(names) if j != i and np.isfinite(r[i, j])} for i, a in enumerate(names)}
    return {"stderr": stderr, "covar": covar, "correl": correl, "errorbars": errorbars}


def _least_squares(
    points: _Points,
    model: Callable[[Array], tuple[Array, Array]],
    x0: Array,
    lower: Array,
    upper: Array,
) -> _Solution:
    """Minimize ``|L⁻¹ (f(x) − data)|²`` within bounds; ``model(x)`` gives ``(f, ∂f/∂x)``."""

    def residual(x: Array) -> Array:
        return points.whiten(model(x)[0] - points.data)

    def jacobian(x: Array) -> Array:
        return points.whiten(model(x)[1])

    x0 = np.clip(x0, lower, upper)
    result = scipy.optimize.least_squares(residual, x0, jac=jacobian, bounds=(lower, upper), x_scale="jac", method="trf")
    return _Solution(
        x=result.x,
        init=x0,
        jacobian=jacobian(result.x),
        residual=residual(result.x),
        success=bool(result.success),
        message=str(result.message),
        nfev=int(result.nfev),
    )


# --------------------------------------------------------------------------------------------
# Oil drag
# --------------------------------------------------------------------------------------------


def _oil_points(data: Columns, drive: Drive, temperature_c: float) -> _Points:
    """``T_oil = K_t (I_oil − I_dry(ω))`` per (speed, pressure, temperature), with covariance."""
    theta = _temperatures(data, temperature_c)
    dry, oil = _select(data, "dry", False), _select(data, "oil", False)
    if not np.any(oil):
        raise ValueError("no steady 'oil' rows to fit")
    dry_keys = [(s,) for s in data["speed_rpm"][dry].tolist()]
    oil_keys = list(zip(data["speed_rpm"][oil].tolist(), data["pressure_mpa"][oil].tolist(), theta[oil].tolist(), strict=True))
    dry_groups, oil_groups = _groups([(data["current_a"][dry], dry_keys), (data["current_a"][oil], oil_keys)])
    dry_index = {key[0]: k for k, key in enumerate(dry_groups.keys)}
    which_dry = np.array([dry_index[key[0]] for key in oil_groups.keys], dtype=np.int64)
    same_speed = which_dry[:, None] == which_dry[None, :]
    covariance = np.diag(oil_groups.stderr**2) + np.where(same_speed, dry_groups.stderr[which_dry][:, None] ** 2, 0.0)
    kt = drive.torque_constant
    coordinates = np.array(oil_groups.keys, dtype=np.float64)
    return _Points(
        data=kt * (oil_groups.mean - dry_groups.mean[which_dry]),
        cholesky=kt * np.linalg.cholesky(covariance),
        speed=coordinates[:, 0] * RPM,
        pressure_mpa=coordinates[:, 1],
        temperature_c=coordinates[:, 2],
        startup=np.zeros(len(coordinates), dtype=bool),
        known=dry_groups.known and oil_groups.known,
    )


def oil_drag(
    data_or_path: Mapping[str, ArrayLike] | PathOrFile,
    drive: Drive = _DRIVE,
    temperature_sensitivity_per_k: float | None = None,
    *,
    reference_pressure_mpa: float = 0.0,
    reference_temperature_c: float | None = None,
    temperature_c: float = _DEFAULT_TEMPERATURE_C,
    scale_covar: bool = True,
) -> OilDragFit:
    """Fit :class:`uwml.losses.OilDrag` to ``ΔI_oil = I_oil − I_dry(ω)`` (module docstring).

    The model, at motor speed ``ω_m = N ω`` and as torque at the motor shaft,
    ``T_oil = K_t ΔI_oil = K_oil exp(a_p (p − p_ref)) exp(−a_T (θ − θ_ref)) ω_m^n``.

    Parameters
    ----------
    data_or_path : mapping or str or path or text file
        Columns (as :func:`uwml.synthetic.three_configuration_experiment` returns) or a CSV file.
    drive : Drive
        Torque constant K_t and ratio N of the joint (``torque_constant=1`` to fit in amperes).
    temperature_sensitivity_per_k : float, optional
        Hold a_T [1/K] at this value (e.g. from :func:`uwml.oil.drag_temperature_sensitivity`).
        None: fit it if the data's temperature varies, else hold it at 0 (the data say nothing
        about temperature; the model is then valid at the data's temperature).
    reference_pressure_mpa : float
        ``p_ref`` of the fitted model [MPa].
    reference_temperature_c : float, optional
        ``θ_ref`` of the fitted model [°C]; None: the mean temperature of the oil points.
    temperature_c : float
        Temperature of the rows when the data have no ``temperature_c`` column [°C].
    scale_covar : bool
        Scale the covariance by the reduced χ² (lmfit's default). Always done when the data
        have no repeats.

    Returns
    -------
    OilDragFit
        ``params``: ``k_oil``, ``exponent``, ``pressure_sensitivity_per_mpa``,
        ``temperature_sensitivity_per_k``, ``reference_pressure_mpa``,
        ``reference_temperature_c`` (the last two always fixed).

    Raises
    ------
    ValueError
        On invalid data (:func:`validate_loss_data`), no steady ``oil`` rows, or invalid
        held values.
    """
    data = _load(data_or_path)
    points = _oil_points(data, drive, temperature_c)
    theta_ref = float(np.mean(points.temperature_c)) if reference_temperature_c is None else float(reference_temperature_c)
    # Build the held values through OilDrag, which checks them.
    held = OilDrag(
        temperature_sensitivity_per_k=0.0 if temperature_sensitivity_per_k is None else temperature_sensitivity_per_k,
        reference_pressure_mpa=reference_pressure_mpa,
        reference_temperature_c=theta_ref,
    )
    fit_temperature = temperature_sensitivity_per_k is None and np.ptp(points.temperature_c) > 0.0
    names = ("k_oil", "exponent", "pressure_sensitivity_per_mpa") + (("temperature_sensitivity_per_k",) if fit_temperature else ())

    omega_m = drive.ratio * points.speed
    dp = points.pressure_mpa - held.reference_pressure_mpa
    dtheta = points.temperature_c - theta_ref
    moving = omega_m > 0.0
    log_omega = np.log(np.where(moving, omega_m, 1.0))

    def model(x: Array) -> tuple[Array, Array]:
        k_oil, exponent, a_p = x[:3]
        a_t = x[3] if fit_temperature else held.temperature_sensitivity_per_k
        shape = np.exp(a_p * dp - a_t * dtheta) * np.where(moving, np.exp(exponent * log_omega), 0.0)
        f = k_oil * shape
        columns = [shape, f * log_omega, f * dp] + ([-f * dtheta] if fit_temperature else [])
        return f, np.stack(columns, axis=1)

    x0 = _oil_start(points, moving, log_omega, dp, dtheta, fit_temperature, held.temperature_sensitivity_per_k)
    lower = np.array([0.0, 1.0, 0.0, 0.0][: len(names)])
    upper = np.array([np.inf, 2.0, np.inf, np.inf][: len(names)])
    solution = _least_squares(points, model, x0, lower, upper)
    stats = _statistics(points, model(solution.x)[0], solution, names, np.eye(len(names)), scale_covar)
    fitted = dict(zip(names, solution.x.tolist(), strict=False))
    fixed = {
        "reference_pressure_mpa": held.reference_pressure_mpa,
        "reference_temperature_c": held.reference_temperature_c,
    }
    if not fit_temperature:
        fixed["temperature_sensitivity_per_k"] = held.temperature_sensitivity_per_k
    order = (
        "k_oil",
        "exponent",
        "pressure_sensitivity_per_mpa",
        "temperature_sensitivity_per_k",
        "reference_pressure_mpa",
        "reference_temperature_c",
    )
    params = {name: float(fitted[name] if name in fitted else fixed[name]) for name in order}
    stats["stderr"] = {name: stats["stderr"].get(name) for name in order}
    return OilDragFit(
        params=params,
        var_names=names,
        fixed=fixed,
        init_values=dict(zip(names, solution.init.tolist(), strict=True)),
        drive=drive,
        unit="N·m at the motor shaft",
        **stats,
    )


def _oil_start(
    points: _Points,
    moving: NDArray[np.bool_],
    log_omega: Array,
    dp: Array,
    dtheta: Array,
    fit_temperature: bool,
    a_t: float,
) -> Array:
    """Log-linear start: ``ln T = ln K + n ln ω_m + a_p Δp − a_T Δθ`` over the positive points,
    each weighted by ``T/σ`` (the inverse standard error of ``ln T``)."""
    usable = moving & (points.data > 0.0)
    columns = [np.ones(usable.sum()), log_omega[usable], dp[usable]] + ([-dtheta[usable]] if fit_temperature else [])
    design = np.stack(columns, axis=1)
    target = np.log(points.data[usable]) + (0.0 if fit_temperature else a_t * dtheta[usable])
    if usable.sum() < design.shape[1] or np.linalg.matrix_rank(design) < design.shape[1]:
        # Too few positive points for the log-linear fit: a generic start.
        scale = float(np.mean(np.abs(points.data))) / max(float(np.mean(np.exp(1.5 * log_omega))), 1.0)
        return np.array([scale, 1.5, 0.0] + ([0.0] if fit_temperature else []))
    weight = (points.data / points.sigma)[usable]
    solution = np.linalg.lstsq(design * weight[:, None], target * weight, rcond=None)[0]
    return np.concatenate([[math.exp(solution[0])], solution[1:]])


# --------------------------------------------------------------------------------------------
# Seal
# --------------------------------------------------------------------------------------------


def _seal_points(data: Columns, drive: Drive, temperature_c: float) -> _Points:
    """``T_seal = N η K_t (I_oil_seal − I_oil)`` per (speed, pressure, temperature) and, for
    start-up rows, per (pressure, temperature), with their standard errors."""
    theta = _temperatures(data, temperature_c)
    parts = []
    for startup in (False, True):
        oil, both = _select(data, "oil", startup), _select(data, "oil_seal", startup)
        if not np.any(both):
            continue

        def keys(mask: NDArray[np.bool_], startup: bool = startup) -> list[tuple[float, ...]]:
            coordinates = (
                [data["pressure_mpa"][mask], theta[mask]] if startup else [data["speed_rpm"][mask], data["pressure_mpa"][mask], theta[mask]]
            )
            return list(zip(*(c.tolist() for c in coordinates), strict=True))

        oil_groups, seal_groups = _groups([(data["current_a"][oil], keys(oil)), (data["current_a"][both], keys(both))])
        oil_index = {key: k for k, key in enumerate(oil_groups.keys)}
        which = np.array([oil_index[key] for key in seal_groups.keys], dtype=np.int64)
        coordinates = np.array(seal_groups.keys, dtype=np.float64)
        if startup:
            coordinates = np.column_stack([np.zeros(len(coordinates)), coordinates])
        parts.append(
            (
                seal_groups.mean - oil_groups.mean[which],
                np.hypot(seal_groups.stderr, oil_groups.stderr[which]),
                coordinates,
                np.full(len(coordinates), startup),
                oil_groups.known and seal_groups.known,
            )
        )
    if not parts:
        raise ValueError("no 'oil_seal' rows to fit")
    scale = drive.ratio * drive.efficiency * drive.torque_constant
    coordinates = np.concatenate([part[2] for part in parts])
    return _Points(
        data=scale * np.concatenate([part[0] for part in parts]),
        cholesky=scale * np.diag(np.concatenate([part[1] for part in parts])),
        speed=coordinates[:, 0] * RPM,
        pressure_mpa=coordinates[:, 1],
        temperature_c=coordinates[:, 2],
        startup=np.concatenate([part[3] for part in parts]),
        known=all(part[4] for part in parts),
    )


#: The seal's parameters in the order of :class:`uwml.losses.Seal`.
_SEAL_NAMES = ("c0", "c1_per_mpa", "s0", "s1_per_mpa", "d0", "d1_per_mpa", "stribeck_speed")
#: Internal parameters ``(C0, C1, S0 − C0, S1 − C1, D0, D1, ω_s)`` → the seal's: ``S = C + excess``.
_SEAL_TRANSFORM = np.array(
    [
        [1, 0, 0, 0, 0, 0, 0],
        [0, 1, 0, 0, 0, 0, 0],
        [1, 0, 1, 0, 0, 0, 0],
        [0, 1, 0, 1, 0, 0, 0],
        [0, 0, 0, 0, 1, 0, 0],
        [0, 0, 0, 0, 0, 1, 0],
        [0, 0, 0, 0, 0, 0, 1],
    ],
    dtype=np.float64,
)
#: Points of the log grid that brackets the 1-D search for ω_s.
_STRIBECK_GRID = 49


def seal(
    data_or_path: Mapping[str, ArrayLike] | PathOrFile,
    drive: Drive = _DRIVE,
    *,
    stribeck_speed: float | None = None,
    stribeck_speed_bounds: tuple[float, float] = (1e-3, 10.0),
    temperature_c: float = _DEFAULT_TEMPERATURE_C,
    scale_covar: bool = True,
) -> SealFit:
    """Fit :class:`uwml.losses.Seal` to ``ΔI_seal = I_oil_seal − I_oil`` (module docstring).

    The model, as torque at the output, ``N η K_t ΔI_seal = sgn(ω) [C(p) + (S(p) − C(p))
    exp(−(ω/ω_s)²)] + D(p) ω`` for steady rows and ``S(p)`` for start-up rows.

    Parameters
    ----------
    data_or_path : mapping or str or path or text file
        Columns (as :func:`uwml.synthetic.three_configuration_experiment` returns) or a CSV file.
    drive : Drive
        Torque constant K_t, ratio N and efficiency η of the joint.
    stribeck_speed : float, optional
        Hold ω_s [rad/s] at this value (when the data have no speeds near it); None: fit it.
    stribeck_speed_bounds : (float, float)
        Search interval for ω_s [rad/s], ``0 < low < high``.
    temperature_c : float
        Temperature of the rows when the data have no ``temperature_c`` column [°C] (pairs
        ``oil_seal`` with ``oil`` rows; the seal model itself does not depend on it).
    scale_covar : bool
        Scale the covariance by the reduced χ² (lmfit's default). Always done when the data
        have no repeats.

    Returns
    -------
    SealFit
        ``params``: ``c0``, ``c1_per_mpa``, ``s0``, ``s1_per_mpa``, ``d0``, ``d1_per_mpa``,
        ``stribeck_speed``.

    Raises
    ------
    ValueError
        On invalid data (:func:`validate_loss_data`), no ``oil_seal`` rows, or invalid bounds
        or held ω_s.
    """
    low, high = (float(x) for x in stribeck_speed_bounds)
    if not (math.isfinite(low) and math.isfinite(high) and 0.0 < low < high):
        raise ValueError(f"stribeck_speed_bounds must be two finite numbers 0 < low < high, got {stribeck_speed_bounds!r}")
    if stribeck_speed is not None and not (math.isfinite(stribeck_speed) and stribeck_speed > 0.0):
        raise ValueError(f"stribeck_speed must be finite and > 0, got {stribeck_speed!r}")
    data = _load(data_or_path)
    points = _seal_points(data, drive, temperature_c)
    p = points.pressure_mpa
    # Start-up points are at ω → 0⁺: sign +1, Stribeck factor 1, no viscous part.
    sign = np.where(points.startup, 1.0, np.sign(points.speed))
    speed = np.where(points.startup, 0.0, points.speed)
    inverse_sigma = 1.0 / points.sigma

    def stribeck(omega_s: float) -> Array:
        return np.exp(-((speed / omega_s) ** 2))

    def design(omega_s: float) -> Array:
        e = stribeck(omega_s)
        return np.stack([sign, sign * p, sign * e, sign * e * p, speed, speed * p], axis=1)

    def levels(omega_s: float) -> tuple[Array, float]:
        """Best ``(C0, C1, S0 − C0, S1 − C1, D0, D1) ≥ 0`` for this ω_s, and its χ²."""
        a, b = design(omega_s) * inverse_sigma[:, None], points.data * inverse_sigma
        # The problem is convex: an unconstrained optimum inside the bounds is the bounded one.
        x = np.linalg.lstsq(a, b, rcond=None)[0]
        if np.any(x < 0.0):
            x = scipy.optimize.lsq_linear(a, b, bounds=(0.0, np.inf), method="bvls").x
        r = a @ x - b
        return x, float(r @ r)

    def model(x: Array) -> tuple[Array, Array]:
        omega_s = x[6] if stribeck_speed is None else stribeck_speed
        e = stribeck(omega_s)
        x_design = design(omega_s)
        f = x_design @ x[:6]
        if stribeck_speed is not None:
            return f, x_design
        d_omega_s = sign * (x[2] + x[3] * p) * e * 2.0 * speed**2 / omega_s**3
        return f, np.column_stack([x_design, d_omega_s])

    if stribeck_speed is None:
        omega_s0 = _stribeck_search(lambda log_omega_s: levels(math.exp(log_omega_s))[1], math.log(low), math.log(high))
        x0 = np.append(levels(omega_s0)[0], omega_s0)
        lower, upper = np.append(np.zeros(6), low), np.append(np.full(6, np.inf), high)
        names, transform = _SEAL_NAMES, _SEAL_TRANSFORM
    else:
        x0 = levels(stribeck_speed)[0]
        lower, upper = np.zeros(6), np.full(6, np.inf)
        names, transform = _SEAL_NAMES[:6], _SEAL_TRANSFORM[:6, :6]
    solution = _least_squares(points, model, x0, lower, upper)
    stats = _statistics(points, model(solution.x)[0], solution, names, transform, scale_covar)
    values = dict(zip(names, (transform @ solution.x).tolist(), strict=True))
    fixed = {} if stribeck_speed is None else {"stribeck_speed": float(stribeck_speed)}
    params = {name: float(values[name] if name in values else fixed[name]) for name in _SEAL_NAMES}
    stats["stderr"] = {name: stats["stderr"].get(name) for name in _SEAL_NAMES}
    return SealFit(
        params=params,
        var_names=names,
        fixed=fixed,
        init_values=dict(zip(names, (transform @ solution.init).tolist(), strict=True)),
        drive=drive,
        unit="N·m at the joint output",
        **stats,
    )


def _stribeck_search(chisqr: Callable[[float], float], low: float, high: float) -> float:
    """ω_s minimizing the profile ``chisqr(log ω_s)`` on ``[low, high]``: the best point of a
    log grid, refined by a bounded Brent search between its neighbours."""
    grid = np.linspace(low, high, _STRIBECK_GRID)
    values = [chisqr(float(x)) for x in grid]
    best = int(np.argmin(values))
    bracket = (float(grid[max(best - 1, 0)]), float(grid[min(best + 1, len(grid) - 1)]))
    result = scipy.optimize.minimize_scalar(chisqr, bounds=bracket, method="bounded")
    return math.exp(float(result.x) if result.fun <= values[best] else float(grid[best]))


# --------------------------------------------------------------------------------------------
# Hydrodynamic coefficients from the land/water experiment
# --------------------------------------------------------------------------------------------

#: Huber's threshold, in (weighted) standard errors of the data.
HUBER_SCALE = 1.345
#: σ of Gaussian noise per median absolute deviation.
_MAD_TO_SIGMA = 1.4826


@dataclass(frozen=True, eq=False, kw_only=True)
class HydroFit(FitResult):
    """Result of :func:`hydro_coefficients`: Cd and Cm (``params``) with the statistics of
    :class:`FitResult`.

    The data are ``−Δτ_motor − τ_buoy`` [N·m] of the selected joints, sample-major (all selected
    joints of sample 0, then of sample 1, …); ``time`` and ``joint`` give each point's time [s]
    and joint index.
    """

    time: Array
    joint: NDArray[np.int64]
    #: "leg", "link" or "direction".
    per: str
    #: The selected joints (0-based).
    joints: tuple[int, ...]
    #: Coefficients without a regressor on the selected joints, left out of the fit.
    dropped: tuple[str, ...]
    #: Where the log came from.
    source: str

    def _report_statistics(self) -> list[str]:
        lines = [f"    joints (0-based)   = {', '.join(str(j) for j in self.joints)}", f"    coefficients per   = {self.per}"]
        if self.dropped:
            lines.append(f"    dropped (no data)  = {', '.join(self.dropped)}")
        return lines

    def _summary_head(self) -> dict[str, Any]:
        return {"model": "hydro", "per": self.per, "joints": list(self.joints), "dropped": list(self.dropped), "source": self.source}

    def _point_coordinates(self) -> dict[str, list[Any]]:
        return {"time": [_json_float(x) for x in self.time], "joint": [int(x) for x in self.joint]}


def _hydro_log(log_or_path: Any, n_joints: int) -> Log:
    """A log of the whole experiment from a :class:`Log`, a file, or a (land, water) pair."""
    if isinstance(log_or_path, tuple | list):
        if len(log_or_path) != 2:
            raise ValueError(f"give one log of the whole experiment or a (land, water) pair of logs, got {len(log_or_path)} items")
        land, water = (item if isinstance(item, Log) else read_log(item, n_joints) for item in log_or_path)
        for item in (land, water):
            if item.n_joints != n_joints:
                raise ValueError(
                    f"{item.source}: row 1 (header), column 'q{item.n_joints}': the log has {item.n_joints} joints, the leg {n_joints}"
                )
        return align_logs(land, water)
    log = log_or_path if isinstance(log_or_path, Log) else read_log(log_or_path, n_joints)
    if log.n_joints != n_joints:
        raise ValueError(f"{log.source}: row 1 (header), column 'q{log.n_joints}': the log has {log.n_joints} joints, the leg {n_joints}")
    if log.tau_land is None or log.tau_water is None:
        raise ValueError(
            f"{log.source}: row 1 (header), column 'tau_land1': need tau_land and tau_water columns "
            "(or give a (land, water) pair of logs of one environment each)"
        )
    return log


#: Samples per chunk of the streamed hydro identification (the design of a chunk is at most
#: ``CHUNK_SAMPLES × J × 4N`` floats: 37 MB for all three joints of the paper leg per direction).
CHUNK_SAMPLES = 1 << 17

#: Default of ``hydro_coefficients(cache_bytes=...)``: designs up to this size stay in memory
#: between passes.
DESIGN_CACHE_BYTES = 1 << 30


def _positive(scale: Array) -> Array:
    """Per-joint scales, with zeros (a joint fitted exactly) replaced by the largest one (or 1)."""
    positive = scale > 0.0
    fallback = float(np.max(scale)) if np.any(positive) else 1.0
    return np.where(positive, scale, fallback)


@dataclass(frozen=True)
class _Moments:
    """Per selected joint ``j``: ``XⱼᵀXⱼ`` (``gram[j]``), ``Xⱼᵀyⱼ``, ``yⱼᵀyⱼ`` of the design."""

    gram: Array  # (J, P, P)
    xty: Array  # (J, P)
    yty: Array  # (J,)

    def kept(self, keep: NDArray[np.bool_]) -> _Moments:
        return _Moments(self.gram[:, keep][:, :, keep], self.xty[:, keep], self.yty)

    def weighted_gram(self, sigma_joint: Array) -> Array:
        return np.einsum("j,jab->ab", sigma_joint**-2.0, self.gram)

    def solve(self, sigma_joint: Array) -> Array:
        """Weighted least squares from the normal equations, with the columns scaled to unit
        norm first (the Gram matrix's condition number is then that of the correlations)."""
        gram = self.weighted_gram(sigma_joint)
        rhs = np.einsum("j,ja->a", sigma_joint**-2.0, self.xty)
        scale = np.sqrt(np.diag(gram))
        scale = np.where(scale > 0.0, scale, 1.0)
        return np.linalg.lstsq(gram / np.outer(scale, scale), rhs / scale, rcond=None)[0] / scale

    def residual_squares(self, x: Array) -> Array:
        """``|Xⱼx − yⱼ|²`` per joint, from the moments (an estimate of scale: it loses the
        digits that ``|y|²`` has beyond the residuals')."""
        return np.clip(self.yty - 2.0 * self.xty @ x + np.einsum("a,jab,b->j", x, self.gram, x), 0.0, None)


class _HydroDesign:
    """The identification design of a log (MODEL.md section 4) and its target
    ``y = −Δτ_motor − τ_buoy`` on the selected joints, assembled by the Rust core in one pass per
    chunk of samples; the chunks are kept while they fit into ``cache_bytes``."""

    def __init__(self, leg: Leg, log: Log, water: Water, per: str, joints: list[int], cache_bytes: int) -> None:
        assert log.qd is not None and log.qdd is not None and log.tau_land is not None and log.tau_water is not None
        self._leg, self._log, self._water, self._per, self._joints = leg, log, water, per, joints
        n_links = leg.n_joints
        self.names: list[str] = []
        for prefix in ("cd", "cm"):
            if per == "leg":
                self.names.append(prefix)
            elif per == "link":
                self.names += [f"{prefix}_link{link}" for link in range(n_links)]
            else:
                self.names += [f"{prefix}_link{link}_n{k}" for link in range(n_links) for k in range(2)]
        size = log.n_samples * len(joints) * (len(self.names) + 1) * 8
        self._cache: list[Array] | None = [] if size <= cache_bytes else None
        self._cached = False
        self._keep: NDArray[np.bool_] | None = None
        # The last coefficients given to `fitted`, and its result (the robust fit's last scale
        # estimate and the result's fitted values are of the same coefficients).
        self._last_fit: tuple[Array, tuple[Array, Array]] | None = None

    def keep(self, keep: NDArray[np.bool_]) -> None:
        """Leave out the design's columns where ``keep`` is False (coefficients then index the
        kept columns only)."""
        self._keep = keep

    def _full(self, x: Array) -> Array:
        """Kept-column coefficients as coefficients of every column (zero where dropped)."""
        if self._keep is None:
            return x
        full = np.zeros(self._keep.size)
        full[self._keep] = x
        return full

    def _compute(self, start: int, stop: int) -> Array:
        log = self._log
        assert log.qd is not None and log.qdd is not None and log.tau_land is not None and log.tau_water is not None
        rows = slice(start, stop)
        chunk = [np.ascontiguousarray(a[rows]) for a in (log.q, log.qd, log.qdd)]
        delta = np.ascontiguousarray(log.tau_water[rows] - log.tau_land[rows])
        return self._leg._chain.hydro_design(*chunk, delta, self._water.density, self._water.gravity, self._joints, self._per)

    def chunks(self) -> Iterator[Array]:
        """The problem chunk by chunk, joint-major ``(J, c, P + 1)``: every column's regressor,
        then the target ``y``."""
        if self._cached and self._cache is not None:
            yield from self._cache
            return
        n = self._log.n_samples
        for start in range(0, n, CHUNK_SAMPLES):
            chunk = self._compute(start, min(start + CHUNK_SAMPLES, n))
            if self._cache is not None:
                self._cache.append(chunk)
            yield chunk
        self._cached = self._cache is not None

    def moments(self) -> _Moments:
        """Per-joint moments of all columns, in one pass (one product ``[X y]ᵀ[X y]`` per joint
        and chunk)."""
        n_selected, p = len(self._joints), len(self.names)
        gram, xty, yty = np.zeros((n_selected, p, p)), np.zeros((n_selected, p)), np.zeros(n_selected)
        for chunk in self.chunks():
            for j, block in enumerate(chunk):
                g = block.T @ block
                gram[j] += g[:p, :p]
                xty[j] += g[:p, p]
                yty[j] += g[p, p]
        return _Moments(gram, xty, yty)

    def _table(self, values: Array) -> Array:
        """One kind of coefficient (the Cd or the Cm half of the columns) as a per link and
        direction table ``(n_links, 2)``."""
        n_links = self._leg.n_joints
        if self._per == "leg":
            return np.full((n_links, 2), values[0])
        if self._per == "link":
            return np.repeat(values[:, None], 2, axis=1)
        return values.reshape(n_links, 2)

    def fitted(self, x: Array) -> tuple[Array, Array]:
        """``(Xx, y)``, sample-major (all selected joints of sample 0, then sample 1, …).

        The torques are linear in the coefficients, so ``Xx`` is the drag plus added-mass torque
        at coefficients ``x`` (negative ones by a second evaluation at their magnitudes): a
        third of the cost of the design's regressors, and nothing to keep between passes."""
        if self._last_fit is not None and np.array_equal(self._last_fit[0], x):
            return self._last_fit[1]
        full = self._full(x)
        half = full.size // 2
        cd, cm = self._table(full[:half]), self._table(full[half:])
        log, leg, joints = self._log, self._leg, self._joints
        assert log.qd is not None and log.qdd is not None and log.tau_land is not None and log.tau_water is not None
        signs = (1.0, -1.0) if np.any(full < 0.0) else (1.0,)
        fits, targets = [], []
        for start in range(0, log.n_samples, CHUNK_SAMPLES):
            rows = slice(start, start + CHUNK_SAMPLES)
            fit = np.zeros((len(log.q[rows]), leg.n_joints))
            buoyancy = fit
            for sign in signs:
                tau = leg.hydro(
                    log.q[rows], log.qd[rows], log.qdd[rows], np.clip(sign * cd, 0.0, None), np.clip(sign * cm, 0.0, None), self._water
                )
                fit += sign * (tau.drag + tau.added_mass)
                buoyancy = tau.buoyancy
            target = -(log.tau_water[rows] - log.tau_land[rows]) - buoyancy
            fits.append(fit[:, joints].reshape(-1))
            targets.append(target[:, joints].reshape(-1))
        result = np.concatenate(fits), np.concatenate(targets)
        self._last_fit = (np.array(x), result)
        return result

    def residuals(self, x: Array) -> Array:
        """``Xx − y``, sample-major."""
        fit, y = self.fitted(x)
        return fit - y

    def huber(self, x: Array, sigma_joint: Array, scale: float, max_passes: int = 200) -> tuple[Array, int, bool]:
        """Huber's estimate by iteratively reweighted least squares from ``x``, on residuals
        whitened by ``sigma_joint``: ``(x, passes, converged)``. The weights are
        ``min(1, scale/|r|)``; the loss is convex, so the iteration converges to its unique
        minimum (the one ``scipy.optimize.least_squares(loss="huber")`` finds)."""
        keep = np.ones(len(self.names), dtype=bool) if self._keep is None else self._keep
        p = keep.size
        passes, converged = 0, False
        for passes in range(1, max_passes + 1):
            coefficients = np.append(self._full(x), -1.0)
            gram, rhs = np.zeros((p, p)), np.zeros(p)
            for chunk in self.chunks():
                r = (chunk @ coefficients) / sigma_joint[:, None]
                w = np.minimum(1.0, scale / np.maximum(np.abs(r), 1e-300)) * sigma_joint[:, None] ** -2.0
                for block, weights in zip(chunk, w, strict=True):
                    g = (block * weights[:, None]).T @ block
                    gram += g[:p, :p]
                    rhs += g[:p, p]
            gram, rhs = gram[keep][:, keep], rhs[keep]
            d = np.sqrt(np.diag(gram))
            d = np.where(d > 0.0, d, 1.0)
            new = np.linalg.lstsq(gram / np.outer(d, d), rhs / d, rcond=None)[0] / d
            converged = bool(np.all(np.abs(new - x) <= 1e-12 * (np.abs(new) + np.max(np.abs(new)) + 1e-300)))
            x = new
            if converged:
                break
        return x, passes, converged


def _huber_covariance(gram: Array, residual: Array, scale: float) -> Array | None:
    """Huber's covariance estimate of a fit with whitened residuals ``residual`` whose whitened
    design has the Gram matrix ``gram`` (``XᵀX``)."""
    n, p = residual.size, gram.shape[0]
    inside = np.abs(residual) <= scale
    mean_slope = float(np.mean(inside))
    if mean_slope == 0.0 or n <= p:
        return None
    psi = np.clip(residual, -scale, scale)
    k = 1.0 + (p / n) * mean_slope * (1.0 - mean_slope) / mean_slope**2
    factor = k**2 * float(psi @ psi) / (n - p) / mean_slope**2
    return factor * np.linalg.inv(gram)


def hydro_coefficients(
    log_or_path: Log | PathOrFile | tuple[Log | PathOrFile, Log | PathOrFile],
    leg: Leg | None = None,
    joints: ArrayLike = (0,),
    per: Literal["leg", "link", "direction"] = "leg",
    water: Water = Water(),  # noqa: B008 (immutable)
    robust: bool = False,
    n_joints: int | None = None,
    *,
    sigma: ArrayLike | None = None,
    scale_covar: bool = True,
    cache_bytes: int = DESIGN_CACHE_BYTES,
) -> HydroFit:
    """Fit Cd and Cm to a land/water experiment (module docstring, "Hydrodynamic coefficients").

    Parameters
    ----------
    log_or_path : Log, file, or (land, water) pair
        A log of the whole experiment (``tau_land*`` and ``tau_water*``), as a :class:`uwml.logs.Log`
        or a file (:func:`uwml.logs.read_log`); or a pair of logs of one environment each
        (``tau*``), aligned by time (:func:`uwml.logs.align_logs`). Missing velocities and
        accelerations are estimated (:meth:`uwml.logs.Log.with_derivatives`).
    leg : Leg, optional
        Default :meth:`uwml.Leg.paper`.
    joints : sequence of int
        The joints whose torques are fitted (0-based; default joint 0, the paper's joint 1).
    per : {"leg", "link", "direction"}
        One Cd and one Cm; one per link; one per link and normal direction.
    water : Water
        The fluid of the water run.
    robust : bool
        Huber's loss instead of squares (resists outliers).
    n_joints : int, optional
        The number of joints the log must have; default the leg's.
    sigma : float or sequence of float, optional
        Standard error of ``−Δτ`` per selected joint [N·m]; None: estimated.
    scale_covar : bool
        Scale the covariance by the reduced χ² (always done when ``sigma`` is estimated).
    cache_bytes : int
        The design is computed by the Rust core chunk by chunk and, while it takes no more than
        this, kept for the later passes; above, each pass computes it again (memory stays
        bounded by one chunk whatever the log's length).

    Returns
    -------
    HydroFit

    Raises
    ------
    ValueError
        On a bad log (naming file, row, column), a log whose number of joints is not the leg's,
        bad joints, ``per`` or ``sigma``, or when no coefficient has a regressor on the
        selected joints.
    """
    from .leg import Leg

    leg = Leg.paper() if leg is None else leg
    if per not in ("leg", "link", "direction"):
        raise ValueError(f"per must be 'leg', 'link' or 'direction', got {per!r}")
    expected = leg.n_joints if n_joints is None else int(n_joints)
    if expected != leg.n_joints:
        raise ValueError(f"n_joints ({n_joints}) differs from the leg's {leg.n_joints} joints")
    selected = [int(j) for j in np.atleast_1d(np.asarray(joints))]
    if not selected or len(set(selected)) != len(selected) or any(not 0 <= j < leg.n_joints for j in selected):
        raise ValueError(f"joints must be distinct indices in 0..{leg.n_joints - 1}, got {joints!r}")
    log = _hydro_log(log_or_path, expected).with_derivatives()
    assert log.qd is not None and log.qdd is not None and log.tau_land is not None and log.tau_water is not None

    n_samples, n_selected = log.n_samples, len(selected)
    known = sigma is not None
    given_sigma: Array | None = None
    if sigma is not None:
        # Checked before the pass over the log.
        given_sigma = np.broadcast_to(np.asarray(sigma, dtype=np.float64), (n_selected,)) if np.ndim(sigma) <= 1 else None
        if given_sigma is None or not np.all(np.isfinite(given_sigma)) or np.any(given_sigma <= 0.0):
            raise ValueError(f"sigma must be a positive number or one per selected joint ({n_selected}), got {sigma!r}")
    design = _HydroDesign(leg, log, water, per, selected, cache_bytes)
    moments = design.moments()
    keep = np.diag(moments.gram.sum(axis=0)) > 0.0
    dropped = tuple(name for name, k in zip(design.names, keep, strict=True) if not k)
    if not np.any(keep):
        raise ValueError(f"no coefficient has a regressor on joints {selected}: do they move?")
    design.keep(keep)
    moments = moments.kept(keep)
    names = [name for name, k in zip(design.names, keep, strict=True) if k]
    p = len(names)
    joint_of_row = np.tile(np.asarray(selected, dtype=np.int64), n_samples)

    def joint_scale_robust(x: Array) -> Array:
        r = design.residuals(x).reshape(n_samples, n_selected)
        return _positive(_MAD_TO_SIGMA * np.median(np.abs(r - np.median(r, axis=0)), axis=0))

    if given_sigma is not None:
        sigma_joint = np.array(given_sigma)
    elif robust:
        sigma_joint = joint_scale_robust(moments.solve(np.ones(n_selected)))
    else:
        first = moments.solve(np.ones(n_selected))
        sigma_joint = _positive(np.sqrt(moments.residual_squares(first) / max(n_samples - p / n_selected, 1.0)))
    x = moments.solve(sigma_joint)
    gram = moments.weighted_gram(sigma_joint)
    init: dict[str, float] = {}
    nfev, success = 1, True
    message = "linear least squares: normal equations accumulated over the log in one pass"
    method = "linear least squares"
    if robust:
        init = dict(zip(names, x.tolist(), strict=True))
        nfev = 0
        for _ in range(2):
            x, passes, success = design.huber(x, sigma_joint, HUBER_SCALE)
            nfev += passes
            if not known:
                sigma_joint = joint_scale_robust(x)
        gram = moments.weighted_gram(sigma_joint)
        message = "Huber's loss by iteratively reweighted least squares, " + ("converged" if success else "not converged")
        method = f"iteratively reweighted least squares (huber, f_scale = {HUBER_SCALE} σ)"
    if dropped:
        message += f"; dropped {', '.join(dropped)} (no regressor on joints {selected})"
    sigma_rows = np.tile(sigma_joint, n_samples)
    best_fit, y_flat = design.fitted(x)
    residual = (best_fit - y_flat) / sigma_rows
    solution = _Solution(x=x, init=x, jacobian=None, residual=residual, success=success, message=message, nfev=nfev, gram=gram)
    stats = _fit_statistics(y_flat, lambda v: v / sigma_rows, known, best_fit, solution, tuple(names), np.eye(p), scale_covar or not known)
    if robust and stats["covar"] is not None:
        stats |= _uncertainties(_huber_covariance(gram, residual, HUBER_SCALE), tuple(names))
    return HydroFit(
        params=dict(zip(names, x.tolist(), strict=True)),
        var_names=tuple(names),
        fixed={},
        init_values=init,
        sigma=sigma_rows,
        time=np.repeat(log.time, n_selected),
        joint=joint_of_row,
        per=per,
        joints=tuple(selected),
        dropped=dropped,
        source=log.source,
        unit="N·m (−Δτ_motor − τ_buoy)",
        method=method,
        **stats,
    )
