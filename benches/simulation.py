"""The cost of a MuJoCo step with uwml inside (uwml.sim.mujoco.Simulation) against a bare mj_step
and against MuJoCo's own fluid models (inertia box; ellipsoid), on robots of tests/data.

    python benches/simulation.py [--steps N]

Prints microseconds per step (median of 5 runs of N steps, each from the same state) and the ratios to a bare mj_step (and
uwml's RK4 step against MuJoCo's own RK4 step, which also makes four forward passes; and
uwml's forward pass alone, of which an RK4 step makes four: the least that step can cost), for
the paper's leg (fixed base, 3 joints) and the arm on a free-floating hull (3 joints), without joint
losses and (Euler) with the default ones at 3000 m. Timings on a
shared machine are noisy: compare ratios from one run.
"""

from __future__ import annotations

import argparse
import copy
import statistics
import time
from pathlib import Path

import mujoco
import numpy as np
import uwml
from uwml.robot.files import model_and_robot
from uwml.sim.mujoco import Simulation
from uwml.sim.prescribed import Trajectory

DATA = Path(__file__).resolve().parents[1] / "tests" / "data"
ROBOTS = {"paper leg (fixed base)": ("paper_leg.xml", "paper_leg.hydro.toml"), "arm on a floating hull": ("arm.xml", "arm.hydro.toml")}


def with_fluid(path: Path, ellipsoid: bool) -> mujoco.MjModel:
    """The description with MuJoCo's fluid model on (water: 1000 kg/m³, 1e-3 Pa·s): the
    inertia-box model, or the ellipsoid model on every collision geom; visual geoms removed."""
    spec = mujoco.MjSpec.from_file(str(path))
    spec.compiler.fusestatic = False
    for geom in list(spec.geoms):
        if not (geom.contype or geom.conaffinity):
            spec.delete(geom)
        elif ellipsoid:
            geom.fluid_ellipsoid = 1.0
    for mesh in list(spec.meshes):
        spec.delete(mesh)
    compiled = spec.compile()
    compiled.opt.density, compiled.opt.viscosity = 1000.0, 1e-3
    return compiled


def per_step(step, steps: int, data: mujoco.MjData) -> float:  # type: ignore[no-untyped-def]
    """Median microseconds per step of 5 runs of ``steps`` steps, each run from the same state
    (``data``'s at the call: positions, velocities, time, the solver's warm start), so that every
    run, and each method, starts alike (a simulation left to run on drifts into other contacts
    and costs)."""
    saved = data.qpos.copy(), data.qvel.copy(), data.time, data.qacc_warmstart.copy()
    runs = []
    for _ in range(5):
        data.qpos[:], data.qvel[:], data.time, data.qacc_warmstart[:] = saved
        start = time.perf_counter()
        for _ in range(steps):
            step()
        runs.append((time.perf_counter() - start) / steps * 1e6)
    return statistics.median(runs)


def robot_steps(file: str, hydro: str, steps: int) -> dict[str, float]:
    """Microseconds per step of one robot of ``ROBOTS``: a bare mj_step, MuJoCo's fluid models
    (inertia box, ellipsoid), uwml's step (Euler, RK4, Euler with the default losses at 3000 m),
    MuJoCo's own RK4 step and uwml's forward pass alone (``Simulation.forward``), by label."""
    model, _ = model_and_robot(DATA / file, DATA / hydro)
    rng = np.random.default_rng(0)
    rows: dict[str, float] = {}
    bare = mujoco.MjData(model)
    bare.qvel[:] = rng.uniform(-0.5, 0.5, model.nv)
    rows["bare mj_step"] = per_step(lambda m=model, d=bare: mujoco.mj_step(m, d), steps, bare)
    # MuJoCo's own RK4: four forward passes a step, as uwml's rk4 (compare its row with this).
    rk4_model = copy.copy(model)
    rk4_model.opt.integrator = mujoco.mjtIntegrator.mjINT_RK4
    rk4_data = mujoco.MjData(rk4_model)
    rk4_data.qvel[:] = bare.qvel
    rk4_bare = per_step(lambda m=rk4_model, d=rk4_data: mujoco.mj_step(m, d), steps // 4, rk4_data)
    for label, ellipsoid in (("MuJoCo fluid, inertia box", False), ("MuJoCo fluid, ellipsoid", True)):
        fluid = with_fluid(DATA / file, ellipsoid)
        data = mujoco.MjData(fluid)
        data.qvel[:] = rng.uniform(-0.5, 0.5, fluid.nv)
        rows[label] = per_step(lambda m=fluid, d=data: mujoco.mj_step(m, d), steps, data)
    for integrator in ("euler", "rk4"):
        sim = Simulation.from_file(DATA / file, DATA / hydro, integrator=integrator)
        sim.data.qvel[:] = rng.uniform(-0.5, 0.5, sim.model.nv)
        rows[f"uwml.sim.mujoco, {integrator}"] = per_step(sim.step, steps // 4 if integrator == "rk4" else steps, sim.data)
    # One forward pass with uwml (Simulation.forward, no integration): an RK4 step makes four.
    sim = Simulation.from_file(DATA / file, DATA / hydro, integrator="rk4")
    sim.data.qvel[:] = bare.qvel
    forward = per_step(sim.forward, steps, sim.data)
    # The default joint losses at 3000 m: the seals' friction a MuJoCo constraint, noslip on.
    sim = Simulation.from_file(DATA / file, DATA / hydro, depth=3000.0, losses=uwml.JointLosses())
    sim.data.qvel[:] = rng.uniform(-0.5, 0.5, sim.model.nv)
    rows["uwml.sim.mujoco, euler, losses"] = per_step(sim.step, steps, sim.data)
    rows["bare mj_step, MuJoCo RK4"] = rk4_bare
    rows["uwml forward pass alone"] = forward
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--steps", type=int, default=2000)
    args = parser.parse_args()
    print(f"microseconds per step (median of 5 × {args.steps} steps); ratio to a bare mj_step")
    for name, (file, hydro) in ROBOTS.items():
        rows = robot_steps(file, hydro, args.steps)
        bare, rk4_bare, forward = rows.pop("bare mj_step"), rows.pop("bare mj_step, MuJoCo RK4"), rows.pop("uwml forward pass alone")
        print(f"\n{name}")
        for label, micro in {"bare mj_step": bare, **rows}.items():
            print(f"  {label:28s} {micro:9.1f} µs   {micro / bare:6.2f} ×")
        rk4 = rows["uwml.sim.mujoco, rk4"]
        print(
            f"  {'bare mj_step, MuJoCo RK4':28s} {rk4_bare:9.1f} µs   {rk4_bare / bare:6.1f} ×   (uwml's rk4: {rk4 / rk4_bare:.1f} × this)"
        )
        print(
            f"  {'uwml forward pass alone':28s} {forward:9.1f} µs   {forward / bare:6.2f} ×   "
            f"(four, an RK4 step's least: {4 * forward / bare:.2f} ×)"
        )
    rows = vehicle_rows(args.steps)
    print("\nBlueROV2 with its arm, floating (examples/bluerov2); ratio to the plain uwml step")
    for label, micro in rows.items():
        print(f"  {label:28s} {micro:9.1f} µs   {micro / rows['uwml step']:6.2f} ×")


def vehicle_rows(steps: int) -> dict[str, float]:
    """The BlueROV2 example with its arm, floating (examples/bluerov2): a plain uwml step against
    one with the arm's two joints on a prescribed motion of samples (docs/model.md section 12.4)
    and one with its eight thrusters pushing (section 13.1); issue 33 asks each within 2× the
    plain step. Microseconds per step, by label."""
    example = Path(__file__).resolve().parents[1] / "examples" / "bluerov2"
    urdf, hydro = example / "bluerov2_arm.urdf", example / "bluerov2_arm.hydro.toml"
    sim = Simulation.from_file(urdf, hydro)
    plain = per_step(sim.step, steps, sim.data)
    sim.command_thrusters([0.3, -0.2, 0.1, 0.4, 0.2, 0.2, -0.1, 0.3])
    thrust = per_step(sim.step, steps, sim.data)
    sim = Simulation.from_file(urdf, hydro)
    t = np.linspace(0.0, 1000.0, 200_001)
    sim.prescribe(["shoulder", "elbow"], Trajectory(t, np.stack([0.4 * np.sin(t), 0.3 * np.sin(2.0 * t)], axis=1)))
    prescribed = per_step(sim.step, steps, sim.data)
    return {"uwml step": plain, "with thrust (8 thrusters)": thrust, "with a prescribed motion": prescribed}


if __name__ == "__main__":
    main()
