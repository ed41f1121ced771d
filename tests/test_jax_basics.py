"""``uwml.jax`` (docs/batched.md) on cases written out by hand and in float32: a two-link arm at rest
in still water (no drag, no added mass; buoyancy and weight the moments of ``ρ V g`` and ``m g``
typed here); float32 within its stated tolerance of float64 on a tree on a moving base; the dtype
following the joint state; the model as a pytree (one compilation per structure); and the
conditions read from a ``uwml.Conditions``."""

import math

import numpy as np
import pytest
import uwml
from robots import motion_arguments, random_robot
from test_robot_lumped import with_lumped

jax = pytest.importorskip("jax")
jax.config.update("jax_enable_x64", True)
import uwml.jax as uj  # after the guard: needs jax

RHO, G = 1025.0, 9.81
#: float32 against float64, relative to the largest force of each kind over the batch
#: (docs/batched.md, "Precision").
F32_TOLERANCE = 1e-5


def arm(lengths: tuple[float, float] = (0.5, 0.4)) -> uwml.Robot:
    """A yaw joint at the base origin, then a pitch joint (axis y) at ``(L1, 0, 0)``; each link's
    COM at ``(a_i, 0, 0)`` and COB at ``(b_i, 0, 0)``; a box and a cylinder along the links, a
    lumped hull on the base."""
    l1, l2 = lengths
    box = uwml.Segment((0, 0, 0), (1, 0, 0), l1, normals=((0, 1, 0), (0, 0, 1)), widths=(0.1, 0.2), area=0.02)
    rod = uwml.Segment((0, 0, 0), (1, 0, 0), l2, section="circular", diameter=0.08)
    hull = uwml.LumpedModel(added_mass=np.diag([5.0, 6, 7, 1, 1, 1]), linear_damping=np.eye(6), quadratic_damping=np.ones(6))
    return uwml.Robot(
        [uwml.Joint((0, 0, 0), (0, 0, 1)), uwml.Joint((l1, 0, 0), (0, 1, 0))],
        [
            uwml.Link(3.0, (0.2, 0, 0), 0.002, cob=(0.25, 0, 0), segments=[box]),
            uwml.Link(2.0, (0.15, 0, 0), 0.0015, cob=(0.1, 0, 0), segments=[rod]),
        ],
        base=uwml.Link(10.0, (0.0, 0.0, 0.1), 0.01, lumped=hull),
        water=uwml.Water(RHO, G),
    )


def test_a_robot_at_rest_feels_only_buoyancy_and_weight_their_moments_by_hand() -> None:
    """Link 1's points ``a (c1 c2, s1 c2, −s2)`` from the elbow ``L1 (c1, s1, 0)``; an upward force
    ``f`` there turns the pitch joint (axis ``(−s1, c1, 0)``) by ``−a cos q2 f`` and the yaw joint
    not at all."""
    robot = arm()
    q1, q2 = 0.4, -0.7
    result = jax.jit(uj.hydro)(uj.compile_robot(robot), np.array([q1, q2]), np.zeros(2), np.zeros(2))
    assert np.all(np.asarray(result.drag) == 0.0) and np.all(np.asarray(result.added_mass) == 0.0)
    assert np.all(np.asarray(result.base.drag) == 0.0) and np.all(np.asarray(result.base.added_mass) == 0.0)
    up = {"buoyancy": [RHO * G * v for v in (0.01, 0.002, 0.0015)], "gravity": [-G * m for m in (10.0, 3.0, 2.0)]}
    arms = {"buoyancy": [(0.0, 0.0, 0.1), 0.25, 0.1], "gravity": [(0.0, 0.0, 0.1), 0.2, 0.15]}
    c1, s1, c2, s2 = math.cos(q1), math.sin(q1), math.cos(q2), math.sin(q2)
    for part in ("buoyancy", "gravity"):
        f0, f1, f2 = up[part]
        origin, a1, a2 = arms[part]
        np.testing.assert_allclose(getattr(result, part), [0.0, -a2 * c2 * f2], atol=1e-12)
        points = [np.array(origin), a1 * np.array([c1, s1, 0.0]), 0.5 * np.array([c1, s1, 0.0]) + a2 * np.array([c1 * c2, s1 * c2, -s2])]
        forces = [np.array([0.0, 0.0, f]) for f in (f0, f1, f2)]
        wrench = np.concatenate([sum(forces), sum(np.cross(p, f) for p, f in zip(points, forces))])
        np.testing.assert_allclose(getattr(result.base, part), wrench, atol=1e-12)
    # Net: (ρV − m) g at each body (here COM and COB differ, so the two moments are apart).
    np.testing.assert_allclose(np.asarray(result.buoyancy + result.gravity)[1], -(0.1 * RHO * 0.0015 - 0.15 * 2.0) * G * c2, atol=1e-12)


def test_float32_is_within_its_tolerance_of_float64() -> None:
    rng = np.random.default_rng(9)
    robot = with_lumped(random_robot(rng, 4, base_body=True, axial=True), rng)
    samples = 64
    state = [rng.uniform(-3, 3, (samples, 4)), rng.uniform(-2, 2, (samples, 4)), rng.uniform(-5, 5, (samples, 4))]
    conditions = uwml.Conditions(base_motion=uwml.BaseMotion(**motion_arguments(rng, samples)), current=rng.normal(size=(samples, 3)))
    model, motion = uj.compile_robot(robot, conditions), uj.motion(conditions, samples=samples)
    hydro = jax.jit(jax.vmap(uj.hydro, in_axes=(None, 0, 0, 0, 0)))
    wide = hydro(model, *state, motion)
    narrow = hydro(model, *(x.astype(np.float32) for x in state), jax.tree_util.tree_map(lambda x: x.astype(np.float32), motion))
    assert wide.drag.dtype == np.float64 and narrow.drag.dtype == np.float32 and narrow.base.total.dtype == np.float32
    for name in ("drag", "added_mass", "buoyancy", "gravity"):
        for what, a, b in (
            (name, getattr(wide, name), getattr(narrow, name)),
            (f"base.{name}", getattr(wide.base, name), getattr(narrow.base, name)),
        ):
            a, b = np.asarray(a), np.asarray(b, dtype=np.float64)
            error = np.max(np.abs(a - b)) / np.max(np.abs(a))
            assert error <= F32_TOLERANCE, f"{what}: {error:.3g}"


def test_the_model_is_a_pytree_compiled_once_per_structure() -> None:
    """Two robots of one structure and different numbers share a compiled function; the model's
    leaves are its arrays (``jax.grad`` returns a model of gradients)."""
    traces = []

    def total(model, q):
        traces.append(1)
        return uj.hydro(model, q, q, q).total.sum()

    evaluate = jax.jit(total)
    one, other = uj.compile_robot(arm((0.5, 0.4))), uj.compile_robot(arm((0.6, 0.3)))
    assert jax.tree_util.tree_structure(one) == jax.tree_util.tree_structure(other)
    first, second = evaluate(one, np.array([0.1, 0.2])), evaluate(other, np.array([0.1, 0.2]))
    assert len(traces) == 1 and first != second
    grads = jax.jit(jax.grad(total))(one, np.array([0.1, 0.2]))
    assert isinstance(grads, uj.RobotModel) and grads.segments.cd.shape == (2, 2)


def test_the_motion_of_conditions() -> None:
    rotation = np.array([0.0, 1.0, 0.0, 0.0])
    single = uj.motion(uwml.Conditions(base_motion=uwml.BaseMotion(orientation=rotation), current=(0.1, 0.2, 0.3)))
    np.testing.assert_array_equal(single.orientation, rotation)
    np.testing.assert_array_equal(single.current, [0.1, 0.2, 0.3])
    assert single.velocity.shape == (3,) and single.current_acceleration.shape == (3,)
    per_sample = uwml.Conditions(current=np.ones((4, 3)))
    batch = uj.motion(per_sample, samples=4)
    assert batch.orientation.shape == (4, 4) and batch.current.shape == (4, 3)
    with pytest.raises(ValueError, match="pass samples="):
        uj.motion(per_sample)
    with pytest.raises(ValueError, match=r"the conditions have \[4\] samples, not 5"):
        uj.motion(per_sample, samples=5)
    with pytest.raises(TypeError, match="robot must be a uwml.Robot"):
        uj.compile_robot("arm")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"cd must be a scalar, \(2,\) or \(2, 2\)"):
        uj.compile_robot(arm(), uwml.Conditions(cd=np.ones(3)))
