"""A vehicle's thrusters (docs/model.md section 13.1): where each sits and pushes, and the thrust
it gives for a command.

A :class:`Thruster` sits at ``position`` on its body (the base, or a link: in that body's frame)
and pushes along the unit ``direction``. Its thrust ``T = f(u)`` of a command ``u`` (normalized,
PWM or rev/s, as the curve says) is a :class:`ThrustCurve`: a table interpolated linearly, or a
polynomial per sign beyond a dead band; forward and reverse differ. ``|T|`` is then limited to
``max_forward`` / ``max_reverse``, and an optional first-order lag ``τ Ṫ + T = f(u)`` delays it.
The wrench on the body at its origin is ``(T d, T r × d)``: :meth:`uwml.Robot.thruster_allocation`
stacks the columns ``(d, r × d)`` into the allocation matrix ``B`` (``W = B T``).

These classes hold and check numbers; the simulation applies them (:mod:`uwml.sim.thrust`).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._checks import Vec3, check_name, scalar, to_float, vec3

__all__ = ["MAX_CURVE_POINTS", "MAX_POLYNOMIAL_DEGREE", "ThrustCurve", "Thruster"]

#: The most points of a tabulated curve, and the highest degree of a polynomial one.
MAX_CURVE_POINTS = 256
MAX_POLYNOMIAL_DEGREE = 8

FloatArray = NDArray[np.float64]


def _numbers(value: object, name: str, *, at_most: int) -> tuple[float, ...]:
    if isinstance(value, (str, bytes)):
        raise TypeError(f"{name} must be a sequence of numbers, got {value!r}")
    try:
        items = tuple(to_float(v) for v in value)  # type: ignore[attr-defined]
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{name} must be a sequence of numbers, got {value!r}") from exc
    if len(items) > at_most:
        raise ValueError(f"{name} may have at most {at_most} entries, got {len(items)}")
    if not all(math.isfinite(x) for x in items):
        raise ValueError(f"{name} must be finite, got {items}")
    return items


@dataclass(frozen=True)
class ThrustCurve:
    """Thrust [N] for a command: ``ThrustCurve.table(commands, thrusts)`` (linear interpolation
    between points given in increasing command; beyond the ends, the ends' thrusts), or
    ``ThrustCurve.polynomial(forward, reverse, dead_band)`` (``T = Σ c_i (u − b)^i`` for
    ``u > b``, ``−Σ r_i (−u − b)^i`` for ``u < −b``, zero between; ``reverse`` the magnitudes of
    the reverse thrust, default ``forward``). Construct through those two."""

    kind: str
    #: The table's commands and thrusts (empty for a polynomial).
    commands: tuple[float, ...] = field(default=())
    thrusts: tuple[float, ...] = field(default=())
    #: A polynomial's coefficients, lowest degree first, in ``u − b`` (empty for a table).
    forward: tuple[float, ...] = field(default=())
    reverse: tuple[float, ...] = field(default=())
    dead_band: float = 0.0

    def __post_init__(self) -> None:
        if self.kind == "table":
            commands = _numbers(self.commands, "curve commands", at_most=MAX_CURVE_POINTS)
            thrusts = _numbers(self.thrusts, "curve thrusts", at_most=MAX_CURVE_POINTS)
            if len(commands) < 2 or len(commands) != len(thrusts):
                raise ValueError(
                    f"a thrust table needs at least 2 points, as many commands as thrusts; got {len(commands)} commands and {len(thrusts)} thrusts"
                )
            if any(b <= a for a, b in itertools.pairwise(commands)):
                raise ValueError(f"a thrust table's commands must increase strictly, got {commands}")
            object.__setattr__(self, "commands", commands)
            object.__setattr__(self, "thrusts", thrusts)
        elif self.kind == "polynomial":
            degree = MAX_POLYNOMIAL_DEGREE + 1
            forward = _numbers(self.forward, "curve forward coefficients", at_most=degree)
            reverse = _numbers(self.reverse, "curve reverse coefficients", at_most=degree) if self.reverse else forward
            if not forward:
                raise ValueError("a polynomial thrust curve needs its forward coefficients")
            object.__setattr__(self, "forward", forward)
            object.__setattr__(self, "reverse", reverse)
            object.__setattr__(self, "dead_band", scalar(self.dead_band, "curve dead_band", positive=False))
        else:
            raise ValueError(f"a thrust curve's kind must be 'table' or 'polynomial', got {self.kind!r}")

    @classmethod
    def table(cls, commands: Sequence[float], thrusts: Sequence[float]) -> ThrustCurve:
        """Linear interpolation through ``(commands[i], thrusts[i])``, commands increasing."""
        return cls("table", commands=tuple(commands), thrusts=tuple(thrusts))

    @classmethod
    def polynomial(cls, forward: Sequence[float], reverse: Sequence[float] | None = None, dead_band: float = 0.0) -> ThrustCurve:
        """A polynomial per sign of the command beyond ``dead_band`` (see the class)."""
        return cls("polynomial", forward=tuple(forward), reverse=tuple(reverse or ()), dead_band=dead_band)

    @classmethod
    def t200(cls) -> ThrustCurve:
        """A T200-like thruster at 16 V, command normalized to ``[-1, 1]`` (ESC pulses 1100-1900
        µs): 51.5 N (5.25 kgf) forward and 40.2 N (4.1 kgf) reverse at full command, as Blue
        Robotics' T200 technical details give them, zero in the ESC's dead band of ±25 µs
        (±0.0625), quadratic in between: an approximation of the published curve, not a fit to it."""
        band = 0.0625
        span = (1.0 - band) ** 2
        return cls.polynomial(forward=(0.0, 0.0, 51.5 / span), reverse=(0.0, 0.0, 40.2 / span), dead_band=band)

    def __call__(self, command: ArrayLike) -> FloatArray:
        """Thrust [N] of each command (any shape); commands must be finite."""
        u = np.asarray(command, dtype=np.float64)
        if not np.all(np.isfinite(u)):
            raise ValueError(f"thruster commands must be finite, got {u.tolist()}")
        if self.kind == "table":
            return np.interp(u, self.commands, self.thrusts)
        b = self.dead_band
        ahead = np.polynomial.polynomial.polyval(np.maximum(u - b, 0.0), self.forward)
        back = np.polynomial.polynomial.polyval(np.maximum(-u - b, 0.0), self.reverse)
        return np.where(u > b, ahead, 0.0) - np.where(u < -b, back, 0.0)


@dataclass(frozen=True)
class Thruster:
    """A thruster at ``position`` [m] on its body, pushing along ``direction`` (normalized here;
    both in the body's frame), its thrust ``curve(u)`` limited to ``max_forward`` [N] forward and
    ``max_reverse`` [N] backward, and lagging by ``time_constant`` [s] (0: none)."""

    position: Vec3
    direction: Vec3
    curve: ThrustCurve = field(default_factory=ThrustCurve.t200)
    max_forward: float = math.inf
    max_reverse: float = math.inf
    time_constant: float = 0.0
    name: str | None = None

    def __post_init__(self) -> None:
        check_name(self.name, "thruster.name")
        object.__setattr__(self, "position", vec3(self.position, "thruster.position"))
        d = vec3(self.direction, "thruster.direction")
        norm = math.sqrt(d[0] ** 2 + d[1] ** 2 + d[2] ** 2)
        if not norm > 1e-9:
            raise ValueError(f"thruster.direction must be a nonzero vector, got {d}")
        object.__setattr__(self, "direction", (d[0] / norm, d[1] / norm, d[2] / norm))
        if not isinstance(self.curve, ThrustCurve):
            raise TypeError(f"thruster.curve must be a uwml.ThrustCurve, got {type(self.curve).__name__}")
        for limit in ("max_forward", "max_reverse"):
            value = to_float(getattr(self, limit))
            if math.isnan(value) or value < 0.0:
                raise ValueError(f"thruster.{limit} must be a non-negative number of newtons (inf: none), got {value}")
            object.__setattr__(self, limit, value)
        object.__setattr__(self, "time_constant", scalar(self.time_constant, "thruster.time_constant", positive=False))

    def thrust(self, command: ArrayLike) -> FloatArray:
        """The steady thrust [N] of ``command``: the curve's, within the limits."""
        return np.clip(self.curve(command), -self.max_reverse, self.max_forward)

    @property
    def moment_arm(self) -> Vec3:
        """``position × direction``: the moment about the body's origin per newton of thrust."""
        (x, y, z), (a, b, c) = self.position, self.direction
        return (y * c - z * b, z * a - x * c, x * b - y * a)
