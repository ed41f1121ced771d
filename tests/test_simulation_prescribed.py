"""Prescribed joint motion (docs/model.md section 12.4, ``Simulation.prescribe``): the joints
follow their trajectory exactly while the floating base responds through ``M + M_A``; in still
water without drag and gravity the whole system's momentum (the rigid bodies' and the water's
impulse, ``(M + M_A) q̇``) is conserved, linear and angular; a trajectory given by samples
interpolates, and bad input is refused."""

from pathlib import Path

import numpy as np
import pytest
import uwml

mujoco = pytest.importorskip("mujoco")

from test_simulation import weightless, without_drag
from uwml.sim.mujoco import Simulation
from uwml.sim.prescribed import SineTrajectory, Trajectory

DATA = Path(__file__).parent / "data"
AMPLITUDES, RATES = np.array([0.6, -0.5, 0.02]), np.array([2.0, 3.0, 4.0])


def waving(t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The arm's three joints waving from rest at 0 (shoulder, elbow [rad], gripper [m])."""
    return AMPLITUDES * np.sin(RATES * t), AMPLITUDES * RATES * np.cos(RATES * t), -AMPLITUDES * RATES**2 * np.sin(RATES * t)


def momentum(sim: Simulation) -> tuple[np.ndarray, np.ndarray]:
    """World linear momentum and angular momentum about the world origin of the bodies and the
    water: ``p = Tᵀ M q̇ + M_A x`` in uwml's coordinates ``x = (Rᵀ v_world, ω_body, q̇)``, ``T``
    MuJoCo's coordinates from uwml's."""
    m, d = sim.model, sim.data
    rigid = mujoco.MjData(m)
    rigid.qpos[:], rigid.qvel[:] = d.qpos, d.qvel
    mujoco.mj_forward(m, rigid)
    mass = np.zeros((m.nv, m.nv))
    mujoco.mj_fullM(m, rigid, mass)
    rotation = rigid.xmat[1].reshape(3, 3)
    qvel = rigid.qvel
    x = np.concatenate([rotation.T @ qvel[0:3], qvel[3:6], qvel[6:]])
    p_mujoco = mass @ qvel
    p = np.concatenate([rotation.T @ p_mujoco[0:3], p_mujoco[3:6], p_mujoco[6:]])
    p += sim.robot.added_mass_matrix(rigid.qpos[7:], water=sim.water) @ x
    linear = rotation @ p[0:3]
    return linear, rotation @ p[3:6] + np.cross(rigid.qpos[0:3], linear)


def arm_simulation(integrator: str) -> Simulation:
    model, robot = uwml.robot.files.model_and_robot(DATA / "arm.xml", DATA / "arm.hydro.toml")
    model = weightless(model)
    model.opt.timestep = 1e-3
    sim = Simulation(model, without_drag(robot), water=uwml.Water(1000.0, 0.0), integrator=integrator, added_mass="kirchhoff")
    sim.model.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_CONSTRAINT)
    return sim


@pytest.mark.parametrize("integrator", ["euler", "rk4"])
def test_the_arm_follows_its_motion_and_the_vehicle_keeps_the_momentum(integrator: str) -> None:
    sim = arm_simulation(integrator)
    sim.prescribe(["shoulder", "elbow", "gripper"], Trajectory.of(waving, joints=3))
    dofs = sim._joint_dofs
    start_linear, start_angular = momentum(sim)
    worst = 0.0
    scale = 1.0 + np.linalg.norm(start_linear) + np.linalg.norm(start_angular)
    for _ in range(1000):
        sim.step()
        q, qd, _ = waving(sim.data.time)
        np.testing.assert_array_equal(sim.data.qvel[dofs], qd)
        np.testing.assert_array_equal(sim.data.qpos[sim._joint_qpos], q)
        linear, angular = momentum(sim)
        worst = max(worst, np.linalg.norm(linear - start_linear) / scale, np.linalg.norm(angular - start_angular) / scale)
    # The vehicle answered (it moved), and the momentum stayed: to the integrator's accuracy.
    assert np.abs(sim.data.qvel[:6]).max() > 1e-3
    assert worst < (1e-6 if integrator == "rk4" else 1e-2), worst
    assert sim.prescribed_torque.shape == (3,) and np.all(np.isfinite(sim.prescribed_torque))


def test_a_trajectory_of_samples_interpolates_and_estimates_what_is_not_given() -> None:
    t = np.linspace(0.0, 2.0, 401)
    q = np.stack([np.sin(2.0 * t), 0.3 * t**3], axis=1)
    trajectory = Trajectory(t, q)
    for at in (0.0, 0.537, 1.99):
        position, velocity, acceleration = trajectory(at)
        np.testing.assert_allclose(position, [np.sin(2 * at), 0.3 * at**3], atol=1e-8)
        np.testing.assert_allclose(velocity, [2 * np.cos(2 * at), 0.9 * at**2], atol=1e-5)
        np.testing.assert_allclose(acceleration, [-4 * np.sin(2 * at), 1.8 * at], atol=2e-3)
    given = Trajectory(t, q, qd=np.stack([2 * np.cos(2 * t), 0.9 * t**2], axis=1))
    np.testing.assert_allclose(given(0.537)[1], [2 * np.cos(2 * 0.537), 0.9 * 0.537**2], atol=1e-9)
    with pytest.raises(ValueError, match=r"from t = 0 to 2 s, not at t = 2.5 s"):
        trajectory(2.5)


def test_a_clock_past_the_end_by_rounding_reads_the_end() -> None:
    """A simulation's clock sums its steps: 8,430 steps of 2 ms from 0.134635 s pass the end of a
    motion sampled up to 0.134635 + 8430 × 0.002 s by rounding (about 1e-11 s). That time reads the
    motion's end (not extrapolated); a time truly past it is refused, with digits that tell them
    apart."""
    clock = 0.134635
    for _ in range(8430):
        clock += 0.002
    grid = np.linspace(0.134635, 0.134635 + 8430 * 0.002, 60)
    motion = Trajectory(grid, np.sin(grid))
    assert clock > motion.end and clock - motion.end < motion.rounding() < 1e-7
    np.testing.assert_array_equal(motion(clock)[0], motion(motion.end)[0])
    with pytest.raises(ValueError, match=r"given from t = 0\.134635 to 16\.994635 s, not at t = 16\.99464"):
        motion(motion.end + 1e-5)


@pytest.mark.parametrize(
    "call, error, message",
    [
        (lambda sim: sim.prescribe(["wrist"], Trajectory.of(waving, joints=3)), ValueError, r"no joint 'wrist' in the robot"),
        (lambda sim: sim.prescribe(["shoulder", "shoulder"], Trajectory.of(waving, joints=2)), ValueError, "each prescribed joint once"),
        (
            lambda sim: sim.prescribe(["shoulder"], Trajectory.of(waving, joints=3)),
            ValueError,
            "the motion is of 3 joints, 1 are prescribed",
        ),
        (lambda sim: sim.prescribe(["shoulder"], waving), TypeError, "motion must be a uwml.sim.prescribed.Trajectory"),
        (lambda sim: Trajectory([0, 1, 1, 2], [0, 0, 0, 0]), ValueError, "strictly increasing"),
        (lambda sim: Trajectory(np.arange(5.0), np.zeros((5, 2)), qd=np.zeros((4, 2))), ValueError, r"qd must have shape \(5, 2\)"),
        (
            lambda sim: sim.prescribe([0], Trajectory.of(lambda t: (np.nan, 0.0, 0.0), joints=1)),
            ValueError,
            "q at t = 0 s must be 1 finite numbers",
        ),
    ],
)
def test_bad_prescriptions_are_refused(call, error: type, message: str) -> None:  # type: ignore[no-untyped-def]
    sim = arm_simulation("euler")
    with pytest.raises(error, match=message):
        call(sim)


@pytest.mark.parametrize("integrator", ["euler", "rk4"])
def test_a_motion_of_samples_is_imposed_natively_as_its_spline(integrator: str) -> None:
    """The coupling evaluates a sampled motion's cubics itself (``Trajectory.pieces``): the same
    simulation, to rounding, as the same spline evaluated by scipy through ``Trajectory.of``;
    the joints sit on the spline after every step."""
    t = np.linspace(0.0, 1.2, 241)
    q, _, _ = waving(t[:, None])
    sampled = Trajectory(t, q)
    native, called = arm_simulation(integrator), arm_simulation(integrator)
    native.prescribe(["shoulder", "elbow", "gripper"], sampled)
    called.prescribe(["shoulder", "elbow", "gripper"], Trajectory.of(sampled, joints=3))
    for _ in range(1000):
        native.step()
        called.step()
        position, velocity, _ = sampled(native.data.time)
        np.testing.assert_allclose(native.data.qpos[native._joint_qpos], position, rtol=0, atol=1e-14)
        np.testing.assert_allclose(native.data.qvel[native._joint_dofs], velocity, rtol=0, atol=1e-12)
    np.testing.assert_allclose(native.data.qpos, called.data.qpos, rtol=0, atol=1e-12)
    np.testing.assert_allclose(native.data.qvel, called.data.qvel, rtol=0, atol=1e-10)
    np.testing.assert_allclose(native.prescribed_torque, called.prescribed_torque, rtol=1e-9, atol=1e-12)
    assert np.abs(native.data.qvel[:6]).max() > 1e-3
    native.prescribe(["shoulder"], None)
    assert native.prescribed_torque.shape == (0,)


def test_the_joint_count_of_a_motion_function_is_a_keyword() -> None:
    """``Trajectory.of(f, 2)`` read like a duration of 2 s: the count must be named."""
    with pytest.raises(TypeError):
        Trajectory.of(waving, 3)  # type: ignore[misc]
    assert Trajectory.of(waving, joints=3).joints == 3


def test_sine_trajectory_derivatives_are_exact() -> None:
    """q̇ and q̈ against central differences of q (step 1e-4 s: truncation ~1e-8 relative)."""
    trajectory = SineTrajectory([0.5, 0.3], period=1.5, offsets=[0.1, -0.2], harmonics=[1, 3], phases=[0.0, 1.0])
    t, h = np.linspace(0.0, 3.0, 31), 1e-4
    q, qd, qdd = trajectory.joint_states(t)
    qp, qm = trajectory.joint_states(t + h)[0], trajectory.joint_states(t - h)[0]
    np.testing.assert_allclose(qd, (qp - qm) / (2 * h), atol=1e-6)
    np.testing.assert_allclose(qdd, (qp - 2 * q + qm) / h**2, atol=1e-4)
    np.testing.assert_allclose(q[0], [0.1, -0.2 + 0.3 * np.sin(1.0)], rtol=1e-15)
    with pytest.raises(ValueError, match="period must be finite and > 0"):
        SineTrajectory([0.1], period=0.0)
