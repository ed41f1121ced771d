"""The command that gives a thrust: each thruster's curve inverted numerically (docs/model.md
section 13.1), for a controller that asks its thrusters for thrusts (:mod:`uwml.sim.station_keeping`).

A thruster's steady thrust ``T = f(u)`` (:meth:`uwml.Thruster.thrust`) is sampled over its
command span and inverted by linear interpolation of the samples:

* **The span.** A table's: its first to its last command (the curve is flat beyond). A
  polynomial's: from the command where its reverse thrust reaches ``max_reverse`` to the one
  where its forward thrust reaches ``max_forward`` (each found by ``scipy.optimize.brentq``);
  a polynomial side without a finite limit has no such command, and is refused (give the
  thruster its ``max_forward`` / ``max_reverse``).
* **The samples.** A table's own points, where the inverse of its linear interpolation is exact;
  a polynomial's, ``SAMPLES`` commands on each side of its dead band plus the band's edges and
  zero (the inverse's error is below 1e-5 N for a T200-like curve, ``tests/test_vehicle_study.py``).
* **Monotone.** The curve must not decrease over the span (a thrust of a decreasing curve has
  more than one command): one that does is refused, naming the thruster and the commands.
* **Flat stretches.** A thrust the curve holds over a stretch of commands (the dead band's zero)
  is given by the stretch's end away from zero thrust, so that a thrust just beyond it is
  interpolated towards the right command; zero thrust by the command of zero thrust nearest 0.
* **Saturation.** A thrust beyond what the thruster gives, ``[low, high]`` (the curve's range
  over its span within ``-max_reverse`` and ``max_forward``), is the command of that end: so
  ``thrust(command(T)) = clip(T, low, high)``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..model.thrusters import Thruster

__all__ = ["SAMPLES", "ThrustInverse", "ThrustInverses"]

FloatArray = NDArray[np.float64]

#: Commands sampled on each side of a polynomial curve's dead band.
SAMPLES = 2049
#: The farthest command searched for a polynomial's limit, in units of the first step tried.
_SEARCH = 2.0**40


def _label(thruster: Thruster, index: int | None) -> str:
    named = f" {thruster.name!r}" if thruster.name else ""
    return f"thruster{named}" if index is None else f"thruster {index}{named}"


def _reach(thruster: Thruster, limit: float, sign: float, where: str) -> float:
    """The command ``u`` (of ``sign``) beyond the dead band where the polynomial's thrust first
    reaches ``sign * limit``."""
    from scipy.optimize import brentq

    curve = thruster.curve
    if not math.isfinite(limit):
        side = "max_forward" if sign > 0 else "max_reverse"
        raise ValueError(
            f"{where}: its polynomial curve has no finite {side}, so no command of its most thrust: give the thruster its {side} [N]"
        )
    band = curve.dead_band

    def excess(u: float) -> float:
        return float(sign * curve(sign * u)) - limit

    step = max(band, 1.0)
    far = band + step
    while excess(far) < 0.0:
        far = band + 2.0 * (far - band)
        if far - band > _SEARCH * step:
            raise ValueError(f"{where}: its curve never reaches its {'max_forward' if sign > 0 else 'max_reverse'} of {limit:g} N")
    if excess(band) >= 0.0:
        return sign * band
    return sign * float(brentq(excess, band, far, xtol=1e-14, rtol=8.9e-16))


class ThrustInverse:
    """The command of each thrust for ``thruster`` (module docstring); ``index``: its place
    among the robot's, for messages. :attr:`low` and :attr:`high`: the thrusts [N] it gives."""

    def __init__(self, thruster: Thruster, index: int | None = None) -> None:
        where = _label(thruster, index)
        curve = thruster.curve
        if curve.kind == "table":
            commands = np.asarray(curve.commands, dtype=np.float64)
        else:
            band = curve.dead_band
            start = _reach(thruster, thruster.max_reverse, -1.0, where)
            end = _reach(thruster, thruster.max_forward, 1.0, where)
            reverse = np.linspace(start, -band, SAMPLES) if start < -band else np.zeros(0)
            forward = np.linspace(band, end, SAMPLES) if end > band else np.zeros(0)
            commands = np.unique(np.concatenate([reverse, [-band, 0.0, band], forward]))
            commands = commands[(commands >= min(start, 0.0)) & (commands <= max(end, 0.0))]
        thrusts = np.asarray(curve(commands), dtype=np.float64)
        scale = max(float(np.max(np.abs(thrusts))), 1e-300)
        falls = np.flatnonzero(np.diff(thrusts) < -1e-12 * scale)
        if falls.size:
            k = int(falls[0])
            raise ValueError(
                f"{where}: its thrust falls from {thrusts[k]:.6g} N at command {commands[k]:.6g} to {thrusts[k + 1]:.6g} N at "
                f"{commands[k + 1]:.6g}: a thrust of a curve that is not monotone has no single command"
            )
        thrusts = np.maximum.accumulate(thrusts)  # rounding's dips below 1e-12 of the range
        #: The thrusts [N] the thruster gives: the curve's over its span, within its limits.
        self.low = max(float(thrusts[0]), -thruster.max_reverse)
        self.high = min(float(thrusts[-1]), thruster.max_forward)
        if not self.low <= self.high:
            raise ValueError(f"{where}: its curve's thrusts ({thrusts[0]:.6g} to {thrusts[-1]:.6g} N) lie outside its limits")
        self.zero = self._zero_command(commands, thrusts)
        # Forward: thrust ≥ 0, each flat stretch by its largest command; reverse: by its smallest.
        ahead = thrusts >= 0.0
        behind = thrusts <= 0.0
        #: The two branches' thrusts (strictly increasing, within ``[low, high]``) and commands.
        self.forward = self._trim(*self._branch(np.append(thrusts[ahead], 0.0), np.append(commands[ahead], self.zero), largest=True))
        self.reverse = self._trim(*self._branch(np.append(thrusts[behind], 0.0), np.append(commands[behind], self.zero), largest=False))

    @staticmethod
    def _zero_command(commands: FloatArray, thrusts: FloatArray) -> float:
        """The command of zero thrust nearest 0 (the crossing interpolated; an end if none)."""
        if commands[0] <= 0.0 <= commands[-1] and np.interp(0.0, commands, thrusts) == 0.0:
            return 0.0
        zeros = commands[thrusts == 0.0]
        if zeros.size:
            return float(zeros[np.argmin(np.abs(zeros))])
        above = np.flatnonzero(thrusts > 0.0)
        if above.size == 0 or above[0] == 0:
            return float(commands[-1] if above.size == 0 else commands[0])
        k = int(above[0])
        t0, t1 = thrusts[k - 1], thrusts[k]
        return float(commands[k - 1] + (commands[k] - commands[k - 1]) * (-t0) / (t1 - t0))

    @staticmethod
    def _branch(thrusts: FloatArray, commands: FloatArray, *, largest: bool) -> tuple[FloatArray, FloatArray]:
        """Strictly increasing thrusts with one command each: of equal thrusts, the largest
        command (``largest``) or the smallest."""
        order = np.lexsort((commands, thrusts))
        thrusts, commands = thrusts[order], commands[order]
        if largest:  # the last of each run of equal thrusts
            keep = np.append(thrusts[1:] != thrusts[:-1], True)
        else:  # the first
            keep = np.insert(thrusts[1:] != thrusts[:-1], 0, True)
        return thrusts[keep], commands[keep]

    def _trim(self, thrusts: FloatArray, commands: FloatArray) -> tuple[FloatArray, FloatArray]:
        """A branch cut to ``[low, high]``, its ends' commands interpolated."""
        ends = np.clip([self.low, self.high], thrusts[0], thrusts[-1])
        inside = (thrusts > ends[0]) & (thrusts < ends[1])
        cut = np.unique(np.concatenate([[ends[0]], thrusts[inside], [ends[1]]]))
        return cut, np.interp(cut, thrusts, commands)

    def command(self, thrust: ArrayLike) -> FloatArray:
        """The command of each ``thrust`` [N] (any shape), saturated to ``[low, high]``."""
        t = np.clip(np.asarray(thrust, dtype=np.float64), self.low, self.high)
        if not np.all(np.isfinite(t)):
            raise ValueError(f"thrusts must be finite, got {np.asarray(thrust).tolist()}")
        ahead = np.interp(t, *self.forward)
        behind = np.interp(t, *self.reverse)
        return np.where(t > 0.0, ahead, np.where(t < 0.0, behind, self.zero))


class ThrustInverses:
    """The inverses of several thrusters (a robot's :attr:`uwml.Robot.thrusters`, in order): the
    commands of a vector of thrusts, each saturated, in one interpolation per branch (thruster
    ``k``'s thrust ``t`` is looked up at ``3k + (t − low_k) / (high_k − low_k)``, so that the
    thrusters' branches, laid end to end, are one increasing table)."""

    def __init__(self, thrusters: Sequence[Thruster]) -> None:
        self.inverses = tuple(ThrustInverse(t, k) for k, t in enumerate(thrusters))
        #: Each thruster's least and greatest thrust [N].
        self.low = np.array([i.low for i in self.inverses])
        self.high = np.array([i.high for i in self.inverses])
        self._zero = np.array([i.zero for i in self.inverses])
        self._offset = 3.0 * np.arange(len(self.inverses))
        self._span = np.where(self.high > self.low, self.high - self.low, 1.0)
        self._tables = [self._table([i.forward for i in self.inverses]), self._table([i.reverse for i in self.inverses])]

    def _key(self, thrusts: FloatArray, k: Any = slice(None)) -> FloatArray:
        key: FloatArray = self._offset[k] + (thrusts - self.low[k]) / self._span[k]
        return key

    def _table(self, branches: list[tuple[FloatArray, FloatArray]]) -> tuple[FloatArray, FloatArray]:
        keys = [self._key(thrusts, k) for k, (thrusts, _) in enumerate(branches)]
        return np.concatenate(keys) if keys else np.zeros(1), np.concatenate([c for _, c in branches]) if keys else np.zeros(1)

    def __len__(self) -> int:
        return len(self.inverses)

    def commands(self, thrusts: ArrayLike) -> FloatArray:
        """One command per thruster for ``thrusts`` ``(n,)``, each saturated."""
        t = np.asarray(thrusts, dtype=np.float64).reshape(-1)
        if t.shape != (len(self.inverses),) or not np.all(np.isfinite(t)):
            raise ValueError(f"thrusts must be {len(self.inverses)} finite numbers (one per thruster), got {t.tolist()}")
        t = np.clip(t, self.low, self.high)
        key = self._key(t)
        ahead, behind = np.interp(key, *self._tables[0]), np.interp(key, *self._tables[1])
        return np.where(t > 0.0, ahead, np.where(t < 0.0, behind, self._zero))
