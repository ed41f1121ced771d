"""Joint losses inside an oil-filled, pressure-compensated joint: parameter descriptions.

Three parts, after the paper's Section IV and the uwml model (docs/losses.md):

- :class:`OilDrag`: viscous (churning) loss of the oil around the motor, at motor speed
  ``ω_m = N·ω``: ``T_oil = k_oil · exp(a_p (p − p_ref)) · exp(−a_T (θ − θ_ref)) · |ω_m|^n · sgn_ε(ω_m)``
  [N·m at the motor shaft].
- :class:`Seal`: friction of the output-shaft dynamic seal, at output speed ω:
  ``T_seal = sgn_ε(ω) · [C(p) + (S(p) − C(p)) · exp(−(|ω|/ω_s)²)] + D(p) · ω`` with
  ``C = c0 + c1 p``, ``S = s0 + s1 p``, ``D = d0 + d1 p`` [N·m at the joint output].
- :class:`Drive`: torque constant, gear ratio, gear efficiency and rated current, which turn
  the two torques into a loss current ``I = T_oil/K_t + T_seal/(N η K_t)`` and a loss torque at
  the output ``N η T_oil + T_seal``.

Units: speeds in rad/s (output side unless said otherwise), pressures in MPa (every name that
takes one says ``mpa``), temperatures in °C, torques in N·m, currents in A.

The defaults are **illustrative**: the paper publishes laws, not parameters. They are chosen so
that the paper's laws hold (the oil loss is the more speed-sensitive, the seal loss the more
pressure-sensitive, breakaway exceeds running friction, both grow with pressure) and the total
loss current at 10 r/min and 10 MPa is 2.85 A, 27.4 % of the 10.4 A rated current. The oil's
speed exponent is 1: laminar Couette flow in the gap (docs/losses.md, "The defaults are illustrative").
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .._checks import to_float

__all__ = ["RPM", "Drive", "OilDrag", "Seal", "rad_s_to_rpm", "rpm_to_rad_s"]

#: One revolution per minute in rad/s.
RPM = 2.0 * math.pi / 60.0


def rpm_to_rad_s(speed_rpm: float) -> float:
    """Revolutions per minute to rad/s."""
    return speed_rpm * RPM


def rad_s_to_rpm(speed: float) -> float:
    """rad/s to revolutions per minute."""
    return speed / RPM


def _number(value: object, name: str, *, low: float | None = None, strict: bool = False, high: float | None = None) -> float:
    try:
        x = to_float(value)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(x):
        raise ValueError(f"{name} must be finite, got {x}")
    if low is not None and (x <= low if strict else x < low):
        raise ValueError(f"{name} must be {'>' if strict else '>='} {low}, got {x}")
    if high is not None and x > high:
        raise ValueError(f"{name} must be <= {high}, got {x}")
    return x


@dataclass(frozen=True)
class OilDrag:
    """Viscous (churning) loss of the compensation oil, as torque at the motor shaft.

    Parameters
    ----------
    k_oil
        Torque at ``|ω_m| = 1 rad/s`` at the reference pressure and temperature [N·m·(rad/s)^−n].
    exponent
        Speed exponent n in [1, 2]: 1 for laminar Couette flow in the gap (the default), 1.5 with
        Taylor vortices (docs/losses.md, "The models"); 1, 1.5 and 2 cost no power function.
    pressure_sensitivity_per_mpa
        a_p [1/MPa]: the Barus pressure-viscosity coefficient α times 1 (laminar) or 0.5 (vortex).
    temperature_sensitivity_per_k
        a_T [1/K]: ``−d ln μ / dθ`` of the oil near the operating temperature (0 to ignore).
    reference_pressure_mpa, reference_temperature_c
        Where ``k_oil`` was measured.
    """

    k_oil: float = 3.3234e-3
    exponent: float = 1.0
    pressure_sensitivity_per_mpa: float = 0.02
    temperature_sensitivity_per_k: float = 0.06
    reference_pressure_mpa: float = 0.0
    reference_temperature_c: float = 20.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "k_oil", _number(self.k_oil, "oil.k_oil", low=0.0))
        object.__setattr__(self, "exponent", _number(self.exponent, "oil.exponent", low=1.0, high=2.0))
        object.__setattr__(
            self, "pressure_sensitivity_per_mpa", _number(self.pressure_sensitivity_per_mpa, "oil.pressure_sensitivity_per_mpa", low=0.0)
        )
        object.__setattr__(
            self, "temperature_sensitivity_per_k", _number(self.temperature_sensitivity_per_k, "oil.temperature_sensitivity_per_k", low=0.0)
        )
        object.__setattr__(self, "reference_pressure_mpa", _number(self.reference_pressure_mpa, "oil.reference_pressure_mpa", low=0.0))
        object.__setattr__(
            self, "reference_temperature_c", _number(self.reference_temperature_c, "oil.reference_temperature_c", low=-273.15, strict=True)
        )


@dataclass(frozen=True)
class Seal:
    """Friction of the output-shaft dynamic seal (Stribeck form, pressure-scheduled levels).

    ``C(p) = c0 + c1_per_mpa·p`` is the running (Coulomb) level, ``S(p) = s0 + s1_per_mpa·p`` the
    breakaway level, ``D(p) = d0 + d1_per_mpa·p`` the viscous slope [N·m·s/rad], all at the joint
    output; ``stribeck_speed`` ω_s [rad/s] is how fast breakaway fades into running friction.
    Physical ordering is required for every pressure ≥ 0: ``S ≥ C ≥ 0`` and ``D ≥ 0``, i.e.
    ``s0 ≥ c0 ≥ 0``, ``s1 ≥ c1 ≥ 0``, ``d0, d1 ≥ 0``.
    """

    c0: float = 16.0
    c1_per_mpa: float = 3.7
    s0: float = 21.0
    s1_per_mpa: float = 6.7
    d0: float = 2.2
    d1_per_mpa: float = 0.34
    stribeck_speed: float = 0.05

    def __post_init__(self) -> None:
        for name in ("c0", "c1_per_mpa", "d0", "d1_per_mpa"):
            object.__setattr__(self, name, _number(getattr(self, name), f"seal.{name}", low=0.0))
        object.__setattr__(self, "s0", _number(self.s0, "seal.s0", low=self.c0))
        object.__setattr__(self, "s1_per_mpa", _number(self.s1_per_mpa, "seal.s1_per_mpa", low=self.c1_per_mpa))
        object.__setattr__(self, "stribeck_speed", _number(self.stribeck_speed, "seal.stribeck_speed", low=0.0, strict=True))


@dataclass(frozen=True)
class Drive:
    """Motor and reducer of a joint.

    Defaults: the paper's hip-roll joint (Kollmorgen TBMS-7646-A frameless motor, harmonic
    reducer N = 160, rated current 10.4 A); the torque constant and gear efficiency are
    illustrative (not published). Where K_t is unknown, ``torque_constant=1`` makes every
    torque a current.
    """

    torque_constant: float = 0.40
    ratio: float = 160.0
    efficiency: float = 0.80
    rated_current: float = 10.4

    def __post_init__(self) -> None:
        object.__setattr__(self, "torque_constant", _number(self.torque_constant, "drive.torque_constant", low=0.0, strict=True))
        object.__setattr__(self, "ratio", _number(self.ratio, "drive.ratio", low=0.0, strict=True))
        object.__setattr__(self, "efficiency", _number(self.efficiency, "drive.efficiency", low=0.0, strict=True, high=1.0))
        object.__setattr__(self, "rated_current", _number(self.rated_current, "drive.rated_current", low=0.0, strict=True))
