"""Steps a second of the BlueROV2 example with its arm in MJX, bare MJX against uwml's full step
(:func:`benchmark_steps`, run by ``benches/accelerated.py --mjx``; docs/performance.md,
"Batched (JAX, MJX)").

Both run the same MJX model (the one :class:`uwml.sim.mjx.Simulation` puts in MJX: floating,
MuJoCo's fluid model off, contacts off, Euler at the example's 2 ms, a dense mass matrix), each
environment from the same start, under ``jax.jit(jax.vmap(...))`` with ``STEPS`` steps in one
``jax.lax.scan`` a call (so that a call's dispatch is not what is timed):

- ``bare MJX``: ``mujoco.mjx.step``, nothing of uwml;
- ``full uwml step``: :meth:`uwml.sim.mjx.Simulation.step`, the hull's lumped model, the arm's
  strips by the exact integrals, the added mass in the mass matrix, buoyancy, a current of
  0.2 m/s across the vehicle, the eight thrusters through their curves (a constant command),
  per-environment :class:`uwml.sim.mjx.Parameters`.

The dtype is JAX's default (float32, or float64 with ``jax_enable_x64``).
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator, Sequence
from typing import Any

import jax
import jax.numpy as jnp
import numpy as np

from .mjx import Action, Simulation

__all__ = ["STEPS", "benchmark_steps"]

#: Steps of every environment in one timed call.
STEPS = 20
#: The thrusters' commands held (surge on the horizontal four, a little heave).
COMMANDS = (0.5, 0.5, 0.5, 0.5, 0.2, -0.2, 0.2, -0.2)


def _waited(out: Any) -> None:
    for leaf in jax.tree_util.tree_leaves(out):
        leaf.block_until_ready()


def _timed(call: Callable[[], Any], repeats: int) -> tuple[float, float]:
    """The first call's seconds (compiling and running) and the best of ``repeats`` more."""
    start = time.perf_counter()
    _waited(call())
    first = time.perf_counter() - start
    best = np.inf
    for _ in range(max(1, repeats)):
        start = time.perf_counter()
        _waited(call())
        best = min(best, time.perf_counter() - start)
    return first, float(best)


def benchmark_steps(sizes: Sequence[int], repeats: int = 5) -> Iterator[tuple[str, int, float, float]]:
    """For each batch size of ``sizes``, bare MJX and then uwml's step (the module):
    ``(what, environments, compile seconds, steps per second)``, the compile time the first
    call's less the best of ``repeats`` later calls, the steps those of every environment."""
    import uwml.examples

    urdf, hydro = (uwml.examples.path("bluerov2", name) for name in ("bluerov2_arm.urdf", "bluerov2_arm.hydro.toml"))
    sim = Simulation.from_file(urdf, hydro, current=(0.0, 0.2, 0.0))
    mjx, model = sim._mjx, sim.mjx_model
    action = Action(jnp.asarray(COMMANDS), jnp.zeros(sim.n_joints))

    def bare(data: Any) -> Any:
        def one(d: Any, _: None) -> tuple[Any, None]:
            return jax.vmap(mjx.step, in_axes=(None, 0))(model, d), None

        return jax.lax.scan(one, data, None, length=STEPS)[0]

    def full(params: Any, states: Any) -> Any:
        def one(s: Any, _: None) -> tuple[Any, None]:
            return jax.vmap(sim.step, in_axes=(0, 0, None))(params, s, action), None

        return jax.lax.scan(one, states, None, length=STEPS)[0]

    bare_run, full_run, reset = jax.jit(bare), jax.jit(full), jax.jit(jax.vmap(sim.reset))
    for size in sizes:
        params = sim.parameters(int(size))
        states = reset(params)
        first, best = _timed(lambda: bare_run(states.data), repeats)  # noqa: B023 (called at once)
        yield "bare MJX", int(size), first - best, size * STEPS / best
        first, best = _timed(lambda: full_run(params, states), repeats)  # noqa: B023 (called at once)
        yield "full uwml step", int(size), first - best, size * STEPS / best
