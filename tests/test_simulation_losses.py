"""Joint losses inside a MuJoCo simulation (uwml.sim.mujoco, "Joint losses"): the seal's dry
friction is a MuJoCo friction constraint at the level of uwml's depth-dependent model, the oil
drag and the seal's viscous term a damping MuJoCo integrates implicitly. Explicit forces made
these simulations diverge (a seal slope of about 2e4 N·m·s/rad at rest against a few hundredths
of kg·m² on a wrist); here they stay finite, settle and stay stopped where friction holds."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
import uwml

mujoco = pytest.importorskip("mujoco")
from uwml import reference
from uwml.robot.files import model_and_robot
from uwml.sim.mujoco import Simulation

DATA = Path(__file__).parent / "data"
HYDRO = DATA / "arm.hydro.toml"


def arm_file(tmp_path: Path, *, fixed: bool = False, mass_scale: float = 1.0) -> Path:
    """tests/data/arm.xml (hull, shoulder, elbow, gripper slide), its hull welded to the world
    (``fixed``) and every mass and inertia scaled by ``mass_scale`` (light links); contacts off
    (the upper arm's cylinder overlaps the hull's box: only joint friction acts here)."""
    text = (DATA / "arm.xml").read_text().replace("<worldbody>", '<option><flag contact="disable"/></option><worldbody>')
    if fixed:
        text = text.replace('<freejoint name="hull_free"/>', "")

    def scaled(match: re.Match[str]) -> str:
        return f'{match.group(1)}="{" ".join(repr(float(x) * mass_scale) for x in match.group(2).split())}"'

    text = re.sub(r'(mass|diaginertia)="([^"]*)"', scaled, text)
    path = tmp_path / "arm.xml"
    path.write_text(text)
    return path


def run(sim: Simulation, seconds: float) -> np.ndarray:
    """Steps for ``seconds``; the joint positions after each step."""
    positions = []
    for _ in range(round(seconds / sim.model.opt.timestep)):
        sim.step()
        positions.append(sim.data.qpos[sim._joint_qpos].copy())
    return np.array(positions)


@pytest.mark.parametrize("timestep", [1e-3, 2e-3])
def test_the_arm_with_losses_at_6000_m_settles_and_stays_stopped(tmp_path: Path, timestep: float) -> None:
    """The fixed-base arm, released at 0.3 rad/s under gravity at 6,000 m with the default
    losses: its seals (about 425 N·m of breakaway there) hold gravity's few N·m, so it stops
    and stays stopped. Without losses the same start falls under gravity (the test has a load)."""
    model, robot = model_and_robot(arm_file(tmp_path, fixed=True), HYDRO)
    start, speed = np.array([0.4, -0.6, 0.01]), np.array([0.3, 0.3, 0.05])
    gravity_load = robot.environment(start, np.zeros(3), np.zeros(3)).total + robot.hydro(start, np.zeros(3), np.zeros(3)).gravity
    assert 0.5 < np.max(np.abs(gravity_load)) < 50.0  # well below the seal's level, not nothing

    sim = Simulation(model, robot, depth=6000.0, losses=uwml.JointLosses())
    sim.model.opt.timestep = timestep
    sim.data.qpos[:], sim.data.qvel[:] = start, speed
    positions = run(sim, 2.0)
    assert np.all(np.isfinite(positions))
    assert np.max(np.abs(sim.data.qvel)) < 1e-6, sim.data.qvel
    last_second = positions[len(positions) // 2 :]
    assert np.max(np.abs(last_second - last_second[0])) < 1e-6
    assert np.max(np.abs(positions[-1] - start)) > 1e-3  # it moved before it stopped

    free = Simulation(model, robot, depth=6000.0, losses=[None, None, None])
    free.model.opt.timestep = timestep
    free.data.qpos[:], free.data.qvel[:] = start, speed
    run(free, 2.0)
    assert np.max(np.abs(free.data.qvel)) > 1e-2


def test_each_step_sets_the_seal_friction_and_the_loss_damping_of_the_reference_formulas(tmp_path: Path) -> None:
    """The model's ``dof_frictionloss`` is its own plus the seal's level ``C + (S − C) e^{−(ω/ω_s)²}``
    and ``dof_damping`` its own plus ``−(τ_oil + D ω)/ω``, from the numpy reference's formulas; a
    sliding joint's constraint force is that level against its motion."""
    path = arm_file(tmp_path, fixed=True)
    text = path.read_text().replace(
        '<joint name="elbow" type="hinge" axis="0 1 0"/>',
        '<joint name="elbow" type="hinge" axis="0 1 0" damping="0.7" frictionloss="1.5"/>',
    )
    path.write_text(text)
    model, robot = model_and_robot(path, HYDRO)
    losses = uwml.JointLosses()
    depth, temperature = 2000.0, 4.0
    sim = Simulation(model, robot, depth=depth, temperature_c=temperature, losses=[losses, losses, None])
    qd = np.array([0.02, -0.7, 0.1])
    sim.data.qpos[:], sim.data.qvel[:] = [0.2, -0.3, 0.0], qd
    sim.forward()
    # The water column above is the robot's own water, as in Robot.environment.
    pressure = reference.hydrostatic_pressure_mpa(depth, robot.water.density, robot.water.gravity)
    seal = losses.seal
    c, s, d = (seal.c0 + seal.c1_per_mpa * pressure, seal.s0 + seal.s1_per_mpa * pressure, seal.d0 + seal.d1_per_mpa * pressure)
    level = c + (s - c) * np.exp(-((qd[:2] / seal.stribeck_speed) ** 2))
    visc = reference.joint_loss_torques(losses.drive, losses.oil, None, qd[:2], pressure, temperature, losses.epsilon)["visc"]
    damping = -visc / qd[:2] + d
    np.testing.assert_allclose(sim.model.dof_frictionloss, [level[0], level[1] + 1.5, 0.0], rtol=1e-12)
    np.testing.assert_allclose(sim.model.dof_damping, [damping[0], damping[1] + 0.7, 0.0], rtol=1e-12)
    assert damping[1] > 10.0 * d  # the oil's part counts
    # MuJoCo's friction force never exceeds the level (it is a soft constraint, which reaches
    # the level only when the load asks for more: the next test).
    assert np.all(np.abs(sim.data.qfrc_constraint) <= sim.model.dof_frictionloss * (1 + 1e-9))
    # No losses in the applied forces: they hold the hydrodynamics (and motor torques) only.
    forces, _ = sim.environment()
    hydro = sim.robot.hydro(sim.data.qpos, qd, np.zeros(3), water=sim.water)
    np.testing.assert_allclose(sim.data.qfrc_applied, hydro.total, rtol=1e-12, atol=1e-12)
    env = sim.robot.environment(
        sim.data.qpos, qd, np.zeros(3), depth=depth, temperature_c=temperature, losses=[losses, losses, None], water=sim.water
    )
    np.testing.assert_allclose(forces[6:], env.total, rtol=1e-12)  # environment(): losses as forces


@pytest.mark.parametrize("timestep", [1e-3, 2e-3])
def test_a_torque_beyond_breakaway_turns_the_joint_against_the_running_friction(tmp_path: Path, timestep: float) -> None:
    """The shoulder (vertical axis: no gravity load) with a motor torque of 0.9 times the seal's
    breakaway level at 2,000 m stays at rest; with 1.1 times it breaks away and turns, and while it
    slides the friction MuJoCo applies is the model's level at its speed, against the motion."""
    model, robot = model_and_robot(arm_file(tmp_path, fixed=True), HYDRO)
    losses, depth = uwml.JointLosses(), 2000.0
    pressure = reference.hydrostatic_pressure_mpa(depth, robot.water.density, robot.water.gravity)
    seal = losses.seal
    c, s = seal.c0 + seal.c1_per_mpa * pressure, seal.s0 + seal.s1_per_mpa * pressure
    for factor, moves in [(0.9, False), (1.1, True)]:
        sim = Simulation(model, robot, depth=depth, losses=losses)  # the other joints held too
        sim.model.opt.timestep = timestep
        for _ in range(round(0.3 / timestep)):
            sim.step(torque=[factor * s, 0.0, 0.0])
        speed = sim.data.qvel[0]
        if not moves:
            assert abs(speed) < 1e-6 and abs(sim.data.qpos[0]) < 1e-6
            continue
        assert speed > 0.05
        sim.forward(torque=[factor * s, 0.0, 0.0])
        level = c + (s - c) * np.exp(-((speed / seal.stribeck_speed) ** 2))
        assert sim.data.qfrc_constraint[0] == pytest.approx(-level, rel=1e-6)


@pytest.mark.parametrize("timestep", [1e-4, 1e-3])
def test_the_floating_arm_with_every_degree_of_freedom_moving_stays_finite(tmp_path: Path, timestep: float) -> None:
    """The floating arm at 6,000 m, every degree of freedom moving: it diverged within a
    millisecond even at a 0.1 ms step; now its joints stop relative to the hull."""
    sim = Simulation.from_file(arm_file(tmp_path), HYDRO, depth=6000.0, losses=uwml.JointLosses())
    sim.model.opt.timestep = timestep
    sim.data.qvel[:] = [0.2, -0.1, 0.3, 0.3, -0.2, 0.1, 0.3, -0.3, 0.05]
    positions = run(sim, 0.5)
    assert np.all(np.isfinite(positions)) and np.all(np.isfinite(sim.data.qvel))
    assert np.max(np.abs(sim.data.qvel[6:])) < 1e-3


@pytest.mark.parametrize("timestep", [1e-3, 2e-3, 5e-3])
def test_light_links_at_11000_m_in_a_20_m_s_current_stay_finite(tmp_path: Path, timestep: float) -> None:
    """Links a twentieth as heavy (lighter than the water they displace), the deepest ocean, a
    20 m/s current: it diverged at 5 ms; it stays finite, and the joints the drag cannot turn
    against the seal stay put."""
    sim = Simulation.from_file(
        arm_file(tmp_path, fixed=True, mass_scale=0.05), HYDRO, depth=11000.0, losses=uwml.JointLosses(), current=(20.0, 0.0, 0.0)
    )
    sim.model.opt.timestep = timestep
    sim.data.qvel[:] = [0.3, 0.3, 0.05]
    positions = run(sim, 1.0)
    assert np.all(np.isfinite(positions)) and np.all(np.isfinite(sim.data.qvel))


def test_simulation_conditions_are_read_only(tmp_path: Path) -> None:
    """``current``, ``depth``, ``water`` and the rest were used by ``environment()`` and ignored
    by ``step()`` when set after construction: now they cannot be set."""
    sim = Simulation.from_file(arm_file(tmp_path), HYDRO, depth=100.0, current=(0.1, 0.0, 0.0))
    for name, value in [
        ("current", (1.0, 0.0, 0.0)), ("depth", 3000.0), ("water", uwml.Water(1000.0)), ("temperature_c", 2.0),
        ("losses", None), ("current_acceleration", (0.0, 0.0, 1.0)), ("scheme", "lagged"), ("integrator", "rk4"),
        ("added_mass", "kirchhoff"), ("robot", None),
    ]:  # fmt: skip
        with pytest.raises(AttributeError):
            setattr(sim, name, value)
    sim.current[0] = 5.0  # a copy: changing it changes nothing
    assert sim.current[0] == 0.1 and sim.depth == 100.0
    with pytest.raises(ValueError, match="depth must be one number"):
        Simulation.from_file(arm_file(tmp_path), HYDRO, depth=[100.0, 200.0])
