"""Cd and Cm from the land/water experiment (:func:`hydro_coefficients`): the streamed design,
weighted and robust linear least squares.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..io.logs import Log
from ..model.parts import Water
from ..robot.presets import paper_leg
from ..robot.tree import Robot
from ._types import Array, PathOrFile
from .design import DESIGN_CACHE_BYTES, _HydroDesign
from .fit_results import FitResult, _json_float, _json_floats
from .least_squares import _fit_statistics, _Solution, _summary_statistics, _uncertainties
from .log_set import LogSet, log_set
from .robot_design import BASE_ROWS, _RobotHydroDesign

# --------------------------------------------------------------------------------------------
# Hydrodynamic coefficients from the land/water experiment
# --------------------------------------------------------------------------------------------

#: Huber's threshold, in (weighted) standard errors of the data.
HUBER_SCALE = 1.345
#: σ of Gaussian noise per median absolute deviation.
_MAD_TO_SIGMA = 1.4826


@dataclass(frozen=True)
class LogDiagnostics:
    """One log of a fit over several (:attr:`HydroFit.logs`): its ``rows`` (samples), the RMS of
    its residuals (``residual_rms``, unweighted, in the data's unit), its own least-squares fit
    from its own normal equations with the pooled fit's weights (``params``; None where its data
    do not determine every coefficient), and whether it ``disagrees`` with the pooled fit by more
    than 3σ: its weighted χ² per point, relative to the pooled fit's, exceeds 1 by more than three
    standard deviations of a χ² of its ``n`` points (``1 + 3 √(2/n)``)."""

    source: str
    rows: int
    residual_rms: float
    params: dict[str, float] | None
    disagrees: bool


@dataclass(frozen=True, eq=False, kw_only=True)
class HydroFit(FitResult):
    """Result of :func:`hydro_coefficients`: Cd and Cm (``params``) with the statistics of
    :class:`FitResult`.

    The data are ``−Δτ_motor − τ_buoy`` [N·m] of the selected joints (and ``−ΔW − W_buoy`` [N,
    N·m] of the selected components of the base's wrench), sample-major (all selected rows of
    sample 0, then of sample 1, …); ``time`` and ``joint`` give each point's time [s] and joint
    index (``-1 … -6`` for the base wrench's ``fx … mz``).
    """

    time: Array
    joint: NDArray[np.int64]
    #: "leg", "link" or "direction".
    per: str
    #: The selected joints (0-based).
    joints: tuple[int, ...]
    #: The selected components of the base's wrench (0 … 5: fx, fy, fz, mx, my, mz).
    base: tuple[int, ...] = ()
    #: Coefficients without a regressor on the selected joints, left out of the fit.
    dropped: tuple[str, ...]
    #: Where the log came from.
    source: str
    #: Each log's diagnostics, in the order read (one entry for one log).
    logs: tuple[LogDiagnostics, ...] = ()

    #: Without σ, the hydrodynamic fit estimates each joint's from the residuals.
    _unknown_sigma_note = " (weighted by σ estimated from the residuals: ≈ N − p and 1 by construction)"

    def _report_statistics(self) -> list[str]:
        numbered = ", ".join(str(j + 1) for j in self.joints) or "none"
        lines = [
            f"    joints             = {numbered} (numbered from 1, as --joints and the columns q1 …)",
            f"    coefficients per   = {self.per}",
        ]
        if self.base:
            lines.insert(1, f"    base wrench rows   = {', '.join(BASE_ROWS[c] for c in self.base)}")
        if self.dropped:
            lines.append(f"    dropped (no data)  = {', '.join(self.dropped)}")
        if len(self.logs) > 1:
            disagreeing = [log.source for log in self.logs if log.disagrees]
            lines.append(f"    logs               = {len(self.logs)}, {sum(log.rows for log in self.logs)} rows")
            lines.append(f"    disagreeing (> 3σ) = {', '.join(disagreeing) if disagreeing else 'none'}")
        return lines

    def _summary_head(self) -> dict[str, Any]:
        return {
            "model": "hydro",
            "per": self.per,
            "joints": list(self.joints),
            "base": [BASE_ROWS[c] for c in self.base],
            "dropped": list(self.dropped),
            "source": self.source,
            "logs": [
                {"source": log.source, "rows": log.rows, "residual_rms": _json_float(log.residual_rms), "disagrees": log.disagrees}
                for log in self.logs
            ],
        }

    def _point_coordinates(self) -> dict[str, list[Any]]:
        return {"time": _json_floats(self.time), "joint": np.asarray(self.joint, dtype=np.int64).tolist()}


def _reduced_statistics(
    sums: list[Array],
    sigma_joint: Array,
    solution: _Solution,
    names: tuple[str, ...],
    design: _HydroDesign,
    logs: LogSet,
    keep: NDArray[np.bool_],
    scaled: bool,
    known: bool,
) -> tuple[dict[str, Any], tuple[LogDiagnostics, ...]]:
    """:func:`_fit_statistics` of a fit from its logs' residual sums (``design.residual_sums``:
    per log and row, the samples, ``Σ r²``, ``Σ y``, ``Σ y²``), without its points; and each
    log's :class:`LogDiagnostics`."""
    total: Array = np.sum(sums, axis=0)
    weights = sigma_joint**-2.0
    n_rows, squares, y_sum, y_squares = total
    ndata = round(float(n_rows.sum()))
    # Σ (y − m)²/σ² about the weighted mean m, and Σ (y − ȳ)² about the plain one.
    weighted_total = float(weights @ y_squares - (weights @ y_sum) ** 2 / (weights @ n_rows))
    plain_total = float(y_squares.sum() - y_sum.sum() ** 2 / ndata)
    rss = float(squares.sum())
    stats = _summary_statistics(ndata, float(weights @ squares), weighted_total, solution, names, np.eye(len(names)), scaled)
    empty = np.empty(0)
    stats |= {"sigma_given": known, "residual": empty, "best_fit": empty, "data": empty}
    stats |= {"rss": rss, "cod": 1.0 - rss / plain_total if plain_total > 0.0 else math.nan}
    per_log = [(float(s[0].sum()), float(s[1].sum()), float(weights @ s[1])) for s in sums]
    return stats, _diagnostics(design, logs, keep, sigma_joint, per_log)


def _log_diagnostics(
    design: _HydroDesign, logs: LogSet, keep: NDArray[np.bool_], sigma_joint: Array, residual: Array, whitened: Array
) -> tuple[LogDiagnostics, ...]:
    """Each log's :class:`LogDiagnostics` from the fit's points (``residual`` unweighted and
    ``whitened``, sample-major)."""
    n_selected = sigma_joint.size
    per_log, start = [], 0
    for item in logs.items:
        points = slice(start * n_selected, (start + item.n_samples) * n_selected)
        start += item.n_samples
        per_log.append(
            (float(whitened[points].size), float(residual[points] @ residual[points]), float(whitened[points] @ whitened[points]))
        )
    return _diagnostics(design, logs, keep, sigma_joint, per_log)


def _diagnostics(
    design: _HydroDesign, logs: LogSet, keep: NDArray[np.bool_], sigma_joint: Array, per_log: list[tuple[float, float, float]]
) -> tuple[LogDiagnostics, ...]:
    """Each log's :class:`LogDiagnostics` from its points' count, ``Σ r²`` and ``Σ (r/σ)²``
    (``per_log``), and its own normal equations (``design.log_moments``)."""
    names = [name for name, k in zip(design.names, keep, strict=True) if k]
    count_all = sum(count for count, _, _ in per_log)
    pooled = sum(chi for _, _, chi in per_log) / count_all if count_all else math.nan
    out = []
    for item, moments, (count, squares, chi) in zip(logs.items, design.log_moments, per_log, strict=True):
        rms = math.sqrt(squares / count) if count else math.nan
        ratio = chi / count / pooled if count and pooled > 0.0 else math.nan
        disagrees = len(logs.items) > 1 and ratio > 1.0 + 3.0 * math.sqrt(2.0 / max(count, 1.0))
        own = moments.kept(keep)
        gram = own.weighted_gram(sigma_joint)
        eigenvalues = np.linalg.eigvalsh(gram) if gram.size else np.zeros(0)
        determined = bool(eigenvalues.size and eigenvalues[0] > 1e-10 * eigenvalues[-1])
        params = dict(zip(names, own.solve(sigma_joint).tolist(), strict=True)) if determined else None
        out.append(LogDiagnostics(item.source, item.n_samples, rms, params, bool(disagrees)))
    return tuple(out)


def _base_words(components: list[int]) -> str:
    return f" and base rows {', '.join(BASE_ROWS[c] for c in components)}" if components else ""


def _positive(scale: Array) -> Array:
    """Per-joint scales, with zeros (a joint fitted exactly) replaced by the largest one (or 1)."""
    positive = scale > 0.0
    fallback = float(np.max(scale)) if np.any(positive) else 1.0
    return np.where(positive, scale, fallback)


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
    covariance: Array = factor * np.asarray(np.linalg.inv(gram), dtype=np.float64)
    return covariance


def hydro_coefficients(
    log_or_path: Log | PathOrFile | tuple[Log | PathOrFile, Log | PathOrFile],
    leg: Robot | None = None,
    joints: ArrayLike = (0,),
    per: Literal["leg", "link", "direction"] = "leg",
    water: Water | None = None,
    robust: bool = False,
    n_joints: int | None = None,
    *,
    sigma: ArrayLike | None = None,
    scale_covar: bool = True,
    cache_bytes: int = DESIGN_CACHE_BYTES,
    base: ArrayLike = (),
    lumped: Literal["diagonal", "full", "given"] = "diagonal",
    on_ray: bool = False,
    address: str | None = None,
    workers: int | None = None,
    points: bool = True,
    columns: Any = None,
) -> HydroFit:
    """Fit Cd and Cm (and a robot's axial drag and lumped models) to a land/water experiment
    (module docstring, "Hydrodynamic coefficients").

    Parameters
    ----------
    log_or_path : Log, file, or (land, water) pair
        A log of the whole experiment (``tau_land*`` and ``tau_water*``), as a :class:`uwml.io.logs.Log`
        or a file (:func:`uwml.io.logs.read_log`); or a pair of logs of one environment each
        (``tau*``), aligned by time (:func:`uwml.io.logs.align_logs`). Missing velocities and
        accelerations are estimated (:meth:`uwml.io.logs.Log.with_derivatives`).
    leg : Robot, optional
        Default :func:`uwml.paper_leg`. Any :class:`uwml.Robot` (a tree, from a URDF, MJCF or
        model file) is on a fixed, upright base in still water, as the leg on its test stand;
        its columns are per body: the base (``base``, if it has segments: on a fixed base they
        are zero and dropped) and every link (``cd_<name>``, or ``cd_link<i>`` for an unnamed
        link), a circular segment's in ``n0``'s column; with its axial drag and lumped models
        (:mod:`uwml.fit.robot_design`), and its base moving as the log's vehicle columns say
        (twist ``u … r``, orientation ``qw … qz``: docs/logs.md).
    joints : sequence of int
        The joints whose torques are fitted (0-based; default joint 0, the paper's joint 1; may
        be empty when ``base`` is not).
    per : {"leg", "link", "direction"}
        One Cd and one Cm for the whole leg or robot; one per link; one per link and normal
        direction.
    water : Water, optional
        The fluid of the water run; default fresh water (a robot: its own, :attr:`uwml.Robot.water`).
    robust : bool
        Huber's loss instead of squares (resists outliers).
    n_joints : int, optional
        The number of joints the log must have; default the leg's.
    sigma : float or sequence of float, optional
        Standard error of ``−Δτ`` per selected row (the joints, then the base's components)
        [N·m, N]; None: estimated.
    scale_covar : bool
        Scale the covariance by the reduced χ² (always done when ``sigma`` is estimated).
    base : sequence of int
        A robot's base wrench components fitted too (0 … 5: fx, fy, fz, mx, my, mz): a captive
        test, the rig's wrench on the vehicle in both runs (``fx_land … mz_land``, ``fx_water …
        mz_water``) with its twist (``u, v, w, p, q, r``, its rate ``u_dot … r_dot`` estimated
        where absent) and orientation (``qw, qx, qy, qz`` or ``roll, pitch, yaw``, upright where
        absent; docs/logs.md); how a hull is identified.
    lumped : {"diagonal", "full", "given"}
        Which entries of a robot's lumped models are fitted (:mod:`uwml.fit.robot_design`).
    on_ray, address, workers : bool, str, int
        Share the logs out among Ray workers, each reducing its own (:mod:`uwml.fit.on_ray`): on
        the Ray this process runs, else the cluster at ``address``, else a local Ray of
        ``workers`` CPUs started for the fit. The result is the one-process fit's.
    points : bool
        Keep every fitted point's data, fit and residual in the result (about 6 floats a point).
        False: the statistics come from sums over the logs (:func:`_reduced_statistics`), and the
        result's per-point arrays are empty, so that memory stays bounded whatever the logs'
        length; plain least squares only (a robust fit's scale is a median of the points).
    columns : path, dict or ColumnMap, optional
        A column map (:mod:`uwml.io.column_map`) every file is read through (each then read
        whole).
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
    leg = paper_leg() if leg is None else leg
    if not isinstance(leg, Robot):
        raise TypeError(f"leg must be a uwml.Robot, got {type(leg).__name__}")
    what = "the robot"
    if water is None:
        water = leg.water
    if per not in ("leg", "link", "direction"):
        raise ValueError(f"per must be 'leg', 'link' or 'direction', got {per!r}")
    expected = leg.n_joints if n_joints is None else int(n_joints)
    if expected != leg.n_joints:
        raise ValueError(f"n_joints ({n_joints}) differs from {what}'s {leg.n_joints} joints")
    selected_joints = [int(j) for j in np.atleast_1d(np.asarray(joints))]
    components = [int(c) for c in np.atleast_1d(np.asarray(base))]
    if len(set(components)) != len(components) or any(not 0 <= c < 6 for c in components):
        raise ValueError(f"base must be distinct components in 0..5 (fx, fy, fz, mx, my, mz), got {base!r}")
    if lumped not in ("diagonal", "full", "given"):
        raise ValueError(f"lumped must be 'diagonal', 'full' or 'given', got {lumped!r}")
    if robust and not points:
        raise ValueError("points=False takes plain least squares: a robust fit's scale is a median of its points")
    if (
        (not selected_joints and not components)
        or len(set(selected_joints)) != len(selected_joints)
        or any(not 0 <= j < leg.n_joints for j in selected_joints)
    ):
        raise ValueError(f"joints must be distinct indices in 0..{leg.n_joints - 1} (at least one, or base rows), got {joints!r}")
    log = log_set(log_or_path, expected, what, torques=bool(selected_joints), wrench=bool(components), columns=columns)
    # The rows fitted: the selected joints, then the base's components; as rows of the whole
    # robot's regressors (base 0 … 5, joint j at 6 + j) and as the points' labels.
    selected = selected_joints + [-1 - c for c in components]
    rows = [6 + j for j in selected_joints] + components

    n_selected = len(selected)
    known = sigma is not None
    given_sigma: Array | None = None
    if sigma is not None:
        # Checked before the pass over the log.
        given_sigma = np.broadcast_to(np.asarray(sigma, dtype=np.float64), (n_selected,)) if np.ndim(sigma) <= 1 else None
        if given_sigma is None or not np.all(np.isfinite(given_sigma)) or np.any(given_sigma <= 0.0):
            raise ValueError(
                f"sigma must be a positive number or one per selected row ({n_selected}: the joints, then the base components), got {sigma!r}"
            )
    what_is_fitted = (log, selected, selected_joints, components, per, robust, known, given_sigma, scale_covar, points)
    if not on_ray:
        return _fit(_RobotHydroDesign(leg, log, water, per, rows, cache_bytes, lumped), *what_is_fitted)
    from .._ray import ray_session
    from .on_ray import RayDesign

    with ray_session(address, workers) as ray:
        spread = RayDesign(ray, leg, log, water, per, rows, cache_bytes, lumped)
        try:
            return _fit(spread, *what_is_fitted)
        finally:
            spread.close()


def _fit(
    design: _HydroDesign,
    log: LogSet,
    selected: list[int],
    selected_joints: list[int],
    components: list[int],
    per: str,
    robust: bool,
    known: bool,
    given_sigma: Array | None,
    scale_covar: bool,
    points: bool = True,
) -> HydroFit:
    """The fit of ``design`` (module docstring): its normal equations, weights, the robust
    iteration, the statistics and the result (``points``: with its per-point arrays)."""
    n_samples, n_selected = log.n_samples, len(selected)
    moments = design.moments()
    keep = np.diag(moments.gram.sum(axis=0)) > 0.0
    dropped = tuple(name for name, k in zip(design.names, keep, strict=True) if not k)
    if not np.any(keep):
        raise ValueError(f"no coefficient has a regressor on joints {selected_joints}{_base_words(components)}: do they move?")
    design.keep(keep)
    moments = moments.kept(keep)
    names = [name for name, k in zip(design.names, keep, strict=True) if k]
    p = len(names)

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
        message += f"; dropped {', '.join(dropped)} (no regressor on joints {selected_joints}{_base_words(components)})"
    if points:
        sigma_rows = np.tile(sigma_joint, n_samples)
        best_fit, y_flat = design.fitted(x)
        residual = (best_fit - y_flat) / sigma_rows
        solution = _Solution(x=x, init=x, jacobian=None, residual=residual, success=success, message=message, nfev=nfev, gram=gram)
        stats = _fit_statistics(
            y_flat, lambda v: v / sigma_rows, known, best_fit, solution, tuple(names), np.eye(p), scale_covar or not known
        )
        if robust and stats["covar"] is not None:
            stats |= _uncertainties(_huber_covariance(gram, residual, HUBER_SCALE), tuple(names))
        diagnostics = _log_diagnostics(design, log, keep, sigma_joint, residual * sigma_rows, residual)
        sigma, time, joint = sigma_rows, np.repeat(design.time, n_selected), np.tile(np.asarray(selected, dtype=np.int64), n_samples)
    else:
        solution = _Solution(x=x, init=x, jacobian=None, residual=np.empty(0), success=success, message=message, nfev=nfev, gram=gram)
        stats, diagnostics = _reduced_statistics(
            design.residual_sums(x), sigma_joint, solution, tuple(names), design, log, keep, scale_covar or not known, known
        )
        sigma, time, joint = np.empty(0), np.empty(0), np.empty(0, dtype=np.int64)
    # Without the points, the unweighted statistics come from the sums (the result has no points
    # to compute them from): set in place of the properties that would.
    unweighted: dict[str, Any] = {name: stats.pop(name) for name in ("rss", "cod") if name in stats}
    result = HydroFit(
        params=dict(zip(names, x.tolist(), strict=True)),
        var_names=tuple(names),
        fixed={},
        init_values=init,
        sigma=sigma,
        time=time,
        joint=joint,
        per=per,
        joints=tuple(selected_joints),
        base=tuple(components),
        dropped=dropped,
        source=log.source,
        logs=diagnostics,
        unit="N·m (−Δτ_motor − τ_buoy)",
        method=method,
        **stats,
    )
    result.__dict__.update(unweighted)
    return result
