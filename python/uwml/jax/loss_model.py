"""The joint losses of an oil-filled, pressure-compensated joint (docs/losses.md, "The models"), for
:mod:`uwml.jax`: the core's ``losses.rs`` (``JointLosses::at`` then ``LossState::evaluate``)
without branches on the data, so that it is differentiable in the speed, the pressure, the
temperature and every parameter. The core's branches become ``jnp.where``: the smooth sign's
``m = 0`` case, the oil's speed exponents 1, 1.5 and 2 (which it takes without a power function)
and the power's zero speed.
"""

from __future__ import annotations

import jax
import jax.numpy as jnp

from ..sea.conditions import hydrostatic_pressure
from .compiled_robot import JointLossParameters
from .strip_integrals import magnitude, safe_sqrt

__all__ = ["joint_losses", "loss_levels"]

Array = jax.Array

#: Pa per MPa: the parameters are in MPa (as :class:`uwml.Seal` and :class:`uwml.OilDrag` give
#: them), the core computes in Pa.
_MPA = 1e6


def smooth_sign(x: Array, epsilon: Array) -> Array:
    """``sgn_ε(x) = x / sqrt(x² + ε²)``, as the core evaluates it (scaled by ``m = max(|x|, ε)``;
    ``x`` itself where ``m = 0``: the hard sign's 0)."""
    m = jnp.maximum(magnitude(x), epsilon)
    scaled = m > 0
    safe = jnp.where(scaled, m, 1)
    a, b = x / safe, epsilon / safe
    return jnp.where(scaled, a / jnp.sqrt(jnp.where(scaled, a * a + b * b, 1)), x)


def _power(speed: Array, exponent: Array) -> Array:
    """``speed^n`` for ``speed ≥ 0``: ``speed``, ``speed·√speed`` (0 at rest) and ``speed²`` for
    n = 1, 1.5 and 2, else ``speed^n`` (0 at rest, with a finite derivative in n there)."""
    moving = speed > 0
    general = jnp.where(moving, jnp.where(moving, speed, 1) ** exponent, 0)
    return jnp.where(
        exponent == 1, speed, jnp.where(exponent == 1.5, speed * safe_sqrt(speed), jnp.where(exponent == 2, speed * speed, general))
    )


def loss_levels(
    p: JointLossParameters, depth: Array, temperature_c: Array, sea_density: Array, gravity: Array
) -> tuple[Array, Array, Array, Array]:
    """The core's ``JointLosses::at`` (in its units, Pa) at the pressure of ``depth`` (the core's
    ``pressure_at_depth``: ``sea_density · gravity · depth``) and oil temperature
    ``temperature_c``: each joint's oil scale, the seal's running level, breakaway excess and
    viscous coefficient ``(N,)`` each."""
    pressure = hydrostatic_pressure(depth, sea_density, gravity)  # type: ignore[arg-type]
    exponent = p.pressure_sensitivity_per_mpa / _MPA * (pressure - p.reference_pressure_mpa * _MPA) - p.temperature_sensitivity_per_k * (
        temperature_c - p.reference_temperature_c
    )
    oil_scale = p.k_oil * jnp.exp(exponent)
    running = p.c0 + p.c1_per_mpa / _MPA * pressure
    excess = p.s0 + p.s1_per_mpa / _MPA * pressure - running
    viscous = p.d0 + p.d1_per_mpa / _MPA * pressure
    return oil_scale, running, excess, viscous


def joint_losses(
    parameters: JointLossParameters, speed: Array, depth: Array, temperature_c: Array, sea_density: Array, gravity: Array
) -> tuple[Array, Array, Array]:
    """``(visc, seal, current)`` of every joint ``(N,)`` at output speeds ``speed``, the pressure
    of ``depth`` (the core's ``pressure_at_depth``: ``sea_density · gravity · depth``) and oil
    temperature ``temperature_c``; zero for a joint without losses (its neutral parameters)."""
    p = parameters
    oil_scale, running, excess, viscous = loss_levels(p, depth, temperature_c, sea_density, gravity)
    output_per_motor_torque = p.ratio * p.efficiency
    # LossState::evaluate.
    sign = smooth_sign(speed, p.epsilon)
    size = magnitude(speed)
    oil = oil_scale * _power(p.ratio * size, p.exponent) * sign
    x = size * (1 / p.stribeck_speed)
    seal = sign * (running + excess * jnp.exp(-(x * x))) + viscous * speed
    current = (oil + seal / output_per_motor_torque) * (1 / p.torque_constant)
    return -output_per_motor_torque * oil, -seal, current
