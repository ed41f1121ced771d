"""Fit results in the style of lmfit: the statistics, report and JSON summary shared by every fit,
and the loss fits' results.
"""

from __future__ import annotations

import dataclasses
import functools
import math
from abc import ABC, abstractmethod
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.linalg
import scipy.optimize
import scipy.stats
from numpy.typing import ArrayLike, NDArray

from ..model.joint_losses import JointLosses
from ..model.losses import Drive, OilDrag, Seal
from ._types import Array

#: Correlations below this are left out of :meth:`LossFit.fit_report`.
_MIN_CORRELATION = 0.1


# --------------------------------------------------------------------------------------------
# Results
# --------------------------------------------------------------------------------------------


def _json_float(x: float | None) -> float | None:
    return None if x is None or not math.isfinite(x) else float(x)


def _json_floats(values: ArrayLike) -> list[float | None]:
    """An array as a JSON-safe list: non-finite entries as None. (Whole arrays at once: a fit
    of a long log has millions of points.)"""
    array = np.asarray(values, dtype=np.float64).ravel()
    finite = np.isfinite(array)
    numbers: list[float] = array.tolist()
    if finite.all():
        return list(numbers)
    return [x if ok else None for x, ok in zip(numbers, finite.tolist(), strict=True)]


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
    #: Whether the points' σ was given (else estimated from the residuals, which makes the
    #: weighted χ² about ``N − p`` and the reduced χ² 1 by construction).
    sigma_given: bool = True

    # --- unweighted statistics, in the data's units (Origin's and lmfit's without weights);
    # the two that pass over every point are computed once (a result's arrays never change) ---

    @functools.cached_property
    def rss(self) -> float:
        """Residual sum of squares, unweighted: ``Σ (data − best_fit)²`` [``unit``²]."""
        return float(np.sum((np.asarray(self.data) - np.asarray(self.best_fit)) ** 2))

    @property
    def squared_unit(self) -> str:
        """The unit of the unweighted χ² and RSS: the data's unit squared (``"N·m²"``)."""
        return f"{self.unit.split()[0]}²" if self.unit.strip() else ""

    @property
    def redchi_unweighted(self) -> float:
        """Reduced χ² without weights, ``RSS / (N − p)`` [``unit``²]: Origin's "Reduced Chi-Sqr"
        of a fit without error bars (the paper's 2.425 N·m²)."""
        return self.rss / self.nfree if self.nfree > 0 else math.nan

    @functools.cached_property
    def cod(self) -> float:
        """Coefficient of determination without weights, ``1 − RSS / Σ (data − mean)²`` (the
        paper's COD, 0.826)."""
        data = np.asarray(self.data)
        total = float(np.sum((data - data.mean()) ** 2))
        return 1.0 - self.rss / total if total > 0.0 else math.nan

    @property
    def adjusted_cod(self) -> float:
        """Adjusted R² without weights, ``1 − (1 − COD)(N − 1)/(N − p)`` (Origin's "Adj. R-Square")."""
        return 1.0 - (1.0 - self.cod) * (self.ndata - 1) / self.nfree if self.nfree > 0 else math.nan

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
        intervals = {}
        for name in self.var_names:
            value, error = self.params[name], self.stderr[name]
            assert error is not None  # a fit with error bars has one for every varied parameter
            intervals[name] = (value - t * error, value + t * error)
        return intervals

    #: What the weighted χ² means when σ was not given (the loss fits weigh every point 1).
    _unknown_sigma_note = " (σ not given: unit weights, as the unweighted value below)"

    def _report_statistics(self) -> list[str]:
        """Extra lines for the ``[[Fit Statistics]]`` block."""
        return []

    def fit_report(self, min_correl: float = _MIN_CORRELATION) -> str:
        """A readable report, as lmfit's: statistics, ``value +/- stderr (pct)``, correlations.

        The weighted statistics (χ², reduced χ², R²) come first, as lmfit prints them; when σ was
        not given it is estimated from the residuals and the report says that χ² and reduced χ²
        are then ≈ N − p and 1 by construction. The unweighted ones follow, in the data's units,
        as Origin prints a fit without error bars (the paper's reduced χ² and COD)."""
        weighted = "" if self.sigma_given else self._unknown_sigma_note
        squared = self.squared_unit
        lines = [
            "[[Fit Statistics]]",
            f"    # fitting method   = {self.method}",
            f"    # function evals   = {self.nfev}",
            f"    # data points      = {self.ndata}",
            f"    # variables        = {self.nvarys}",
            f"    chi-square         = {self.chisqr:.7g}{weighted}",
            f"    reduced chi-square = {self.redchi:.7g}{weighted}",
            f"    Akaike info crit   = {self.aic:.7g}",
            f"    Bayesian info crit = {self.bic:.7g}",
            f"    R-squared (COD)    = {self.rsquared:.7g} (weighted)",
            f"    data unit          = {self.unit}",
            f"    residual sum of squares, unweighted = {self.rss:.7g} {squared}",
            f"    reduced chi-square, unweighted      = {self.redchi_unweighted:.7g} {squared}",
            f"    COD, unweighted                     = {self.cod:.7g}",
            f"    adjusted COD, unweighted            = {self.adjusted_cod:.7g}",
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
                "data": _json_floats(self.data),
                "sigma": _json_floats(self.sigma),
                "best_fit": _json_floats(self.best_fit),
                "residual": _json_floats(self.residual),
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
            "sigma_given": bool(self.sigma_given),
            "rss": _json_float(self.rss),
            "redchi_unweighted": _json_float(self.redchi_unweighted),
            "cod": _json_float(self.cod),
            "adjusted_cod": _json_float(self.adjusted_cod),
            "aic": _json_float(self.aic),
            "bic": _json_float(self.bic),
            **self._summary_tail(),
        }


@dataclass(frozen=True, eq=False, kw_only=True)
class LossFit(FitResult, ABC):
    """Result of a loss fit, in the style of lmfit's ``MinimizerResult`` / ``ModelResult``.

    Parameters are in the units of :mod:`uwml.model.losses`; ``data``, ``sigma`` and ``best_fit`` are
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
    """Result of :func:`oil_drag`; ``model`` is the fitted :class:`uwml.model.losses.OilDrag`."""

    @property
    def model(self) -> OilDrag:
        """The fitted :class:`uwml.model.losses.OilDrag`."""
        return OilDrag(**self.params)

    def eval(self, speed: ArrayLike, pressure_mpa: ArrayLike, temperature_c: ArrayLike = 20.0) -> Array:
        """``T_oil`` [N·m at the motor shaft] at output speed ``speed`` [rad/s] (motor speed N ω)."""
        # The loss current of the oil alone with K_t = 1 is T_oil itself (the core's, hard sign).
        drive = dataclasses.replace(self.drive, torque_constant=1.0)
        oil = JointLosses(drive=drive, oil=self.model, seal=None, epsilon=0.0)
        return oil.torques(speed, pressure_mpa, temperature_c).current


@dataclass(frozen=True, eq=False)
class SealFit(LossFit):
    """Result of :func:`seal`; ``model`` is the fitted :class:`uwml.model.losses.Seal`."""

    @property
    def model(self) -> Seal:
        """The fitted :class:`uwml.model.losses.Seal`."""
        return Seal(**self.params)

    def eval(self, speed: ArrayLike, pressure_mpa: ArrayLike, temperature_c: ArrayLike = 20.0) -> Array:
        """``T_seal`` [N·m at the output] at output speed ``speed`` [rad/s] (temperature unused)."""
        # The core's seal torque, an environment torque (−T_seal), hard sign; no temperature law.
        seal = JointLosses(drive=self.drive, oil=None, seal=self.model, epsilon=0.0)
        return -seal.torques(speed, pressure_mpa).seal
