"""Cd and Cm from the land/water experiment (:func:`hydro_coefficients`): the streamed design,
weighted and robust linear least squares.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..io.logs import Log, align_logs, read_log
from ..model.parts import Water
from ..robot.leg import Leg
from ..robot.tree import Robot
from ._types import Array, PathOrFile
from .least_squares import _fit_statistics, _Solution, _uncertainties
from .results import FitResult, _json_floats

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

    #: Without σ, the hydrodynamic fit estimates each joint's from the residuals.
    _unknown_sigma_note = " (weighted by σ estimated from the residuals: ≈ N − p and 1 by construction)"

    def _report_statistics(self) -> list[str]:
        lines = [f"    joints (0-based)   = {', '.join(str(j) for j in self.joints)}", f"    coefficients per   = {self.per}"]
        if self.dropped:
            lines.append(f"    dropped (no data)  = {', '.join(self.dropped)}")
        return lines

    def _summary_head(self) -> dict[str, Any]:
        return {"model": "hydro", "per": self.per, "joints": list(self.joints), "dropped": list(self.dropped), "source": self.source}

    def _point_coordinates(self) -> dict[str, list[Any]]:
        return {"time": _json_floats(self.time), "joint": np.asarray(self.joint, dtype=np.int64).tolist()}


def _hydro_log(log_or_path: Any, n_joints: int, what: str = "the leg") -> Log:
    """A log of the whole experiment from a :class:`Log`, a file, or a (land, water) pair."""
    if isinstance(log_or_path, tuple | list):
        if len(log_or_path) != 2:
            raise ValueError(f"give one log of the whole experiment or a (land, water) pair of logs, got {len(log_or_path)} items")
        land, water = (item if isinstance(item, Log) else read_log(item, n_joints) for item in log_or_path)
        for item in (land, water):
            if item.n_joints != n_joints:
                raise ValueError(
                    f"{item.source}: row 1 (header), column 'q{item.n_joints}': the log has {item.n_joints} joints, {what} {n_joints}"
                )
        return align_logs(land, water)
    log = log_or_path if isinstance(log_or_path, Log) else read_log(log_or_path, n_joints)
    if log.n_joints != n_joints:
        raise ValueError(f"{log.source}: row 1 (header), column 'q{log.n_joints}': the log has {log.n_joints} joints, {what} {n_joints}")
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
        gram: Array = np.einsum("j,jab->ab", sigma_joint**-2.0, self.gram)
        return gram

    def solve(self, sigma_joint: Array) -> Array:
        """Weighted least squares from the normal equations, with the columns scaled to unit
        norm first (the Gram matrix's condition number is then that of the correlations)."""
        gram = self.weighted_gram(sigma_joint)
        rhs = np.einsum("j,ja->a", sigma_joint**-2.0, self.xty)
        scale = np.sqrt(np.diag(gram))
        scale = np.where(scale > 0.0, scale, 1.0)
        return np.asarray(np.linalg.lstsq(gram / np.outer(scale, scale), rhs / scale, rcond=None)[0], dtype=np.float64) / scale

    def residual_squares(self, x: Array) -> Array:
        """``|Xⱼx − yⱼ|²`` per joint, from the moments (an estimate of scale: it loses the
        digits that ``|y|²`` has beyond the residuals')."""
        squares: Array = np.clip(self.yty - 2.0 * self.xty @ x + np.einsum("a,jab,b->j", x, self.gram, x), 0.0, None)
        return squares


class _HydroDesign:
    """The identification design of a log (docs/model.md section 4) and its target
    ``y = −Δτ_motor − τ_buoy`` on the selected joints, assembled by the Rust core in one pass per
    chunk of samples; the chunks are kept while they fit into ``cache_bytes``."""

    def __init__(self, leg: Leg, log: Log, water: Water, per: str, joints: list[int], cache_bytes: int) -> None:
        self._leg = leg
        n_links = leg.n_joints
        names: list[str] = []
        for prefix in ("cd", "cm"):
            if per == "leg":
                names.append(prefix)
            elif per == "link":
                names += [f"{prefix}_link{link}" for link in range(n_links)]
            else:
                names += [f"{prefix}_link{link}_n{k}" for link in range(n_links) for k in range(2)]
        self._setup(log, water, per, joints, cache_bytes, names)

    def _setup(self, log: Log, water: Water, per: str, joints: list[int], cache_bytes: int, names: list[str]) -> None:
        """What every design keeps: the log, the water, the columns' names, the chunk cache."""
        assert log.qd is not None and log.qdd is not None and log.tau_land is not None and log.tau_water is not None
        self._log, self._water, self._per, self._joints = log, water, per, joints
        self.names = names
        size = log.n_samples * len(joints) * (len(names) + 1) * 8
        self._cache: list[Array] | None = [] if size <= cache_bytes else None
        self._cached = False
        self._keep: NDArray[np.bool_] | None = None
        # The last coefficients given to `fitted`, and its result (the robust fit's last scale
        # estimate and the result's fitted values are of the same coefficients).
        self._last_fit: tuple[Array, tuple[Array, Array]] | None = None

    def _chunk_samples(self) -> int:
        return CHUNK_SAMPLES

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
        q, qd, qdd = (np.ascontiguousarray(a[rows]) for a in (log.q, log.qd, log.qdd))
        delta = np.ascontiguousarray(log.tau_water[rows] - log.tau_land[rows])
        return self._leg._chain.hydro_design(q, qd, qdd, delta, self._water.density, self._water.gravity, self._joints, self._per)

    def chunks(self) -> Iterator[Array]:
        """The problem chunk by chunk, joint-major ``(J, c, P + 1)``: every column's regressor,
        then the target ``y``."""
        if self._cached and self._cache is not None:
            yield from self._cache
            return
        n, step = self._log.n_samples, self._chunk_samples()
        for start in range(0, n, step):
            chunk = self._compute(start, min(start + step, n))
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
                with np.errstate(over="ignore", invalid="ignore"):  # refused below, with the log named
                    g = block.T @ block
                if not np.all(np.isfinite(g)):
                    raise ValueError(
                        f"{self._log.source}: the regressors' and torques' products overflow float64 "
                        f"(values near 1e150 or beyond, far outside any robot's speeds and torques)"
                    )
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


class _RobotHydroDesign(_HydroDesign):
    """The design of a :class:`uwml.Robot` on a fixed, upright base in still water: the
    regressors of the whole-robot core (one column per segment and normal direction) summed
    into the columns of ``per``. Bodies are the base (if it has segments; named ``base``) and
    every link (named by its name, else ``link<i>``); a circular segment's drag and added mass
    are along its whole normal velocity, so they fall in ``n0``'s column."""

    #: Bytes of regressors (all rows, segments and directions, drag and added mass) per chunk.
    REGRESSOR_BYTES = 1 << 26

    def __init__(self, robot: Robot, log: Log, water: Water, per: str, joints: list[int], cache_bytes: int) -> None:
        self._robot = robot
        owners = [-1] * (len(robot.base.segments) if robot.base is not None else 0)
        owners += [i for i, link in enumerate(robot.links) for _ in link.segments]
        bodies = ([-1] if owners and owners[0] == -1 else []) + list(range(robot.n_joints))
        labels = {b: "base" if b < 0 else (robot.links[b].name or f"link{b}") for b in bodies}
        n_segments = len(owners)
        if per == "leg":
            columns = [(k, d, 0) for k in range(n_segments) for d in range(2)]
            half = ["" for _ in range(1)]
        elif per == "link":
            columns = [(k, d, bodies.index(o)) for k, o in enumerate(owners) for d in range(2)]
            half = [f"_{labels[b]}" for b in bodies]
        else:
            columns = [(k, d, 2 * bodies.index(o) + d) for k, o in enumerate(owners) for d in range(2)]
            half = [f"_{labels[b]}_n{d}" for b in bodies for d in range(2)]
        # (segment, direction) -> column of one half (the Cd half or the Cm half).
        self._map = np.zeros((n_segments * 2, len(half)))
        for k, d, column in columns:
            self._map[2 * k + d, column] = 1.0
        self._setup(log, water, per, joints, cache_bytes, [f"{prefix}{suffix}" for prefix in ("cd", "cm") for suffix in half])
        self._rows = max(64, self.REGRESSOR_BYTES // (2 * (6 + robot.n_joints) * max(n_segments, 1) * 2 * 8))

    def _chunk_samples(self) -> int:
        return min(CHUNK_SAMPLES, self._rows)

    def _compute(self, start: int, stop: int) -> Array:
        log = self._log
        assert log.qd is not None and log.qdd is not None and log.tau_land is not None and log.tau_water is not None
        rows = slice(start, stop)
        regressors = self._robot.hydro_regressors(log.q[rows], log.qd[rows], log.qdd[rows], water=self._water)
        joints = self._joints
        n = stop - start

        def columns(values: Array) -> Array:
            return values[:, joints].reshape(n, len(joints), -1) @ self._map

        target = -(log.tau_water[rows] - log.tau_land[rows]) - regressors.buoyancy
        problem = np.concatenate([columns(regressors.drag), columns(regressors.added_mass), target[:, joints, None]], axis=2)
        return np.ascontiguousarray(problem.transpose(1, 0, 2))

    def fitted(self, x: Array) -> tuple[Array, Array]:
        """``(Xx, y)``, sample-major, from the design's chunks."""
        if self._last_fit is not None and np.array_equal(self._last_fit[0], x):
            return self._last_fit[1]
        full = self._full(x)
        fits, targets = [], []
        for chunk in self.chunks():
            fits.append((chunk[:, :, :-1] @ full).T.reshape(-1))
            targets.append(chunk[:, :, -1].T.reshape(-1))
        result = np.concatenate(fits), np.concatenate(targets)
        self._last_fit = (np.array(x), result)
        return result


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
    leg: Leg | Robot | None = None,
    joints: ArrayLike = (0,),
    per: Literal["leg", "link", "direction"] = "leg",
    water: Water | None = None,
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
        A log of the whole experiment (``tau_land*`` and ``tau_water*``), as a :class:`uwml.io.logs.Log`
        or a file (:func:`uwml.io.logs.read_log`); or a pair of logs of one environment each
        (``tau*``), aligned by time (:func:`uwml.io.logs.align_logs`). Missing velocities and
        accelerations are estimated (:meth:`uwml.io.logs.Log.with_derivatives`).
    leg : Leg or Robot, optional
        Default :meth:`uwml.Leg.paper`. A :class:`uwml.Robot` (any tree, from a URDF, MJCF or
        model file) is on a fixed, upright base in still water, as the leg on its test stand;
        its columns are per body: the base (``base``, if it has segments: on a fixed base they
        are zero and dropped) and every link (``cd_<name>``, or ``cd_link<i>`` for an unnamed
        link), a circular segment's in ``n0``'s column.
    joints : sequence of int
        The joints whose torques are fitted (0-based; default joint 0, the paper's joint 1).
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
    leg = Leg.paper() if leg is None else leg
    if not isinstance(leg, (Leg, Robot)):
        raise TypeError(f"leg must be a uwml.Leg or a uwml.Robot, got {type(leg).__name__}")
    # A Leg is a Robot; it keeps the leg's design (columns per leg, link or direction).
    whole_robot = not isinstance(leg, Leg)
    what = "the robot" if whole_robot else "the leg"
    if water is None:
        water = leg.water
    if per not in ("leg", "link", "direction"):
        raise ValueError(f"per must be 'leg', 'link' or 'direction', got {per!r}")
    expected = leg.n_joints if n_joints is None else int(n_joints)
    if expected != leg.n_joints:
        raise ValueError(f"n_joints ({n_joints}) differs from {what}'s {leg.n_joints} joints")
    selected = [int(j) for j in np.atleast_1d(np.asarray(joints))]
    if not selected or len(set(selected)) != len(selected) or any(not 0 <= j < leg.n_joints for j in selected):
        raise ValueError(f"joints must be distinct indices in 0..{leg.n_joints - 1}, got {joints!r}")
    log = _hydro_log(log_or_path, expected, what).with_derivatives()
    assert log.qd is not None and log.qdd is not None and log.tau_land is not None and log.tau_water is not None

    n_samples, n_selected = log.n_samples, len(selected)
    known = sigma is not None
    given_sigma: Array | None = None
    if sigma is not None:
        # Checked before the pass over the log.
        given_sigma = np.broadcast_to(np.asarray(sigma, dtype=np.float64), (n_selected,)) if np.ndim(sigma) <= 1 else None
        if given_sigma is None or not np.all(np.isfinite(given_sigma)) or np.any(given_sigma <= 0.0):
            raise ValueError(f"sigma must be a positive number or one per selected joint ({n_selected}), got {sigma!r}")
    design: _HydroDesign = (
        _HydroDesign(leg, log, water, per, selected, cache_bytes)
        if isinstance(leg, Leg)
        else _RobotHydroDesign(leg, log, water, per, selected, cache_bytes)
    )
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
