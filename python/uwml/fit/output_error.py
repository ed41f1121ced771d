"""Output-error least squares whose model is a simulation, and its result for a free-floating
vehicle (:class:`VehicleFit`; docs/model.md section 13, "13.3 Identifying a vehicle";
docs/identification.md, "A vehicle from free-floating trials").

:func:`output_error` minimizes ``Σ_k ((m_k(θ) − y_k) / σ_k)²`` over the parameters ``θ`` within
their bounds (``scipy.optimize.least_squares``, trust region reflective, ``x_scale="jac"``),
where the model values ``m(θ)`` come from ``evaluate``, a function of a batch of parameter
vectors (for a vehicle: each vector a replay of every training trial, so that a caller can run
a batch in parallel). The Jacobian is the caller's where it has one (``jacobian``: exact
derivatives, e.g. JAX's through :mod:`uwml.sim.mjx`), else taken by forward differences: column ``i`` from
``m(θ + h_i e_i)``, ``h_i = diff_step · max(|θ_i|, s_i)`` with ``s_i`` the parameter's typical
scale (:func:`uwml.fit.vehicle_parameters.typical_scale`; 0.01 rad or rad/s for a trial's start
state), stepped backwards where the upper
bound is nearer than ``h_i``; the ``p`` columns are one batch. A simulation's rounding is far
below such a step's effect (``DIFF_STEP`` = 1e-6: the columns agree with central differences to
about 1e-6 of their size).

Standard errors come from the whitened Jacobian ``J`` at the optimum: ``covar = s² (JᵀJ)⁻¹``,
``s²`` the reduced χ² (``scale_covar``, and always when σ was not given), with the statistics of
:class:`uwml.fit.FitResult`; a singular ``JᵀJ`` (a parameter the data do not determine) gives no
error bars and says which parameter is least sensitive.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.optimize
from numpy.typing import NDArray

from ..model.parts import Link
from ._types import Array
from .fit_results import FitResult, _json_float, _json_floats
from .least_squares import _fit_statistics, _Solution
from .vehicle_parameters import with_parameters

__all__ = ["DIFF_STEP", "FORWARD_DIFFERENCES", "TrialRMS", "VehicleFit", "output_error", "split_parameters"]

#: The relative step of the forward differences (module docstring).
DIFF_STEP = 1e-6
#: :attr:`VehicleFit.jacobian` of a fit whose Jacobian was taken by forward differences.
FORWARD_DIFFERENCES = "forward differences"
#: The angles compared, in the order of each sample's two points.
ANGLES = ("roll", "pitch")
#: A trial's start state that a fit may refine: roll, pitch [rad] (turns about the body's x and
#: y axes), and the replay's start twist (MuJoCo's free joint: world-frame velocity vx, vy, vz
#: [m/s], body-frame angular velocity wx, wy, wz [rad/s]).
START_STATE = ("roll", "pitch", "vx", "vy", "vz", "wx", "wy", "wz")

#: Model values at a batch of parameter vectors, one array per vector.
Evaluate = Callable[[Sequence[Array]], list[Array]]


@dataclass(frozen=True)
class TrialRMS:
    """One trial of a :class:`VehicleFit`: its ``source``, ``role`` (``"train"``: fitted;
    ``"test"``: held out), the ``samples`` compared (the first, where the replay starts, aside)
    and the RMS of the simulated against the measured roll and pitch [rad], replayed with the
    description's parameters (``described``) and with the fitted ones (``fitted``)."""

    source: str
    role: str
    samples: int
    described: tuple[float, float]
    fitted: tuple[float, float]
    #: A training trial's start state fitted with the parameters (``fit_start``): the offsets
    #: from the window's estimate of :data:`START_STATE` (roll, pitch [rad]; the twist [m/s,
    #: rad/s]), each ``(value, stderr)``; None where the start was the window's estimate.
    start_offset: tuple[tuple[float, float | None], ...] | None = None

    def as_dict(self) -> dict[str, Any]:
        """The trial for JSON."""
        offset = None
        if self.start_offset is not None:
            offset = {
                name: {"value": _json_float(value), "stderr": _json_float(error)}
                for name, (value, error) in zip(START_STATE, self.start_offset, strict=True)
            }
        return {
            "source": self.source,
            "role": self.role,
            "samples": self.samples,
            "described": dict(zip(ANGLES, (_json_float(x) for x in self.described), strict=True)),
            "fitted": dict(zip(ANGLES, (_json_float(x) for x in self.fitted), strict=True)),
            "start_offset": offset,
        }


@dataclass(frozen=True, eq=False, kw_only=True)
class VehicleFit(FitResult):
    """Result of :func:`uwml.sim.free_floating.vehicle_from_trials`: the chosen parameters
    (``params``, names of :data:`uwml.fit.vehicle_parameters.VEHICLE_PARAMETERS`) with the
    statistics of :class:`uwml.fit.FitResult`. The data are the measured roll and pitch [rad] of
    the training trials, two points a sample (roll, then pitch), trial after trial; ``time``,
    ``trial`` (index into the training trials) and ``angle`` (0 roll, 1 pitch) say where each was
    taken. ``trials``: each trial's RMS before and after, training trials first, then the held-out
    ones."""

    time: Array
    trial: NDArray[np.int64]
    angle: NDArray[np.int64]
    trials: tuple[TrialRMS, ...]
    #: Each parameter's bounds.
    bounds: dict[str, tuple[float, float]]
    #: Each parameter's value in the description (0 for an offset): the fit's default start.
    described: dict[str, float]
    #: The hull as described (the fitted values go into a copy: :meth:`base_link`).
    described_base: Link
    source: str
    #: The replays' step [s] and integrator.
    timestep: float
    integrator: str
    diff_step: float = DIFF_STEP
    #: Whether each training trial's start state was fitted too (:attr:`TrialRMS.start_offset`).
    start_fitted: bool = False
    #: How the Jacobian was taken: :data:`FORWARD_DIFFERENCES`, or the exact derivatives' source.
    jacobian: str = FORWARD_DIFFERENCES

    def base_link(self) -> Link:
        """The described hull with the fitted parameters put in (a :class:`uwml.Link` for a
        :class:`uwml.Robot`'s ``base``)."""
        return with_parameters(self.described_base, self.var_names, [self.params[name] for name in self.var_names])

    def rms(self, role: str = "test", fitted: bool = True) -> float:
        """The RMS of roll and pitch together [rad] over the trials of ``role`` (``"train"`` or
        ``"test"``; each sample counted once), with the fitted or (``fitted=False``) the
        described parameters; NaN without such trials."""
        chosen = [t for t in self.trials if t.role == role]
        count = sum(t.samples for t in chosen)
        if not count:
            return math.nan
        squares = sum(t.samples * sum(x * x for x in (t.fitted if fitted else t.described)) for t in chosen)
        return math.sqrt(squares / (2 * count))

    def _report_statistics(self) -> list[str]:
        train = sum(t.role == "train" for t in self.trials)
        how = f"forward differences (step {self.diff_step:g})" if self.jacobian == FORWARD_DIFFERENCES else self.jacobian
        replays = f"{self.integrator}, timestep {self.timestep:g} s; Jacobian by {how}"
        starts = "the start window's estimates"
        if self.start_fitted:
            starts = f"fitted: roll, pitch and twist of each trial ({self.nvarys - len(self.var_names)} parameters, under [[Trials]])"
        return [
            "    compared           = roll, pitch [rad] at the trials' samples (replays from an estimated start state)",
            f"    trials             = {train} fitted, {len(self.trials) - train} held out",
            f"    replays            = {replays}",
            f"    start states       = {starts}",
        ]

    def fit_report(self, min_correl: float = 0.1) -> str:
        """:meth:`uwml.fit.FitResult.fit_report`, then each trial's RMS of roll and pitch with
        the described and the fitted parameters, and each parameter's bounds."""
        lines = [super().fit_report(min_correl), "[[Bounds]]"]
        width = max(len(name) for name in self.var_names) + 1
        lines += [f"    {(name + ':').ljust(width)} [{low:.7g}, {high:.7g}]" for name, (low, high) in self.bounds.items()]
        lines.append("[[Trials]] RMS [rad], described -> fitted")
        for t in self.trials:
            (r0, p0), (r1, p1) = t.described, t.fitted
            lines.append(f"    {t.role:5s} {t.source}: {t.samples} samples, roll {r0:.4g} -> {r1:.4g}, pitch {p0:.4g} -> {p1:.4g}")
            if t.start_offset is not None:
                shown = [
                    f"{n} {v:+.3g}" + ("" if e is None else f" +/- {e:.2g}") for n, (v, e) in zip(START_STATE, t.start_offset, strict=True)
                ]
                lines.append(f"          start offset: {', '.join(shown)}")
        for role in ("train", "test"):
            if any(t.role == role for t in self.trials):
                lines.append(f"    {role} (all): {self.rms(role, False):.4g} -> {self.rms(role):.4g}")
        return "\n".join(lines)

    def _summary_head(self) -> dict[str, Any]:
        return {
            "model": "vehicle",
            "source": self.source,
            "trials": [t.as_dict() for t in self.trials],
            "rms": {
                role: {"described": _json_float(self.rms(role, False)), "fitted": _json_float(self.rms(role))} for role in ("train", "test")
            },
            "bounds": {name: [_json_float(low), _json_float(high)] for name, (low, high) in self.bounds.items()},
            "described": {name: _json_float(value) for name, value in self.described.items()},
            "timestep": self.timestep,
            "integrator": self.integrator,
            "start_fitted": self.start_fitted,
            "jacobian": self.jacobian,
        }

    def _point_coordinates(self) -> dict[str, list[Any]]:
        return {"time": _json_floats(self.time), "trial": self.trial.tolist(), "angle": self.angle.tolist()}


def _steps(scales: Array, x: Array, upper: Array, diff_step: float) -> Array:
    """The signed forward-difference steps at ``x`` (module docstring)."""
    size = diff_step * np.maximum(np.abs(x), scales)
    return np.where(x + size > upper, -size, size)


def output_error(
    evaluate: Evaluate,
    data: Array,
    sigma: Array,
    names: Sequence[str],
    start: Array,
    lower: Array,
    upper: Array,
    scales: Array,
    *,
    sigma_given: bool,
    scale_covar: bool = True,
    diff_step: float = DIFF_STEP,
    max_nfev: int | None = None,
    jacobian: Callable[[Array], Array] | None = None,
) -> tuple[dict[str, Any], Array, Array]:
    """Fit ``names`` (from ``start``, within ``lower`` … ``upper``; ``scales``: their typical
    sizes, for the steps) so that ``evaluate``'s model values match ``data`` with standard errors
    ``sigma`` (module docstring); ``jacobian``: the model values' derivatives ``(n, p)`` at a
    point (None: forward differences of ``evaluate``). Returns the
    statistics of :class:`uwml.fit.FitResult` (``params`` … ``nfev``: the model's evaluations,
    the Jacobian's columns counted), the model values at the start and at the optimum."""
    if not (isinstance(diff_step, float | int) and 0.0 < diff_step < 0.1):
        raise ValueError(f"diff_step must be a number in (0, 0.1), got {diff_step!r}")
    start = np.asarray(start, dtype=np.float64)
    # The values of the last batches (the residual at x, then the Jacobian there, reuse them);
    # the start's kept throughout, for the result.
    cache: dict[bytes, Array] = {}
    keep, count = 2 * (start.size + 1), [0]

    def values(points: Sequence[Array]) -> list[Array]:
        missing = [x for x in points if x.tobytes() not in cache]
        if missing:
            count[0] += len(missing)
            for x, value in zip(missing, evaluate(missing), strict=True):
                cache[x.tobytes()] = np.asarray(value, dtype=np.float64)
        found = [cache[x.tobytes()] for x in points]
        for key in list(cache)[1 : max(1, len(cache) - keep)]:
            del cache[key]
        return found

    def residual(x: Array) -> Array:
        return np.asarray((values([x])[0] - data) / sigma, dtype=np.float64)

    def derivatives(x: Array) -> Array:
        if jacobian is not None:
            return np.asarray(jacobian(x), dtype=np.float64) / sigma[:, None]
        steps = _steps(scales, x, upper, float(diff_step))
        moved = [x + np.eye(x.size)[i] * steps[i] for i in range(x.size)]
        here, *columns = values([x, *moved])
        return np.column_stack([(column - here) / step for column, step in zip(columns, steps, strict=True)]) / sigma[:, None]

    values([start])
    found = scipy.optimize.least_squares(
        residual, start, jac=derivatives, bounds=(lower, upper), x_scale="jac", method="trf", max_nfev=max_nfev
    )
    x = np.asarray(found.x, dtype=np.float64)
    solution = _Solution(
        x=x, init=start, jacobian=derivatives(x), residual=residual(x), success=bool(found.status > 0), message=str(found.message), nfev=count[0]
    )  # fmt: skip
    best = values([x])[0]
    stats = _fit_statistics(data, lambda v: v / sigma, sigma_given, best, solution, tuple(names), np.eye(x.size), scale_covar)
    stats |= {
        "params": dict(zip(names, x.tolist(), strict=True)),
        "var_names": tuple(names),
        "fixed": {},
        "init_values": dict(zip(names, start.tolist(), strict=True)),
        "sigma": sigma,
        "unit": "rad",
        "method": "least_squares (output error)",
    }
    return stats, values([start])[0], best


def split_parameters(stats: dict[str, Any], count: int) -> tuple[dict[str, Any], dict[str, tuple[float, float | None]]]:
    """``stats`` of :func:`output_error` with its parameters cut to the first ``count`` (their
    covariance the block of the whole one: the others marginalized, ``nvarys`` still counting
    them), and the others' ``name: (value, stderr)``."""
    names = stats["var_names"]
    kept, others = names[:count], names[count:]
    covar = None if stats["covar"] is None else stats["covar"][:count, :count]
    cut = {
        "params": {name: stats["params"][name] for name in kept},
        "stderr": {name: stats["stderr"][name] for name in kept},
        "init_values": {name: stats["init_values"][name] for name in kept},
        "correl": {a: {b: c for b, c in row.items() if b in kept} for a, row in stats["correl"].items() if a in kept},
        "var_names": tuple(kept),
        "covar": covar,
    }
    return stats | cut, {name: (stats["params"][name], stats["stderr"][name]) for name in others}
