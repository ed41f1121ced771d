"""``uwml.sim.mjx`` (docs/batched.md, "Simulating with MJX") against the CPU simulation,
:class:`uwml.sim.mujoco.Simulation`, on the BlueROV2 example (a floating vehicle with a 2-joint
arm and 8 thrusters) over 1 s of Euler steps at the example's 2 ms, in float64: the vehicle's
pose and the joints within 1e-6 (measured: about 1e-15) in a current with thrusters and motor
torques driving the shoulder into its limit, with joint losses (the CPU simulation's noslip
solver off: MJX has none), with the arm on a prescribed motion from samples, another in each
environment of a batch. Then a batch: environment i of a vmapped batch equals environment i stepped
alone, and each environment's parameters act as they should (more drag, a slower vehicle; a
payload, a heavier one; a current, a drift); the step compiles once for any parameters. Contacts
are off in both (open water)."""

import numpy as np
import pytest
import uwml
import uwml.examples

jax = pytest.importorskip("jax")
pytest.importorskip("mujoco.mjx")
jax.config.update("jax_enable_x64", True)
import mujoco  # after the guard: needs mujoco
from uwml.robot.files import model_and_robot
from uwml.sim import mjx as umjx
from uwml.sim.mujoco import Simulation as CpuSimulation
from uwml.sim.prescribed import Trajectory

URDF, HYDRO = (uwml.examples.path("bluerov2", name) for name in ("bluerov2_arm.urdf", "bluerov2_arm.hydro.toml"))
#: The agreement asked of MJX with the CPU simulation: positions [m, rad] and speeds.
TOLERANCE = 1e-6
STEPS = 500  # 1 s at the example's 2 ms
CURRENT = np.array([0.3, -0.1, 0.05])
#: Thruster commands (surge on the horizontal four, a little heave and roll) and joint torques.
COMMANDS = np.array([0.5, 0.5, 0.5, 0.5, 0.2, -0.2, 0.3, 0.0])
TORQUE = np.array([0.3, -0.2])
#: A light seal and oil drag (so that the torques above turn the joints) with the default drive.
LOSSES = uwml.JointLosses(
    oil=uwml.OilDrag(k_oil=1e-5), seal=uwml.Seal(c0=0.05, c1_per_mpa=0.01, s0=0.075, s1_per_mpa=0.02, d0=0.01, d1_per_mpa=0.001)
)
DEPTH = 100.0


@pytest.fixture(scope="module")
def description():
    model, robot = model_and_robot(URDF, HYDRO, None)
    model.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_CONTACT)  # open water, as the MJX simulation
    return model, robot


def start(model):
    """A start with every degree of freedom moving: the arm bent, the vehicle drifting and turning."""
    qpos = np.array(model.qpos0)
    qpos[7:] = (0.3, -0.2)
    return qpos, np.array([0.2, 0.0, 0.1, 0.05, -0.1, 0.2, 0.5, -0.3])


@pytest.fixture(scope="module")
def driven(description):
    """The MJX simulation with the current, thrusters, joint losses at depth; its jitted step."""
    model, robot = description
    sim = umjx.Simulation(model, robot, current=CURRENT, losses=LOSSES, depth=DEPTH, payload_body="forearm")
    return sim, jax.jit(sim.step)


def run_cpu(cpu, steps=STEPS, commands=None, torque=None):
    if commands is not None:
        cpu.command_thrusters(commands)
    for _ in range(steps):
        cpu.step(torque=torque)
    return np.array(cpu.data.qpos), np.array(cpu.data.qvel)


def run_mjx(step, params, state, action, steps=STEPS):
    for _ in range(steps):
        state = step(params, state, action)
    return state


def assert_agree(state, qpos, qvel):
    assert np.max(np.abs(np.asarray(state.data.qpos) - qpos)) <= TOLERANCE
    assert np.max(np.abs(np.asarray(state.data.qvel) - qvel)) <= TOLERANCE
    assert float(state.data.time) == pytest.approx(STEPS * 0.002, abs=1e-12)


def test_floating_in_a_current_with_thrusters_and_joint_losses(description, driven):
    model, robot = description
    sim, step = driven
    cpu = CpuSimulation(model, robot, current=CURRENT, losses=LOSSES, depth=DEPTH)
    cpu.model.opt.noslip_iterations = 0  # MJX has no noslip solver (docs/batched.md)
    qpos, qvel = start(model)
    cpu.data.qpos[:], cpu.data.qvel[:] = qpos, qvel
    params = sim.parameters()
    state = run_mjx(step, params, sim.reset(params, qpos, qvel), umjx.Action(COMMANDS, TORQUE))
    expected = run_cpu(cpu, commands=COMMANDS, torque=TORQUE)
    assert_agree(state, *expected)
    # The motion is not trivial: the vehicle travels, the shoulder reaches its limit (1.5 rad),
    # the elbow turns against its seal.
    assert np.linalg.norm(expected[0][:3] - qpos[:3]) > 0.2
    assert abs(expected[0][7]) > 1.45 and abs(expected[0][8] - qpos[8]) > 0.3
    np.testing.assert_allclose(np.asarray(state.thrust), cpu.thrust, rtol=0, atol=1e-12)
    position, quaternion = sim.base_pose(state)
    np.testing.assert_allclose(np.concatenate([position, quaternion]), expected[0][:7], atol=TOLERANCE)
    q, qd = sim.joint_state(state)
    np.testing.assert_allclose(np.concatenate([q, qd]), np.concatenate([expected[0][7:], expected[1][6:]]), atol=TOLERANCE)


def test_prescribed_arm_motions_from_samples_one_per_environment(description):
    """Both joints on a motion from samples, another in each of two environments of a vmapped
    batch (the CPU simulation's Trajectory, its cubics): the vehicle responds to the arm through
    M + M_A, and the imposing torques agree."""
    model, robot = description
    t = np.linspace(0.0, 1.2, 61)
    angles = np.stack(
        [np.stack([0.8 * np.sin(2 * np.pi * t), 0.5 * np.sin(3.0 * t)], axis=1), np.stack([0.4 * np.cos(5.0 * t), -0.7 * t], axis=1)]
    )
    sim = umjx.Simulation(model, robot, current=CURRENT, prescribed=["shoulder", "elbow"])
    params = sim.parameters(2, motion=umjx.spline(t, angles))
    states = jax.vmap(sim.reset)(params)
    step = jax.jit(jax.vmap(sim.step, in_axes=(0, 0, None)))
    states = run_mjx(step, params, states, np.zeros(sim.action_size))
    for env in range(2):
        cpu = CpuSimulation(model, robot, current=CURRENT)
        cpu.prescribe(["shoulder", "elbow"], Trajectory(t, angles[env]))
        alone = jax.tree_util.tree_map(lambda x, env=env: x[env], states)
        assert_agree(alone, *run_cpu(cpu))
        np.testing.assert_allclose(np.asarray(alone.prescribed_torque), cpu.prescribed_torque, rtol=0, atol=1e-9)
        assert np.max(np.abs(cpu.data.qpos[3:7] - (1, 0, 0, 0))) > 0.01  # the arm turned the vehicle


def test_a_batch_each_with_its_parameters(description, driven):
    """Four environments in one vmapped step: the example's, with twice the drag, a 2 kg payload
    in the gripper, a current of 0.5 m/s across. Each equals its own run alone; more drag makes
    the vehicle slower, the payload sinks it, the current carries it along."""
    model, _ = description
    sim, step = driven
    batch = 4
    current = np.tile(CURRENT, (batch, 1))
    current[3] = (0.0, 0.5, 0.0)
    params = sim.parameters(batch, drag_scale=[1.0, 2.0, 1.0, 1.0], payload=[0.0, 0.0, 2.0, 0.0], current=current)
    qpos, qvel = start(model)
    states = jax.vmap(sim.reset, in_axes=(0, None, None))(params, qpos, qvel)
    batched = jax.jit(jax.vmap(step, in_axes=(0, 0, None)))
    action = umjx.Action(COMMANDS, TORQUE)
    steps = 250
    states = run_mjx(batched, params, states, action, steps)
    alone = sim.parameters(drag_scale=2.0)
    single = run_mjx(step, alone, sim.reset(alone, qpos, qvel), action, steps)
    for name in ("qpos", "qvel"):
        np.testing.assert_allclose(np.asarray(getattr(states.data, name))[1], np.asarray(getattr(single.data, name)), rtol=0, atol=1e-12)
    position, _ = sim.base_pose(states)
    velocity = np.asarray(states.data.qvel)[:, :3]
    speed = np.linalg.norm(velocity, axis=1)
    assert speed[1] < 0.9 * speed[0]  # more drag, slower
    assert position[2, 2] < position[0, 2] - 0.01  # the payload sinks the vehicle
    assert position[3, 1] > position[0, 1] + 0.05  # carried across by the current
    # The step compiled once for every environment's parameters, and once alone.
    assert batched._cache_size() == 1
    assert step._cache_size() == 1
