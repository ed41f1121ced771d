"""The identification design of the land/water experiment (docs/model.md section 4): the
regressors of every coefficient and the target ``y = −Δτ_motor − τ_buoy`` on the selected
joints, assembled by the Rust core chunk by chunk in one pass over a log, reduced to the normal
equations (:class:`_Moments`), and iteratively reweighted for Huber's loss: what every design
shares. A robot's own (its columns, its base's wrench too) is :mod:`uwml.fit.robot_design`."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..io.logs import Log
from ..model.parts import Water
from ._types import Array
from .log_set import LogSet

#: Samples per chunk of the streamed hydro identification (the design of a chunk is at most
#: ``CHUNK_SAMPLES × J × 4N`` floats: 37 MB for all three joints of the paper leg per direction).
CHUNK_SAMPLES = 1 << 17

#: Default of ``hydro_coefficients(cache_bytes=...)``: designs up to this size stay in memory
#: between passes.
DESIGN_CACHE_BYTES = 1 << 30


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
    """The identification design of a set of logs (docs/model.md section 4) and its target
    ``y = −Δτ_motor − τ_buoy`` on the selected rows, assembled chunk by chunk (:meth:`_compute`,
    a subclass's); the chunks are kept while they fit into ``cache_bytes``. The first pass also
    keeps the logs' time stamps and each log's own moments (:attr:`log_moments`)."""

    def _setup(self, log: LogSet, water: Water, per: str, joints: list[int], cache_bytes: int, names: list[str]) -> None:
        """What every design keeps: the logs, the water, the columns' names, the chunk cache."""
        self._log, self._water, self._per, self._joints = log, water, per, joints
        #: The time stamps of every log, one after the other (after the first pass).
        self.time = np.empty(0)
        #: Each log's moments (after :meth:`moments`).
        self.log_moments: list[_Moments] = []
        self.names = names
        size = log.n_samples * len(joints) * (len(names) + 1) * 8
        self._cache: list[tuple[int, Array]] | None = [] if size <= cache_bytes else None
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

    def _compute(self, log: Log) -> Array:
        """The problem of one chunk, joint-major ``(J, c, P + 1)`` (a subclass's)."""
        raise NotImplementedError

    def indexed_chunks(self) -> Iterator[tuple[int, Array]]:
        """``(index of the log, chunk)``: the problem chunk by chunk, joint-major ``(J, c, P + 1)``:
        every column's regressor, then the target ``y``."""
        if self._cached and self._cache is not None:
            yield from self._cache
            return
        times = []
        for index, log in self._log.chunks(self._chunk_samples()):
            chunk = self._compute(log)
            times.append(log.time)
            if self._cache is not None:
                self._cache.append((index, chunk))
            yield index, chunk
        self.time = np.concatenate(times) if times else np.empty(0)
        self._cached = self._cache is not None

    def chunks(self) -> Iterator[Array]:
        """The problem chunk by chunk (:meth:`indexed_chunks` without the logs' indices)."""
        for _, chunk in self.indexed_chunks():
            yield chunk

    def moments(self) -> _Moments:
        """Per-joint moments of all columns, in one pass (one product ``[X y]ᵀ[X y]`` per joint
        and chunk), and each log's (:attr:`log_moments`)."""
        n_selected, p = len(self._joints), len(self.names)
        logs = [_Moments(np.zeros((n_selected, p, p)), np.zeros((n_selected, p)), np.zeros(n_selected)) for _ in self._log.items]
        for index, chunk in self.indexed_chunks():
            gram, xty, yty = logs[index].gram, logs[index].xty, logs[index].yty
            for j, block in enumerate(chunk):
                with np.errstate(over="ignore", invalid="ignore"):  # refused below, with the log named
                    g = block.T @ block
                if not np.all(np.isfinite(g)):
                    raise ValueError(
                        f"{self._log.items[index].source}: the regressors' and torques' products overflow float64 "
                        f"(values near 1e150 or beyond, far outside any robot's speeds and torques)"
                    )
                gram[j] += g[:p, :p]
                xty[j] += g[:p, p]
                yty[j] += g[p, p]
        self.log_moments = logs
        return _Moments(sum(m.gram for m in logs), sum(m.xty for m in logs), sum(m.yty for m in logs))  # type: ignore[arg-type]

    def fitted(self, x: Array) -> tuple[Array, Array]:
        """``(Xx, y)``, sample-major, from the design's chunks (kept in memory, or computed
        again)."""
        if self._last_fit is not None and np.array_equal(self._last_fit[0], x):
            return self._last_fit[1]
        return self._fitted_from_chunks(x)

    def _fitted_from_chunks(self, x: Array) -> tuple[Array, Array]:
        """``(Xx, y)``, sample-major, from the design's chunks."""
        full = self._full(x)
        fits, targets = [], []
        for chunk in self.chunks():
            fits.append((chunk[:, :, :-1] @ full).T.reshape(-1))
            targets.append(chunk[:, :, -1].T.reshape(-1))
        result = np.concatenate(fits), np.concatenate(targets)
        self._last_fit = (np.array(x), result)
        return result

    def residual_sums(self, x: Array) -> list[Array]:
        """Per log, per selected row ``j``: the samples, ``Σ r_j²`` (``r = Xx − y``), ``Σ y_j`` and
        ``Σ y_j²`` as an array ``(4, J)``: the statistics of a fit without its points."""
        full = self._full(x)
        sums = [np.zeros((4, len(self._joints))) for _ in self._log.items]
        for index, chunk in self.indexed_chunks():
            y = chunk[:, :, -1]
            r = chunk[:, :, :-1] @ full - y
            sums[index] += np.stack(
                [np.full(len(self._joints), y.shape[1]), np.sum(r * r, axis=1), np.sum(y, axis=1), np.sum(y * y, axis=1)]
            )
        return sums

    def residuals(self, x: Array) -> Array:
        """``Xx − y``, sample-major."""
        fit, y = self.fitted(x)
        return fit - y

    def huber_normal_equations(self, x: Array, sigma_joint: Array, scale: float) -> tuple[Array, Array]:
        """One pass of Huber's iteration at ``x``: ``XᵀWX`` and ``XᵀWy`` of every column (kept or
        not), ``W`` the weights ``min(1, scale/|r|) / σ²`` of the whitened residuals ``r``."""
        p = len(self.names)
        coefficients = np.append(self._full(x), -1.0)
        gram, rhs = np.zeros((p, p)), np.zeros(p)
        for chunk in self.chunks():
            r = (chunk @ coefficients) / sigma_joint[:, None]
            w = np.minimum(1.0, scale / np.maximum(np.abs(r), 1e-300)) * sigma_joint[:, None] ** -2.0
            for block, weights in zip(chunk, w, strict=True):
                g = (block * weights[:, None]).T @ block
                gram += g[:p, :p]
                rhs += g[:p, p]
        return gram, rhs

    def huber(self, x: Array, sigma_joint: Array, scale: float, max_passes: int = 200) -> tuple[Array, int, bool]:
        """Huber's estimate by iteratively reweighted least squares from ``x``, on residuals
        whitened by ``sigma_joint``: ``(x, passes, converged)``. The weights are
        ``min(1, scale/|r|)``; the loss is convex, so the iteration converges to its unique
        minimum (the one ``scipy.optimize.least_squares(loss="huber")`` finds)."""
        keep = np.ones(len(self.names), dtype=bool) if self._keep is None else self._keep
        passes, converged = 0, False
        for passes in range(1, max_passes + 1):
            gram, rhs = self.huber_normal_equations(x, sigma_joint, scale)
            gram, rhs = gram[keep][:, keep], rhs[keep]
            d = np.sqrt(np.diag(gram))
            d = np.where(d > 0.0, d, 1.0)
            new = np.linalg.lstsq(gram / np.outer(d, d), rhs / d, rcond=None)[0] / d
            converged = bool(np.all(np.abs(new - x) <= 1e-12 * (np.abs(new) + np.max(np.abs(new)) + 1e-300)))
            x = new
            if converged:
                break
        return x, passes, converged
