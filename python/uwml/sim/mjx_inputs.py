"""What drives a :class:`uwml.sim.mjx.Simulation` besides its state, as JAX arrays: the robot's
thrusters (their curves, limits and lags, docs/model.md section 13.1) and a prescribed joint
motion (docs/model.md section 12.4), each the same arithmetic as the CPU simulation's
(:mod:`uwml.sim.thrust`, :mod:`uwml.sim.prescribed`), written without Python branches on the data
so that it works under ``jax.jit`` and ``jax.vmap``.

**Thrusters.** A step's command ``u`` (one per thruster, in its curve's units) gives the steady
thrust ``f(u)``, within the thruster's limits. A thruster without a lag pushes with ``f(u)`` in
that step; one with a time constant ``τ`` pushes with the thrust the state carries, which then
moves to ``f + (T − f) e^{−h/τ}`` (the lag's exact solution under a held command, as
:class:`uwml.sim.thrust.SimulatedThrusters` advances it). The thrust acts on its body as a
wrench at the body's centre of mass in world components (MuJoCo's ``xfrc_applied``), turned by
the body's orientation of the step's position stage.

**Prescribed motion.** :class:`Spline` holds a motion from samples as the CPU simulation's
:class:`uwml.sim.prescribed.Trajectory` does, its cubics on each interval (``q``, ``q̇``, ``q̈``):
a pytree, so each environment of a batch may follow its own (stack them, or give
:func:`spline` samples with a leading batch axis). A time outside the samples' span is clamped
to it (the CPU simulation refuses it): give a motion that covers the rollout.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, NamedTuple

import jax
import jax.numpy as jnp
import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..model.thrusters import Thruster
from .prescribed import Trajectory
from .thrust import SimulatedThrusters

__all__ = ["MotionFunction", "Spline", "ThrusterArrays", "evaluate", "spline"]

Array = jax.Array
FloatArray = NDArray[np.float64]
#: A prescribed motion in closed form: ``t -> (q, q̇, q̈)``, each ``(k,)``, traceable by JAX.
MotionFunction = Callable[[Array], tuple[Array, Array, Array]]


class Spline(NamedTuple):
    """A motion of ``k`` joints from samples: the sample times ``knots`` ``(n,)`` and, on each of
    the ``n − 1`` intervals, the cubics of ``q``, ``q̇`` and ``q̈`` ``(4, n − 1, k)`` (highest
    degree first, in ``t − knots[i]``: scipy's ``PPoly.c``, as :attr:`Trajectory.pieces`). A
    batch of motions has a leading batch axis on every field."""

    knots: Any
    q: Any
    qd: Any
    qdd: Any

    @classmethod
    def of(cls, trajectory: Trajectory) -> Spline:
        """The cubics of a CPU :class:`uwml.sim.prescribed.Trajectory` made from samples."""
        if not isinstance(trajectory, Trajectory):
            raise TypeError(f"a motion from samples must be a uwml.sim.prescribed.Trajectory, got {type(trajectory).__name__}")
        if trajectory.pieces is None:
            raise ValueError("Trajectory.of(function) has no samples: give its function as a JAX function of time instead")
        knots, (q, qd, qdd) = trajectory.pieces
        return cls(knots.copy(), q.copy(), qd.copy(), qdd.copy())

    @property
    def joints(self) -> int:
        """How many joints it moves."""
        return int(np.shape(self.q)[-1])


def spline(time: ArrayLike, q: ArrayLike, qd: ArrayLike | None = None, qdd: ArrayLike | None = None) -> Spline:
    """The :class:`Spline` of samples, interpolated as :class:`uwml.sim.prescribed.Trajectory`
    interpolates them (the not-a-knot cubic spline of ``q``, its derivatives where ``qd`` and
    ``qdd`` are not given): ``time`` ``(n,)`` strictly increasing [s], ``q`` ``(n, k)``, or
    ``(batch, n, k)`` for one motion per environment (then ``qd``, ``qdd`` alike); the knots are
    shared, repeated along the batch axis."""
    angles = np.asarray(q, dtype=np.float64)
    if angles.ndim != 3:
        return Spline.of(Trajectory(time, angles, qd, qdd))

    def sample(values: ArrayLike | None, b: int) -> FloatArray | None:
        if values is None:
            return None
        array = np.asarray(values, dtype=np.float64)
        if array.shape != angles.shape:
            raise ValueError(f"a batch of motions' qd and qdd must have q's shape {angles.shape}, got {array.shape}")
        row: FloatArray = array[b]
        return row

    motions = [Spline.of(Trajectory(time, angles[b], sample(qd, b), sample(qdd, b))) for b in range(angles.shape[0])]
    return Spline(*(np.stack(field) for field in zip(*motions, strict=True)))


def evaluate(motion: Spline, t: Array) -> tuple[Array, Array, Array]:
    """``(q, q̇, q̈)`` of one motion at time ``t`` (clamped to the knots' span): the interval's
    cubics by Horner's rule, as the CPU simulation's native coupling evaluates them."""
    knots = jnp.asarray(motion.knots)
    t = jnp.clip(t, knots[0], knots[-1])
    interval = jnp.clip(jnp.searchsorted(knots, t, side="right") - 1, 0, knots.shape[0] - 2)
    dt = t - knots[interval]

    def cubic(coefficients: Any) -> Array:
        c = jnp.asarray(coefficients)[:, interval, :]
        value: Array = ((c[0] * dt + c[1]) * dt + c[2]) * dt + c[3]
        return value

    return cubic(motion.q), cubic(motion.qd), cubic(motion.qdd)


def _horner(x: Array, coefficients: tuple[float, ...]) -> Array:
    """``Σ c_i x^i`` as numpy's ``polyval`` evaluates it (lowest degree first)."""
    value = coefficients[-1] + 0.0 * x
    for c in reversed(coefficients[:-1]):
        value = c + value * x
    return value


class ThrusterArrays:
    """The thrusters of a robot on a MuJoCo model, as constants for JAX (see the module): the
    bodies they push, each one's force and moment about its centre of mass per newton of each
    thruster in its frame (:class:`uwml.sim.thrust.SimulatedThrusters`' placement), the curves,
    limits and lags."""

    def __init__(self, mujoco: Any, model: Any, robot: Any, root: int | None, joint_dofs: NDArray[np.int64]) -> None:
        placed = SimulatedThrusters(mujoco, model, robot, root, joint_dofs)
        self.thrusters: tuple[Thruster, ...] = tuple(t for _, t in robot.thrusters)
        #: The bodies pushed and ``(n_bodies, 6, n)``: each body's wrench per newton of each thruster.
        self.bodies: NDArray[np.int64] = placed.bodies.copy()
        self.local: FloatArray = placed._local.copy()  # the CPU simulation's own placement
        self.time_constants = np.array([t.time_constant for t in self.thrusters], dtype=np.float64)
        self.lags = self.time_constants > 0.0

    def __len__(self) -> int:
        return len(self.thrusters)

    def steady(self, command: Array) -> Array:
        """Each thruster's steady thrust [N] of ``command`` ``(n,)``: its curve's, within its limits."""
        if not self.thrusters:
            return jnp.zeros(0, command.dtype)
        values = []
        for i, thruster in enumerate(self.thrusters):
            curve, u = thruster.curve, command[i]
            if curve.kind == "table":
                value = jnp.interp(u, jnp.asarray(curve.commands, u.dtype), jnp.asarray(curve.thrusts, u.dtype))
            else:
                b = curve.dead_band
                ahead = _horner(jnp.maximum(u - b, 0.0), curve.forward)
                back = _horner(jnp.maximum(-u - b, 0.0), curve.reverse)
                value = jnp.where(u > b, ahead, 0.0) - jnp.where(u < -b, back, 0.0)
            values.append(jnp.clip(value, -thruster.max_reverse, thruster.max_forward))
        return jnp.stack(values)

    def acting(self, held: Array, steady: Array) -> Array:
        """The thrust that acts in a step: the lagging thrusters' ``held`` thrust, the others'
        ``steady`` one."""
        return jnp.where(jnp.asarray(self.lags), held, steady)

    def advance(self, acting: Array, steady: Array, h: Array) -> Array:
        """The thrust a step ``h`` later: ``f + (T − f) e^{−h/τ}`` (``f`` without a lag)."""
        tau = jnp.asarray(np.where(self.lags, self.time_constants, 1.0), acting.dtype)
        decay = jnp.where(jnp.asarray(self.lags), jnp.exp(-h / tau), 0.0)
        return steady + (acting - steady) * decay

    def applied(self, thrust: Array, xmat: Array, nbody: int) -> Array:
        """``xfrc_applied`` ``(nbody, 6)`` of ``thrust``: each pushed body's force and moment
        about its centre of mass in world components, its orientation ``xmat`` (MuJoCo's)."""
        out = jnp.zeros((nbody, 6), thrust.dtype)
        if not len(self.bodies):
            return out
        local = jnp.einsum("bcn,n->bc", jnp.asarray(self.local, thrust.dtype), thrust).reshape(-1, 2, 3)
        turns = xmat[self.bodies].reshape(-1, 3, 3)
        world = jnp.einsum("bij,bkj->bki", turns, local).reshape(-1, 6)
        return out.at[self.bodies].set(world)
