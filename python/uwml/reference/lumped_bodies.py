"""Fossen's lumped hydrodynamic model of a body, for the whole-robot reference (:mod:`.robot_hydro`;
docs/model.md section 12.1). numpy only, like the rest of the reference.

A body may carry, beside or instead of its strips, an added-mass matrix ``M_A``, a linear damping
matrix ``D_L`` and quadratic damping ``d`` about a reference point ``P`` fixed to it (in the
body's frame), the matrices in the model's axes ``A`` (a rotation, body from model; the identity
unless given), entries ordered ``(x, y, z, roll, pitch, yaw)``. With ``R`` the model's axes'
rotation (world from model: the body's rotation times ``A``), ``v_P`` and ``a_P`` the velocity
and classical acceleration of the material
point ``P`` (world), ``ω`` and ``α`` the body's angular velocity and acceleration (world), and
``c``, ``ċ`` the current (world):

* the relative twist at ``P`` in the model's components: ``ν_r = (Rᵀ(v_P − c), Rᵀω)``;
* the time derivative of those six components: ``ν̇_r = (Rᵀ(a_P − ċ) − ω_b × ν_r[0:3], Rᵀα)``,
  ``ω_b = Rᵀω`` (``d/dt Rᵀ = −[ω_b]× Rᵀ``; the angular part's ``−ω_b × ω_b`` vanishes);
* the wrench at ``P`` in body components, ``W = −M_A ν̇_r − C_A(ν_r) ν_r − D_L ν_r − D_Q(ν_r) ν_r``,
  with Fossen's added-mass Coriolis-centripetal term ``C_A(ν) ν = (ω_b × p, v × p + ω_b × h)``,
  ``(p, h) = M_A ν``, and ``D_Q(ν) ν = (d_i |ν_i| ν_i)``. The damping terms are reported as
  ``drag``, the added-mass ones as ``added_mass``.

:func:`_lumped_wrenches` turns that wrench into the reference's convention: force and moment
about the base origin, world components, summed per body; the generalized forces and the base
wrench then follow by virtual work like every other force on the body (:func:`.robot._generalized`).
In still water ``C_A`` does no work (``νᵀ C_A(ν) ν = v·(ω × p) + ω·(v × p) = 0``), and with every
velocity zero ``W = −M_A ν̇_r``, so each lumped body adds ``J_Pᵀ M_A J_P`` to the added-mass matrix
(``J_P`` the map from the generalized velocity to ``ν`` at ``P``).
"""

# No ``from __future__ import annotations``: see uwml.reference.chain.
from typing import TYPE_CHECKING

import numpy as np

from ._inputs import Array
from .robot_inputs import IndexArray, _Motion, _Robot

if TYPE_CHECKING:  # pragma: no cover - the reference imports this module, not the reverse
    from .robot_hydro import _Kinematics


def _fossen(nu: Array, nu_dot: Array, added_mass: Array, linear: Array, quadratic: Array) -> tuple[Array, Array]:
    """The damping and added-mass wrenches ``(…, 6)`` at ``P`` in body components, for relative
    twists ``nu`` and their component derivatives ``nu_dot`` ``(…, L, 6)`` and each body's ``M_A``,
    ``D_L`` ``(L, 6, 6)`` and ``d`` ``(L, 6)``."""
    momentum = np.einsum("lij,...lj->...li", added_mass, nu)
    v, w = nu[..., 0:3], nu[..., 3:6]
    p, h = momentum[..., 0:3], momentum[..., 3:6]
    coriolis = np.concatenate([np.cross(w, p), np.cross(v, p) + np.cross(w, h)], axis=-1)
    added = -np.einsum("lij,...lj->...li", added_mass, nu_dot) - coriolis
    drag = -np.einsum("lij,...lj->...li", linear, nu) - quadratic * np.abs(nu) * nu
    return drag, added


def _body_rates(robot: _Robot, motion: _Motion, kin: "_Kinematics", bodies: IndexArray) -> tuple[Array, Array]:
    """Angular velocities and accelerations (n, L, 3), world, of ``bodies`` (L,): the base's plus
    ``q̇_j z_j`` and ``q̈_j z_j + q̇_j ż_j`` for every revolute joint ``j`` that moves the body."""
    count = len(bodies)
    omega = np.repeat(kin.w0[:, None, :], count, axis=1)
    alpha = np.repeat(kin.alpha0[:, None, :], count, axis=1)
    for j in range(robot.n_joints):
        mask = robot.moves[bodies, j]
        if robot.prismatic[j] or not mask.any():
            continue
        z, zdot = kin.axes[:, j, None, :], kin.axis_rates[:, j, None, :]
        omega = omega + mask[None, :, None] * motion.qd[:, j, None, None] * z
        alpha = alpha + mask[None, :, None] * (motion.qdd[:, j, None, None] * z + motion.qd[:, j, None, None] * zdot)
    return omega, alpha


def _lumped_wrenches(robot: _Robot, motion: _Motion, kin: "_Kinematics", parts: tuple[str, ...]) -> dict[str, tuple[Array, Array]]:
    """Per part (``drag``, ``added_mass``, those in ``parts``), the lumped models' force and moment
    about the base origin on each body, world components: ``(F, M)``, each (n, B, 3)."""
    n_bodies = robot.n_bodies
    bodies = robot.lumped_body
    body_rotation = kin.rotations[:, bodies]  # (n, L, 3, 3) world from body
    point = kin.positions[:, bodies] + np.einsum("nlab,lb->nla", body_rotation, robot.lumped_point)
    rot = np.einsum("nlab,lbc->nlac", body_rotation, robot.lumped_axes)  # world from the model's axes
    velocity = kin.velocity(point, bodies)
    omega, alpha = _body_rates(robot, motion, kin, bodies)

    def body(w: Array) -> Array:
        """Components ``(R A)ᵀ w`` of world vectors (n, L, 3) in the model's axes (``A``: body from
        model; the body's own axes where ``A`` is the identity)."""
        out: Array = np.einsum("nlab,nla->nlb", rot, w)
        return out

    linear = body(velocity - motion.current[:, None, :])
    omega_b = body(omega)
    nu = np.concatenate([linear, omega_b], axis=-1)
    if "added_mass" in parts:
        acceleration = kin.acceleration(point, velocity, bodies)
        linear_dot = body(acceleration - motion.current_acceleration[:, None, :]) - np.cross(omega_b, linear)
        nu_dot = np.concatenate([linear_dot, body(alpha)], axis=-1)
    else:
        nu_dot = np.zeros_like(nu)
    drag, added = _fossen(nu, nu_dot, robot.lumped_mass, robot.lumped_linear, robot.lumped_quadratic)
    one_hot = np.eye(n_bodies)[bodies] if len(bodies) else np.zeros((0, n_bodies))  # (L, B)
    out: dict[str, tuple[Array, Array]] = {}
    for part, wrench in (("drag", drag), ("added_mass", added)):
        if part not in parts:
            continue
        force = np.einsum("nlab,nlb->nla", rot, wrench[..., 0:3])
        moment = np.cross(point, force) + np.einsum("nlab,nlb->nla", rot, wrench[..., 3:6])
        out[part] = (np.einsum("nlc,lb->nbc", force, one_hot), np.einsum("nlc,lb->nbc", moment, one_hot))
    return out
