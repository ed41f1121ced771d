"""Synthetic logs of a floating vehicle made by the simulation, for trying and testing the fits
on files that look recorded (docs/identification.md, "A hull from free-running logs"):
:func:`free_running` drives a vehicle's thrusters with sums of sines, its arm held still, and
logs what a navigation system would (the pose, the body twist and its rate, the arm's joints,
the thruster commands)."""

from __future__ import annotations

import os

import numpy as np

from ..io.logs import Log
from .mujoco import Simulation
from .prescribed import Trajectory

__all__ = ["free_running"]


def free_running(
    description: str | os.PathLike[str],
    hydro: str | os.PathLike[str] | None = None,
    *,
    seconds: float = 20.0,
    timestep: float = 0.002,
    every: int = 5,
    logged_noise: float = 0.0,
    seed: int = 0,
) -> Log:
    """The floating vehicle of ``description`` (and its ``hydro`` file) on its thrusters for
    ``seconds``: each command a sum of two sines (every thruster its own frequencies, up to about
    2 Hz, random phases of ``seed``), held for one step of MuJoCo's Euler integrator at
    ``timestep``, the arm's joints held at 0; the state at the start of every ``every``-th step
    logged with that step's acceleration (the twist's rate ``ν̇ = Rᵀ v̇_world − ω × ν``) and the
    command, plus ``logged_noise`` of Gaussian noise on the logged commands (the thrusters got
    the exact ones)."""
    import mujoco

    sim = Simulation.from_file(description, hydro)
    sim.model.opt.timestep = timestep
    n_joints, n_thrusters = sim.robot.n_joints, len(sim.robot.thrusters)
    if n_joints:
        still = np.zeros(n_joints)
        sim.prescribe(list(range(n_joints)), Trajectory.of(lambda t: (still, still, still), joints=n_joints))
    rng = np.random.default_rng(seed)
    k = np.arange(n_thrusters)
    frequency, phase = 0.05 + 0.037 * k + 0.011 * k**2, rng.uniform(0.0, 2.0 * np.pi, n_thrusters)
    d, rows = sim.data, []
    for i in range(round(seconds / timestep)):
        now = i * timestep
        command = 0.55 * np.sin(2 * np.pi * frequency * now + phase) + 0.35 * np.sin(2 * np.pi * 2.3 * frequency * now + 2 * phase)
        sim.command_thrusters(command)
        qpos, qvel = d.qpos.copy(), d.qvel.copy()
        sim.step()
        if i % every == 0:
            rows.append((now, qpos, qvel, d.qacc.copy(), command + logged_noise * rng.standard_normal(n_thrusters)))
    t, qpos, qvel, qacc, commands = (np.array([row[j] for row in rows]) for j in range(5))
    turn = np.zeros((len(t), 9))
    for i, quaternion in enumerate(qpos[:, 3:7]):
        mujoco.mju_quat2Mat(turn[i], quaternion)
    rotation = turn.reshape(-1, 3, 3)
    v, w = np.einsum("nji,nj->ni", rotation, qvel[:, :3]), qvel[:, 3:6]
    v_dot = np.einsum("nji,nj->ni", rotation, qacc[:, :3]) - np.cross(w, v)
    return Log(
        time=t, q=qpos[:, 7:], qd=qvel[:, 6:], qdd=qacc[:, 6:], base_position=qpos[:, :3], base_orientation=qpos[:, 3:7],
        base_twist=np.hstack([v, w]), base_twist_dot=np.hstack([v_dot, qacc[:, 3:6]]), thruster_commands=commands,
        source="free-running",
    )  # fmt: skip
