"""uwml inside MuJoCo (uwml.sim.mujoco.Simulation): the added mass in the mass matrix, checked
against closed forms, an independent integration with scipy, and the lagged scheme that
simulators use (which diverges on a light link)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import uwml

mujoco = pytest.importorskip("mujoco")
from scipy.integrate import solve_ivp
from uwml.sim.mujoco import Simulation

RHO, G = 1000.0, 9.81
D, L = 0.1, 1.0  # the sinking log: a horizontal cylinder
LOG_VOLUME = math.pi * D**2 / 4 * L
TAG = 0.001  # the mass of the log's jointed tag (a robot needs one joint)


def log_model(mass: float, floor: bool = False) -> object:
    """A horizontal cylinder on a free joint (turned 0.3 rad about z), with a massless-looking
    tag on a hinge through its centre (no geometry, COM on the axis: it never moves)."""
    scenery = '<geom type="plane" size="5 5 0.1" pos="0 0 -0.5"/>' if floor else ""
    return mujoco.MjModel.from_xml_string(
        f"""<mujoco><compiler angle="radian"/><option timestep="0.002"/><worldbody>{scenery}
        <body name="log" euler="0 0 0.3"><freejoint/>
          <inertial pos="0 0 0" mass="{mass!r}" diaginertia="0.01 0.1 0.1"/>
          <geom type="cylinder" size="{D / 2} {L / 2}" euler="0 1.5707963267948966 0"/>
          <body name="tag"><joint name="spin" type="hinge" axis="1 0 0"/>
            <inertial pos="0 0 0" mass="{TAG}" diaginertia="1e-6 1e-6 1e-6"/></body>
        </body></worldbody></mujoco>"""
    )


@pytest.mark.parametrize("ratio", [2.0, 0.5])
@pytest.mark.parametrize("integrator", ["euler", "rk4"])
def test_a_released_log_sinks_or_rises_as_the_closed_form(ratio: float, integrator: str) -> None:
    """(m + m_A) v̇ = −(m − ρV) g − ½ ρ Cd D L |v| v with m_A = ρ Cm V (Cm = 1, Cd = 1.2: the
    circular defaults): v(t) = −v_t tanh(a t / v_t), v_t = √(2 (m − ρV) g / (ρ Cd D L)),
    a = (m − ρV) g / (m + m_A) (for m < ρV, the same upwards)."""
    mass = ratio * RHO * LOG_VOLUME
    sim = Simulation(log_model(mass), integrator=integrator)
    for _ in range(1000):
        sim.step()
    total = mass + TAG
    net = (total - RHO * LOG_VOLUME) * G
    terminal = math.sqrt(2.0 * abs(net) / (RHO * 1.2 * D * L))
    expected = -math.copysign(terminal * math.tanh(abs(net) / (total + RHO * LOG_VOLUME) * sim.data.time / terminal), net)
    tolerance = 1e-9 if integrator == "rk4" else 1e-3
    assert sim.data.qvel[2] == pytest.approx(expected, rel=tolerance)
    # No sideways motion and no turning: the forces are vertical and through the centre.
    assert np.max(np.abs(sim.data.qvel[[0, 1, 3, 4, 5]])) < 1e-9
    assert sim.data.time == pytest.approx(2.0, rel=1e-12)


def pendulum(cm: float = 1.0) -> tuple[object, float]:
    """A light hollow rod on a hinge (axis y) hanging along −z: 0.2 kg against the ~3.9 kg of
    water its cylinder drags along (M_A/I ≈ 20 about the hinge). Returns the model and its
    rigid inertia about the hinge."""
    mass, length = 0.2, 0.5
    inertia = mass * length**2 / 12.0
    model = mujoco.MjModel.from_xml_string(
        f"""<mujoco><option timestep="0.001"><flag contact="disable"/></option><worldbody>
        <body name="stand"><geom type="box" size="0.05 0.05 0.05" pos="0 0 0.1"/>
          <body name="rod"><joint name="hinge" type="hinge" axis="0 1 0"/>
            <inertial pos="0 0 -0.25" mass="{mass}" diaginertia="{inertia} {inertia} 1e-5"/>
            <geom type="cylinder" size="{D / 2} {length / 2}" pos="0 0 -0.25"/>
          </body></body></worldbody></mujoco>"""
    )
    return model, inertia + mass * 0.25**2


def test_a_light_link_is_stable_and_matches_solve_ivp() -> None:
    """The same equations integrated by scipy (RK45, tight tolerances) from uwml's forces and
    added-mass matrix and the rod's rigid inertia: (I + M_A(q)) q̈ = τ_env,0(q, q̇) + τ_gravity."""
    model, rigid = pendulum()
    sim = Simulation(model, integrator="rk4")
    robot = sim.robot
    added = robot.added_mass_matrix([0.0])[6, 6]
    assert added > 5.0 * rigid  # lighter than the water it drags along
    sim.data.qpos[0], sim.data.qvel[0] = 2.5, 0.0

    def rate(_t: float, state: np.ndarray) -> list[float]:
        q, qd = state[:1], state[1:]
        env = robot.environment(q, qd, [0.0])
        m_a = robot.added_mass_matrix(q)[6, 6]
        return [qd[0], float(env.total[0] + env.gravity[0]) / (rigid + m_a)]

    times = np.linspace(0.0, 3.0, 31)
    reference = solve_ivp(rate, (0.0, 3.0), [2.5, 0.0], t_eval=times, rtol=1e-11, atol=1e-12, method="DOP853")
    simulated = []
    for k in range(3001):
        if k % 100 == 0:
            simulated.append((sim.data.qpos[0], sim.data.qvel[0]))
        if k < 3000:
            sim.step()
    simulated_array = np.array(simulated)
    np.testing.assert_allclose(simulated_array[:, 0], reference.y[0], atol=1e-6)
    np.testing.assert_allclose(simulated_array[:, 1], reference.y[1], atol=1e-6)
    # It moves: the buoyant rod swings up through the inverted position (π) and back.
    assert np.ptp(simulated_array[:, 0]) > 0.5 and np.max(simulated_array[:, 0]) > math.pi and np.max(np.abs(simulated_array[:, 1])) < 20.0


def test_the_lagged_added_mass_force_diverges_where_the_matrix_does_not() -> None:
    model, _ = pendulum()
    lagged, matrix = Simulation(model, scheme="lagged"), Simulation(model)
    for sim in (lagged, matrix):
        sim.data.qpos[0] = 0.5
    peak = 0.0
    with pytest.raises(FloatingPointError, match=r"the simulation diverged at t = 0\.\d+ s"), np.errstate(all="ignore"):
        # The previous step's acceleration, fed back, grows about 20 times a step.
        for _ in range(200):
            lagged.step()
            peak = max(peak, abs(lagged.data.qvel[0]))
    assert peak > 1e6
    for _ in range(2000):
        matrix.step()
        assert abs(matrix.data.qvel[0]) < 10.0


def test_a_body_settles_on_the_seabed() -> None:
    """Contacts work with the added mass in the mass matrix: a heavy log sinks onto the floor
    (0.5 m below) and rests there, its centre one radius above it."""
    sim = Simulation(log_model(3.0 * RHO * LOG_VOLUME, floor=True))
    for _ in range(2500):
        sim.step()
    assert sim.data.qpos[2] == pytest.approx(-0.5 + D / 2, abs=2e-3)
    assert np.max(np.abs(sim.data.qvel[:6])) < 1e-2


def test_bad_inputs() -> None:
    model = log_model(10.0)
    with pytest.raises(ValueError, match=r"gravity .* must be \(0, 0, -9.81\)"):
        bad = log_model(10.0)
        bad.opt.gravity[:] = (0.0, 0.0, -9.7)  # type: ignore[attr-defined]
        Simulation(bad)
    with pytest.raises(ValueError, match="scheme must be one of matrix, lagged"):
        Simulation(model, scheme="implicit")
    with pytest.raises(ValueError, match="integrator must be one of euler, rk4"):
        Simulation(model, integrator="rk45")
    with pytest.raises(ValueError, match="depth must be finite and from 0 to 11000 m"):
        Simulation(model, depth=-1.0)
    with pytest.raises(ValueError, match="depth is 12000.0 m"):
        Simulation(model, depth=12000.0)
    with pytest.raises(ValueError, match="above absolute zero"):
        Simulation(model, temperature_c=-300.0)
    with pytest.raises(ValueError, match="current must be 3 finite numbers"):
        Simulation(model, current=(0.0, math.nan, 0.0))
    with pytest.raises(TypeError, match="model must be a mujoco.MjModel"):
        Simulation("log.xml")
    other, _ = pendulum()
    with pytest.raises(ValueError, match="is not the robot's joint 0"):
        Simulation(
            other,
            robot=Simulation(model).robot.__class__([uwml.Joint((0, 0, 0), (1, 0, 0), kind="prismatic")], [uwml.Link(1.0, (0, 0, 0), 0.0)]),
        )
    ball = mujoco.MjModel.from_xml_string(
        """<mujoco><worldbody><body name="a"><geom type="sphere" size="0.1"/>
        <body name="b"><joint type="ball"/><geom type="sphere" size="0.1" pos="0 0 -0.3"/></body>
        <body name="c"><joint type="hinge"/><geom type="sphere" size="0.1" pos="0 0 -0.3"/></body></body></worldbody></mujoco>"""
    )
    with pytest.raises(ValueError, match="ball joint"):
        Simulation(ball, robot=Simulation(pendulum()[0]).robot)
    sim = Simulation(model)
    with pytest.raises(ValueError, match="torque must be 1 finite numbers"):
        sim.step(torque=[1.0, 2.0])
    with pytest.raises(ValueError, match="torque must be 1 finite numbers"):
        sim.step(torque=np.array([np.nan], dtype=np.float32))
    with pytest.raises(AttributeError):
        sim.data = mujoco.MjData(sim.model)  # type: ignore[misc]  # the simulation keeps views of its data
    # The caller's model keeps its fluid settings; the simulation's has MuJoCo's fluid model off.
    model.opt.density = 1000.0  # type: ignore[attr-defined]
    assert Simulation(model).model.opt.density == 0.0 and model.opt.density == 1000.0  # type: ignore[attr-defined]


@pytest.mark.parametrize("scheme", ["matrix", "lagged"])
def test_each_step_applies_the_public_apis_forces_and_added_mass(scheme: str) -> None:
    """The per-step arithmetic is native (``MujocoCoupling``); what it writes into MuJoCo is
    held here against the public path (``Simulation.environment``: ``Robot.environment`` and
    ``Robot.added_mass_matrix``) mapped by hand: on the floating arm at depth with joint losses
    in a current, ``qfrc_applied = T (τ_env,0 − [0, τ_losses] + [0, τ_motor])`` and MuJoCo's inertia grows by
    ``T M_A Tᵀ``, ``T = diag(R, I, I)``; lagged: no growth, and ``− M_A a_previous`` in the forces,
    ``a_previous`` the last step's ``(Rᵀ v̇_world − ω × v, ω̇, q̈)``."""
    from pathlib import Path

    data = Path(__file__).parent / "data"
    current = (0.3, -0.1, 0.05)
    sim = Simulation.from_file(
        data / "arm.xml", data / "arm.hydro.toml", depth=3000.0, temperature_c=4.0, losses=uwml.JointLosses(),
        current=current, scheme=scheme, added_mass="kirchhoff",
    )  # fmt: skip
    model, d = sim.model, sim.data
    model.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_CONSTRAINT)  # type: ignore[attr-defined]
    rng = np.random.default_rng(11)
    quaternion = rng.normal(size=4)
    d.qpos[3:7] = quaternion / np.linalg.norm(quaternion)
    d.qvel[:] = rng.uniform(-0.5, 0.5, model.nv)
    n = sim.robot.n_joints
    motor = rng.uniform(-2.0, 2.0, n)
    before = d.qvel.copy()
    sim.step(torque=motor)  # a step first: the lagged scheme then has an acceleration to lag
    rotation = d.xmat[1].reshape(3, 3)  # the step's forward pass (mj_Euler moves qpos and qvel only)
    w, v = before[3:6], rotation.T @ before[0:3]
    previous = np.concatenate([rotation.T @ d.qacc[0:3] - np.cross(w, v), d.qacc[3:]])
    mujoco.mj_step1(model, d)  # kinematics of the new state (d.xmat), as forward's first stage
    rotation = d.xmat[1].reshape(3, 3)
    forces, added_mass = sim.environment()
    sim.forward(torque=np.float32(1.0) * motor.astype(np.float32))  # any float array is taken
    turn = np.eye(6 + n)
    turn[:3, :3] = rotation
    # The joint losses are MuJoCo's friction and damping (tests/test_simulation_losses.py), not
    # applied forces: environment() returns them, qfrc_applied holds the rest.
    pressure = uwml.reference.hydrostatic_pressure_mpa(3000.0, sim.water.density, sim.water.gravity)
    loss = uwml.JointLosses().torques(d.qvel[6:], pressure, 4.0)
    expected = forces - np.concatenate([np.zeros(6), loss.visc + loss.seal]) + np.concatenate([np.zeros(6), motor.astype(np.float32)])
    if scheme == "lagged":
        expected = expected - added_mass @ previous
    np.testing.assert_allclose(d.qfrc_applied, turn @ expected, rtol=1e-12, atol=1e-12 * np.max(np.abs(expected)))
    with_added, rigid = np.zeros((model.nv, model.nv)), np.zeros((model.nv, model.nv))
    mujoco.mj_fullM(model, d, with_added)
    bare = mujoco.MjData(model)
    bare.qpos[:] = d.qpos
    mujoco.mj_forward(model, bare)
    mujoco.mj_fullM(model, bare, rigid)
    grown = turn @ added_mass @ turn.T if scheme == "matrix" else np.zeros_like(rigid)
    np.testing.assert_allclose(with_added - rigid, grown, rtol=0, atol=1e-12 * np.max(np.abs(added_mass)))
    assert np.max(np.abs(added_mass)) > 1.0 and np.max(np.abs(forces[6:])) > 1e-2


@pytest.mark.parametrize("file, hydro", [("arm.xml", "arm.hydro.toml"), ("hexapod.xml", None)])
def test_the_forward_pass_solves_rigid_plus_environment_on_a_floating_base(file: str, hydro: str | None) -> None:
    """At a random state of a free-floating robot (base turned and moving, joints moving, in a
    current), MuJoCo's accelerations with uwml inside satisfy M(q) q̈ + bias(q, q̇) = Sᵀ τ_env
    with τ_env uwml's full environment (drag, added mass at those accelerations, buoyancy,
    Froude-Krylov) evaluated directly, ν̇ = Rᵀ v̇_world − ω × v, and M, bias MuJoCo's rigid body
    alone: the split τ_env,0 − M_A q̈ and the map between the coordinates are exact."""
    from pathlib import Path

    data = Path(__file__).parent / "data"
    current = (0.3, -0.1, 0.05)
    sim = Simulation.from_file(
        data / file, None if hydro is None else data / hydro, current=current, current_acceleration=(0.02, 0.0, -0.01)
    )
    model = sim.model
    model.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_CONSTRAINT)  # type: ignore[attr-defined]  # no contacts, no limits
    rng = np.random.default_rng(3)
    quaternion = rng.normal(size=4)
    sim.data.qpos[3:7] = quaternion / np.linalg.norm(quaternion)
    sim.data.qpos[7:] = rng.uniform(-0.3, 0.3, model.nq - 7) * np.where(model.jnt_type[1:] == 2, 0.05, 1.0)  # type: ignore[attr-defined]
    sim.data.qvel[:] = rng.uniform(-0.5, 0.5, model.nv)
    sim.forward()
    qacc = sim.data.qacc.copy()
    rigid = mujoco.MjData(sim.model)
    rigid.qpos[:], rigid.qvel[:] = sim.data.qpos, sim.data.qvel
    mujoco.mj_forward(sim.model, rigid)
    mass = np.zeros((model.nv, model.nv))
    mujoco.mj_fullM(sim.model, rigid, mass)
    assert rigid.nefc == 0  # no constraint acts
    rotation = rigid.xmat[1].reshape(3, 3)
    velocity, angular = rotation.T @ rigid.qvel[0:3], rigid.qvel[3:6]
    motion = uwml.BaseMotion(
        orientation=rigid.xquat[1],
        velocity=velocity,
        angular_velocity=angular,
        acceleration=rotation.T @ qacc[0:3] - np.cross(angular, velocity),
        angular_acceleration=qacc[3:6],
    )
    env = sim.robot.environment(
        rigid.qpos[7:], rigid.qvel[6:], qacc[6:], base_motion=motion, current=current, current_acceleration=(0.02, 0.0, -0.01)
    )
    generalized = np.concatenate([rotation @ env.base.total[:3], env.base.total[3:], env.total])
    lhs = mass @ qacc + rigid.qfrc_bias
    np.testing.assert_allclose(lhs, generalized, rtol=1e-9, atol=1e-9 * float(np.max(np.abs(generalized))))
    assert np.max(np.abs(env.added_mass)) > 1e-3 * np.max(np.abs(env.total))  # the added mass matters here


def test_the_tours_simulation_example_runs(monkeypatch: pytest.MonkeyPatch) -> None:
    """The tour's "Simulating in water" (docs/tour.md): run as written, from the repository's root (examples/)."""
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    section = (root / "docs" / "tour.md").read_text(encoding="utf-8").split("## Simulating in water", 1)[1]
    code = section.split("```python\n", 1)[1].split("```", 1)[0]
    monkeypatch.chdir(root)
    namespace: dict = {}
    exec(compile(code, "docs/tour.md", "exec"), namespace)  # noqa: S102 - the tour's own example
    sim = namespace["sim"]
    assert sim.data.time == pytest.approx(1000 * sim.model.opt.timestep) and sim.depth == 1000.0
    assert np.all(np.isfinite(sim.data.qvel)) and abs(sim.data.qvel[0]) > 1e-3  # the current pushes the hull


def without_drag(robot: uwml.Robot) -> uwml.Robot:
    """The same robot with every segment's Cd zero (its Cm kept)."""
    import dataclasses

    def strip(link: uwml.Link) -> uwml.Link:
        segments = [
            dataclasses.replace(s, cd=0.0, cm=s.cm[0]) if s.section == "circular" else dataclasses.replace(s, cd=(0.0, 0.0))  # type: ignore[index]
            for s in link.segments
        ]
        return uwml.Link(link.mass, link.com, link.volume, cob=link.cob, segments=segments, name=link.name)

    base = None if robot.base is None else strip(robot.base)
    return uwml.Robot(robot.joints, [strip(link) for link in robot.links], base=base, water=robot.water)


def weightless(model: object) -> object:
    model.opt.gravity[:] = 0.0  # type: ignore[attr-defined]
    return model


def energy(sim: Simulation) -> float:
    """``T_rigid + T_A`` (no gravity: no potential): ½ q̇ᵀ M q̇ from MuJoCo's rigid inertia, and
    ½ xᵀ M_A x with x = (Rᵀ v_world, ω_body, q̇)."""
    rigid = mujoco.MjData(sim.model)
    rigid.qpos[:], rigid.qvel[:] = sim.data.qpos, sim.data.qvel
    mujoco.mj_forward(sim.model, rigid)
    mass = np.zeros((sim.model.nv, sim.model.nv))
    mujoco.mj_fullM(sim.model, rigid, mass)
    qvel = rigid.qvel
    rotation = rigid.xmat[1].reshape(3, 3)
    x = np.concatenate([rotation.T @ qvel[0:3], qvel[3:6], qvel[6:]])
    added = sim.robot.added_mass_matrix(rigid.qpos[7:], water=sim.water)
    return 0.5 * float(qvel @ mass @ qvel) + 0.5 * float(x @ added @ x)


def test_kirchhoff_conserves_the_energy_and_drag_only_dissipates_it() -> None:
    """Drag and losses off, still water, no gravity (so no potential), no motor torque: the arm
    on its free hull, set spinning, keeps T_rigid + T_A to the RK4 integrator's accuracy with
    Kirchhoff's added mass and not with Morison's; with its drag on, the energy only falls."""
    from pathlib import Path

    from uwml.robot.files import model_and_robot

    data = Path(__file__).parent / "data"
    model, robot = model_and_robot(data / "arm.xml", data / "arm.hydro.toml")
    model = weightless(model)
    water = uwml.Water(1000.0, 0.0)
    rng = np.random.default_rng(4)
    start = rng.uniform(-0.6, 0.6, model.nv)  # type: ignore[attr-defined]
    model.opt.timestep = 1e-3  # type: ignore[attr-defined]

    def drift(robot: uwml.Robot, step: float, **kwargs: str) -> float:
        model.opt.timestep = step  # type: ignore[attr-defined]
        sim = Simulation(model, robot, water=water, integrator="rk4", **kwargs)
        sim.model.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_CONSTRAINT)  # type: ignore[attr-defined]
        sim.data.qvel[:] = start
        first, worst = energy(sim), 0.0
        while sim.data.time < 1.5 - 1e-9:
            sim.step()
            worst = max(worst, abs(energy(sim) - first) / first)
        return worst

    coarse, fine = drift(without_drag(robot), 1e-3, added_mass="kirchhoff"), drift(without_drag(robot), 5e-4, added_mass="kirchhoff")
    morison = drift(without_drag(robot), 1e-3)
    # Conserved to the integrator's accuracy: the drift falls with the step (about 4× per halving:
    # RK4 on body-frame angular velocities averaged through quaternions is second order).
    assert coarse < 1e-7 and fine < coarse / 3.0, (coarse, fine)
    assert morison > 1e-2, morison
    model.opt.timestep = 1e-3  # type: ignore[attr-defined]
    sim = Simulation(model, robot, water=water, integrator="rk4", added_mass="kirchhoff")
    sim.model.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_CONSTRAINT)  # type: ignore[attr-defined]
    sim.data.qvel[:] = start
    values = [energy(sim)]
    for _ in range(1500):
        sim.step()
        values.append(energy(sim))
    assert np.all(np.diff(values) <= 1e-12 * values[0]) and values[-1] < 0.9 * values[0]


def test_morison_energy_rate_is_the_documented_integral() -> None:
    """With Morison's added mass (drag off, still water, no gravity) the energy of a spinning,
    moving log changes at Σ_k ∫ ρ Cm A v_k (ṅ_k·v) ds (docs/simulation.md, "Energy-consistent
    added mass"), computed here by Gauss-Legendre quadrature from the log's state; dE/dt by
    central differences of the energy along the RK4 trajectory."""
    model = weightless(log_model(1.5 * RHO * LOG_VOLUME))
    robot = without_drag(uwml.Robot.from_mujoco(model))
    sim = Simulation(model, robot, water=uwml.Water(1000.0, 0.0), integrator="rk4")
    sim.data.qvel[:6] = (0.3, -0.2, 0.4, 0.5, -0.7, 0.9)  # linear (world), angular (body)
    h = sim.model.opt.timestep  # type: ignore[attr-defined]
    energies, rates = [], []
    nodes, weights = np.polynomial.legendre.leggauss(6)
    area = math.pi * D**2 / 4
    for _ in range(400):
        mujoco.mj_forward(sim.model, sim.data)
        rotation = sim.data.xmat[1].reshape(3, 3)
        omega = rotation @ sim.data.qvel[3:6]
        u = rotation @ np.array([1.0, 0.0, 0.0])
        normals = [rotation @ np.array([0.0, 1.0, 0.0]), rotation @ np.array([0.0, 0.0, 1.0])]
        rate = 0.0
        for s, w in zip(nodes * L / 2, weights * L / 2, strict=True):
            v = sim.data.qvel[0:3] + np.cross(omega, s * u)
            rate += w * sum(RHO * area * (n @ v) * (np.cross(omega, n) @ v) for n in normals)
        rates.append(rate)
        energies.append(energy(sim))
        sim.step()
    measured = (np.array(energies[2:]) - np.array(energies[:-2])) / (2 * h)
    expected = np.array(rates[1:-1])
    assert np.max(np.abs(expected)) > 1e-2
    np.testing.assert_allclose(measured, expected, atol=1e-5 * np.max(np.abs(expected)))


def test_mjcf_of_a_robot() -> None:
    """uwml.sim.mujoco.mjcf_of: bodies, joints and masses of the robot; a link's inertia that of its
    mass spread over its segments' solids (here by hand: one box, one cylinder)."""
    from uwml.examples import arm_on_rov
    from uwml.sim.mujoco import mjcf_of

    box = uwml.Segment((0, 0, 0), (1, 0, 0), 0.6, normals=((0, 1, 0), (0, 0, 1)), widths=(0.1, 0.2), area=0.02)
    tube = uwml.Segment((0, 0, 0), (0, 0, -1), 0.4, section="circular", diameter=0.1)
    robot = uwml.Robot(
        [uwml.Joint((0, 0, 0), (0, 0, 1), name="yaw"), uwml.Joint((0.6, 0, 0), (0, 1, 0), name="pitch")],
        [uwml.Link(3.0, (0.3, 0, 0), 0.0, segments=[box], name="upper"), uwml.Link(2.0, (0, 0, -0.2), 0.0, segments=[tube], name="lower")],
    )
    model = mujoco.MjModel.from_xml_string(mjcf_of(robot))
    np.testing.assert_allclose(model.body_mass[2:], [3.0, 2.0], rtol=1e-15)
    # The box 0.6 (x) × 0.2 (y: along n0 the extent is widths[1]) × 0.1 (z).
    a, b, c = 0.6, 0.2, 0.1
    np.testing.assert_allclose(
        np.sort(model.body_inertia[2]), np.sort(3.0 / 12 * np.array([b * b + c * c, a * a + c * c, a * a + b * b])), rtol=1e-12
    )
    r, length = 0.05, 0.4
    np.testing.assert_allclose(
        np.sort(model.body_inertia[3]),
        np.sort([2.0 * r * r / 2, 2.0 * (3 * r * r + length**2) / 12, 2.0 * (3 * r * r + length**2) / 12]),
        rtol=1e-12,
    )
    assert [model.joint(j).name for j in range(model.njnt)] == ["yaw", "pitch"]
    floating = mujoco.MjModel.from_xml_string(mjcf_of(arm_on_rov(), floating=True))
    assert floating.nv == 6 + 7 and floating.body_mass[1] == 300.0
    with pytest.raises(ValueError, match="a floating base needs a base body with a mass"):
        mjcf_of(robot, floating=True)
    sim = Simulation(floating, arm_on_rov())
    with pytest.raises(ValueError, match="qfrc must be 13 finite numbers"):
        sim.step(qfrc=np.zeros(6))


def test_the_native_rk4_bookkeeping_is_the_numpy_method_bit_for_bit() -> None:
    """The Runge-Kutta step's stage velocities, accelerations and averages are kept by the native
    coupling: 300 steps of the floating arm in a current give exactly the bits of the classical
    method written here in numpy (the step's former code)."""
    from pathlib import Path

    from uwml.robot.files import model_and_robot

    data = Path(__file__).parent / "data"
    model, robot = model_and_robot(data / "arm.xml", data / "arm.hydro.toml")

    def numpy_step(sim: Simulation) -> None:
        mj, m, d = mujoco, sim.model, sim.data
        h = m.opt.timestep
        qpos0, qvel0, time0 = d.qpos.copy(), d.qvel.copy(), d.time
        velocities: list[np.ndarray] = []
        accelerations: list[np.ndarray] = []
        for fraction, index in ((0.0, None), (0.5, 0), (0.5, 1), (1.0, 2)):
            velocity = qvel0 if index is None else qvel0 + fraction * h * accelerations[index]
            d.qpos[:] = qpos0
            if index is not None:
                mj.mj_integratePos(m, d.qpos, velocities[index], fraction * h)
            d.qvel[:] = velocity
            d.time = time0 + fraction * h
            sim.forward()
            velocities.append(velocity.copy())
            accelerations.append(d.qacc.copy())
        d.qpos[:] = qpos0
        mj.mj_integratePos(m, d.qpos, (velocities[0] + 2.0 * velocities[1] + 2.0 * velocities[2] + velocities[3]) / 6.0, h)
        d.qvel[:] = qvel0 + h * (accelerations[0] + 2.0 * accelerations[1] + 2.0 * accelerations[2] + accelerations[3]) / 6.0
        d.time = time0 + h

    start = np.random.default_rng(1).uniform(-0.5, 0.5, model.nv)  # type: ignore[attr-defined]
    native, written = (Simulation(model, robot, integrator="rk4", current=(0.2, 0.1, 0.0)) for _ in range(2))
    for sim in (native, written):
        sim.data.qvel[:] = start
    for _ in range(300):
        native.step()
        numpy_step(written)
    assert np.array_equal(native.data.qpos, written.data.qpos) and np.array_equal(native.data.qvel, written.data.qvel)
    assert native.data.time == written.data.time
    assert np.max(np.abs(native.data.qvel - start)) > 1e-3  # it moved
