"""What ``uwml.sim.mjx`` refuses, before anything is compiled (docs/batched.md, "Simulating with
MJX"): a model with contacts MJX cannot collide, parameters, states and actions of the wrong
shape, prescribed joints and motions that do not fit, an unknown payload body, a gravity that is
not the water's; and a reset that puts the prescribed joints on their motion (from samples, one
per environment, or a JAX function of time)."""

import numpy as np
import pytest
import uwml
import uwml.examples

jax = pytest.importorskip("jax")
pytest.importorskip("mujoco.mjx")
jax.config.update("jax_enable_x64", True)
import jax.numpy as jnp  # after the guard: needs jax
from uwml.robot.files import model_and_robot
from uwml.sim import mjx as umjx
from uwml.sim.prescribed import Trajectory

URDF, HYDRO = (uwml.examples.path("bluerov2", name) for name in ("bluerov2_arm.urdf", "bluerov2_arm.hydro.toml"))


@pytest.fixture(scope="module")
def description():
    return model_and_robot(URDF, HYDRO, None)


@pytest.fixture(scope="module")
def sim(description):
    return umjx.Simulation(*description)


def test_contacts_mjx_cannot_collide_are_refused(description):
    # The hull's box and the forearm's cylinder may touch: MJX has no box-cylinder collision.
    with pytest.raises(ValueError, match=r"MJX cannot simulate this model: .*collisions not implemented.*contacts=True"):
        umjx.Simulation(*description, contacts=True)


def test_the_model_must_be_the_robots(description):
    model, robot = description
    with pytest.raises(TypeError, match="mujoco.MjModel"):
        umjx.Simulation("bluerov2.urdf", robot)
    with pytest.raises(TypeError, match="uwml.Robot"):
        umjx.Simulation(model, "robot")
    with pytest.raises(ValueError, match="gravity"):
        umjx.Simulation(model, robot, water=uwml.Water(1000.0, 9.0))
    with pytest.raises(ValueError, match="added_mass"):
        umjx.Simulation(model, robot, added_mass="lagged")


def test_parameters_of_the_wrong_shape_are_refused(sim):
    segments = np.shape(sim.parameters().cd)[0]
    with pytest.raises(ValueError, match=rf"parameter cd must have shape \({segments}, 2\), got \(3,\)"):
        sim.parameters(cd=[1.0, 1.0, 1.0])
    with pytest.raises(ValueError, match=r"parameter current must have shape \(3,\) or \(5, 3\), got \(4, 3\)"):
        sim.parameters(5, current=np.zeros((4, 3)))
    with pytest.raises(TypeError, match="no parameter cd_scale"):
        sim.parameters(cd_scale=2.0)
    with pytest.raises(ValueError, match="batch must be a positive integer"):
        sim.parameters(0)
    batch = sim.parameters(3, drag_scale=[1.0, 2.0, 3.0], depth=50.0)
    assert np.shape(batch.drag_scale) == (3,) and np.shape(batch.cd) == (3, segments, 2)
    np.testing.assert_array_equal(batch.depth, [50.0, 50.0, 50.0])


def test_states_and_actions_of_the_wrong_shape_are_refused(sim):
    params = sim.parameters()
    with pytest.raises(ValueError, match=r"qpos must have shape \(9,\), got \(7,\)"):
        sim.reset(params, np.zeros(7))
    state = sim.reset(params)
    assert sim.action_size == 10
    with pytest.raises(ValueError, match=r"a flat action \(8 thruster commands, then 2 torques\) must have shape \(10,\), got \(9,\)"):
        sim.step(params, state, np.zeros(9))
    with pytest.raises(ValueError, match=r"action.thrusters must have shape \(8,\), got \(4,\)"):
        sim.step(params, state, umjx.Action(np.zeros(4), np.zeros(2)))
    with pytest.raises(ValueError, match=r"action.torque must have shape \(2,\)"):
        jax.jit(sim.step)(params, state, umjx.Action(np.zeros(8), np.zeros(3)))
    with pytest.raises(ValueError, match=r"parameter drag_scale must have shape \(\), got \(2,\)"):
        sim.step(params._replace(drag_scale=np.ones(2)), state, np.zeros(10))
    with pytest.raises(TypeError, match="Parameters"):
        sim.step((1.0,), state, np.zeros(10))


def test_prescribed_joints_and_motions_must_fit(description):
    model, robot = description
    t = np.linspace(0.0, 1.0, 11)
    one = Trajectory(t, np.sin(t))
    with pytest.raises(ValueError, match="no joint 'wrist'"):
        umjx.Simulation(model, robot, prescribed=["wrist"], motion=one)
    with pytest.raises(ValueError, match="each joint once"):
        umjx.Simulation(model, robot, prescribed=["elbow", 1], motion=one)
    with pytest.raises(ValueError, match="the motion is of 1 joints, 2 are prescribed"):
        umjx.Simulation(model, robot, prescribed=["shoulder", "elbow"], motion=one)
    with pytest.raises(ValueError, match="without prescribed joints"):
        umjx.Simulation(model, robot, motion=one)
    with pytest.raises(ValueError, match="no samples"):
        umjx.Simulation(model, robot, prescribed=["elbow"], motion=Trajectory.of(lambda t: (0, 0, 0), joints=1))
    with pytest.raises(ValueError, match="payload_body: no body named 'gripper'"):
        umjx.Simulation(model, robot, payload_body="gripper")
    sim = umjx.Simulation(model, robot, prescribed=["elbow"])
    with pytest.raises(ValueError, match="have no motion"):
        sim.reset(sim.parameters())
    with pytest.raises(ValueError, match=r"a batch of 2 motions for 3 environments"):
        sim.parameters(3, motion=umjx.spline(t, np.sin(t)[None, :, None].repeat(2, axis=0)))


def test_reset_puts_the_prescribed_joints_on_their_motions(description):
    """A batch of motions from samples, one per environment (a leading batch axis)."""
    model, robot = description
    t = np.linspace(0.0, 1.0, 11)
    angles = np.stack([0.1 + 0.2 * t, -0.3 + 0.1 * t**2], axis=-1)[None] * np.array([1.0, 2.0])[:, None, None]
    motions = umjx.spline(t, angles)
    assert np.shape(motions.knots) == (2, 11) and motions.joints == 2
    sim = umjx.Simulation(model, robot, prescribed=["shoulder", "elbow"])
    params = sim.parameters(2, motion=motions)
    states = jax.vmap(sim.reset)(params)
    q, qd = sim.joint_state(states)
    np.testing.assert_allclose(q, angles[:, 0, :], atol=1e-12)
    np.testing.assert_allclose(qd, [[0.2, 0.0], [0.4, 0.0]], atol=1e-9)


def test_reset_puts_a_joint_on_its_motion_as_a_function_of_time(description):
    """A motion in closed form, a JAX function of time (the same for every environment)."""
    model, robot = description

    def swing(t):
        return jnp.stack([0.6 * jnp.cos(4.0 * t)]), jnp.stack([-2.4 * jnp.sin(4.0 * t)]), jnp.stack([-9.6 * jnp.cos(4.0 * t)])

    sim = umjx.Simulation(model, robot, prescribed=["shoulder"], motion=swing)
    state = sim.reset(sim.parameters(), qvel=np.full(8, 0.1))
    q, qd = sim.joint_state(state)
    np.testing.assert_allclose(q, [0.6, 0.0], atol=1e-15)
    np.testing.assert_allclose(qd, [0.0, 0.1], atol=1e-15)

    def wrong(t):
        return jnp.zeros(2), jnp.zeros(2), jnp.zeros(2)

    with pytest.raises(ValueError, match=r"the prescribed motion's q must have shape \(1,\), got \(2,\)"):
        umjx.Simulation(model, robot, prescribed=["shoulder"], motion=wrong).reset(sim.parameters())
