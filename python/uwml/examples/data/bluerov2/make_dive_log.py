"""A free-running log of the BlueROV2 (synthetic: a vehicle's navigation log has the same
columns), as ``examples/bluerov2/dive.csv`` ships it: the vehicle floating in the simulation
(``uwml.sim.mujoco.Simulation``, Euler, 2 ms), its eight thrusters driven by sums of sines (each
its own frequencies, up to about 2 Hz), the arm held still; every 10th step logged at its start:
the pose, the body twist ``u … r`` and its rate ``u_dot … r_dot``, the arm's joints and the
thruster commands ``u1 … u8``, 12 s at 50 Hz. Written to ``dive.csv`` in the current folder:

    python examples/bluerov2/make_dive_log.py

``uwml fit hull dive.csv --robot examples/bluerov2/bluerov2_arm.urdf --hydro
examples/bluerov2/bluerov2_arm.hydro.toml`` gives the hull's published diagonals back
(docs/identification.md).
"""

import mujoco
import numpy as np
import uwml
import uwml.examples
from uwml.io.logs import Log
from uwml.sim.mujoco import Simulation
from uwml.sim.prescribed import Trajectory

folder = uwml.examples.path("bluerov2")
sim = Simulation.from_file(folder / "bluerov2_arm.urdf", folder / "bluerov2_arm.hydro.toml")
timestep, every, seconds = 0.002, 10, 12.0
sim.model.opt.timestep = timestep
sim.prescribe(["shoulder", "elbow"], Trajectory.of(lambda t: (np.zeros(2), np.zeros(2), np.zeros(2)), joints=2))
rng = np.random.default_rng(0)
k = np.arange(8)
frequency, phase = 0.05 + 0.037 * k + 0.011 * k**2, rng.uniform(0.0, 2.0 * np.pi, 8)
d, rows = sim.data, []
for i in range(round(seconds / timestep)):
    now = i * timestep
    command = 0.55 * np.sin(2 * np.pi * frequency * now + phase) + 0.35 * np.sin(2 * np.pi * 2.3 * frequency * now + 2 * phase)
    sim.command_thrusters(command)
    qpos, qvel = d.qpos.copy(), d.qvel.copy()
    sim.step()
    if i % every == 0:
        rows.append((now, qpos, qvel, d.qacc.copy(), command))
t, qpos, qvel, qacc, commands = (np.array([row[j] for row in rows]) for j in range(5))
turn = np.zeros((len(t), 9))
for i, quaternion in enumerate(qpos[:, 3:7]):
    mujoco.mju_quat2Mat(turn[i], quaternion)
rotation = turn.reshape(-1, 3, 3)
v, w = np.einsum("nji,nj->ni", rotation, qvel[:, :3]), qvel[:, 3:6]
v_dot = np.einsum("nji,nj->ni", rotation, qacc[:, :3]) - np.cross(w, v)
log = Log(
    time=t, q=qpos[:, 7:], qd=qvel[:, 6:], qdd=qacc[:, 6:], base_position=qpos[:, :3], base_orientation=qpos[:, 3:7],
    base_twist=np.hstack([v, w]), base_twist_dot=np.hstack([v_dot, qacc[:, 3:6]]), thruster_commands=commands,
)  # fmt: skip
uwml.write_log(log, "dive.csv")
print(f"wrote dive.csv: {len(t)} samples")
