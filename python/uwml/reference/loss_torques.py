"""Joint losses of an oil-filled, pressure-compensated joint (docs/losses.md, "The models"), in numpy.

Written literally from the formulas of docs/losses.md, "The models": the oil's churning torque
(:func:`oil_drag_torque`), the seal's Stribeck friction (:func:`seal_torque`), the motor current
they cost (:func:`loss_current`), both as environment torques at the joint
(:func:`joint_loss_torques`), the smooth sign (:func:`smooth_sign`) and the core's uniform-sea
pressure (:func:`hydrostatic_pressure_mpa`). The parameters are duck-typed: any objects with the
attributes of :class:`uwml.model.losses.OilDrag`, :class:`uwml.model.losses.Seal` and :class:`uwml.model.losses.Drive`
will do.
"""

from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from ._inputs import Array, _number

__all__ = ["hydrostatic_pressure_mpa", "joint_loss_torques", "loss_current", "oil_drag_torque", "seal_torque", "smooth_sign"]

# --------------------------------------------------------------------------------------------
# Joint losses (docs/losses.md, "The models")
# --------------------------------------------------------------------------------------------

#: Absolute zero [°C]: temperatures must lie above it.
_ABSOLUTE_ZERO_C = -273.15


def _samples(value: ArrayLike, name: str, *, low: float | None = None, strict: bool = False) -> Array:
    """A float array of finite numbers, optionally ``>= low`` (``> low`` if ``strict``)."""
    try:
        a = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a number or an array of numbers, got {value!r}") from exc
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite")
    if low is not None and np.any(a <= low if strict else a < low):
        raise ValueError(f"{name} must be {'>' if strict else '>='} {low}, got minimum {a.min()}")
    return a


def _oil_parameters(oil: Any) -> tuple[float, float, float, float, float, float]:
    """``(k_oil, n, a_p, a_T, p_ref, θ_ref)`` of a duck-typed :class:`uwml.model.losses.OilDrag`, checked."""
    exponent = _number(oil.exponent, "oil.exponent", positive=True)
    if not 1.0 <= exponent <= 2.0:
        raise ValueError(f"oil.exponent must lie in [1, 2], got {exponent}")
    reference_temperature = float(_samples(oil.reference_temperature_c, "oil.reference_temperature_c", low=_ABSOLUTE_ZERO_C, strict=True))
    return (
        _number(oil.k_oil, "oil.k_oil", positive=False),
        exponent,
        _number(oil.pressure_sensitivity_per_mpa, "oil.pressure_sensitivity_per_mpa", positive=False),
        _number(oil.temperature_sensitivity_per_k, "oil.temperature_sensitivity_per_k", positive=False),
        _number(oil.reference_pressure_mpa, "oil.reference_pressure_mpa", positive=False),
        reference_temperature,
    )


def _seal_parameters(seal: Any) -> tuple[float, float, float, float, float, float, float]:
    """``(C0, C1, S0, S1, D0, D1, ω_s)`` of a duck-typed :class:`uwml.model.losses.Seal`, checked."""
    c0 = _number(seal.c0, "seal.c0", positive=False)
    c1 = _number(seal.c1_per_mpa, "seal.c1_per_mpa", positive=False)
    s0 = _number(seal.s0, "seal.s0", positive=False)
    s1 = _number(seal.s1_per_mpa, "seal.s1_per_mpa", positive=False)
    if s0 < c0:
        raise ValueError(f"seal.s0 must be >= seal.c0 = {c0} (breakaway at least running friction), got {s0}")
    if s1 < c1:
        raise ValueError(f"seal.s1_per_mpa must be >= seal.c1_per_mpa = {c1} (breakaway at least running friction), got {s1}")
    return (
        c0,
        c1,
        s0,
        s1,
        _number(seal.d0, "seal.d0", positive=False),
        _number(seal.d1_per_mpa, "seal.d1_per_mpa", positive=False),
        _number(seal.stribeck_speed, "seal.stribeck_speed", positive=True),
    )


def _drive_parameters(drive: Any) -> tuple[float, float, float]:
    """``(K_t, N, η)`` of a duck-typed :class:`uwml.model.losses.Drive`, checked."""
    efficiency = _number(drive.efficiency, "drive.efficiency", positive=True)
    if efficiency > 1.0:
        raise ValueError(f"drive.efficiency must lie in (0, 1], got {efficiency}")
    return (
        _number(drive.torque_constant, "drive.torque_constant", positive=True),
        _number(drive.ratio, "drive.ratio", positive=True),
        efficiency,
    )


def smooth_sign(x: ArrayLike, epsilon: float) -> Array:
    """The smooth sign ``sgn_ε(x) = x / sqrt(x² + ε²)`` (docs/losses.md, "The models").

    Odd, strictly inside (−1, 1) for ε > 0, and ``sgn_ε(0) = 0``; ε = 0 gives the hard sign
    ``np.sign`` (again with ``sgn(0) = 0``).

    Parameters
    ----------
    x : array_like
        Finite numbers (typically a speed).
    epsilon : float
        Smoothing width, ≥ 0, in the units of ``x``.

    Returns
    -------
    ndarray
        Shaped like ``x``.

    Raises
    ------
    ValueError
        If ``x`` is not finite or ``epsilon`` is negative or not finite.
    """
    x = _samples(x, "x")
    epsilon = _number(epsilon, "epsilon", positive=False)
    if epsilon == 0.0:
        return np.sign(x)
    # hypot, not sqrt(x² + ε²): the same number where the squares neither underflow (x = 0 with
    # ε below 1e-154 would give 0/0) nor overflow.
    return x / np.hypot(x, epsilon)


def oil_drag_torque(
    oil: Any,
    motor_speed: ArrayLike,
    pressure_mpa: ArrayLike,
    temperature_c: ArrayLike,
    epsilon: float = 0.0,
) -> Array:
    """Viscous (churning) torque of the compensation oil at the motor shaft (docs/losses.md, "The models").

    ``T_oil = K_oil · exp(a_p (p − p_ref)) · exp(−a_T (θ − θ_ref)) · |ω_m|^n · sgn_ε(ω_m)``: the
    torque that drives the oil, in the direction of ``ω_m`` (the motor supplies it).

    Parameters
    ----------
    oil : OilDrag-like
        ``k_oil`` [N·m·(rad/s)^−n] ≥ 0, ``exponent`` n in [1, 2], ``pressure_sensitivity_per_mpa``
        a_p ≥ 0, ``temperature_sensitivity_per_k`` a_T ≥ 0, ``reference_pressure_mpa`` ≥ 0,
        ``reference_temperature_c`` > −273.15.
    motor_speed : array_like
        Motor speed ``ω_m = N·ω`` [rad/s].
    pressure_mpa : array_like
        Ambient (gauge) pressure [MPa], ≥ 0.
    temperature_c : array_like
        Oil temperature [°C], > −273.15.
    epsilon : float
        Smooth-sign width [rad/s, at the motor], ≥ 0.

    Returns
    -------
    ndarray
        ``T_oil`` [N·m], the broadcast shape of the three inputs.

    Raises
    ------
    ValueError
        On parameters out of range, non-finite inputs, negative pressures, temperatures at or
        below absolute zero, or a negative ``epsilon``; the message names the argument.
    """
    k_oil, exponent, a_p, a_t, p_ref, theta_ref = _oil_parameters(oil)
    omega_m = _samples(motor_speed, "motor_speed")
    p = _samples(pressure_mpa, "pressure_mpa", low=0.0)
    theta = _samples(temperature_c, "temperature_c", low=_ABSOLUTE_ZERO_C, strict=True)
    omega_m, p, theta = np.broadcast_arrays(omega_m, p, theta)
    scale = k_oil * np.exp(a_p * (p - p_ref)) * np.exp(-a_t * (theta - theta_ref))
    return scale * np.abs(omega_m) ** exponent * smooth_sign(omega_m, epsilon)


def seal_torque(seal: Any, speed: ArrayLike, pressure_mpa: ArrayLike, epsilon: float = 0.0) -> Array:
    """Friction torque of the output-shaft dynamic seal at the joint output (docs/losses.md, "The models").

    ``T_seal = sgn_ε(ω) · [C(p) + (S(p) − C(p)) · exp(−(|ω|/ω_s)²)] + D(p) · ω`` with
    ``C = C0 + C1 p``, ``S = S0 + S1 p``, ``D = D0 + D1 p``: the torque that overcomes the seal,
    in the direction of ω. At ``ω → 0⁺`` (ε = 0) it is the breakaway level S(p).

    Parameters
    ----------
    seal : Seal-like
        ``c0``, ``c1_per_mpa``, ``s0``, ``s1_per_mpa`` [N·m, N·m/MPa] with ``s0 >= c0 >= 0`` and
        ``s1_per_mpa >= c1_per_mpa >= 0``; ``d0``, ``d1_per_mpa`` [N·m·s/rad, per MPa] ≥ 0;
        ``stribeck_speed`` ω_s [rad/s] > 0.
    speed : array_like
        Output speed ω [rad/s].
    pressure_mpa : array_like
        Ambient (gauge) pressure [MPa], ≥ 0.
    epsilon : float
        Smooth-sign width [rad/s], ≥ 0.

    Returns
    -------
    ndarray
        ``T_seal`` [N·m], the broadcast shape of ``speed`` and ``pressure_mpa``.

    Raises
    ------
    ValueError
        On parameters out of range or out of order, non-finite inputs, negative pressures or a
        negative ``epsilon``; the message names the argument.
    """
    c0, c1, s0, s1, d0, d1, omega_s = _seal_parameters(seal)
    omega = _samples(speed, "speed")
    p = _samples(pressure_mpa, "pressure_mpa", low=0.0)
    omega, p = np.broadcast_arrays(omega, p)
    running = c0 + c1 * p
    breakaway = s0 + s1 * p
    viscous = d0 + d1 * p
    stribeck = np.exp(-((np.abs(omega) / omega_s) ** 2))
    return smooth_sign(omega, epsilon) * (running + (breakaway - running) * stribeck) + viscous * omega


def loss_current(drive: Any, oil_torque: ArrayLike, seal_torque: ArrayLike) -> Array:
    """Motor current that the two losses cost: ``I_loss = T_oil/K_t + T_seal/(N η K_t)`` [A].

    Parameters
    ----------
    drive : Drive-like
        ``torque_constant`` K_t [N·m/A] > 0, ``ratio`` N > 0, ``efficiency`` η in (0, 1].
    oil_torque : array_like
        ``T_oil`` at the motor shaft [N·m] (:func:`oil_drag_torque`).
    seal_torque : array_like
        ``T_seal`` at the joint output [N·m] (:func:`seal_torque`).

    Returns
    -------
    ndarray
        ``I_loss`` [A], the broadcast shape of the two torques (signed like them).

    Raises
    ------
    ValueError
        On drive parameters out of range or non-finite torques.
    """
    torque_constant, ratio, efficiency = _drive_parameters(drive)
    t_oil = _samples(oil_torque, "oil_torque")
    t_seal = _samples(seal_torque, "seal_torque")
    return t_oil / torque_constant + t_seal / (ratio * efficiency * torque_constant)


def joint_loss_torques(
    drive: Any,
    oil: Any | None,
    seal: Any | None,
    speed: ArrayLike,
    pressure_mpa: ArrayLike,
    temperature_c: ArrayLike,
    epsilon: float = 0.0,
) -> dict[str, Array]:
    """Joint losses as environment torques at the output and as motor current (docs/losses.md, "The models").

    The oil is sheared at the motor speed ``ω_m = N ω``; the seal slides at the output speed ω.
    In docs/model.md section 1's sign (the environment's torque on the joint, so losses oppose motion):
    ``visc = −N η T_oil(N ω, p, θ)`` and ``seal = −T_seal(ω, p)``; ``current`` is
    ``I_loss = T_oil/K_t + T_seal/(N η K_t)``, the extra motor current they cost.

    Parameters
    ----------
    drive : Drive-like
        ``torque_constant`` K_t [N·m/A], ``ratio`` N, ``efficiency`` η.
    oil : OilDrag-like or None
        Oil drag parameters (:func:`oil_drag_torque`); None: no oil (zero).
    seal : Seal-like or None
        Seal parameters (:func:`seal_torque`); None: no seal (zero).
    speed : array_like
        Output speed ω [rad/s].
    pressure_mpa : array_like
        Ambient (gauge) pressure [MPa], ≥ 0.
    temperature_c : array_like
        Oil temperature [°C], > −273.15.
    epsilon : float
        Smooth-sign width [rad/s at the output], ≥ 0; the oil's sign uses ``N ε`` at the motor,
        so both signs switch over the same output speeds.

    Returns
    -------
    dict
        ``visc``, ``seal`` [N·m at the output] and ``current`` [A], each of the broadcast shape
        of ``speed``, ``pressure_mpa`` and ``temperature_c``.

    Raises
    ------
    ValueError
        On parameters out of range or out-of-range inputs; the message names the argument.
    """
    _, ratio, efficiency = _drive_parameters(drive)
    omega = _samples(speed, "speed")
    p = _samples(pressure_mpa, "pressure_mpa", low=0.0)
    theta = _samples(temperature_c, "temperature_c", low=_ABSOLUTE_ZERO_C, strict=True)
    epsilon = _number(epsilon, "epsilon", positive=False)
    omega, p, theta = np.broadcast_arrays(omega, p, theta)
    t_oil = np.zeros(omega.shape) if oil is None else oil_drag_torque(oil, ratio * omega, p, theta, ratio * epsilon)
    t_seal = np.zeros(omega.shape) if seal is None else seal_torque(seal, omega, p, epsilon)
    return {
        "visc": -ratio * efficiency * t_oil,
        "seal": -t_seal,
        "current": loss_current(drive, t_oil, t_seal),
    }


def hydrostatic_pressure_mpa(depth_m: ArrayLike, sea_density: float = 1025.0, gravity: float = 9.81) -> Array:
    """Gauge pressure of a uniform sea at depth: ``p = ρ g z`` [MPa].

    The core's model (docs/losses.md, "Pressure from depth"); :func:`uwml.sea.seawater.pressure_at_depth_mpa` gives the
    TEOS-10 value, and docs/losses.md the measured difference.

    Parameters
    ----------
    depth_m : array_like
        Depth below the surface z [m], ≥ 0.
    sea_density : float
        Sea-water density ρ [kg/m³], > 0.
    gravity : float
        Gravitational acceleration g [m/s²], ≥ 0.

    Returns
    -------
    ndarray
        Pressure [MPa], shaped like ``depth_m``.

    Raises
    ------
    ValueError
        If ``depth_m`` is negative or not finite, ``sea_density <= 0`` or ``gravity < 0``.
    """
    z = _samples(depth_m, "depth_m", low=0.0)
    rho = _number(sea_density, "sea_density", positive=True)
    g = _number(gravity, "gravity", positive=False)
    return rho * g * z * 1e-6
