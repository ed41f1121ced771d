"""The figures of docs/gallery.md: every figure the package writes, each made by the command (or
function) that writes it, on the examples that ship with uwml and on synthetic data, in one empty
folder; copied to ``docs/figures/gallery/`` under the names :data:`FIGURES` gives.

Run: ``python docs/figures/make_gallery.py [OUT]`` (OUT: where to put the figures instead of
``docs/figures/gallery/``). About 40 s.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
#: Where the figures are kept, relative to docs/ (the page shows ``figures/gallery/NAME``).
FOLDER = "figures/gallery"
ROBOT = ["--robot", "examples/bluerov2/bluerov2_arm.urdf", "--hydro", "examples/bluerov2/bluerov2_arm.hydro.toml"]
ARM = ["--robot", "examples/my_arm/my_arm.urdf", "--hydro", "examples/my_arm/my_arm.hydro.toml"]

#: Synthetic inputs the commands read, each made by a short program (run in the folder).
INPUTS = {
    "losses.csv": """
from uwml.fit import write_loss_csv
from uwml.paper.synthetic import three_configuration_experiment
write_loss_csv(three_configuration_experiment(startup=3, rng=0), "losses.csv")
""",
    "trial.csv": """
import numpy as np
import uwml
from uwml import examples
from uwml.sim.mujoco import Simulation
from uwml.sim.prescribed import SineTrajectory, Trajectory
# A trial of the BlueROV2: the arm swinging, surge then heave; the pose recorded at 100 Hz.
urdf, hydro = examples.path("bluerov2", "bluerov2_arm.urdf"), examples.path("bluerov2", "bluerov2_arm.hydro.toml")
sim = Simulation.from_file(urdf, hydro)
h = sim.model.opt.timestep
t = np.arange(0.0, 3.0 + 2 * h, h)
sim.prescribe(["shoulder", "elbow"], Trajectory(t, *SineTrajectory([0.5, 0.3], period=3.0).joint_states(t)))
schedule = {0: [0.3, 0.3, 0.3, 0.3, 0, 0, 0, 0], 750: [0, 0, 0, 0, 0.3, 0.3, 0.3, 0.3]}
rows = []
for k in range(1501):
    if k in schedule:
        sim.command_thrusters(schedule[k])
        command = schedule[k]
    if k % 5 == 0:
        d = sim.data
        rows.append([d.time, *d.qpos[7:9], *d.qpos[:7], *command])
    sim.step()
table = np.array(rows)
uwml.write_log(uwml.Log(time=table[:, 0], q=table[:, 1:3], base_position=table[:, 3:6], base_orientation=table[:, 6:10],
                        thruster_commands=table[:, 10:18]), "trial.csv")
""",
    "leg_study.toml": """
from pathlib import Path
Path("leg_study.toml").write_text('''
[scenario]
kind = "paper_leg"
cycles = 0.1

[parameters]
depth = [0.0, 3000.0, 6000.0]
controller = ["land", "hydro", "hydro_losses"]
coefficient_scale = { distribution = "uniform", low = 0.7, high = 1.3 }

[sampling]
samples = 2
''')
""",
}

#: The commands, in order (``uwml`` as ``python -m uwml``).
COMMANDS = [
    ["examples", "."],
    ["describe", "--plot", "describe_paper_leg.png"],
    ["describe", *ROBOT, "--plot", "describe_bluerov2.png"],
    ["paper", "--out", "paper"],
    ["fit", "hydro", "examples/my_arm/land_water.csv", *ARM, "--joints", "1,2", "--per", "link", "--plot", "fit_hydro.png"],
    ["fit", "losses", "losses.csv", "--plot", "losses"],
    ["simulate", "--depths", "0,3000", "--cycles", "1", "--out", "simulate"],
    ["replay", "trial.csv", *ROBOT, "--out", "replay"],
    ["study", "leg_study.toml", "--out", "leg-study", "--serial"],
]

#: Each figure (where the commands write it) and its name in FOLDER.
FIGURES = {
    "describe_paper_leg.png": "describe_paper_leg.png",
    "describe_bluerov2.png": "describe_bluerov2.png",
    "paper/fig8_torques.png": "paper_fig8_torques.png",
    "paper/fig7_fit.png": "paper_fig7_fit.png",
    "paper/fig13_14_loss_maps.png": "paper_fig13_14_loss_maps.png",
    "paper/efficiency_map.png": "paper_efficiency_map.png",
    "fit_hydro.png": "fit_hydro_my_arm.png",
    "losses/oil_drag_fit.png": "fit_losses_oil_drag.png",
    "losses/seal_fit.png": "fit_losses_seal.png",
    "simulate/tracking.png": "simulate_tracking.png",
    "simulate/depth_sweep.png": "simulate_depth_sweep.png",
    "simulate/fluid_models.png": "simulate_fluid_models.png",
    "replay/replay.png": "replay.png",
    "leg-study/figures/rms_error_1.png": "study_rms_error_1.png",
    "leg-study/figures/positive_work.png": "study_positive_work.png",
}


def main(out: Path) -> None:
    with tempfile.TemporaryDirectory() as folder:
        for made, code in INPUTS.items():
            done = subprocess.run([sys.executable, "-W", "error", "-c", code], cwd=folder, capture_output=True, text=True, check=False)
            if done.returncode:
                raise SystemExit(f"making {made} failed:\n{done.stderr}")
        for command in COMMANDS:
            start = time.perf_counter()
            done = subprocess.run([sys.executable, "-m", "uwml", *command], cwd=folder, capture_output=True, text=True, check=False)
            if done.returncode:
                raise SystemExit(f"uwml {' '.join(command)} failed:\n{done.stderr[-3000:]}")
            print(f"uwml {' '.join(command)}: {time.perf_counter() - start:.1f} s")
        out.mkdir(parents=True, exist_ok=True)
        for made, name in FIGURES.items():
            source = Path(folder) / made
            if not source.is_file():
                raise SystemExit(f"no command wrote {made}")
            shutil.copyfile(source, out / name)
            print(f"wrote {out / name}")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "docs" / FOLDER)
