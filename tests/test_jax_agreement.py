"""``uwml.jax`` (docs/batched.md) held to the Rust core in float64: a random tree with every kind of
part (revolute and prismatic joints, rectangular and circular segments, axial drag, lumped models
on the base and on links) on a moving base in a current, in both added-mass forms, with joint
losses at depth; its regressors and added-mass matrix; a tree on a fixed base in still water; and
the paper's leg against docs/model.md section 5's numbers. Each compiled function is made once
per module (``jit`` of ``vmap`` over the samples) and compared with ``uwml.Robot``'s evaluation of
the same robot and conditions to 1e-10 of each sample's largest entry (robots.RTOL_REFERENCE)."""

import numpy as np
import pytest
import uwml
from robots import COMPONENTS, RTOL_REFERENCE, assert_close, motion_arguments, random_robot
from test_robot_lumped import with_lumped

jax = pytest.importorskip("jax")
jax.config.update("jax_enable_x64", True)
import uwml.jax as uj  # after the guard: needs jax

SAMPLES = 12
LOSS_FIELDS = ("visc", "seal", "current")


def per_sample(actual: object, expected: np.ndarray, what: str) -> None:
    """``actual`` within RTOL_REFERENCE of ``expected``, relative to each sample's largest entry."""
    actual = np.asarray(actual)
    assert actual.shape == expected.shape, f"{what}: shape {actual.shape} != {expected.shape}"
    scale = np.max(np.abs(expected).reshape(len(expected), -1), axis=1) + 1e-300
    assert_close(actual, expected, scale, RTOL_REFERENCE, what)


def assert_torques(actual: uwml.Torques, expected: uwml.Torques, losses: bool = False) -> None:
    for name in COMPONENTS + (LOSS_FIELDS if losses else ()):
        per_sample(getattr(actual, name), getattr(expected, name), name)
    for name in COMPONENTS:
        per_sample(getattr(actual.base, name), getattr(expected.base, name), f"base.{name}")


@pytest.fixture(scope="module")
def tree() -> dict:
    """A random tree of 5 joints with every kind of part, states and moving-water conditions."""
    rng = np.random.default_rng(2024)
    robot = with_lumped(random_robot(rng, 5, base_body=True, axial=True), rng)
    kinds = {j.kind for j in robot.joints}
    sections = {s.section for s in robot.segments}
    assert kinds == {"revolute", "prismatic"} and sections == {"rectangular", "circular"}, (kinds, sections)
    assert any(s.cd_axial > 0 for s in robot.segments) and len(robot.lumped_models) >= 2
    q, qd, qdd = (rng.uniform(-3, 3, (SAMPLES, 5)), rng.uniform(-2, 2, (SAMPLES, 5)), rng.uniform(-5, 5, (SAMPLES, 5)))
    qd[0, 1] = 0.0  # a joint at rest: the smooth sign's middle
    conditions = uwml.Conditions(
        water=uwml.Water(1025.0, 9.80),
        base_motion=uwml.BaseMotion(**motion_arguments(rng, SAMPLES)),
        current=rng.normal(size=(SAMPLES, 3)),
        current_acceleration=rng.normal(size=(SAMPLES, 3)),
        losses=[uwml.JointLosses(), None, uwml.JointLosses(oil=uwml.OilDrag(exponent=1.5), seal=None), uwml.JointLosses(oil=None), None],
        depth=rng.uniform(0.0, 4000.0, SAMPLES),
        temperature_c=rng.uniform(0.0, 30.0, SAMPLES),
    )
    return {"robot": robot, "state": (q, qd, qdd), "conditions": conditions, "motion": uj.motion(conditions, samples=SAMPLES)}


@pytest.fixture(scope="module")
def environment():
    return jax.jit(jax.vmap(uj.environment, in_axes=(None, 0, 0, 0, 0, 0, 0)))


@pytest.fixture(scope="module")
def hydro():
    return jax.jit(jax.vmap(uj.hydro, in_axes=(None, 0, 0, 0, 0)))


def test_environment_matches_the_core_on_a_moving_base_in_a_current(tree: dict, environment) -> None:
    robot, conditions = tree["robot"], tree["conditions"]
    model = uj.compile_robot(robot, conditions)
    got = environment(model, *tree["state"], tree["motion"], conditions.depth, conditions.temperature_c)
    expected = robot.environment(*tree["state"], conditions)
    assert_torques(got, expected, losses=True)
    assert np.all(np.asarray(got.visc)[:, [1, 4]] == 0.0) and np.any(np.asarray(got.seal)[:, 0] != 0.0)


def test_kirchhoffs_added_mass_and_other_coefficients_match_the_core(tree: dict, hydro) -> None:
    robot = tree["robot"]
    count = len(robot.segments)
    rng = np.random.default_rng(5)
    cd, cm = rng.uniform(0.5, 2.5, (count, 2)), rng.uniform(0.2, 1.5, (count, 2))
    circular = np.array([s.section == "circular" for s in robot.segments])
    cd[circular, 1], cm[circular, 1] = cd[circular, 0], cm[circular, 0]
    conditions = tree["conditions"].replace(added_mass="kirchhoff", cd=cd, cm=cm, losses=None)
    got = hydro(uj.compile_robot(robot, conditions), *tree["state"], tree["motion"])
    assert_torques(got, robot.hydro(*tree["state"], conditions))


def test_regressors_match_the_core(tree: dict) -> None:
    robot, conditions = tree["robot"], tree["conditions"]
    regressors = jax.jit(jax.vmap(uj.regressors, in_axes=(None, 0, 0, 0, 0)))
    got = regressors(uj.compile_robot(robot, conditions), *tree["state"], tree["motion"])
    expected = robot.hydro_regressors(*tree["state"], conditions)
    for name in ("buoyancy", "gravity", "drag", "added_mass", "axial_drag", "lumped"):
        per_sample(getattr(got, name), getattr(expected, name), name)
        per_sample(getattr(got, f"base_{name}"), getattr(expected, f"base_{name}"), f"base_{name}")
    # The columns times the robot's own coefficients: its forces (the CPU class's own method).
    lumped = [m.coefficients() for _, m in robot.lumped_models]
    cd_axial = [s.cd_axial for s in robot.segments]
    own = jax.tree_util.tree_map(np.asarray, got).torques(
        np.array([s.cd for s in robot.segments]), np.array([s.cm for s in robot.segments]), cd_axial, lumped
    )
    per_sample(own.drag, robot.hydro(*tree["state"], conditions).drag, "drag from the regressors")


def test_added_mass_matrix_matches_the_core(tree: dict) -> None:
    robot, conditions = tree["robot"], tree["conditions"]
    matrices = jax.jit(jax.vmap(uj.added_mass_matrix, in_axes=(None, 0)))(uj.compile_robot(robot, conditions), tree["state"][0])
    expected = robot.added_mass_matrix(tree["state"][0], conditions)
    per_sample(matrices, expected, "added-mass matrix")
    np.testing.assert_array_equal(matrices, np.swapaxes(matrices, 1, 2))


def test_a_tree_on_a_fixed_base_in_still_water(hydro) -> None:
    """No base body, and the motion of default conditions (:func:`uwml.jax.motion`): a fixed,
    upright base in still water."""
    rng = np.random.default_rng(11)
    robot = random_robot(rng, 4, base_body=False, axes="mixed")
    q, qd, qdd = rng.uniform(-3, 3, (SAMPLES, 4)), rng.uniform(-2, 2, (SAMPLES, 4)), rng.uniform(-5, 5, (SAMPLES, 4))
    got = hydro(uj.compile_robot(robot), q, qd, qdd, uj.motion(uwml.Conditions(), samples=SAMPLES))
    assert_torques(got, robot.hydro(q, qd, qdd, base=True))


def test_the_paper_leg_gives_section_5s_numbers() -> None:
    """docs/model.md section 5 (typed from it), one state, no vmap: and the core's bits to 1e-13."""
    leg = uwml.paper_leg()
    state = ([0.3, -0.4, 0.6], [0.8, 0.5, -0.7], [1.0, -2.0, 0.5])
    got = jax.jit(uj.hydro)(uj.compile_robot(leg), *state)
    np.testing.assert_allclose(got.drag, [-24.24084, -5.060505, -0.7383118], rtol=1e-6)
    np.testing.assert_allclose(got.added_mass, [-8.525438, 21.77596, 9.484545], rtol=1e-6)
    np.testing.assert_allclose(got.buoyancy, [0.0, 59.72457, 4.193843], rtol=1e-6, atol=1e-12)
    expected = leg.hydro(*state, base=True)
    for name in COMPONENTS:
        np.testing.assert_allclose(getattr(got, name), getattr(expected, name), rtol=1e-13, atol=1e-12)
        np.testing.assert_allclose(getattr(got.base, name), getattr(expected.base, name), rtol=1e-13, atol=1e-12)
