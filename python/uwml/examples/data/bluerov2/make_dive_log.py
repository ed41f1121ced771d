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

import uwml
import uwml.examples
from uwml.sim.synthetic_logs import free_running

folder = uwml.examples.path("bluerov2")
log = free_running(folder / "bluerov2_arm.urdf", folder / "bluerov2_arm.hydro.toml", seconds=12.0, timestep=0.002, every=10)
uwml.write_log(log, "dive.csv")
print(f"wrote dive.csv: {log.n_samples} samples")
