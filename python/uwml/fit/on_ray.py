"""A hydrodynamic fit over many logs on Ray (``hydro_coefficients(..., on_ray=True)``; docs/scale.md,
"Fits over many logs"): the logs are shared out among actors, one per worker, each holding the
designs of its own logs (their chunks cached as one process caches them); every pass of the fit
is a reduction over them:

* the normal equations of each log (``XᵀX``, ``Xᵀy``, ``yᵀy`` per fitted row) and its time
  stamps, which the driver sums and solves;
* the fitted values at given coefficients, log after log (the result's per-point arrays);
* for a robust fit, each pass of Huber's iteration: each log's ``XᵀWX`` and ``XᵀWy``.

The driver does what one process does with these (:class:`RayDesign` has the interface of
:class:`uwml.fit.design._HydroDesign`), so the result is the one-process fit's, up to the order
of the sums.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..model.parts import Water
from ..robot.tree import Robot
from ._types import Array
from .design import _HydroDesign, _Moments
from .log_set import LogSet, _Item
from .robot_design import _RobotHydroDesign

__all__ = ["RayDesign"]


def _spec(robot: Robot, water: Water, per: str, rows: list[int], cache_bytes: int, lumped: str) -> dict[str, Any]:
    """What a worker needs to build a log's design: the robot's parts (plain, picklable data)."""
    return {
        "joints": robot.joints,
        "links": robot.links,
        "base": robot.base,
        "water": water,
        "per": per,
        "rows": rows,
        "cache_bytes": cache_bytes,
        "lumped": lumped,
    }


def _design(spec: dict[str, Any], logs: LogSet) -> _HydroDesign:
    s = spec
    robot = Robot(s["joints"], s["links"], base=s["base"], water=s["water"])
    return _RobotHydroDesign(robot, logs, s["water"], s["per"], s["rows"], s["cache_bytes"], s["lumped"])


class _Worker:
    """The designs of some logs, in one Ray actor."""

    def __init__(self, spec: dict[str, Any], items: list[_Item]) -> None:
        self.designs = [_design(spec, LogSet([item])) for item in items]

    def moments(self) -> list[tuple[_Moments, Array]]:
        out = []
        for design in self.designs:
            moments = design.moments()
            out.append((moments, design.time))
        return out

    def keep(self, keep: NDArray[np.bool_]) -> None:
        for design in self.designs:
            design.keep(keep)

    def fitted(self, x: Array) -> list[tuple[Array, Array]]:
        return [design.fitted(x) for design in self.designs]

    def residual_sums(self, x: Array) -> list[Array]:
        return [design.residual_sums(x)[0] for design in self.designs]

    def huber_normal_equations(self, x: Array, sigma_joint: Array, scale: float) -> tuple[Array, Array]:
        sums = [design.huber_normal_equations(x, sigma_joint, scale) for design in self.designs]
        return sum(g for g, _ in sums), sum(r for _, r in sums)  # type: ignore[return-value]


class RayDesign(_HydroDesign):
    """The design of a set of logs shared out among Ray actors (module docstring)."""

    def __init__(
        self, ray: Any, robot: Robot, logs: LogSet, water: Water, per: str, rows: list[int], cache_bytes: int, lumped: str
    ) -> None:
        spec = _spec(robot, water, per, rows, cache_bytes, lumped)
        # The columns' names, from a design of the first log alone (built here, nothing computed).
        self.names = _design(spec, LogSet(logs.items[:1])).names
        self._log, self._joints, self._keep = logs, rows, None
        self._last_fit: tuple[Array, tuple[Array, Array]] | None = None
        self.time = np.empty(0)
        self.log_moments: list[_Moments] = []
        self._ray = ray
        cpus = max(1, int(ray.cluster_resources().get("CPU", 1)))
        n = min(cpus, len(logs.items))
        #: Which logs each actor holds: log i goes to actor i mod n.
        self._shares = [list(range(k, len(logs.items), n)) for k in range(n)]
        actor = ray.remote(num_cpus=1)(_Worker)
        self._actors = [actor.remote(spec, [logs.items[i] for i in share]) for share in self._shares]

    def _gather(self, results: list[list[Any]]) -> list[Any]:
        """Each actor's per-log results, back in the logs' order."""
        ordered: list[Any] = [None] * len(self._log.items)
        for share, values in zip(self._shares, results, strict=True):
            for i, value in zip(share, values, strict=True):
                ordered[i] = value
        return ordered

    def moments(self) -> _Moments:
        per_log = self._gather(self._ray.get([a.moments.remote() for a in self._actors]))
        self.log_moments = [m for m, _ in per_log]
        self.time = np.concatenate([t for _, t in per_log])
        logs = self.log_moments
        return _Moments(sum(m.gram for m in logs), sum(m.xty for m in logs), sum(m.yty for m in logs))  # type: ignore[arg-type]

    def keep(self, keep: NDArray[np.bool_]) -> None:
        self._keep = keep
        self._ray.get([a.keep.remote(keep) for a in self._actors])

    def fitted(self, x: Array) -> tuple[Array, Array]:
        if self._last_fit is not None and np.array_equal(self._last_fit[0], x):
            return self._last_fit[1]
        per_log = self._gather(self._ray.get([a.fitted.remote(x) for a in self._actors]))
        result = np.concatenate([f for f, _ in per_log]), np.concatenate([y for _, y in per_log])
        self._last_fit = (np.array(x), result)
        return result

    def huber_normal_equations(self, x: Array, sigma_joint: Array, scale: float) -> tuple[Array, Array]:
        sums = self._ray.get([a.huber_normal_equations.remote(x, sigma_joint, scale) for a in self._actors])
        return sum(g for g, _ in sums), sum(r for _, r in sums)

    def residual_sums(self, x: Array) -> list[Array]:
        return self._gather(self._ray.get([a.residual_sums.remote(x) for a in self._actors]))

    def close(self) -> None:
        for actor in self._actors:
            self._ray.kill(actor)
