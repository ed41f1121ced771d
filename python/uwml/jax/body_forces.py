"""The water's and gravity's forces on every body of a robot, for :mod:`uwml.jax`, and their
generalized forces (docs/model.md sections 3, 10 and 12): each segment's drag and added mass by
the exact strip integrals (:mod:`.strip_integrals`; the added mass in Morison's or Kirchhoff's
form, the core's ``segment_forces.rs`` term for term), its axial drag, each lumped model's
wrench (Fossen's, the core's ``lumped.rs``), buoyancy with Froude-Krylov and weight; summed per
body as a force and a moment about the base origin, in base components (:mod:`.tree_motion`),
then turned into joint forces and the base wrench by virtual work.
"""

from __future__ import annotations

from typing import NamedTuple

import jax
import jax.numpy as jnp
import numpy as np

from .compiled_robot import RobotModel
from .strip_integrals import added_mass_moments, circular_speed_moments, drag_moments, magnitude
from .tree_motion import Frames

__all__ = ["Coefficients", "Wrenches", "body_wrenches", "generalized"]

Array = jax.Array

#: The parts of the environment's forces, as :class:`uwml.Torques` names them.
PARTS = ("drag", "added_mass", "buoyancy", "gravity")


class Wrenches(NamedTuple):
    """Force and moment about the base origin on each body, base components: ``(B, 3)`` each."""

    force: Array
    moment: Array


class Coefficients(NamedTuple):
    """The coefficients the forces are linear in: the segments' ``cd``, ``cm`` ``(S, 2)`` and
    ``cd_axial`` ``(S,)``, and each lumped model's ``M_A``, ``D_L`` ``(L, 6, 6)`` and ``d``
    ``(L, 6)`` (the regressors differentiate with respect to them)."""

    cd: Array
    cm: Array
    cd_axial: Array
    added_mass: Array
    linear_damping: Array
    quadratic_damping: Array


def _dot(a: Array, b: Array) -> Array:
    return jnp.sum(a * b, axis=-1)


def _normal(x: Array, u: Array) -> Array:
    """The part of ``x`` perpendicular to the unit ``u``."""
    return x - u * _dot(u, x)[..., None]


def _per_body(force: Array, moment: Array, bodies: tuple[int, ...], count: int) -> Wrenches:
    """Items' wrenches ``(P, 3)`` summed onto their bodies: ``(count, 3)``."""
    one_hot = jnp.asarray(np.eye(count)[list(bodies)].reshape(len(bodies), count), force.dtype)
    return Wrenches(one_hot.T @ force, one_hot.T @ moment)


def _rectangular(
    u: Array, normals: Array, v0: Array, a0: Array, w: Array, alpha: Array, length: Array, drag: Array, mass: Array, kirchhoff: bool
) -> tuple[Array, Array, Array, Array]:
    """Drag and added-mass force and moment about the start, of rectangular segments (``(R, 3)``
    each): per normal ``n_k``, ``drag`` = ``−½ ρ Cd_k w_k`` and ``mass`` = ``−ρ A Cm_k`` ``(R, 2)``."""
    v1 = jnp.cross(w, u)
    a1 = jnp.cross(alpha, u) + jnp.cross(w, v1)
    n = normals  # (R, 2, 3)
    d0, d1 = drag_moments(_dot(n, v0[:, None]), _dot(n, v1[:, None]), length[:, None])
    m0, m1 = added_mass_moments(_dot(n, a0[:, None]), _dot(n, a1[:, None]), length[:, None])
    arms = jnp.cross(u[:, None], n)  # u × n_k
    drag_force = jnp.einsum("rk,rkc->rc", drag * d0, n)
    drag_moment = jnp.einsum("rk,rkc->rc", drag * d1, arms)
    mass_force = jnp.einsum("rk,rkc->rc", mass * m0, n)
    mass_moment = jnp.einsum("rk,rkc->rc", mass * m1, arms)
    if kirchhoff:
        # ṅ = ω × n: extra force density m[(ṅ·v) n + (n·v) ṅ]; couple m (n·v)(v × n), v = v0 + s v1.
        n_dot = jnp.cross(w[:, None], n)
        e0, e1 = added_mass_moments(_dot(n_dot, v0[:, None]), _dot(n_dot, v1[:, None]), length[:, None])
        c0, c1 = added_mass_moments(_dot(n, v0[:, None]), _dot(n, v1[:, None]), length[:, None])
        mk = mass[..., None]
        mass_force += jnp.sum(mk * (n * e0[..., None] + n_dot * c0[..., None]), axis=1)
        couple = jnp.cross(v0[:, None], n) * c0[..., None] + jnp.cross(v1[:, None], n) * c1[..., None]
        mass_moment += jnp.sum(mk * (arms * e1[..., None] + jnp.cross(u[:, None], n_dot) * c1[..., None] + couple), axis=1)
    return drag_force, drag_moment, mass_force, mass_moment


def _circular(
    u: Array, v0: Array, a0: Array, w: Array, alpha: Array, length: Array, drag: Array, mass: Array, kirchhoff: bool
) -> tuple[Array, Array, Array, Array]:
    """As :func:`_rectangular`, for circular segments (cross-flow principle): ``drag`` =
    ``−½ ρ Cd D``, ``mass`` = ``−ρ A Cm`` ``(C,)``."""
    v1 = jnp.cross(w, u)
    a1 = jnp.cross(alpha, u) + jnp.cross(w, v1)
    p0, a0n, a1n = _normal(v0, u), _normal(a0, u), _normal(a1, u)
    moments = circular_speed_moments(p0, v1, length)
    i0, i1, i2 = (moments[:, k, None] for k in range(3))
    d, m = drag[:, None], mass[:, None]
    drag_force = d * (p0 * i0 + v1 * i1)
    drag_moment = d * jnp.cross(u, p0 * i1 + v1 * i2)
    ell = length[:, None]
    l1, l2 = added_mass_moments(jnp.ones_like(ell), jnp.zeros_like(ell), ell)
    _, l3 = added_mass_moments(jnp.zeros_like(ell), jnp.ones_like(ell), ell)
    mass_force = m * (a0n * l1 + a1n * l2)
    mass_moment = m * jnp.cross(u, a0n * l2 + a1n * l3)
    if kirchhoff:
        # dv⊥/dt = a⊥ − v1 c − u (v1·v), c = u·v: extra force density −m[−v1 c − u (v1·v)];
        # couple −m c u × v⊥.
        c = _dot(u, v0)[:, None]
        f0, _ = added_mass_moments(_dot(v1, v0), _dot(v1, v1), length)
        mass_force += -m * (v1 * (c * l1) + u * f0[:, None])
        mass_moment += -m * (jnp.cross(u, v1) * (c * l2) - jnp.cross(u, p0 * l1 + v1 * l2) * c)
    return drag_force, drag_moment, mass_force, mass_moment


def _segments(model: RobotModel, frames: Frames, coefficients: Coefficients, density: Array) -> tuple[Wrenches, Wrenches]:
    """Every segment's drag (with its axial drag) and added mass, summed per body."""
    structure, seg = model.structure, model.segments
    count = structure.n_bodies
    bodies = np.array(structure.segment_bodies, dtype=np.intp)
    p0, v0, a0 = frames.point_motion(bodies, seg.start)
    u = jnp.einsum("sab,sb->sa", frames.rotation[bodies], seg.axis)
    w, alpha = frames.angular_velocity[bodies], frames.angular_acceleration[bodies]
    kirchhoff = structure.form == "kirchhoff"
    parts = []
    for circular in (False, True):
        index = np.flatnonzero(np.array(structure.circular, dtype=bool) == circular)
        if not index.size:
            continue
        args = (u[index], v0[index], a0[index], w[index], alpha[index], seg.length[index])
        if circular:
            drag = -0.5 * density * coefficients.cd[index, 0] * seg.widths[index, 0]
            forces = _circular(*args, drag, -density * seg.area[index] * coefficients.cm[index, 0], kirchhoff)
        else:
            normals = jnp.einsum("sab,skb->ska", frames.rotation[bodies[index]], seg.normals[index])
            drag = -0.5 * density * coefficients.cd[index] * seg.widths[index]
            mass = -density * seg.area[index, None] * coefficients.cm[index]
            forces = _rectangular(args[0], normals, *args[1:], drag, mass, kirchhoff)
        parts.append((index, forces))
    order = np.concatenate([index for index, _ in parts]) if parts else np.zeros(0, dtype=np.intp)
    at = np.argsort(order)  # the segments' own order
    drag_f, drag_m, mass_f, mass_m = (
        jnp.concatenate([f[k] for _, f in parts])[at] if parts else jnp.zeros((0, 3), p0.dtype) for k in range(4)
    )
    # Axial drag (docs/model.md section 12.2): −½ ρ cd_axial A_axial |u·v| (u·v) u, along the axis.
    speed = _dot(u, v0)
    axial = (-0.5 * density * coefficients.cd_axial * seg.axial_area * magnitude(speed) * speed)[:, None] * u
    segment_bodies = structure.segment_bodies
    drag = _per_body(drag_f + axial, drag_m + jnp.cross(p0, drag_f + axial), segment_bodies, count)
    added = _per_body(mass_f, mass_m + jnp.cross(p0, mass_f), segment_bodies, count)
    return drag, added


def _lumped(model: RobotModel, frames: Frames, coefficients: Coefficients) -> tuple[Wrenches, Wrenches]:
    """Each lumped model's damping (drag) and added-mass wrenches, summed per body (docs/model.md
    section 12.1): at ``P``, in the model's axes, ``−M_A ν̇ − C_A(ν) ν`` and ``−D_L ν − d |ν| ν``."""
    structure = model.structure
    bodies = np.array(structure.lumped_bodies, dtype=np.intp)
    point, velocity, acceleration = frames.point_motion(bodies, model.lumped.point)
    turn = jnp.einsum("lab,lbc->lac", frames.rotation[bodies], model.lumped.axes)  # base from model

    def own(x: Array) -> Array:
        return jnp.einsum("lab,la->lb", turn, x)

    v, w = own(velocity), own(frames.angular_velocity[bodies])
    nu = jnp.concatenate([v, w], axis=-1)
    nu_dot = jnp.concatenate([own(acceleration) - jnp.cross(w, v), own(frames.angular_acceleration[bodies])], axis=-1)
    momentum = jnp.einsum("lij,lj->li", coefficients.added_mass, nu)
    p, h = momentum[:, :3], momentum[:, 3:]
    inertial = jnp.einsum("lij,lj->li", coefficients.added_mass, nu_dot)
    added = -(inertial + jnp.concatenate([jnp.cross(w, p), jnp.cross(v, p) + jnp.cross(w, h)], axis=-1))
    damping = -(jnp.einsum("lij,lj->li", coefficients.linear_damping, nu) + coefficients.quadratic_damping * magnitude(nu) * nu)

    def about_origin(wrench: Array) -> Wrenches:
        force = jnp.einsum("lab,lb->la", turn, wrench[:, :3])
        moment = jnp.cross(point, force) + jnp.einsum("lab,lb->la", turn, wrench[:, 3:])
        return _per_body(force, moment, structure.lumped_bodies, structure.n_bodies)

    return about_origin(damping), about_origin(added)


def body_wrenches(model: RobotModel, frames: Frames, coefficients: Coefficients, density: Array) -> dict[str, Wrenches]:
    """Per part (:data:`PARTS`), the wrench on every body, about the base origin, base components."""
    drag, added = _segments(model, frames, coefficients, density)
    if model.structure.lumped_bodies:
        lumped_drag, lumped_added = _lumped(model, frames, coefficients)
        drag = Wrenches(drag.force + lumped_drag.force, drag.moment + lumped_drag.moment)
        added = Wrenches(added.force + lumped_added.force, added.moment + lumped_added.moment)
    bodies = model.bodies
    every = np.arange(model.structure.n_bodies)
    cob, _, _ = frames.point_motion(every, bodies.cob)
    com, _, _ = frames.point_motion(every, bodies.com)
    buoyancy = (density * bodies.volume)[:, None] * (frames.current_acceleration - frames.gravity)
    weight = bodies.mass[:, None] * frames.gravity
    return {
        "drag": drag,
        "added_mass": added,
        "buoyancy": Wrenches(buoyancy, jnp.cross(cob, buoyancy)),
        "gravity": Wrenches(weight, jnp.cross(com, weight)),
    }


def generalized(model: RobotModel, frames: Frames, wrenches: Wrenches) -> tuple[Array, Array]:
    """The joints' generalized forces ``(N,)`` and the base wrench ``(6,)`` of body wrenches, by
    virtual work: ``z_j · Σ (M_b − o_j × F_b)`` (revolute) or ``z_j · Σ F_b`` (prismatic) over the
    bodies joint ``j`` moves; the base's over all bodies."""
    structure = model.structure
    moves = jnp.asarray(structure.moves(), wrenches.force.dtype)
    force = moves.T @ wrenches.force
    moment = moves.T @ wrenches.moment
    about_joint = moment - jnp.cross(frames.points, force)
    prismatic = np.array(structure.prismatic, dtype=bool)
    joints = jnp.where(prismatic, _dot(frames.axes, force), _dot(frames.axes, about_joint))
    base = jnp.concatenate([jnp.sum(wrenches.force, axis=0), jnp.sum(wrenches.moment, axis=0)])
    return joints, base
