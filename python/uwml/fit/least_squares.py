"""The generalized least-squares engine of the loss fits: whitened points, the solver, statistics
and uncertainties.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.linalg
import scipy.optimize
import scipy.stats
from numpy.typing import NDArray

from ._types import Array

#: Relative singular value below which the Jacobian is taken as rank-deficient.
_RANK_TOLERANCE = 1e-10


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
        sigma: Array = np.sqrt(np.sum(self.cholesky**2, axis=1))
        return sigma

    def whiten(self, x: Array) -> Array:
        """``L⁻¹ x``: uncorrelated, unit-variance residuals from raw ones."""
        whitened: Array = scipy.linalg.solve_triangular(self.cholesky, x, lower=True)
        return whitened


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
            return np.asarray(np.linalg.svd(self.jacobian, compute_uv=False), dtype=np.float64)
        return np.asarray(np.sqrt(np.clip(np.linalg.eigvalsh(self.normal_matrix())[::-1], 0.0, None)), dtype=np.float64)

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
    ndata = len(data)
    chisqr = float(solution.residual @ solution.residual)
    ones, z = whiten(np.ones(ndata)), whiten(data)
    centred = z - ones * (ones @ z) / (ones @ ones)
    stats = _summary_statistics(ndata, chisqr, float(centred @ centred), solution, names, transform, scale_covar or not known)
    return stats | {"sigma_given": known, "residual": solution.residual, "best_fit": best_fit, "data": data}


def _summary_statistics(
    ndata: int, chisqr: float, total: float, solution: _Solution, names: tuple[str, ...], transform: Array, scaled: bool
) -> dict[str, Any]:
    """lmfit's statistics of a fit of ``ndata`` points from its weighted χ² and the weighted total
    sum of squares about the weighted mean (``total``), and the covariance of ``transform @ x``
    (times the reduced χ² if ``scaled``): all but the points and ``sigma_given``."""
    nvarys = len(names)
    nfree = ndata - nvarys
    redchi = chisqr / nfree if nfree > 0 else math.nan
    neg2_log_likelihood = ndata * math.log(max(chisqr, np.finfo(float).tiny) / ndata)
    covar, message = _parameter_covariance(solution, names, transform, nfree, redchi, scaled)
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
        "success": solution.success,
        "message": message,
        "nfev": solution.nfev,
    }


def _parameter_covariance(
    solution: _Solution, names: tuple[str, ...], transform: Array, nfree: int, redchi: float, scaled: bool
) -> tuple[Array | None, str]:
    """The covariance of ``transform @ x`` (None where the data do not determine it) and the
    solution's message with the reason; ``scaled``: times the reduced χ²."""
    covar: Array | None = None
    message = solution.message
    singular = solution.singular_values()
    gram = solution.normal_matrix()
    if nfree <= 0:
        message += "; no degrees of freedom left for uncertainties"
    elif singular.size < len(names) or singular[-1] <= solution.rank_tolerance() * singular[0]:
        weakest = names[int(np.argmin(np.diag(gram)))]
        message += f"; the data do not determine every parameter (singular Jacobian; least sensitive: {weakest})"
    else:
        covar = np.asarray(np.linalg.inv(gram), dtype=np.float64)
        if scaled:
            covar = covar * redchi
        covar = transform @ covar @ transform.T
    return covar, message


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
