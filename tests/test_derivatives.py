"""Derivatives for control (``Leg.jacobians``): against central finite differences of
``Leg.environment``, the added-mass matrix against the numpy reference, shapes and bad inputs."""

import math

import numpy as np
import pytest
import uwml
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


def assert_matches_finite_differences(leg, q, qd, qdd, **kwargs):
    jac = leg.jacobians(q, qd, qdd, **kwargs)

    def total(q=q, qd=qd, qdd=qdd):
        return leg.environment(q, qd, qdd, **kwargs).total

    # The same torques: the batch evaluates four states at once with a SIMD sine and cosine, the
    # derivatives one state at a time with the platform's, which differ by a few units in the
    # last place.
    value = total()
    scale = np.maximum(np.abs(value).max(axis=1, keepdims=True), 1.0)
    assert (np.abs(jac.value - value) / scale).max() <= 1e-13
    for name, fd in (("d_q", central(lambda x: total(q=x), q)), ("d_qd", central(lambda x: total(qd=x), qd))):
        scale = np.maximum(np.abs(fd).max(axis=(1, 2)), 1.0)[:, None, None]
        error = np.abs(getattr(jac, name) - fd) / scale
        assert error.max() <= 1e-7, (name, error.max())
    # Linear in q̈: ∂τ/∂q̈ = −M_A.
    fd_qdd = central(lambda x: total(qdd=x), qdd)
    np.testing.assert_allclose(-jac.added_mass_matrix, fd_qdd, rtol=0, atol=1e-7 * np.abs(fd_qdd).max())
    return jac


def test_paper_leg_without_losses_matches_finite_differences():
    leg = uwml.Leg.paper()
    assert_matches_finite_differences(leg, *random_states(1), water=uwml.Water(density=1025.0))


def test_paper_leg_with_losses_matches_finite_differences():
    leg = uwml.Leg.paper()
    q, qd, qdd = random_states(2)
    depth = np.random.default_rng(3).uniform(0, 3000, q.shape[0])
    joint = uwml.JointLosses(epsilon=1e-2)
    jac = assert_matches_finite_differences(
        leg, q, qd, qdd, depth=depth, temperature_c=4.0, losses=[None, joint, joint], cd=[0.0, 2.0, 2.4]
    )
    # Losses depend on the joint's own speed only: nothing in q, a diagonal in q̇.
    plain = leg.jacobians(q, qd, qdd, cd=[0.0, 2.0, 2.4])
    np.testing.assert_array_equal(jac.d_q, plain.d_q)
    np.testing.assert_array_equal(jac.added_mass_matrix, plain.added_mass_matrix)
    extra = jac.d_qd - plain.d_qd
    off_diagonal = ~np.eye(3, dtype=bool)
    assert np.all(extra[:, off_diagonal] == 0) and np.all(extra[:, 0, 0] == 0)


def test_added_mass_matrix_is_the_references_symmetric_psd_and_gives_the_added_mass_torque():
    leg = uwml.Leg.paper()
    rng = np.random.default_rng(5)
    n = 100
    q = rng.uniform(-3, 3, (n, 3))
    cm = rng.uniform(0.1, 1.5, (3, 2))
    m = leg.jacobians(q, rng.uniform(-2, 2, (n, 3)), rng.uniform(-5, 5, (n, 3)), cm=cm, water=uwml.Water()).added_mass_matrix
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
    added_mass = leg.hydro(q, np.zeros((n, 3)), qdd, cm=cm).added_mass
    np.testing.assert_allclose(added_mass, -np.einsum("sij,sj->si", m, qdd), rtol=0, atol=1e-12 * np.abs(added_mass).max())


def test_a_chain_of_your_own():
    leg = uwml.Leg(
        joints=[uwml.Joint(origin=(0, 0, 0), axis=(0, 0, 1)), uwml.Joint(origin=(0.3, 0.1, 0), axis=(0.6, 0, 0.8))],
        links=[
            uwml.Link(mass=2.0, com=(0.1, 0, 0), volume=1e-3),
            uwml.Link(
                mass=20.0,
                com=(0.5, 0, 0),
                volume=0.00785,
                segment=uwml.Segment(
                    start=(0, 0, 0.1), axis=(0, 1, 0), length=1.0, normals=((0, 0, 1), (1, 0, 0)), widths=(0.1, 0.2), area=0.00785
                ),
            ),
        ],
    )
    q, qd, qdd = random_states(6, n=50, n_joints=2)
    assert_matches_finite_differences(leg, q, qd, qdd, losses=uwml.JointLosses(), depth=500.0)


def test_shapes_of_one_state_and_of_a_batch():
    leg = uwml.Leg.paper()
    one = leg.jacobians([0.1, 0.2, 0.3], [0.5, -0.5, 0.2], [0.0, 1.0, 0.0])
    assert isinstance(one, uwml.EnvironmentJacobians)
    assert one.value.shape == (3,) and one.d_q.shape == one.d_qd.shape == one.added_mass_matrix.shape == (3, 3)
    q, qd, qdd = random_states(7, n=4)
    batch = leg.jacobians(q, qd, qdd, losses=uwml.JointLosses(), depth=[0.0, 10.0, 100.0, 1000.0])
    assert batch.value.shape == (4, 3) and batch.d_q.shape == batch.d_qd.shape == batch.added_mass_matrix.shape == (4, 3, 3)
    for s in range(4):
        single = leg.jacobians(q[s], qd[s], qdd[s], losses=uwml.JointLosses(), depth=[0.0, 10.0, 100.0, 1000.0][s])
        for name in ("value", "d_q", "d_qd", "added_mass_matrix"):
            np.testing.assert_array_equal(getattr(single, name), getattr(batch, name)[s])
    empty = leg.jacobians(np.zeros((0, 3)), np.zeros((0, 3)), np.zeros((0, 3)))
    assert empty.value.shape == (0, 3) and empty.d_q.shape == (0, 3, 3)
    with pytest.raises(AttributeError):
        one.value = one.value  # frozen


@pytest.mark.parametrize(
    ("kwargs", "error", "match"),
    [
        ({"q": [0.0, 0.0]}, ValueError, "q must have shape"),
        ({"qd": [[0.0, 0.0, 0.0]]}, ValueError, "qd must have the same shape"),
        ({"qdd": "fast"}, TypeError, "qdd"),
        ({"q": [0.0, math.nan, 0.0]}, ValueError, r"q\[0, 1\]"),
        ({"qd": [0.0, 0.0, math.inf]}, ValueError, r"qd\[0, 2\]"),
        ({"qdd": [math.nan, 0.0, 0.0]}, ValueError, r"qdd\[0, 0\]"),
        ({"losses": [uwml.JointLosses()]}, ValueError, "one entry per joint"),
        ({"depth": -5.0}, ValueError, "depth"),
        ({"depth": [1.0, 2.0]}, ValueError, "depth"),
        ({"temperature_c": math.nan}, ValueError, "temperature"),
        ({"sea_density": 0.0}, ValueError, "sea_density"),
        ({"cd": -1.0}, ValueError, "cd"),
        ({"cm": [1.0, 2.0]}, ValueError, "cm"),
        ({"water": 1000.0}, TypeError, "water"),
    ],
)
def test_bad_inputs_name_the_argument(kwargs, error, match):
    leg = uwml.Leg.paper()
    arguments = {"q": [0.0, 0.0, 0.0], "qd": [1.0, 0.0, 0.0], "qdd": [0.0, 0.0, 0.0]}
    arguments.update(kwargs)
    with pytest.raises(error, match=match):
        leg.jacobians(**arguments)
