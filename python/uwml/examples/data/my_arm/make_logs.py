"""Logs of the README's arm, made from its model (synthetic: for trying the command line on files
that exist; a real rig's logs have the same columns). Run from the repository's root:

    python examples/my_arm/make_logs.py

writes ``arm_log.csv`` (a trajectory: time, q, qd, qdd) and ``land_water.csv`` (the same
trajectory run on land and in water with Cd = 1.1 and Cm = 0.9: time, q, qd, qdd, tau_land,
tau_water) in the current folder. ``examples/my_arm/land_water.csv`` is a small log of the same
kind, kept in the repository (2 cycles at 100 Hz, 400 rows).
"""

import uwml
from uwml.io.logs import Log
from uwml.paper import synthetic
from uwml.sim.prescribed import SineTrajectory

arm = uwml.Robot.from_urdf("examples/my_arm/my_arm.urdf", hydro="examples/my_arm/my_arm.hydro.toml")
motion = SineTrajectory([0.6, 0.8], period=2.0)  # the shoulder and the elbow swing
experiment = synthetic.land_water_experiment(arm, motion, cycles=4, rate_hz=200.0, cd=1.1, cm=0.9, seed=0)
uwml.write_log(experiment, "land_water.csv")
uwml.write_log(Log(time=experiment.time, q=experiment.q, qd=experiment.qd, qdd=experiment.qdd), "arm_log.csv")
print(f"wrote arm_log.csv and land_water.csv: {experiment.n_samples} samples of {arm.n_joints} joints")
