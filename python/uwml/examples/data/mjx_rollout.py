"""A batched rollout in MJX with uwml's forces (docs/batched.md, "Simulating with MJX"): the
BlueROV2 example (a floating vehicle, a 2-joint arm, eight thrusters) in 64 environments, each
with its own drag and added mass, current and payload in the gripper (domain randomization),
driven for 2 s toward a point 1 m ahead by a PD controller through the thrusters; each
environment's return is minus its distance to the point, integrated, less a little effort.

    python examples/mjx_rollout.py [--batch 64] [--seconds 2] [--x64]

Any RL library that takes pure ``reset``/``step`` functions drives ``sim.reset`` and
``sim.step`` the same way; here the policy is a fixed controller and the rollout one
``jax.lax.scan`` under ``jax.jit(jax.vmap(...))``.
"""

from __future__ import annotations

import argparse
import os
import time
from typing import TYPE_CHECKING

import numpy as np
import uwml.examples

if TYPE_CHECKING:
    import jax

TARGET = np.array([1.0, 0.0, 0.0])  # [m], world: 1 m ahead of the start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--batch", type=int, default=64, help="environments (default 64)")
    parser.add_argument("--seconds", type=float, default=2.0, help="simulated time (default 2 s)")
    parser.add_argument("--x64", action="store_true", help="float64 (default float32)")
    args = parser.parse_args()
    os.environ["JAX_ENABLE_X64"] = "1" if args.x64 else "0"  # before JAX is imported
    import jax
    import jax.numpy as jnp
    from uwml.jax.tree_motion import quaternion_matrix
    from uwml.sim.mjx import Action, Parameters, Simulation, State

    urdf, hydro = (uwml.examples.path("bluerov2", name) for name in ("bluerov2_arm.urdf", "bluerov2_arm.hydro.toml"))
    sim = Simulation.from_file(urdf, hydro, payload_body="forearm")
    steps = round(args.seconds / sim.timestep)
    # Domain randomization: one set of parameters per environment.
    keys = jax.random.split(jax.random.PRNGKey(0), 4)
    batch = args.batch
    params = sim.parameters(
        batch,
        drag_scale=jax.random.uniform(keys[0], (batch,), minval=0.7, maxval=1.3),
        added_mass_scale=jax.random.uniform(keys[1], (batch,), minval=0.8, maxval=1.2),
        current=0.1 * jax.random.normal(keys[2], (batch, 3)),
        payload=jax.random.uniform(keys[3], (batch,), maxval=0.5),  # kg in the gripper
    )
    # The thrusters' allocation (a wrench on the hull is B @ thrust) inverted, and the T200
    # curve (51.5 N at full command, quadratic beyond a dead band) inverted crudely.
    allocation = np.linalg.pinv(sim.robot.thruster_allocation())

    def policy(state: State) -> Action:
        position, quaternion = sim.base_pose(state)
        turn = quaternion_matrix(quaternion)  # world from body
        velocity, angular_velocity = turn.T @ state.data.qvel[:3], state.data.qvel[3:6]
        force = 120.0 * (turn.T @ (jnp.asarray(TARGET) - position)) - 40.0 * velocity
        moment = -8.0 * quaternion[1:] * jnp.sign(quaternion[0]) - 2.0 * angular_velocity  # level, heading 0
        thrust = jnp.asarray(allocation) @ jnp.concatenate([force, moment])
        command = jnp.sign(thrust) * (0.0625 + 0.9375 * jnp.sqrt(jnp.minimum(jnp.abs(thrust) / 51.5, 1.0)))
        return Action(jnp.where(jnp.abs(thrust) > 1e-3, command, 0.0), jnp.zeros(sim.n_joints))

    def episode(params: Parameters, state: State) -> tuple[State, jax.Array]:
        def one(state: State, step: None) -> tuple[State, jax.Array]:
            action = policy(state)
            state = sim.step(params, state, action)
            position = sim.base_pose(state)[0]
            reward = -jnp.linalg.norm(position - jnp.asarray(TARGET)) - 1e-3 * jnp.sum(action.thrusters**2)
            return state, reward * sim.timestep

        state, rewards = jax.lax.scan(one, state, None, length=steps)
        return state, jnp.sum(rewards)

    run = jax.jit(jax.vmap(episode))
    states = jax.vmap(sim.reset)(params)
    started = time.perf_counter()
    run(params, states)[1].block_until_ready()
    compiled = time.perf_counter() - started
    started = time.perf_counter()
    final, returns = run(params, states)
    returns.block_until_ready()
    elapsed = time.perf_counter() - started
    distance = np.linalg.norm(np.asarray(sim.base_pose(final)[0]) - TARGET, axis=1)
    print(f"{batch} environments x {steps} steps of {sim.timestep * 1e3:g} ms ({final.data.qpos.dtype})")
    print(f"return: mean {float(np.mean(returns)):.3f}, worst {float(np.min(returns)):.3f}, best {float(np.max(returns)):.3f}")
    print(f"distance to the target at the end: mean {distance.mean():.3f} m, worst {distance.max():.3f} m (1 m at the start)")
    print(f"compiled in {compiled:.1f} s; {batch * steps / elapsed:,.0f} environment steps/s on {jax.devices()[0].platform}")


if __name__ == "__main__":
    main()
