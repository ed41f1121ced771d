"""The core-backed joint losses and the whole-leg environment torque, held against the numpy
reference (``uwml.reference``) and the paper's findings."""

import math
import warnings

import numpy as np
import pytest
import uwml
from hypothesis import given
from hypothesis import strategies as st
from uwml import _core, reference
from uwml.examples import arm_on_rov
from uwml.model.losses import rpm_to_rad_s


def assert_close(actual, expected, rel=1e-12, atol=0.0):
    actual, expected = np.asarray(actual), np.asarray(expected)
    scale = np.maximum(np.abs(expected), atol / rel if rel else 0.0)
    assert np.all(np.abs(actual - expected) <= rel * scale + atol), (actual, expected)


positive = st.floats(1e-3, 10.0)
oils = st.builds(
    uwml.OilDrag,
    k_oil=st.floats(1e-5, 1e-2),
    exponent=st.sampled_from([1.0, 1.5, 2.0]) | st.floats(1.0, 2.0),
    pressure_sensitivity_per_mpa=st.floats(0.0, 0.05),
    temperature_sensitivity_per_k=st.floats(0.0, 0.1),
    reference_pressure_mpa=st.floats(0.0, 1.0),
    reference_temperature_c=st.floats(0.0, 40.0),
)


@st.composite
def seals(draw):
    c0, c1 = draw(st.floats(0.0, 30.0)), draw(st.floats(0.0, 5.0))
    return uwml.Seal(
        c0=c0,
        c1_per_mpa=c1,
        s0=c0 + draw(st.floats(0.0, 20.0)),
        s1_per_mpa=c1 + draw(st.floats(0.0, 5.0)),
        d0=draw(st.floats(0.0, 5.0)),
        d1_per_mpa=draw(st.floats(0.0, 1.0)),
        stribeck_speed=draw(st.floats(1e-3, 1.0)),
    )


drives = st.builds(
    uwml.Drive, torque_constant=positive, ratio=st.floats(1.0, 200.0), efficiency=st.floats(0.3, 1.0), rated_current=positive
)


@given(
    drive=drives,
    oil=st.none() | oils,
    seal=st.none() | seals(),
    epsilon=st.sampled_from([0.0, 1e-3]) | st.floats(1e-9, 0.1),
    seed=st.integers(0, 2**32 - 1),
)
def test_joint_losses_match_the_reference(drive, oil, seal, epsilon, seed):
    rng = np.random.default_rng(seed)
    speed = rng.uniform(-3, 3, 200) * 10.0 ** rng.uniform(-5, 0, 200)
    speed[:3] = [0.0, epsilon, -epsilon]
    pressure = rng.uniform(0, 20, 200)
    temperature = rng.uniform(0, 30, 200)
    losses = uwml.JointLosses(drive=drive, oil=oil, seal=seal, epsilon=epsilon)
    core = losses.torques(speed, pressure, temperature)
    ref = reference.joint_loss_torques(drive, oil, seal, speed, pressure, temperature, epsilon)
    scale = {name: np.max(np.abs(ref[name])) for name in ref}
    for name in ("visc", "seal", "current"):
        assert_close(getattr(core, name), ref[name], rel=1e-12, atol=1e-13 * scale[name])
    # Losses oppose motion; the current is signed like the motion.
    assert np.all(speed * core.visc <= 0) and np.all(speed * core.seal <= 0) and np.all(speed * core.current >= 0)


def test_python_defaults_are_the_cores_defaults():
    speed = np.linspace(-2, 2, 41)
    pressure = np.full_like(speed, 7.5e6)
    temperature = np.full_like(speed, 3.0)
    core_default = _core.joint_losses(None, speed, pressure, temperature)
    python_default = uwml.JointLosses().torques(speed, 7.5, 3.0)
    for a, b in zip(core_default, (python_default.visc, python_default.seal, python_default.current)):
        assert_close(b, a, rel=1e-15, atol=1e-15)


def test_the_papers_27_4_percent_at_10_rpm_and_10_mpa():
    losses = uwml.JointLosses()
    t = losses.torques(rpm_to_rad_s(10.0), 10.0, 20.0)
    assert abs(float(t.current) - 2.85) < 1e-3
    assert abs(float(t.current) / 10.4 - 0.274) < 5e-4
    # Loss torque at the output = loss current × K_t × N × η (the drive's bookkeeping).
    assert_close(-(t.visc + t.seal), float(t.current) * 0.40 * 160 * 0.80, rel=1e-3)


def test_environment_adds_losses_to_hydrodynamics():
    leg = uwml.paper_leg()
    rng = np.random.default_rng(4)
    q, qd, qdd = rng.uniform(-1, 1, (3, 50, 3))
    depth = rng.uniform(0, 3000, 50)
    temperature = rng.uniform(2, 20, 50)
    joint = uwml.JointLosses(epsilon=1e-2)
    water = uwml.Water(density=1025.0)
    env = leg.environment(q, qd, qdd, depth=depth, temperature_c=temperature, losses=[None, joint, joint], water=water)
    hydro = leg.hydro(q, qd, qdd, water=water)
    for name in ("drag", "added_mass", "buoyancy", "gravity"):
        np.testing.assert_array_equal(getattr(env, name), getattr(hydro, name))
    pressure = reference.hydrostatic_pressure_mpa(depth, 1025.0, 9.81)
    for j in (1, 2):
        ref = reference.joint_loss_torques(joint.drive, joint.oil, joint.seal, qd[:, j], pressure, temperature, 1e-2)
        for name in ("visc", "seal", "current"):
            assert_close(getattr(env, name)[:, j], ref[name], rel=1e-11, atol=1e-12)
    assert np.all(env.visc[:, 0] == 0) and np.all(env.current[:, 0] == 0)
    assert_close(env.total, hydro.total + env.visc + env.seal, rel=1e-15, atol=1e-12)
    # One JointLosses for every joint, and no losses at all.
    every = leg.environment(q[0], qd[0], qdd[0], depth=100.0, losses=joint)
    assert every.visc.shape == (3,) and np.all(every.visc * qd[0] <= 0)
    none = leg.environment(q[0], qd[0], qdd[0], depth=100.0)
    np.testing.assert_array_equal(none.total, leg.hydro(q[0], qd[0], qdd[0]).total)


def test_environment_on_a_moving_base_is_hydro_plus_the_joints_losses() -> None:
    """The losses of each joint depend on its speed, depth and temperature only: on a moving
    base (and on two threads) a robot's environment is its hydro plus the reference's losses at
    the same joint speeds, and the base wrench is the hydro's (losses act inside the robot)."""
    robot = uwml.paper_leg()
    rng = np.random.default_rng(8)
    q, qd, qdd = rng.uniform(-2, 2, (40, 3)), rng.uniform(-1, 1, (40, 3)), rng.uniform(-3, 3, (40, 3))
    depth, temperature = rng.uniform(0, 6000, 40), rng.uniform(0, 20, 40)
    joint = uwml.JointLosses()
    motion = uwml.BaseMotion(velocity=(0.3, 0.0, 0.1))
    env = robot.environment(q, qd, qdd, depth=depth, temperature_c=temperature, losses=[None, joint, joint], base_motion=motion, threads=2)
    hydro = robot.hydro(q, qd, qdd, base_motion=motion)
    pressure = reference.hydrostatic_pressure_mpa(depth, robot.water.density, robot.water.gravity)
    for j in (1, 2):
        ref = reference.joint_loss_torques(joint.drive, joint.oil, joint.seal, qd[:, j], pressure, temperature, joint.epsilon)
        for name in ("visc", "seal", "current"):
            assert_close(getattr(env, name)[:, j], ref[name], rel=1e-11, atol=1e-12)
    assert np.all(env.seal[:, 0] == 0.0) and np.all(env.seal[:, 1:] * qd[:, 1:] <= 0.0)
    np.testing.assert_array_equal(env.hydro, hydro.total)
    np.testing.assert_array_equal(env.base.total, hydro.base.total)
    np.testing.assert_array_equal(env.total, hydro.total + env.visc + env.seal)


def test_environment_defaults_to_the_robots_one_water_for_the_hydrodynamics_and_the_pressure() -> None:
    """At depth the links move in the water whose column gives the pressure: by default the
    robot's water (the paper's leg: fresh water, 1000 kg/m³, as for every evaluation) for both;
    ``sea_density`` defaults to ``water``'s density, so a water given is used for both too."""
    leg = uwml.paper_leg()
    rng = np.random.default_rng(3)
    q, qd, qdd = rng.uniform(-1, 1, (6, 3)), rng.uniform(-1, 1, (6, 3)), rng.uniform(-2, 2, (6, 3))
    joint = uwml.JointLosses(epsilon=1e-2)
    assert leg.water == uwml.Water()
    for water, density in ((None, 1000.0), (uwml.Water(density=1025.0), 1025.0), (uwml.Water(density=1030.0, gravity=9.8), 1030.0)):
        kwargs = {} if water is None else {"water": water}
        env = leg.environment(q, qd, qdd, depth=3000.0, temperature_c=4.0, losses=joint, **kwargs)
        gravity = 9.81 if water is None else water.gravity
        hydro = leg.hydro(q, qd, qdd, water=uwml.Water(density=density, gravity=gravity))
        np.testing.assert_array_equal(env.drag, hydro.drag)
        np.testing.assert_array_equal(env.buoyancy, hydro.buoyancy)
        pressure = reference.hydrostatic_pressure_mpa(3000.0, density, gravity)
        for j in range(3):
            ref = reference.joint_loss_torques(joint.drive, joint.oil, joint.seal, qd[:, j], pressure, 4.0, 1e-2)
            assert_close(env.seal[:, j], ref["seal"], rel=1e-11, atol=1e-12)
        one = leg.environment(q[0], qd[0], qdd[0], depth=3000.0, temperature_c=4.0, losses=joint, **kwargs)
        np.testing.assert_array_equal(one.total, env.total[0])
    # An explicit sea_density still sets the column alone.
    column = leg.environment(q, qd, qdd, depth=3000.0, temperature_c=4.0, losses=joint, water=uwml.Water(), sea_density=1025.0)
    pressure = reference.hydrostatic_pressure_mpa(3000.0, 1025.0, 9.81)
    ref = reference.joint_loss_torques(joint.drive, joint.oil, joint.seal, qd[:, 1], pressure, 4.0, 1e-2)
    assert_close(column.seal[:, 1], ref["seal"], rel=1e-11, atol=1e-12)


def test_losses_grow_with_depth():
    leg = uwml.paper_leg()
    state = ([0.2, -0.3, 0.5], [0.5, 0.5, 0.5], [0.0, 0.0, 0.0])
    shallow = leg.environment(*state, depth=10.0, losses=uwml.JointLosses())
    deep = leg.environment(*state, depth=3000.0, losses=uwml.JointLosses())
    assert np.all(np.abs(deep.visc) > np.abs(shallow.visc)) and np.all(np.abs(deep.seal) > np.abs(shallow.seal))


def test_core_hydrostatic_formula():
    depth = np.array([0.0, 10.0, 1000.0, 11000.0])
    assert_close(uwml.hydrostatic_pressure_mpa(depth), 1025.0 * 9.81 * depth / 1e6, rel=1e-15)
    assert_close(uwml.hydrostatic_pressure_mpa(depth), reference.hydrostatic_pressure_mpa(depth), rel=1e-15)
    assert_close(uwml.hydrostatic_pressure_mpa(1000.0, sea_density=1000.0, gravity=9.8), 9.8, rel=1e-15)
    for bad, match in ((-1.0, "depth_m is -1.0 m"), (11000.5, "from 0 to 11000 m"), ([5.0, math.nan], r"depth_m\[1\] is nan")):
        with pytest.raises(ValueError, match=match):
            uwml.hydrostatic_pressure_mpa(bad)
    for kwargs in ({"sea_density": -1025.0}, {"sea_density": math.nan}, {"gravity": 0.0}):
        with pytest.raises(ValueError, match=f"{next(iter(kwargs))} must be finite and positive"):
            uwml.hydrostatic_pressure_mpa(100.0, **kwargs)
    # The density is keyword-only: a second positional number (a latitude for uwml.sea.seawater's
    # TEOS-10 pressure_at_depth_mpa) is refused rather than read as a density.
    with pytest.raises(TypeError):
        uwml.hydrostatic_pressure_mpa(1000.0, 45.0)  # type: ignore[misc]


STATE = ([0.2, -0.3, 0.5], [0.5, 0.5, 0.5], [0.0, 0.0, 0.0])


@pytest.mark.parametrize("one_state", [True, False])
@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"depth": 1e9}, r"depth is 1000000000.0 m: depth must be finite and from 0 to 11000 m"),
        ({"depth": 11000.5}, "from 0 to 11000 m"),
        ({"depth": -3.0}, "depth is -3.0 m"),
        ({"temperature_c": -300.0}, r"temperature_c is -300.0 °C: temperature_c must be finite and above absolute zero"),
        ({"temperature_c": -273.15}, "above absolute zero"),
        ({"sea_density": -1025.0}, "sea_density must be finite and positive"),
        ({"sea_density": math.nan}, "sea_density must be finite and positive"),
    ],
)
def test_conditions_outside_the_physics_are_refused(kwargs: dict, match: str, one_state: bool) -> None:
    """Depth from 0 to the deepest ocean (11 km), temperature above absolute zero, a positive
    sea density: outside, a ValueError naming the argument (it was inf, 1e11 N·m or 1.5e10 N·m),
    for one state and a batch, for the leg and the arm on an ROV."""
    state = STATE if one_state else tuple(np.array([x, x]) for x in STATE)
    for model in (uwml.paper_leg(), arm_on_rov()):
        state = tuple(np.resize(x, (*np.shape(x)[:-1], model.n_joints)) for x in state)
        with pytest.raises(ValueError, match=match):
            model.environment(*state, losses=uwml.JointLosses(), **kwargs)
        with pytest.raises(ValueError, match=match):
            model.jacobians(*state, losses=uwml.JointLosses(), **kwargs)


def test_per_sample_conditions_name_the_sample() -> None:
    q = np.zeros((3, 3))
    with pytest.raises(ValueError, match=r"depth\[2\] is 20000.0 m"):
        uwml.paper_leg().environment(q, q, q, depth=[10.0, 20.0, 20000.0])
    with pytest.raises(ValueError, match=r"temperature_c\[1\] is -280.0"):
        uwml.paper_leg().environment(q, q, q, temperature_c=[4.0, -280.0, 4.0])


@pytest.mark.parametrize("temperature", [-5.0, 60.0])
def test_oil_temperatures_outside_the_sea_warn_and_still_evaluate(temperature: float) -> None:
    """Inside the physics but outside the oil model's range (−2 to 40 °C): the losses are
    evaluated (the exponential law extrapolates) with an ExtrapolationWarning naming the value;
    inside the range, no warning. The one-state path gives the batch path's numbers."""
    leg = uwml.paper_leg()
    with pytest.warns(uwml.ExtrapolationWarning, match=f"temperature_c is {temperature} °C, outside the oil model's range"):
        one = leg.environment(*STATE, temperature_c=temperature, losses=uwml.JointLosses())
    with pytest.warns(uwml.ExtrapolationWarning):
        batch = leg.environment(*(np.array([x]) for x in STATE), temperature_c=temperature, losses=uwml.JointLosses())
    np.testing.assert_array_equal(one.total, batch.total[0])
    colder = 4.0 if temperature < 0 else 40.0
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        inside = leg.environment(*STATE, temperature_c=colder, losses=uwml.JointLosses())
    # Colder oil is thicker: more oil drag at −5 °C than at 4 °C, less at 60 °C than at 40 °C.
    assert (np.abs(one.visc[1]) > np.abs(inside.visc[1])) == (temperature < 0)
    with pytest.warns(uwml.ExtrapolationWarning):
        uwml.JointLosses().torques(0.5, 10.0, temperature)


def test_joint_losses_refuse_pressures_beyond_the_ocean() -> None:
    losses = uwml.JointLosses()
    for pressure, match in ((-1.0, r"pressure_mpa\[0\] is -1.0"), (121.0, "at most 120 MPa"), (math.inf, "finite")):
        with pytest.raises(ValueError, match=match):
            losses.torques(0.5, pressure, 4.0)
    with pytest.raises(ValueError, match="above absolute zero"):
        losses.torques(0.5, 10.0, -274.0)
    with pytest.raises(ValueError, match=r"speed\[1\] is nan"):
        losses.torques([0.5, math.nan], 10.0, 4.0)


@pytest.mark.parametrize(
    ("kwargs", "error", "match"),
    [
        ({"losses": [uwml.JointLosses()]}, ValueError, "one entry per joint"),
        ({"losses": 3}, TypeError, "losses"),
        ({"losses": [None, "seal", None]}, TypeError, r"losses\[1\]"),
        ({"depth": -5.0}, ValueError, "depth"),
        ({"depth": [[1.0, 2.0]]}, ValueError, "depth"),
        ({"depth": "deep"}, TypeError, "depth"),
        ({"temperature_c": [[1.0]]}, ValueError, "temperature_c"),
        ({"temperature_c": math.nan}, ValueError, "temperature"),
        ({"sea_density": 0.0}, ValueError, "sea_density"),
        ({"cd": -1.0}, ValueError, "cd"),
    ],
)
def test_environment_bad_inputs(kwargs, error, match):
    leg = uwml.paper_leg()
    with pytest.raises(error, match=match):
        leg.environment([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0], **kwargs)


@pytest.mark.parametrize(
    ("make", "error", "match"),
    [
        (lambda: uwml.JointLosses(epsilon=-1.0), ValueError, "epsilon"),
        (lambda: uwml.JointLosses(oil="oil"), TypeError, "oil"),
        (lambda: uwml.JointLosses(drive=None), TypeError, "drive"),
        (lambda: uwml.JointLosses().torques([1.0, 2.0], [1.0, 2.0, 3.0]), ValueError, "broadcast"),
        (lambda: uwml.JointLosses().torques(1.0, -1.0), ValueError, "pressure_mpa"),
        (lambda: uwml.JointLosses().torques("fast"), TypeError, "speed"),
        (lambda: uwml.JointLosses().torques(math.inf), ValueError, "speed"),
        (lambda: uwml.Seal(s0=1.0), ValueError, "seal.s0"),
        (lambda: uwml.OilDrag(exponent=2.5), ValueError, "oil.exponent"),
        (lambda: uwml.Drive(efficiency=1.5), ValueError, "drive.efficiency"),
    ],
)
def test_loss_bad_inputs(make, error, match):
    with pytest.raises(error, match=match):
        make()


@pytest.mark.filterwarnings("ignore::uwml.PlausibilityWarning")  # values beyond plausible on purpose
@pytest.mark.parametrize("one_state", [True, False])
def test_forces_that_overflow_raise_naming_the_sample(one_state: bool) -> None:
    """A finite state whose forces exceed float64 (a joint speed of 1e300 rad/s: the drag goes
    as its square) is outside the physics' domain: a ValueError naming the sample, not inf or NaN
    returned silently; a large but representable one evaluates."""
    leg = uwml.paper_leg()
    q, qd, qdd = np.zeros((3, 3)), np.zeros((3, 3)), np.zeros((3, 3))
    qd[2, 1] = 1e300
    if one_state:
        q, qd, qdd = q[2], qd[2], qdd[2]
    where = "the state" if one_state else "sample 2"
    for evaluate in (leg.hydro, leg.environment, leg.jacobians, leg.hydro_regressors, leg.link_wrenches):
        with pytest.raises(ValueError, match=f"the forces of {where} overflow float64 .joint speeds up to 1e\\+300"):
            evaluate(q, qd, qdd)
    with pytest.raises(ValueError, match=f"the forces of {where} overflow float64"):
        leg.hydro(q, qd, qdd, base=True)
    qd = np.where(qd == 1e300, 1e100, qd)
    for evaluate in (leg.hydro, leg.environment):
        assert np.all(np.isfinite(evaluate(q, qd, qdd).total))


def test_the_domains_are_the_cores() -> None:
    """uwml.domains (pure Python, for the modules that need no compiled core) and the Rust core
    hold the same numbers."""
    from uwml import domains

    assert domains.MAX_DEPTH == _core.MAX_DEPTH
    assert domains.MAX_PRESSURE == _core.MAX_PRESSURE
    assert domains.ABSOLUTE_ZERO_C == _core.ABSOLUTE_ZERO_C
    assert domains.OIL_TEMPERATURE_RANGE_C == _core.OIL_TEMPERATURE_RANGE_C
    for name in ("MAX_ROBOT_JOINTS", "MAX_LENGTH", "MAX_MASS", "MAX_VOLUME", "MAX_AREA", "MAX_COEFFICIENT", "MAX_DENSITY", "MAX_GRAVITY"):
        assert getattr(domains, name) == getattr(_core, name), name
