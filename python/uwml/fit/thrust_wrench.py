"""The thrusters' wrench on the base from a log's commands ``u1 … un`` (docs/model.md section 13.1):
each command through its thruster's curve and limits (:meth:`uwml.Thruster.thrust`), the lag of
a thruster with a time constant advanced exactly under each held command, as a simulation holds
it (``T_{i+1} = f(u_i) + (T_i − f(u_i)) e^{−Δt/τ}``, the thrusters steady at the log's first
sample), and the allocation ``B`` (:meth:`uwml.Robot.thruster_allocation`, at each sample's joint
positions where a thruster sits on a link): ``W = B T``, about the base's origin in its axes.
"""

from __future__ import annotations

import numpy as np

from ..io.logs import Log
from ..robot.tree import Robot
from ._types import Array

__all__ = ["check_thruster_commands", "thrust", "thrust_wrench"]


def check_thruster_commands(log: Log, robot: Robot) -> Array:
    """The log's commands ``(n, n_thrusters)``, or a ValueError naming the column: none, or not
    one per thruster of the description."""
    names = [thruster.name or f"thruster {k + 1}" for k, (_, thruster) in enumerate(robot.thrusters)]
    if not names:
        raise ValueError("the description has no thrusters (a hydro file's [[links.NAME.thrusters]]): nothing turns commands into thrust")
    commands = log.thruster_commands
    if commands is None:
        raise ValueError(
            f"{log.source}: row 1 (header), column 'u1': missing column (the thruster commands u1 … u{len(names)}, one per thruster "
            f"of the description: {', '.join(names)})"
        )
    if commands.shape[1] != len(names):
        column = f"u{min(commands.shape[1], len(names)) + 1}"
        raise ValueError(
            f"{log.source}: row 1 (header), column {column!r}: the log has {commands.shape[1]} thruster commands (u1 … "
            f"u{commands.shape[1]}), the description {len(names)} thrusters ({', '.join(names)})"
        )
    return commands


def thrust(log: Log, robot: Robot) -> Array:
    """Each thruster's thrust [N] at every sample ``(n, n_thrusters)`` (module docstring)."""
    commands = check_thruster_commands(log, robot)
    out = np.empty_like(commands)
    for k, (_, thruster) in enumerate(robot.thrusters):
        steady = thruster.thrust(commands[:, k])
        tau = thruster.time_constant
        if tau <= 0.0:
            out[:, k] = steady
            continue
        decay = np.exp(-np.diff(log.time) / tau)
        out[0, k] = steady[0]
        for i in range(1, len(steady)):
            out[i, k] = steady[i - 1] + (out[i - 1, k] - steady[i - 1]) * decay[i - 1]
    return out


def thrust_wrench(log: Log, robot: Robot) -> Array:
    """``B T`` at every sample ``(n, 6)``: force [N] and moment [N·m] about the base's origin, base
    axes (module docstring)."""
    forces = thrust(log, robot)
    if all(body < 0 for body, _ in robot.thrusters):
        wrench: Array = forces @ robot.thruster_allocation().T
        return wrench
    return np.stack([robot.thruster_allocation(q) @ f for q, f in zip(log.q, forces, strict=True)])
