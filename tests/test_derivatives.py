"""Derivatives for control (``Robot.jacobians``): against central finite differences of
``Robot.environment`` (the joints of a chain on its fixed base, and a tree on a moving base in a
current, base rows and twist columns too), the added-mass matrix against the numpy reference,
shapes and bad inputs."""

import math

import numpy as np
import pytest
import uwml
from robots import motion_arguments, random_robot
from uwml import reference

H = 1e-6


def central(f, x, h=H):
    """Central differences of ``f`` (``(n, N) -> (n, N)``) in each column of ``x``: ``(n, N, N)``,
    entry ``[s, i, j] = ∂f_i/∂x_j``."""
    columns = []
    for j in range(x.shape[1]):
        step = np.zeros_like(x)
        step[:, j] = h
        columns.append((f(x + step) - f(x - step)) / (2 * h))
    return np.stack(columns, axis=-1)


def random_states(seed, n=200, n_joints=3):
    rng = np.random.default_rng(seed)
    q = rng.uniform(-3, 3, (n, n_joints))
    # Speeds away from the smooth sign's width, where finite differences would need a smaller step.
    qd = rng.uniform(0.05, 2, (n, n_joints)) * rng.choice([-1.0, 1.0], (n, n_joints))
    qdd = rng.uniform(-5, 5, (n, n_joints))
    return q, qd, qdd


def joints(jac: uwml.Jacobians) -> uwml.Jacobians:
    """The joint-space block of ``jac`` (a fixed base: rows and columns after the base's six)."""
    return uwml.Jacobians(
        value=jac.value[..., 6:],
        d_q=jac.d_q[..., 6:, :],
        d_velocity=jac.d_velocity[..., 6:, 6:],
        added_mass_matrix=jac.added_mass_matrix[..., 6:, 6:],
    )


def assert_matches_finite_differences(leg, q, qd, qdd, **kwargs):
    jac = joints(leg.jacobians(q, qd, qdd, **kwargs))

    def total(q=q, qd=qd, qdd=qdd):
        return leg.environment(q, qd, qdd, **kwargs).total

    # The same torques: the batch evaluates four states at once with a SIMD sine and cosine, the
    # derivatives one state at a time with the platform's, which differ by a few units in the
    # last place.
    value = total()
    scale = np.maximum(np.abs(value).max(axis=1, keepdims=True), 1.0)
    assert (np.abs(jac.value - value) / scale).max() <= 1e-13
    for name, fd in (("d_q", central(lambda x: total(q=x), q)), ("d_velocity", central(lambda x: total(qd=x), qd))):
        scale = np.maximum(np.abs(fd).max(axis=(1, 2)), 1.0)[:, None, None]
        error = np.abs(getattr(jac, name) - fd) / scale
        assert error.max() <= 1e-7, (name, error.max())
    # Linear in q̈: ∂τ/∂q̈ = −M_A.
    fd_qdd = central(lambda x: total(qdd=x), qdd)
    np.testing.assert_allclose(-jac.added_mass_matrix, fd_qdd, rtol=0, atol=1e-7 * np.abs(fd_qdd).max())
    return jac


def test_paper_leg_without_losses_matches_finite_differences():
    leg = uwml.paper_leg()
    assert_matches_finite_differences(leg, *random_states(1), water=uwml.Water(density=1025.0))


def test_paper_leg_with_losses_matches_finite_differences():
    leg = uwml.paper_leg()
    q, qd, qdd = random_states(2)
    depth = np.random.default_rng(3).uniform(0, 3000, q.shape[0])
    joint = uwml.JointLosses(epsilon=1e-2)
    jac = assert_matches_finite_differences(leg, q, qd, qdd, depth=depth, temperature_c=4.0, losses=[None, joint, joint], cd=[2.0, 2.4])
    # Losses depend on the joint's own speed only: nothing in q, a diagonal in q̇.
    plain = joints(leg.jacobians(q, qd, qdd, cd=[2.0, 2.4]))
    np.testing.assert_array_equal(jac.d_q, plain.d_q)
    np.testing.assert_array_equal(jac.added_mass_matrix, plain.added_mass_matrix)
    extra = jac.d_velocity - plain.d_velocity
    off_diagonal = ~np.eye(3, dtype=bool)
    assert np.all(extra[:, off_diagonal] == 0) and np.all(extra[:, 0, 0] == 0)


def test_added_mass_matrix_is_the_references_symmetric_psd_and_gives_the_added_mass_torque():
    leg = uwml.paper_leg()
    rng = np.random.default_rng(5)
    n = 100
    q = rng.uniform(-3, 3, (n, 3))
    cm = rng.uniform(0.1, 1.5, (3, 2))
    cm[0] = 0.0  # the reference's per link: link 0 has no segment
    whole = leg.jacobians(q, rng.uniform(-2, 2, (n, 3)), rng.uniform(-5, 5, (n, 3)), cm=cm[1:], water=uwml.Water()).added_mass_matrix
    np.testing.assert_array_equal(whole, leg.added_mass_matrix(q, cm=cm[1:]))
    m = whole[:, 6:, 6:]
    np.testing.assert_array_equal(m, np.swapaxes(m, 1, 2))
    eigenvalues = np.linalg.eigvalsh(m)
    assert eigenvalues.min() >= -1e-12 * np.abs(m).max()
    # The independent numpy reference: column j is −added_mass(q, 0, e_j).
    joints, links = reference.paper_leg()
    ref = np.empty_like(m)
    for j in range(3):
        unit = np.zeros((n, 3))
        unit[:, j] = 1.0
        ref[:, :, j] = -reference.hydro(joints, links, q, np.zeros((n, 3)), unit, cm=cm)["added_mass"]
    np.testing.assert_allclose(m, ref, rtol=0, atol=1e-12 * np.abs(ref).max())
    # added_mass(q, 0, q̈) = −M_A q̈.
    qdd = rng.uniform(-5, 5, (n, 3))
    added_mass = leg.hydro(q, np.zeros((n, 3)), qdd, cm=cm[1:]).added_mass
    np.testing.assert_allclose(added_mass, -np.einsum("sij,sj->si", m, qdd), rtol=0, atol=1e-12 * np.abs(added_mass).max())


def test_a_chain_of_your_own():
    leg = uwml.Robot(
        joints=[uwml.Joint(origin=(0, 0, 0), axis=(0, 0, 1)), uwml.Joint(origin=(0.3, 0.1, 0), axis=(0.6, 0, 0.8))],
        links=[
            uwml.Link(mass=2.0, com=(0.1, 0, 0), volume=1e-3),
            uwml.Link(
                mass=20.0,
                com=(0.5, 0, 0),
                volume=0.00785,
                segments=[
                    uwml.Segment(
                        start=(0, 0, 0.1), axis=(0, 1, 0), length=1.0, normals=((0, 0, 1), (1, 0, 0)), widths=(0.1, 0.2), area=0.00785
                    )
                ],
            ),
        ],
    )
    q, qd, qdd = random_states(6, n=50, n_joints=2)
    assert_matches_finite_differences(leg, q, qd, qdd, losses=uwml.JointLosses(), depth=500.0)


def test_shapes_of_one_state_and_of_a_batch():
    leg = uwml.paper_leg()
    one = leg.jacobians([0.1, 0.2, 0.3], [0.5, -0.5, 0.2], [0.0, 1.0, 0.0])
    assert isinstance(one, uwml.Jacobians)
    assert one.value.shape == (9,) and one.d_q.shape == (9, 3) and one.d_velocity.shape == one.added_mass_matrix.shape == (9, 9)
    q, qd, qdd = random_states(7, n=4)
    batch = leg.jacobians(q, qd, qdd, losses=uwml.JointLosses(), depth=[0.0, 10.0, 100.0, 1000.0])
    assert batch.value.shape == (4, 9) and batch.d_q.shape == (4, 9, 3) and batch.added_mass_matrix.shape == (4, 9, 9)
    for s in range(4):
        single = leg.jacobians(q[s], qd[s], qdd[s], losses=uwml.JointLosses(), depth=[0.0, 10.0, 100.0, 1000.0][s])
        for name in ("value", "d_q", "d_velocity", "added_mass_matrix"):
            np.testing.assert_array_equal(getattr(single, name), getattr(batch, name)[s])
    empty = leg.jacobians(np.zeros((0, 3)), np.zeros((0, 3)), np.zeros((0, 3)))
    assert empty.value.shape == (0, 9) and empty.d_q.shape == (0, 9, 3)
    with pytest.raises(AttributeError):
        one.value = one.value  # frozen


@pytest.mark.parametrize(
    ("kwargs", "error", "match"),
    [
        ({"q": [0.0, 0.0]}, ValueError, "q must have shape"),
        ({"qd": [[0.0, 0.0, 0.0]]}, ValueError, "qd must have the same shape"),
        ({"qdd": "fast"}, TypeError, "qdd"),
        ({"q": [[0.0, 0.0, 0.0], [0.0, math.nan, 0.0], [0.0] * 3]}, ValueError, r"q\[1, 1\]"),
        ({"qd": [[0.0, 0.0, math.inf]] * 3}, ValueError, r"qd\[0, 2\]"),
        ({"qdd": [[math.nan, 0.0, 0.0]] * 3}, ValueError, r"qdd\[0, 0\]"),
        ({"losses": [uwml.JointLosses()]}, ValueError, "one entry per joint"),
        ({"depth": -5.0}, ValueError, "depth"),
        ({"depth": [1.0, 2.0]}, ValueError, "must agree on the number of samples"),
        ({"temperature_c": math.nan}, ValueError, "temperature"),
        ({"sea_density": 0.0}, ValueError, "sea_density"),
        ({"cd": -1.0}, ValueError, "cd"),
        ({"cm": [1.0, 2.0, 3.0]}, ValueError, "cm"),
        ({"water": 1000.0}, TypeError, "water"),
    ],
)
def test_bad_inputs_name_the_argument(kwargs, error, match):
    leg = uwml.paper_leg()
    arguments = {"q": [[0.0, 0.0, 0.0]] * 3, "qd": [[1.0, 0.0, 0.0]] * 3, "qdd": [[0.0, 0.0, 0.0]] * 3}
    arguments.update(kwargs)
    with pytest.raises(error, match=match):
        leg.jacobians(**arguments)


def test_jacobians_of_a_tree_on_a_moving_base_are_the_slopes() -> None:
    rng = np.random.default_rng(21)
    robot = random_robot(rng, 5)
    q, qd, qdd = rng.uniform(-2, 2, 5), rng.uniform(-1, 1, 5), rng.uniform(-3, 3, 5)
    motion = {k: v[0] for k, v in motion_arguments(rng, 1).items()}
    losses = [uwml.JointLosses(epsilon=0.01)] * 5
    kwargs = {"depth": 2000.0, "temperature_c": 4.0, "losses": losses, "current": (0.3, -0.1, 0.0)}
    jac = robot.jacobians(q, qd, qdd, base_motion=uwml.BaseMotion(**motion), **kwargs)

    def value(q: np.ndarray, qd: np.ndarray, velocity: np.ndarray, angular_velocity: np.ndarray) -> np.ndarray:
        moved = uwml.BaseMotion(**(motion | {"velocity": velocity, "angular_velocity": angular_velocity}))
        env = robot.environment(q, qd, qdd, base_motion=moved, **kwargs)
        return np.concatenate([env.base.total, env.total])

    v, w = np.asarray(motion["velocity"]), np.asarray(motion["angular_velocity"])
    here = value(q, qd, v, w)
    np.testing.assert_allclose(jac.value, here, rtol=0, atol=1e-13 * np.abs(here).max())
    h, scale = 1e-6, np.abs(here).max()
    for k in range(5):
        e = np.eye(5)[k] * h
        np.testing.assert_allclose(jac.d_q[:, k], (value(q + e, qd, v, w) - value(q - e, qd, v, w)) / (2 * h), atol=1e-6 * scale)
        np.testing.assert_allclose(jac.d_velocity[:, 6 + k], (value(q, qd + e, v, w) - value(q, qd - e, v, w)) / (2 * h), atol=1e-6 * scale)
    for k in range(6):
        e = np.eye(6)[k] * h
        slope = (value(q, qd, v + e[:3], w + e[3:]) - value(q, qd, v - e[:3], w - e[3:])) / (2 * h)
        np.testing.assert_allclose(jac.d_velocity[:, k], slope, atol=1e-6 * scale)
    np.testing.assert_array_equal(jac.added_mass_matrix, robot.added_mass_matrix(q))


def test_a_hull_at_rest_in_still_water_has_its_damping_as_the_base_twists_slope() -> None:
    """At rest in still water the core took a shortcut for a still base that dropped the
    derivative seeded on the base's twist (a dual number equal to zero in value): the base
    columns of ``d_velocity`` were zero. A hull with linear damping ``D`` has ``−D`` there."""
    damping = np.diag([13.7, 5.0, 33.0, 1.5, 0.8, 2.0])
    hull = uwml.Link(13.5, (0, 0, 0), 0.0134, cob=(0, 0, 0.01), lumped=uwml.LumpedModel(linear_damping=damping))
    robot = uwml.Robot([uwml.Joint((0.2, 0, -0.1), (0, 0, 1))], [uwml.Link(0.3, (0.1, 0, 0), 0.0003)], base=hull)
    q = qd = qdd = np.zeros(1)
    jac = robot.jacobians(q, qd, qdd)
    # The wrench about the base origin, the model's point 0.01 m above it: −D at the point,
    # carried to the origin (a pure translation of the twist and of the wrench).
    h = 1e-6

    def base_wrench(twist: np.ndarray) -> np.ndarray:
        motion = uwml.BaseMotion(velocity=twist[:3], angular_velocity=twist[3:])
        return robot.environment(q, qd, qdd, base_motion=motion).base.total

    for k in range(6):
        e = np.eye(6)[k] * h
        slope = (base_wrench(e) - base_wrench(-e)) / (2 * h)
        np.testing.assert_allclose(jac.d_velocity[:6, k], slope, rtol=1e-6, atol=1e-9)
    assert np.abs(np.diag(jac.d_velocity[:6, :6]) + np.diag(damping)).max() < 0.5  # about −D
