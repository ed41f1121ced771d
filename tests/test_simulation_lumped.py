"""Lumped models (docs/model.md section 12.1) in a MuJoCo simulation (``uwml.sim.mujoco``): a
floating hull reaches the terminal speed of its damping's closed form along each axis it is
pushed; the added mass of a hull and an arm, without drag and gravity, keeps ``T_rigid + T_A``;
and an added mass ten times the hull's own stays stable (it is in the mass matrix, not lagged).
"""

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest
import uwml

mujoco = pytest.importorskip("mujoco")

from test_simulation import energy, weightless, without_drag
from uwml.sim.mujoco import Simulation, mjcf_of

DATA = Path(__file__).parent / "data"
WATER = uwml.Water(1000.0, 9.81)


def hull_robot(lumped: uwml.LumpedModel, mass: float = 20.0) -> uwml.Robot:
    """A neutrally buoyant hull (centres of mass and buoyancy together) carrying ``lumped``, with
    a light, neutrally buoyant link turning about the hull's vertical through its centre (so that
    the whole's centre of mass stays at the hull's origin), and nothing else in the water."""
    hull = uwml.Link(mass, (0.0, 0.0, 0.0), mass / WATER.density, lumped=lumped)
    link = uwml.Link(0.5, (0.0, 0.0, 0.0), 0.5 / WATER.density)
    return uwml.Robot([uwml.Joint((0.0, 0.0, 0.0), (0.0, 0.0, 1.0), parent=-1)], [link], base=hull, water=WATER)


@pytest.mark.parametrize("axis", range(6))
def test_a_pushed_hull_reaches_the_terminal_speed_of_its_damping(axis: int) -> None:
    # Constant generalized force F on one degree of freedom of the free joint (world force along
    # x, y, z; body moment about x, y, z): the speed settles where d u + q u² = F.
    linear, quadratic = [12.0, 18.0, 25.0, 1.5, 2.0, 2.5], [60.0, 90.0, 110.0, 4.0, 5.0, 6.0]
    lumped = uwml.LumpedModel(
        added_mass=np.diag([8.0, 12.0, 15.0, 0.4, 0.6, 0.5]), linear_damping=np.diag(linear), quadratic_damping=quadratic
    )
    robot = hull_robot(lumped)
    model = mujoco.MjModel.from_xml_string(mjcf_of(robot, floating=True))
    sim = Simulation(model, robot, water=WATER)
    force = 30.0 if axis < 3 else 2.0
    qfrc = np.zeros(model.nv)
    qfrc[axis] = force
    for _ in range(15000):
        sim.step(qfrc=qfrc)
    d, q = linear[axis], quadratic[axis]
    expected = (-d + math.sqrt(d * d + 4.0 * q * force)) / (2.0 * q)
    speed = sim.data.qvel[axis]
    assert abs(speed - expected) <= 1e-3 * expected, (speed, expected)
    # Nothing else moves (the pushed axis alone: the models are diagonal, the hull's centre at its
    # origin, and a turn keeps its axis).
    others = np.delete(sim.data.qvel[:6], axis)
    assert np.max(np.abs(others)) <= 1e-6 * expected, others


def test_lumped_added_mass_keeps_the_kinetic_energy_of_a_hull_and_its_arm() -> None:
    """No drag, no gravity, still water: the arm on its free hull, the hull with a full (coupled)
    lumped added mass beside its strips, Kirchhoff's form for the strips: T_rigid + T_A is kept
    to the RK4 integrator's accuracy, falling with the step."""
    from uwml.robot.files import model_and_robot

    model, robot = model_and_robot(DATA / "arm.xml", DATA / "arm.hydro.toml")
    model = weightless(model)
    rng = np.random.default_rng(11)
    a = rng.normal(size=(6, 6)) * 3.0
    lumped = uwml.LumpedModel(point=(0.05, -0.02, 0.03), added_mass=a @ a.T + np.diag([20.0, 30.0, 40.0, 1.0, 2.0, 1.5]))
    bare = without_drag(robot)
    assert bare.base is not None
    robot = uwml.Robot(bare.joints, bare.links, base=dataclasses.replace(bare.base, lumped=lumped), water=bare.water)
    water = uwml.Water(1000.0, 0.0)
    start = rng.uniform(-0.6, 0.6, model.nv)

    def drift(step: float) -> float:
        model.opt.timestep = step
        sim = Simulation(model, robot, water=water, integrator="rk4", added_mass="kirchhoff")
        sim.model.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_CONSTRAINT)
        sim.data.qvel[:] = start
        first, worst = energy(sim), 0.0
        while sim.data.time < 1.0 - 1e-9:
            sim.step()
            worst = max(worst, abs(energy(sim) - first) / first)
        return worst

    coarse, fine = drift(1e-3), drift(5e-4)
    assert coarse < 1e-7 and fine < coarse / 3.0, (coarse, fine)


def test_an_added_mass_far_above_the_hulls_own_is_stable() -> None:
    # Ten times the hull's mass and inertia, with damping: the motion decays, finite throughout
    # (a lagged added mass would diverge once it exceeds the body's own: docs/simulation.md).
    lumped = uwml.LumpedModel(
        added_mass=np.diag([200.0, 200.0, 200.0, 5.0, 5.0, 5.0]), linear_damping=np.diag([5.0, 5.0, 5.0, 0.5, 0.5, 0.5])
    )
    robot = hull_robot(lumped)
    model = mujoco.MjModel.from_xml_string(mjcf_of(robot, floating=True))
    sim = Simulation(model, robot, water=WATER)
    sim.data.qvel[:6] = [0.5, -0.3, 0.2, 0.4, -0.2, 0.3]
    start = np.abs(sim.data.qvel[:6]).max()
    for _ in range(3000):
        sim.step()
        assert np.all(np.isfinite(sim.data.qvel))
    assert np.abs(sim.data.qvel[:6]).max() < start
