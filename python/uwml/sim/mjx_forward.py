"""One step of :class:`uwml.sim.mjx.Simulation`: MJX's forward dynamics with uwml's forces and
the added mass in the mass matrix (docs/model.md section 11; docs/batched.md, "Simulating with
MJX"), the same arithmetic as the CPU simulation's per-step coupling (:mod:`uwml.sim.mujoco`).

MJX's position stage is run stage by stage (``kinematics``, ``com_pos``, ``camlight``,
``tendon``, ``crb``, ``tendon_armature``); once the composite-rigid-body stage has formed the
dense joint-space inertia ``M(q)`` (``data._impl.M``), uwml's added-mass matrix ``M_A(q)`` is
added to it, then MJX factorizes it, builds the constraints (``collision``,
``make_constraint``, ``transmission``) and runs the velocity, actuation and acceleration stages
and its constraint solver as its ``forward`` does: MJX solves ``(M + M_A) q̈ = τ + τ_env,0``
with its constraints. ``τ_env,0`` (uwml at zero joint and base acceleration: drag, buoyancy and
Froude-Krylov, the added mass's velocity terms; no weight, which is MuJoCo's) is the applied
generalized force ``qfrc_applied``, with the motor torques. MJX's Euler step then integrates,
its damping implicit with ``M + M_A + h D``.

Coordinates: uwml's base twist is Fossen's ``ν`` (base frame); MJX's free joint has the world
velocity of the body's origin and the body's angular velocity, so ``ν = (Rᵀ v, ω)`` and zero
MuJoCo acceleration is ``ν̇ = (−ω × v, 0)``, given to uwml as the base's acceleration; the forces
and ``M_A`` are mapped with ``T = diag(R, I)``: ``T τ`` and ``T M_A Tᵀ``.

Joint losses (docs/simulation.md, "Joint losses: friction as a constraint, damping implicit"):
each step, at each joint's speed, the seal's dry-friction level is added to the joint's
``dof_frictionloss`` (an MJX friction constraint) and the secant damping of the oil drag and the
seal's viscous term, ``−(τ_oil + D ω)/ω``, to its ``dof_damping`` (MJX's Euler step takes it
implicitly): ``LossState::dry_friction_split`` of the core, in JAX.

Prescribed joints (docs/model.md section 12.4): after the forward pass, the torque on the
prescribed degrees of freedom ``p`` that makes their accelerations the motion's,
``τ_p = [(M⁻¹)_pp]⁻¹ (q̈* − q̈_p)`` (``M`` with the added mass), is added to the applied forces
and the velocity, actuation, acceleration and constraint stages run again; after the step the
joints are put on the motion at the new time (as the CPU simulation's native coupling does).
"""

from __future__ import annotations

import dataclasses
from typing import Any, NamedTuple

import jax
import jax.numpy as jnp
import numpy as np
from numpy.typing import NDArray

from .. import jax as ujax
from ..jax.compiled_robot import JointLossParameters, RobotModel
from ..jax.loss_model import _power, loss_levels, smooth_sign
from ..jax.strip_integrals import magnitude
from .mjx_inputs import ThrusterArrays

__all__ = ["Layout", "dry_friction_split", "robot_model_for", "step_dynamics"]

Array = jax.Array
IntArray = NDArray[np.int64]


class Layout(NamedTuple):
    """Where uwml's coordinates sit among the MJX model's degrees of freedom (static)."""

    #: The root body (the base) and whether the base is the world frame (the root hangs from the
    #: world by a joint) or floats (the free joint's first dof and qpos entry, else None).
    root: int
    base_is_world: bool
    free_dof: int | None
    free_qpos: int | None
    joint_dofs: IntArray
    joint_qpos: IntArray
    #: The prescribed joints' dofs and qpos entries (empty: none).
    prescribed_dofs: IntArray
    prescribed_qpos: IntArray
    #: Each joint's model damping and friction loss (the losses add to them).
    own_damping: NDArray[np.float64]
    own_frictionloss: NDArray[np.float64]
    #: Whether any joint has losses.
    losses: bool
    #: The body that carries the payload.
    payload_body: int


class Inputs(NamedTuple):
    """What one step of one environment takes besides its MJX data (all arrays, cast)."""

    robot: RobotModel
    current: Array
    current_acceleration: Array
    depth: Array
    temperature_c: Array
    payload: Array
    torque: Array
    #: The thrust acting in this step, one per thruster [N].
    thrust: Array


def robot_model_for(
    model: RobotModel,
    cd: Any,
    cm: Any,
    drag_scale: Any,
    added_mass_scale: Any,
    lumped: tuple[Any, Any, Any] | None = None,
    bodies: tuple[Any, Any] | None = None,
) -> RobotModel:
    """``model`` with an environment's coefficients: the segments' ``cd`` and ``cm`` ``(S, 2)``,
    each lumped model's ``(M_A, D_L, d)`` ``((L, 6, 6), (L, 6, 6), (L, 6))`` (None: the model's),
    each body's centre of buoyancy ``(B, 3)`` and displaced volume ``(B,)`` (None: the model's);
    every drag coefficient (``cd``, axial ``cd``, the lumped models' damping) times
    ``drag_scale``, every added-mass coefficient (``cm``, the lumped models' ``M_A``) times
    ``added_mass_scale``."""
    added, linear, quadratic = (
        (model.lumped.added_mass, model.lumped.linear_damping, model.lumped.quadratic_damping) if lumped is None else lumped
    )
    segments = model.segments._replace(
        cd=cd * drag_scale, cm=cm * added_mass_scale, cd_axial=jnp.asarray(model.segments.cd_axial) * drag_scale
    )
    lumped_models = model.lumped._replace(
        added_mass=jnp.asarray(added) * added_mass_scale,
        linear_damping=jnp.asarray(linear) * drag_scale,
        quadratic_damping=jnp.asarray(quadratic) * drag_scale,
    )
    body_parts = model.bodies if bodies is None else model.bodies._replace(cob=bodies[0], volume=bodies[1])
    return dataclasses.replace(model, segments=segments, lumped=lumped_models, bodies=body_parts)


def dry_friction_split(
    p: JointLossParameters, speed: Array, depth: Array, temperature_c: Array, sea_density: Array, gravity: Array
) -> tuple[Array, Array]:
    """Each joint's seal dry-friction level and secant damping at output ``speed`` ``(N,)``
    (the core's ``LossState::dry_friction_split`` at the pressure of ``depth``, oil at
    ``temperature_c``): ``C + (S − C) exp(−(ω/ω_s)²)`` and ``max(N η k_oil(p, T) (N|ω|)ⁿ
    sgn_ε(ω)/ω, 0) + D``, the laminar oil's slope at rest with the hard sign. Zero for a joint
    without losses (its neutral parameters)."""
    oil_scale, running, excess, viscous = loss_levels(p, depth, temperature_c, sea_density, gravity)
    output_per_motor_torque = p.ratio * p.efficiency
    size = magnitude(speed)
    x = size * (1 / p.stribeck_speed)
    friction = running + excess * jnp.exp(-(x * x))
    moving = size > 0
    safe_speed = jnp.where(moving, speed, 1)
    secant = output_per_motor_torque * oil_scale * _power(p.ratio * size, p.exponent) * smooth_sign(speed, p.epsilon) / safe_speed
    at_rest = jnp.where((p.exponent == 1) & (p.epsilon == 0), output_per_motor_torque * oil_scale * p.ratio, 0)
    oil = jnp.where(moving, secant, at_rest)
    return friction, jnp.maximum(oil, 0) + viscous


def _base_motion(layout: Layout, d: Any, inputs: Inputs, dtype: Any) -> tuple[ujax.Motion, Array]:
    """uwml's base motion at zero MuJoCo acceleration and ``R`` (world from base)."""
    zero = jnp.zeros(3, dtype)
    if layout.base_is_world:
        orientation, rotation = jnp.array([1.0, 0.0, 0.0, 0.0], dtype), jnp.eye(3, dtype=dtype)
    else:
        orientation, rotation = d.xquat[layout.root], d.xmat[layout.root]
    if layout.free_dof is None:
        velocity, angular_velocity, acceleration = zero, zero, zero
    else:
        free = layout.free_dof
        velocity, angular_velocity = rotation.T @ d.qvel[free : free + 3], d.qvel[free + 3 : free + 6]
        acceleration = -jnp.cross(angular_velocity, velocity)  # ν̇ = Rᵀ v̇ − ω × v at v̇ = 0
    motion = ujax.Motion(orientation, velocity, angular_velocity, acceleration, zero, inputs.current, inputs.current_acceleration)
    return motion, rotation


def _environment(layout: Layout, d: Any, inputs: Inputs) -> tuple[Array, Array]:
    """``τ_env,0`` ``(nv,)`` and ``M_A`` ``(nv, nv)`` in MuJoCo's coordinates (the module)."""
    dtype = d.qpos.dtype
    nv = d.qvel.shape[0]
    q, qd = d.qpos[layout.joint_qpos], d.qvel[layout.joint_dofs]
    motion, rotation = _base_motion(layout, d, inputs, dtype)
    forces = ujax.hydro(inputs.robot, q, qd, jnp.zeros_like(q), motion)
    assert forces.base is not None
    added_mass = ujax.added_mass_matrix(inputs.robot, q)
    joints = jnp.asarray(layout.joint_dofs)
    qfrc = jnp.zeros(nv, dtype).at[joints].set(forces.total + inputs.torque)
    inertia = jnp.zeros((nv, nv), dtype).at[joints[:, None], joints[None, :]].set(added_mass[6:, 6:])
    if layout.free_dof is not None:
        free = layout.free_dof
        base = jnp.arange(free, free + 6)
        turn = jax.scipy.linalg.block_diag(rotation, jnp.eye(3, dtype=dtype))  # T = diag(R, I) on the base rows
        qfrc = qfrc.at[base].set(turn @ forces.base.total)
        coupled = added_mass.at[:6, :].set(turn @ added_mass[:6, :])
        coupled = coupled.at[:, :6].set(coupled[:, :6] @ turn.T)
        every = jnp.concatenate([base, joints])
        inertia = jnp.zeros((nv, nv), dtype).at[every[:, None], every[None, :]].set(coupled)
    return qfrc, inertia


def _solve(mjx: Any, m: Any, d: Any) -> Any:
    """MJX's stages after the position stage (its ``forward``'s): velocity, actuation,
    acceleration, and the constraint solver where there are constraints."""
    d = mjx.sensor_pos(m, d)
    d = mjx.fwd_velocity(m, d)
    d = mjx.sensor_vel(m, d)
    d = mjx.fwd_actuation(m, d)
    d = mjx.fwd_acceleration(m, d)
    if d._impl.efc_J.size == 0:
        return d.replace(qacc=d.qacc_smooth)
    d = mjx.solve(m, d)
    return mjx.sensor_acc(m, d)


def _impose(mjx: Any, m: Any, d: Any, layout: Layout, target: Array) -> tuple[Any, Array]:
    """The prescribed joints' accelerations made ``target`` by the torque on them (the module),
    the stages after the position stage run again; that torque."""
    dofs = jnp.asarray(layout.prescribed_dofs)
    unit = jnp.zeros((d.qvel.shape[0], len(layout.prescribed_dofs)), d.qvel.dtype).at[dofs, jnp.arange(dofs.shape[0])].set(1)
    solved = jax.scipy.linalg.cho_solve((d._impl.qLD, False), unit)  # M⁻¹[:, p], M factored with the added mass
    torque = jnp.linalg.solve(solved[dofs, :], target - d.qacc[dofs])
    d = d.replace(qfrc_applied=d.qfrc_applied.at[dofs].add(torque))
    return _solve(mjx, m, d), torque


def step_dynamics(
    mjx: Any, m: Any, d: Any, layout: Layout, inputs: Inputs, thrusters: ThrusterArrays, target: Array | None
) -> tuple[Any, Array]:
    """One Euler step of the MJX model ``m`` (per environment: its losses, payload) from ``d``
    with ``inputs`` and the ``thrusters`` pushing with ``inputs.thrust``; ``target``: the
    prescribed joints' accelerations (None: none). The data after the step and the imposing
    torque (empty without a prescribed motion)."""
    robot = inputs.robot
    changes: dict[str, Array] = {"body_mass": m.body_mass.at[layout.payload_body].add(inputs.payload)}
    if layout.losses:
        friction, damping = dry_friction_split(
            robot.losses, d.qvel[layout.joint_dofs], inputs.depth, inputs.temperature_c, robot.sea_density, robot.gravity
        )
        dofs = jnp.asarray(layout.joint_dofs)
        changes["dof_frictionloss"] = m.dof_frictionloss.at[dofs].set(layout.own_frictionloss + friction)
        changes["dof_damping"] = m.dof_damping.at[dofs].set(layout.own_damping + damping)
    m = m.replace(**changes)
    # The position stage, MJX's fwd_position with M_A added between crb and factor_m.
    for stage in (mjx.kinematics, mjx.com_pos, mjx.camlight, mjx.tendon, mjx.crb, mjx.tendon_armature):
        d = stage(m, d)
    qfrc, added_mass = _environment(layout, d, inputs)
    d = d.tree_replace({"_impl.M": d._impl.M + added_mass})
    for stage in (mjx.factor_m, mjx.collision, mjx.make_constraint, mjx.transmission):
        d = stage(m, d)
    d = d.replace(qfrc_applied=qfrc, xfrc_applied=thrusters.applied(inputs.thrust, d.xmat, m.nbody))
    d = _solve(mjx, m, d)
    torque = jnp.zeros(0, d.qpos.dtype)
    if target is not None:
        d, torque = _impose(mjx, m, d, layout, target)
    return mjx.euler(m, d), torque
