"""A log's sampling: the time column's domain, its step, and derivatives estimated from it by a
Savitzky-Golay filter (the rules are in :mod:`uwml.io.logs`, "Derivatives")."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["MAX_TIME_S", "POLYORDER", "UNIFORM_TOLERANCE", "WINDOW_S", "estimate_derivatives", "estimate_rates", "savgol_window"]

Array = NDArray[np.float64]

#: Time covered by the Savitzky-Golay window [s].
WINDOW_S = 0.1
#: Polynomial order of the Savitzky-Golay filter.
POLYORDER = 3
#: Largest relative deviation of a time step from the median step for derivative estimation.
UNIFORM_TOLERANCE = 0.01
#: Largest magnitude of a time stamp [s] (:mod:`uwml.io.logs`).
MAX_TIME_S = 1e10


def savgol_window(rate_hz: float, window_s: float = WINDOW_S, polyorder: int = POLYORDER) -> int:
    """The Savitzky-Golay window [samples] of the window rule (:mod:`uwml.io.logs`, "Derivatives")."""
    if not (math.isfinite(rate_hz) and rate_hz > 0.0):
        raise ValueError(f"rate_hz must be finite and > 0, got {rate_hz!r}")
    if not (math.isfinite(window_s) and window_s > 0.0):
        raise ValueError(f"window_s must be finite and > 0, got {window_s!r}")
    window = 2 * round(0.5 * window_s * rate_hz) + 1
    smallest = polyorder + 2 + (polyorder + 2 + 1) % 2
    return max(int(window), smallest)


def estimate_derivatives(
    time: ArrayLike, q: ArrayLike, window_s: float = WINDOW_S, polyorder: int = POLYORDER, *, source: str = "<log>"
) -> tuple[Array, Array]:
    """Velocities and accelerations of ``q`` (shape ``(n, n_joints)``) by a Savitzky-Golay filter.

    Raises
    ------
    ValueError
        Naming the first row (the header is row 1) whose time step is not within
        ``UNIFORM_TOLERANCE`` of the median step, or when the log is shorter than the window.
    """
    dt, qd, qdd = _filtered(time, q, "q (n, n_joints)", window_s, polyorder, source)
    _check_derivatives(qd, qdd, source, dt)
    return qd, qdd


def _filtered(time: ArrayLike, x: ArrayLike, what: str, window_s: float, polyorder: int, source: str) -> tuple[float, Array, Array]:
    """The time step, and the first and second derivatives of ``x`` (rows: the samples of
    ``time``; ``what`` names its shape in the error) by the Savitzky-Golay filter."""
    t = np.asarray(time, dtype=np.float64)
    values = np.asarray(x, dtype=np.float64)
    if t.ndim != 1 or values.ndim != 2 or values.shape[0] != t.shape[0]:
        raise ValueError(f"{source}: time must have shape (n,) and {what}, got {t.shape} and {values.shape}")
    dt, window = _sampling(t, window_s, polyorder, source)
    first, second = _savgol(values, window, polyorder, dt)
    return dt, first, second


def _sampling(t: Array, window_s: float, polyorder: int, source: str) -> tuple[float, int]:
    """The time step [s] and the Savitzky-Golay window [samples] of a log's time column, checked
    as :func:`estimate_derivatives` says."""
    if t.size < 2:
        raise ValueError(f"{source}: row 2, column 'time': need at least 2 samples to estimate derivatives")
    _check_time(t, source)
    step = np.diff(t)
    dt = float(np.median(step))
    bad = np.flatnonzero(~(np.abs(step - dt) <= UNIFORM_TOLERANCE * dt))
    if bad.size:
        i = int(bad[0])
        raise ValueError(
            f"{source}: row {i + 3}, column 'time': non-uniform sampling (step {step[i]:.6g} s, median {dt:.6g} s); "
            "velocities and accelerations are estimated by a Savitzky-Golay filter, which needs uniform sampling: "
            "resample the log, or give qd and qdd columns"
        )
    rate = 1.0 / dt
    if not math.isfinite(rate):  # a subnormal step
        raise ValueError(f"{source}: row 3, column 'time': median time step {dt!r} s, too short to estimate derivatives")
    window = savgol_window(rate, window_s, polyorder)
    if window > t.size:
        count = str(window) if window < 10**9 else f"{float(window):.3g}"
        raise ValueError(
            f"{source}: row {t.size + 1}, column 'time': {t.size} samples, fewer than the Savitzky-Golay window ({count} samples: "
            f"{window_s:g} s at a median time step of {dt:.6g} s)"
        )
    return dt, window


def _savgol(positions: Array, window: int, polyorder: int, dt: float) -> tuple[Array, Array]:
    # Imported here: scipy.signal takes most of a second to import, and `import uwml` should not.
    from scipy.signal import savgol_filter

    # Overflow gives inf (or NaN), refused by _check_derivatives, not a warning.
    with np.errstate(over="ignore", invalid="ignore"):
        qd = savgol_filter(positions, window, polyorder, deriv=1, delta=dt, axis=0, mode="interp")
        qdd = savgol_filter(positions, window, polyorder, deriv=2, delta=dt, axis=0, mode="interp")
    return np.asarray(qd, dtype=np.float64), np.asarray(qdd, dtype=np.float64)


def _check_derivatives(qd: Array, qdd: Array, source: str, dt: float, first_row: int = 2) -> None:
    """Estimated velocities and accelerations finite, or a ValueError naming the first row
    (``first_row`` for the first sample) and the joint's position column."""
    for what, unit, values in (("velocity", "rad/s", qd), ("acceleration", "rad/s²", qdd)):
        bad = np.flatnonzero(~np.isfinite(values).all(axis=1))
        if bad.size:
            i = int(bad[0])
            k = int(np.flatnonzero(~np.isfinite(values[i]))[0])
            raise ValueError(
                f"{source}: row {i + first_row}, column 'q{k + 1}': the estimated {what} [{unit}] is not finite: the positions "
                f"change too much for a time step of {dt:.6g} s"
            )


def estimate_rates(
    time: ArrayLike,
    x: ArrayLike,
    window_s: float = WINDOW_S,
    polyorder: int = POLYORDER,
    *,
    source: str = "<log>",
    columns: Sequence[str] = ("u", "v", "w", "p", "q", "r"),
) -> Array:
    """The time derivative of ``x`` (shape ``(n, k)``: a vehicle's twist) by the Savitzky-Golay
    filter of :func:`estimate_derivatives`, with its checks; errors name the column of ``columns``
    (one per column of ``x``)."""
    dt, rates, _ = _filtered(time, x, f"{', '.join(columns)} (n, {len(columns)})", window_s, polyorder, source)
    bad = np.flatnonzero(~np.isfinite(rates).all(axis=1))
    if bad.size:
        i = int(bad[0])
        k = int(np.flatnonzero(~np.isfinite(rates[i]))[0])
        raise ValueError(f"{source}: row {i + 2}, column {columns[k]!r}: its estimated rate is not finite for a time step of {dt:.6g} s")
    return rates


def _check_time(time: Array, source: str, first_row: int = 2) -> None:
    """The time column in its domain (module docstring): finite, within ±MAX_TIME_S, strictly
    increasing, or a ValueError naming the row (``first_row`` for ``time[0]``)."""
    outside = np.flatnonzero(~(np.abs(time) <= MAX_TIME_S))
    if outside.size:
        i = int(outside[0])
        value = float(time[i])
        if not math.isfinite(value):
            raise ValueError(f"{source}: row {i + first_row}, column 'time': expected a finite number, got {value!r}")
        raise ValueError(
            f"{source}: row {i + first_row}, column 'time': {value!r} s is beyond ±{MAX_TIME_S:g} s (317 years): "
            "time must be in seconds (Unix time in seconds fits; milli- or nanosecond stamps do not)"
        )
    bad = np.flatnonzero(np.diff(time) <= 0.0)
    if bad.size:
        i = int(bad[0]) + 1
        raise ValueError(
            f"{source}: row {i + first_row}, column 'time': time must increase strictly ({float(time[i - 1])!r} then {float(time[i])!r})"
        )
