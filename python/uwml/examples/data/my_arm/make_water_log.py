"""The water-only log of the 2-joint arm (synthetic: a real arm's log has the same columns), as
``examples/my_arm/water.csv`` ships it: 8 s of the shoulder and elbow swinging at 100 Hz, the motor
torques ``τ_motor = ID_RB − τ_env`` with ``ID_RB`` the description's rigid-body inverse dynamics
(MuJoCo's ``mj_inverse``, its fluid model and constraints off) and ``τ_env`` uwml's environment at
Cd = 1.1, Cm = 0.9 (no joint losses), and 0.05 N·m of noise (seed 0). Written to ``water.csv`` in
the current folder:

    python examples/my_arm/make_water_log.py

``uwml fit hydro water.csv --water-only --robot examples/my_arm/my_arm.urdf --hydro
examples/my_arm/my_arm.hydro.toml --per leg`` gives Cd and Cm back (docs/identification.md).
"""

import copy

import mujoco
import numpy as np
import uwml
import uwml.examples
from uwml.io.logs import Log
from uwml.robot.files import model_and_robot
from uwml.sim.prescribed import SineTrajectory

folder = uwml.examples.path("my_arm")
model, arm = model_and_robot(folder / "my_arm.urdf", folder / "my_arm.hydro.toml")
t = np.arange(800) / 100.0
q, qd, qdd = SineTrajectory([0.6, 0.8], period=2.0).joint_states(t)
inverse = copy.deepcopy(model)
inverse.opt.density, inverse.opt.viscosity = 0.0, 0.0
inverse.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_CONSTRAINT)
data, rigid = mujoco.MjData(inverse), np.zeros_like(q)
for i in range(len(t)):
    data.qpos[:], data.qvel[:], data.qacc[:] = q[i], qd[i], qdd[i]
    mujoco.mj_inverse(inverse, data)
    rigid[i] = data.qfrc_inverse
environment = arm.environment(q, qd, qdd, cd=1.1, cm=0.9, losses=[None, None]).total
tau = rigid - environment + 0.05 * np.random.default_rng(0).standard_normal(q.shape)
uwml.write_log(Log(time=t, q=q, qd=qd, qdd=qdd, tau=tau), "water.csv")
print(f"wrote water.csv: {len(t)} samples of {arm.n_joints} joints")
