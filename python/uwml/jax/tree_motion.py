"""How the base and every link move, for :mod:`uwml.jax` (docs/model.md section 10, "Base motion
and current"): the base's motion and the current of one sample (:class:`Motion`, made from a
:class:`uwml.Conditions` by :func:`motion`), and the forward pass over the tree (:func:`forward`).

Everything is in BASE components, about the base origin: the rotations are base-from-body, and
the velocities and accelerations are the classical (inertial) ones, expressed in the base's axes.
So the base wrench needs no turning at the end, and the base's orientation enters only through
gravity and the current seen in the base's axes.
"""

from __future__ import annotations

from typing import NamedTuple

import jax
import jax.numpy as jnp
import numpy as np
from numpy.typing import NDArray

from ..robot.evaluation_conditions import Conditions
from .compiled_robot import Leaf, RobotModel

__all__ = ["Frames", "Motion", "forward", "motion", "still"]

Array = jax.Array


class Motion(NamedTuple):
    """The base's motion and the current at one sample (the fields of :class:`uwml.BaseMotion`,
    then the current's, docs/model.md section 10): ``orientation`` world from base, a unit
    quaternion ``(w, x, y, z)``; ``velocity``, ``angular_velocity`` the base twist in base
    components, ``acceleration``, ``angular_acceleration`` their components' time derivatives;
    ``current``, ``current_acceleration`` the water's velocity and acceleration, world components.
    Under ``jax.vmap`` each field may carry a sample axis of its own."""

    orientation: Leaf
    velocity: Leaf
    angular_velocity: Leaf
    acceleration: Leaf
    angular_acceleration: Leaf
    current: Leaf
    current_acceleration: Leaf


def still(dtype: jnp.dtype) -> Motion:
    """A fixed, upright base in still water."""
    zero = jnp.zeros(3, dtype)
    return Motion(jnp.array([1, 0, 0, 0], dtype), zero, zero, zero, zero, zero, zero)


def motion(conditions: Conditions | None = None, samples: int | None = None) -> Motion:
    """The base motion and current of ``conditions`` (:class:`uwml.Conditions`; None: a fixed,
    upright base in still water) as a :class:`Motion` of float64 numpy arrays: one value per
    field, or, with ``samples``, every field broadcast to a leading axis of that many samples
    (what ``jax.vmap`` over samples takes; a field given per sample must have that many)."""
    conditions = Conditions() if conditions is None else conditions
    base = conditions.base_motion
    fields: list[NDArray[np.float64]] = []
    for name, width in (("orientation", 4), ("velocity", 3), ("angular_velocity", 3), ("acceleration", 3), ("angular_acceleration", 3)):
        default = np.array([1.0, 0.0, 0.0, 0.0]) if name == "orientation" else np.zeros(3)
        fields.append(np.asarray(default if base is None else getattr(base, name), dtype=np.float64).reshape(-1, width))
    fields += [np.asarray(conditions.current).reshape(-1, 3), np.asarray(conditions.current_acceleration).reshape(-1, 3)]
    given = {len(f) for f in fields if len(f) > 1}
    if samples is None:
        if given:
            raise ValueError("these conditions are given per sample: pass samples= (the number of samples)")
        return Motion(*(f[0] for f in fields))
    if given - {samples}:
        raise ValueError(f"the conditions have {sorted(given)} samples, not {samples}")
    return Motion(*(np.ascontiguousarray(np.broadcast_to(f, (samples, f.shape[1]))) for f in fields))


def quaternion_matrix(quaternion: Array) -> Array:
    """World from base, of a quaternion ``(w, x, y, z)`` (normalized first, as the core does)."""
    w, x, y, z = quaternion / jnp.sqrt(jnp.sum(quaternion * quaternion))
    return jnp.stack(
        [
            jnp.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)]),
            jnp.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)]),
            jnp.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]),
        ]
    )


def _rodrigues(axis: Array, angle: Array) -> Array:
    k = jnp.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]], dtype=axis.dtype)
    return jnp.eye(3, dtype=axis.dtype) + jnp.sin(angle) * k + (1 - jnp.cos(angle)) * (k @ k)


class Frames(NamedTuple):
    """Every body's pose and motion (row 0 the base, ``i + 1`` link ``i``), base components about
    the base origin; each joint's axis and a point on it; the water's velocity and acceleration and
    gravity, base components."""

    rotation: Array  # (B, 3, 3) base from body
    position: Array  # (B, 3) the body frame's origin
    velocity: Array  # (B, 3) of that origin
    acceleration: Array  # (B, 3)
    angular_velocity: Array  # (B, 3)
    angular_acceleration: Array  # (B, 3)
    axes: Array  # (N, 3)
    points: Array  # (N, 3)
    current: Array  # (3,)
    current_acceleration: Array  # (3,)
    gravity: Array  # (3,)

    def point_motion(self, bodies: NDArray[np.intp], local: Array) -> tuple[Array, Array, Array]:
        """Position, and velocity and acceleration relative to the water, of points ``local``
        ``(P, 3)`` fixed to ``bodies`` ``(P,)`` (given in their frames)."""
        rotation, origin = self.rotation[bodies], self.position[bodies]
        d = jnp.einsum("pab,pb->pa", rotation, local)
        w, alpha = self.angular_velocity[bodies], self.angular_acceleration[bodies]
        wd = jnp.cross(w, d)
        velocity = self.velocity[bodies] + wd - self.current
        acceleration = self.acceleration[bodies] + jnp.cross(alpha, d) + jnp.cross(w, wd) - self.current_acceleration
        return origin + d, velocity, acceleration


def forward(model: RobotModel, q: Array, qd: Array, qdd: Array, motion: Motion, gravity: Array) -> Frames:
    """The forward pass over the joints, parents first (docs/model.md section 10, "What is
    computed"): rigid-body kinematics of every body from the base's motion and the joint state."""
    structure = model.structure
    world = quaternion_matrix(motion.orientation)  # world from base
    v, w = motion.velocity, motion.angular_velocity
    rotation, position = [jnp.eye(3, dtype=q.dtype)], [jnp.zeros(3, q.dtype)]
    velocity, acceleration = [v], [motion.acceleration + jnp.cross(w, v)]
    omega, alpha = [w], [motion.angular_acceleration]
    axes, points = [], []
    for i, (parent, prismatic) in enumerate(zip(structure.parents, structure.prismatic, strict=True)):
        r_p, w_p, a_p = rotation[parent], omega[parent], alpha[parent]
        z = r_p @ model.joints.axis[i]
        point = position[parent] + r_p @ model.joints.origin[i]
        offset = point - position[parent]
        if prismatic:
            offset = offset + q[i] * z
        w_offset = jnp.cross(w_p, offset)
        v_i = velocity[parent] + w_offset
        a_i = acceleration[parent] + jnp.cross(a_p, offset) + jnp.cross(w_p, w_offset)
        if prismatic:
            rotation.append(r_p)
            position.append(point + q[i] * z)
            velocity.append(v_i + qd[i] * z)
            acceleration.append(a_i + qdd[i] * z + 2 * qd[i] * jnp.cross(w_p, z))
            omega.append(w_p)
            alpha.append(a_p)
        else:
            rotation.append(r_p @ _rodrigues(model.joints.axis[i], q[i]))
            position.append(point)
            velocity.append(v_i)
            acceleration.append(a_i)
            omega.append(w_p + qd[i] * z)
            alpha.append(a_p + qdd[i] * z + qd[i] * jnp.cross(w_p, z))
        axes.append(z)
        points.append(point)
    stack = jnp.stack
    n = structure.n_joints
    return Frames(
        rotation=stack(rotation),
        position=stack(position),
        velocity=stack(velocity),
        acceleration=stack(acceleration),
        angular_velocity=stack(omega),
        angular_acceleration=stack(alpha),
        axes=stack(axes) if n else jnp.zeros((0, 3), q.dtype),
        points=stack(points) if n else jnp.zeros((0, 3), q.dtype),
        current=world.T @ motion.current,
        current_acceleration=world.T @ motion.current_acceleration,
        gravity=-gravity * world[2],
    )
