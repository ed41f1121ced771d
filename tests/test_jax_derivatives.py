"""Gradients through ``uwml.jax`` (docs/batched.md): ``uwml.jax.jacobians`` (forward mode) against
the core's dual-number ``uwml.Robot.jacobians`` on a tree on a moving base in a current, away
from kinks (joint speeds away from the losses' smooth sign); the base-twist columns of a base at
rest against central differences of the core's forces; ``jax.grad`` with respect to the model's
parameters (the segments' Cd and Cm, a lumped hull's linear and quadratic damping) against
central differences of the core's forces with those parameters changed (the forces are linear in
them, so the differences are exact to rounding); and finite gradients where the strip integrals
branch: every body at rest, and a cylinder turning about its own end (its normal speed zero at
that end: the circular closed form's ``c = 0``)."""

import dataclasses

import numpy as np
import pytest
import uwml
from robots import motion_arguments, random_robot
from test_robot_lumped import random_lumped

jax = pytest.importorskip("jax")
jax.config.update("jax_enable_x64", True)
import jax.numpy as jnp  # after the guard: needs jax
import uwml.jax as uj

SAMPLES = 6
H = 1e-6


def relative_error(actual: object, expected: np.ndarray) -> float:
    """The largest error relative to each sample's largest entry (at least 1)."""
    actual = np.asarray(actual)
    assert actual.shape == expected.shape, (actual.shape, expected.shape)
    scale = np.maximum(np.max(np.abs(expected).reshape(len(expected), -1), axis=1), 1.0)
    return float(np.max(np.abs(actual - expected).reshape(len(expected), -1).max(axis=1) / scale))


@pytest.fixture(scope="module")
def arm() -> dict:
    """A tree of 4 joints on a hull with a lumped model, losses on every joint."""
    rng = np.random.default_rng(72)
    robot = random_robot(rng, 4, base_body=True, axial=True)
    lumped = random_lumped(rng)  # its damping made definite: the differences below change its entries
    lumped = dataclasses.replace(lumped, linear_damping=np.array(lumped.linear_damping) + 5.0 * np.eye(6))
    hull = dataclasses.replace(robot.base, lumped=lumped)
    robot = uwml.Robot(robot.joints, robot.links, base=hull, losses=uwml.JointLosses())
    assert {s.section for s in robot.segments} == {"rectangular", "circular"} and {j.kind for j in robot.joints} == {
        "revolute",
        "prismatic",
    }
    qd = rng.uniform(0.1, 2.0, (SAMPLES, 4)) * rng.choice([-1.0, 1.0], (SAMPLES, 4))
    state = (rng.uniform(-3, 3, (SAMPLES, 4)), qd, rng.uniform(-5, 5, (SAMPLES, 4)))
    return {"robot": robot, "state": state, "rng": rng}


@pytest.fixture(scope="module")
def jacobians():
    return jax.jit(jax.vmap(uj.jacobians, in_axes=(None, 0, 0, 0, 0, None, None)))


def test_jacobians_match_the_cores_dual_numbers_on_a_moving_base(arm: dict, jacobians) -> None:
    robot, rng = arm["robot"], arm["rng"]
    conditions = uwml.Conditions(
        base_motion=uwml.BaseMotion(**motion_arguments(rng, SAMPLES)),
        current=rng.normal(size=(SAMPLES, 3)),
        depth=500.0,
        temperature_c=4.0,
    )
    got = jacobians(uj.compile_robot(robot, conditions), *arm["state"], uj.motion(conditions, samples=SAMPLES), 500.0, 4.0)
    expected = robot.jacobians(*arm["state"], conditions)
    for name in ("value", "d_q", "d_velocity", "added_mass_matrix"):
        assert relative_error(getattr(got, name), getattr(expected, name)) <= 1e-10, name


def test_base_twist_derivatives_of_a_base_at_rest_match_central_differences(arm: dict, jacobians) -> None:
    """At a base at rest in still water the velocity columns of the base twist are the hull's
    damping and the arm's drag slopes, which central differences of the core's forces give."""
    robot = arm["robot"]
    q, qd, qdd = arm["state"]
    got = jacobians(uj.compile_robot(robot), q, qd, qdd, uj.motion(uwml.Conditions(), samples=SAMPLES), 0.0, 20.0)

    def forces(velocity: np.ndarray, angular_velocity: np.ndarray) -> np.ndarray:
        result = robot.environment(q, qd, qdd, base_motion=uwml.BaseMotion(velocity=velocity, angular_velocity=angular_velocity))
        return np.concatenate([result.base.total, result.total], axis=1)

    def central(k: int, h: float) -> np.ndarray:
        step = np.zeros(6)
        step[k] = h
        return (forces(step[:3], step[3:]) - forces(-step[:3], -step[3:])) / (2 * h)

    # The hull's d|ν|ν at ν = 0 puts d·h in a central difference: Richardson's step removes it.
    columns = [2.0 * central(k, H) - central(k, 2 * H) for k in range(6)]
    assert relative_error(np.asarray(got.d_velocity)[:, :, :6], np.stack(columns, axis=-1)) <= 1e-7


def test_parameter_gradients_match_central_differences_of_the_core(arm: dict) -> None:
    """``jax.grad`` of a weighted sum of every force on base and joints, under ``jit`` and over a
    batch (``vmap``), with respect to the segments' Cd and Cm and the hull's damping."""
    robot, rng = arm["robot"], arm["rng"]
    q, qd, qdd = arm["state"]
    conditions = uwml.Conditions(base_motion=uwml.BaseMotion(**motion_arguments(rng, SAMPLES)), current=rng.normal(size=(SAMPLES, 3)))
    weights = rng.normal(size=(SAMPLES, 6 + robot.n_joints))

    def weighted(model, q, qd, qdd, motion, w):
        result = uj.hydro(model, q, qd, qdd, motion)
        return jnp.dot(w, jnp.concatenate([result.base.total, result.total]))

    gradient = jax.jit(jax.vmap(jax.grad(weighted), in_axes=(None, 0, 0, 0, 0, 0)))
    grads = gradient(uj.compile_robot(robot, conditions), q, qd, qdd, uj.motion(conditions, samples=SAMPLES), weights)

    def core(robot: uwml.Robot, **changes: np.ndarray) -> np.ndarray:
        result = robot.hydro(q, qd, qdd, conditions.replace(**changes))
        return np.sum(weights * np.concatenate([result.base.total, result.total], axis=1), axis=1)

    count = len(robot.segments)
    for name in ("cd", "cm"):
        own = np.array([getattr(s, name) for s in robot.segments])
        for k in range(count):
            circular = robot.segments[k].section == "circular"
            for d in (0,) if circular else (0, 1):
                step = np.zeros((count, 2))
                step[k, (0, 1) if circular else d] = H
                fd = (core(robot, **{name: own + step}) - core(robot, **{name: own - step})) / (2 * H)
                got = (
                    np.asarray(getattr(grads.segments, name))[:, k].sum(axis=-1)
                    if circular
                    else np.asarray(getattr(grads.segments, name))[:, k, d]
                )
                np.testing.assert_allclose(got, fd, rtol=1e-6, atol=1e-6 * np.abs(fd).max(), err_msg=f"{name}[{k}, {d}]")
    hull = robot.base.lumped

    def changed(name: str, index: tuple[int, ...], step: float) -> uwml.Robot:
        values = np.array(getattr(hull, name))
        values[index] += step
        lumped = dataclasses.replace(hull, **{name: values})
        return uwml.Robot(robot.joints, robot.links, base=dataclasses.replace(robot.base, lumped=lumped))

    for name, index in (("linear_damping", (0, 0)), ("linear_damping", (4, 1)), ("quadratic_damping", (2,)), ("quadratic_damping", (5,))):
        fd = (core(changed(name, index, H)) - core(changed(name, index, -H))) / (2 * H)
        got = np.asarray(getattr(grads.lumped, name))[(slice(None), 0, *index)]
        np.testing.assert_allclose(got, fd, rtol=1e-6, atol=1e-6 * np.abs(fd).max(), err_msg=f"{name}{index}")


def test_gradients_are_finite_where_the_strip_integrals_branch() -> None:
    """A cylinder turning about its own start (the circular closed form at ``c = 0``, its speed
    zero at an end), a box hanging from the next joint, a hull with a lumped model: gradients in
    ``q``, ``q̇``, ``q̈`` at rest and in motion are finite and, in motion, central differences of
    the core's forces."""
    rod = uwml.Segment((0, 0, 0), (1, 0, 0), 0.5, section="circular", diameter=0.1)
    box = uwml.Segment((0, 0, 0), (0, 0, -1), 0.4, normals=((1, 0, 0), (0, 1, 0)), widths=(0.1, 0.2), area=0.02)
    lumped = uwml.LumpedModel(added_mass=np.eye(6), linear_damping=np.eye(6), quadratic_damping=np.ones(6))
    robot = uwml.Robot(
        [uwml.Joint((0, 0, 0), (0, 0, 1)), uwml.Joint((0.5, 0, 0), (0, 1, 0))],
        [uwml.Link(1.0, (0.25, 0, 0), 0.001, segments=[rod]), uwml.Link(1.0, (0, 0, -0.2), 0.001, segments=[box])],
        base=uwml.Link(2.0, (0, 0, 0), 0.002, lumped=lumped),
    )
    model = uj.compile_robot(robot)

    def total(q, qd, qdd):
        result = uj.hydro(model, q, qd, qdd)
        return jnp.sum(result.total) + jnp.sum(result.base.total)

    gradient = jax.jit(jax.grad(total, argnums=(0, 1, 2)))
    q = np.array([0.3, 0.2])
    for qd in ([0.0, 0.0], [1.0, 0.0], [0.0, -1.0], [0.7, 1.3], [-1.1, 0.4]):
        grads = [np.asarray(g) for g in gradient(q, np.array(qd), np.zeros(2))]
        assert all(np.all(np.isfinite(g)) for g in grads), (qd, grads)
        if qd == [0.0, 0.0]:
            assert np.all(grads[1] == 0.0), "no drag slope at rest"
        if 0.0 in qd:
            continue  # central differences of v|v| at v = 0 are off by O(h): compared in motion

        def core(rates: np.ndarray) -> float:
            result = robot.hydro(q, rates, np.zeros(2), base=True)
            return float(np.sum(result.total) + np.sum(result.base.total))

        fd = [(core(np.array(qd) + step) - core(np.array(qd) - step)) / (2 * H) for step in np.eye(2) * H]
        np.testing.assert_allclose(grads[1], fd, rtol=1e-6, atol=1e-6)
