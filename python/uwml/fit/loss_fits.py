"""The oil-drag and seal fits of the three-configuration experiment (:func:`oil_drag`,
:func:`seal`).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping

import numpy as np
import scipy.linalg
import scipy.optimize
import scipy.stats
from numpy.typing import ArrayLike, NDArray

from ..model.losses import RPM, Drive, OilDrag
from ._types import Array, Columns, PathOrFile
from .fit_results import OilDragFit, SealFit
from .least_squares import _least_squares, _Points, _statistics
from .loss_data import _DEFAULT_TEMPERATURE_C, _groups, _load, _select, _temperatures

#: The default drive (the paper's hip-roll joint, illustrative K_t and η).
_DRIVE = Drive()


# --------------------------------------------------------------------------------------------
# Oil drag
# --------------------------------------------------------------------------------------------


def _oil_points(data: Columns, drive: Drive, temperature_c: float) -> _Points:
    """``T_oil = K_t (I_oil − I_dry(ω))`` per (speed, pressure, temperature), with covariance."""
    theta = _temperatures(data, temperature_c)
    dry, oil = _select(data, "dry", False), _select(data, "oil", False)
    if not np.any(oil):
        raise ValueError("no steady 'oil' rows to fit")
    dry_keys: list[tuple[float, ...]] = [(s,) for s in data["speed_rpm"][dry].tolist()]
    oil_keys: list[tuple[float, ...]] = list(
        zip(data["speed_rpm"][oil].tolist(), data["pressure_mpa"][oil].tolist(), theta[oil].tolist(), strict=True)
    )
    dry_groups, oil_groups = _groups([(data["current_a"][dry], dry_keys), (data["current_a"][oil], oil_keys)])
    dry_index = {key[0]: k for k, key in enumerate(dry_groups.keys)}
    which_dry = np.array([dry_index[key[0]] for key in oil_groups.keys], dtype=np.int64)
    same_speed = which_dry[:, None] == which_dry[None, :]
    covariance = np.diag(oil_groups.stderr**2) + np.where(same_speed, dry_groups.stderr[which_dry][:, None] ** 2, 0.0)
    kt = drive.torque_constant
    coordinates = np.array(oil_groups.keys, dtype=np.float64)
    return _Points(
        data=kt * (oil_groups.mean - dry_groups.mean[which_dry]),
        cholesky=kt * np.asarray(np.linalg.cholesky(covariance), dtype=np.float64),
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
    """Fit :class:`uwml.model.losses.OilDrag` to ``ΔI_oil = I_oil − I_dry(ω)`` (module docstring).

    The model, at motor speed ``ω_m = N ω`` and as torque at the motor shaft,
    ``T_oil = K_t ΔI_oil = K_oil exp(a_p (p − p_ref)) exp(−a_T (θ − θ_ref)) ω_m^n``.

    Parameters
    ----------
    data_or_path : mapping or str or path or text file
        Columns (as :func:`uwml.paper.synthetic.three_configuration_experiment` returns) or a CSV file.
    drive : Drive
        Torque constant K_t and ratio N of the joint (``torque_constant=1`` to fit in amperes).
    temperature_sensitivity_per_k : float, optional
        Hold a_T [1/K] at this value (e.g. from :func:`uwml.sea.oil.drag_temperature_sensitivity`).
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
    fit_temperature = temperature_sensitivity_per_k is None and bool(np.ptp(points.temperature_c) > 0.0)
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


#: The seal's parameters in the order of :class:`uwml.model.losses.Seal`.
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
    """Fit :class:`uwml.model.losses.Seal` to ``ΔI_seal = I_oil_seal − I_oil`` (module docstring).

    The model, as torque at the output, ``N η K_t ΔI_seal = sgn(ω) [C(p) + (S(p) − C(p))
    exp(−(ω/ω_s)²)] + D(p) ω`` for steady rows and ``S(p)`` for start-up rows.

    Parameters
    ----------
    data_or_path : mapping or str or path or text file
        Columns (as :func:`uwml.paper.synthetic.three_configuration_experiment` returns) or a CSV file.
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
        x = np.asarray(np.linalg.lstsq(a, b, rcond=None)[0], dtype=np.float64)
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

    names: tuple[str, ...]
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
