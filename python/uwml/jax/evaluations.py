"""The evaluations of :mod:`uwml.jax`: pure functions of a compiled robot (:class:`RobotModel`),
one joint state and one :class:`Motion`, which work under ``jax.jit``, ``jax.vmap`` and
``jax.grad`` (docs/batched.md).

They return uwml's own result classes, :class:`uwml.Torques` (with its :class:`uwml.BaseWrench`),
:class:`uwml.Regressors` and :class:`uwml.Jacobians`, registered here as pytrees (their fields are
the leaves): the same fields and properties (``total``, ``hydro``) as the CPU path's, holding JAX
arrays. A JAX ``Torques`` always has its ``base``.

Precision: every evaluation runs in the floating dtype of its joint state (``q``, ``qd``,
``qdd`` promoted together; Python numbers and integers take JAX's default, float32 unless
``jax_enable_x64``); the model's arrays and the motion are cast to it.
"""

from __future__ import annotations

from typing import Any

import jax
import jax.numpy as jnp
import numpy as np
from jax.typing import ArrayLike

from ..robot.results import BaseWrench, Jacobians, Regressors, Torques
from .body_forces import PARTS, Coefficients, body_wrenches, generalized
from .compiled_robot import RobotModel
from .loss_model import joint_losses
from .tree_motion import Motion, forward, still

__all__ = ["added_mass_matrix", "environment", "hydro", "jacobians", "regressors"]

Array = jax.Array

for _result in (BaseWrench, Torques, Regressors, Jacobians):
    try:
        jax.tree_util.register_dataclass(_result)
    except ValueError:  # registered already (the module imported again)
        pass

#: The lumped models' 21 independent added-mass entries (upper triangle, row by row).
_UPPER = np.triu_indices(6)


def _dtype(*states: ArrayLike) -> jnp.dtype:
    """The floating dtype of joint states (lists and tuples read as arrays)."""
    return jnp.result_type(float, *(jnp.asarray(x) for x in states))


def _motion(motion: Motion | None, dtype: jnp.dtype) -> Motion:
    """``motion`` cast to ``dtype`` (None: a fixed, upright base in still water)."""
    return still(dtype) if motion is None else Motion(*(jnp.asarray(x, dtype) for x in motion))


def _cast(model: RobotModel, motion: Motion | None, dtype: jnp.dtype) -> tuple[RobotModel, Motion]:
    return jax.tree_util.tree_map(lambda x: jnp.asarray(x, dtype), model), _motion(motion, dtype)


def _coefficients(model: RobotModel) -> Coefficients:
    seg, lumped = model.segments, model.lumped
    return Coefficients(seg.cd, seg.cm, seg.cd_axial, lumped.added_mass, lumped.linear_damping, lumped.quadratic_damping)


def _forces(
    model: RobotModel, state: tuple[Array, Array, Array], motion: Motion, coefficients: Coefficients
) -> dict[str, tuple[Array, Array]]:
    """Per part, the joints' generalized forces and the base wrench (cast inputs)."""
    frames = forward(model, *state, motion, model.gravity)
    wrenches = body_wrenches(model, frames, coefficients, model.density)
    return {part: generalized(model, frames, wrenches[part]) for part in PARTS}


def _state(q: ArrayLike, qd: ArrayLike, qdd: ArrayLike, dtype: jnp.dtype) -> tuple[Array, Array, Array]:
    return jnp.asarray(q, dtype), jnp.asarray(qd, dtype), jnp.asarray(qdd, dtype)


def _torques(forces: dict[str, tuple[Array, Array]], losses: tuple[Array, Array, Array] | None) -> Torques:
    arrays: dict[str, Any] = {part: forces[part][0] for part in PARTS}
    base: dict[str, Any] = {part: forces[part][1] for part in PARTS}
    zero = jnp.zeros_like(arrays["drag"])
    arrays["visc"], arrays["seal"], arrays["current"] = (zero, zero, zero) if losses is None else losses
    return Torques(**arrays, base=BaseWrench(**base))


def hydro(model: RobotModel, q: ArrayLike, qd: ArrayLike, qdd: ArrayLike, motion: Motion | None = None) -> Torques:
    """Drag, added mass, buoyancy (with Froude-Krylov) and gravity on every joint and on the base
    (:meth:`uwml.Robot.hydro`'s, for one state): ``q``, ``qd``, ``qdd`` ``(n_joints,)``,
    ``motion`` the base's motion and the current (None: a fixed, upright base in still water).
    ``visc``, ``seal`` and ``current`` are zeros."""
    dtype = _dtype(q, qd, qdd)
    model, motion = _cast(model, motion, dtype)
    return _torques(_forces(model, _state(q, qd, qdd, dtype), motion, _coefficients(model)), None)


def environment(
    model: RobotModel,
    q: ArrayLike,
    qd: ArrayLike,
    qdd: ArrayLike,
    motion: Motion | None = None,
    depth: ArrayLike = 0.0,
    temperature_c: ArrayLike = 20.0,
) -> Torques:
    """:func:`hydro` and the joint losses at ``depth`` [m] and oil temperature ``temperature_c``
    [°C] (:meth:`uwml.Robot.environment`'s): ``visc``, ``seal``, ``current`` of the losses the
    model was compiled with (:func:`uwml.jax.compile_robot`), at the pressure
    ``sea_density · g · depth``. Unchecked: give depths and temperatures in their domains
    (docs/domains.md)."""
    dtype = _dtype(q, qd, qdd)
    model, motion = _cast(model, motion, dtype)
    state = _state(q, qd, qdd, dtype)
    losses = joint_losses(
        model.losses, state[1], jnp.asarray(depth, dtype), jnp.asarray(temperature_c, dtype), model.sea_density, model.gravity
    )
    return _torques(_forces(model, state, motion, _coefficients(model)), losses)


def regressors(model: RobotModel, q: ArrayLike, qd: ArrayLike, qdd: ArrayLike, motion: Motion | None = None) -> Regressors:
    """The regressors of :meth:`uwml.Robot.hydro_regressors` (:class:`uwml.Regressors`, one
    state): the forces of each coefficient at unit value. The forces are linear in the
    coefficients, so each column is their exact derivative in it (forward mode, ``jax.jacfwd``);
    they do not depend on the model's coefficients."""
    dtype = _dtype(q, qd, qdd)
    model, motion = _cast(model, motion, dtype)
    state = _state(q, qd, qdd, dtype)
    own = _coefficients(model)
    n_lumped = len(model.structure.lumped_bodies)

    def forces(drag_coefficients: tuple[Array, Array, Array, Array], mass_coefficients: tuple[Array, Array]) -> tuple[Array, Array]:
        cd, cd_axial, linear, quadratic = drag_coefficients
        cm, upper = mass_coefficients
        added_mass = jnp.zeros((n_lumped, 6, 6), dtype).at[:, _UPPER[0], _UPPER[1]].set(upper)
        added_mass = added_mass.at[:, _UPPER[1], _UPPER[0]].set(upper)
        found = _forces(model, state, motion, Coefficients(cd, cm, cd_axial, added_mass, linear, quadratic))
        return jnp.concatenate([found["drag"][1], found["drag"][0]]), jnp.concatenate([found["added_mass"][1], found["added_mass"][0]])

    drag_at = (own.cd, own.cd_axial, own.linear_damping, own.quadratic_damping)
    mass_at = (own.cm, own.added_mass[:, _UPPER[0], _UPPER[1]])
    # One forward pass: [output][argument], the drag's columns and the added mass's.
    ((d_cd, d_axial, d_linear, d_quadratic), _), (_, (m_cm, m_upper)) = jax.jacfwd(forces, argnums=(0, 1))(drag_at, mass_at)
    rows = d_cd.shape[0]
    lumped = jnp.concatenate([m_upper, d_linear.reshape(rows, n_lumped, 36), d_quadratic], axis=-1)
    plain = _forces(model, state, motion, own)
    columns = {"drag": d_cd, "added_mass": m_cm, "axial_drag": d_axial, "lumped": lumped}
    fields: dict[str, Any] = {"buoyancy": plain["buoyancy"][0], "gravity": plain["gravity"][0]}
    fields |= {"base_buoyancy": plain["buoyancy"][1], "base_gravity": plain["gravity"][1]}
    fields |= {name: value[6:] for name, value in columns.items()} | {f"base_{name}": value[:6] for name, value in columns.items()}
    return Regressors(**fields)


def _added_mass(model: RobotModel, q: Array, accelerations: Array, dtype: jnp.dtype) -> Array:
    """The added-mass forces on base and joints at zero velocities (cast model), ``(6 + N,)``."""
    zero = jnp.zeros(3, dtype)
    motion = Motion(jnp.array([1, 0, 0, 0], dtype), zero, zero, accelerations[:3], accelerations[3:6], zero, zero)
    found = _forces(model, (q, jnp.zeros_like(q), accelerations[6:]), motion, _coefficients(model))["added_mass"]
    return jnp.concatenate([found[1], found[0]])


def added_mass_matrix(model: RobotModel, q: ArrayLike) -> Array:
    """``M_A = −∂(W_am, τ_am)/∂(ν̇, q̈)`` (:meth:`uwml.Robot.added_mass_matrix`, one state):
    ``(6 + N, 6 + N)``, base first (linear, angular, base components), then the joints. The
    added-mass forces are linear in the accelerations at zero velocity, so this is their exact
    Jacobian there (forward mode), made exactly symmetric (the mean of it and its transpose)."""
    dtype = _dtype(q)
    model, _ = _cast(model, None, dtype)
    angles = jnp.asarray(q, dtype)
    size = 6 + model.structure.n_joints
    jac: Array = jax.jacfwd(lambda x: _added_mass(model, angles, x, dtype))(jnp.zeros(size, dtype))
    return -0.5 * (jac + jac.T)


def jacobians(
    model: RobotModel,
    q: ArrayLike,
    qd: ArrayLike,
    qdd: ArrayLike,
    motion: Motion | None = None,
    depth: ArrayLike = 0.0,
    temperature_c: ArrayLike = 20.0,
) -> Jacobians:
    """:meth:`uwml.Robot.jacobians`' (one state): the forces of :func:`environment` on base and
    joints ``(base.total, total)`` and their derivatives in ``q`` and in ``(ν, q̇)`` (base twist,
    base components, then the joint rates), by forward mode, and :func:`added_mass_matrix`."""
    dtype = _dtype(q, qd, qdd)
    state = _state(q, qd, qdd, dtype)
    base_motion = _motion(motion, dtype)

    def value(angles: Array, rates: Array) -> Array:
        moved = base_motion._replace(velocity=rates[:3], angular_velocity=rates[3:6])
        found = environment(model, angles, rates[6:], state[2], moved, depth, temperature_c)
        assert found.base is not None
        return jnp.concatenate([found.base.total, found.total])

    rates = jnp.concatenate([base_motion.velocity, base_motion.angular_velocity, state[1]])
    d_q, d_velocity = jax.jacfwd(value, argnums=(0, 1))(state[0], rates)
    result: dict[str, Any] = {"value": value(state[0], rates), "d_q": d_q, "d_velocity": d_velocity}
    result["added_mass_matrix"] = added_mass_matrix(model, state[0])
    return Jacobians(**result)
