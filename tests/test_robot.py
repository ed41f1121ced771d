"""``uwml.Robot`` (the Rust path) held against the numpy reference ``uwml.reference.robot_hydro``
on random trees, base motions and currents (to 1e-10 of each sample's forces), and checked for
its inputs: shapes, broadcasting, orientations, errors that name the argument.

Expected values come from the reference (an independent numpy implementation) or from numbers
written here. Serial chains against the chain reference are ``test_chain_reference.py``'s.
"""

import numpy as np
import pytest
import uwml
from hypothesis import given, settings
from hypothesis import strategies as st
from robots import COMPONENTS, RTOL_REFERENCE, assert_close, motion_arguments, random_quaternions, random_robot
from scipy.spatial.transform import Rotation
from uwml import reference as ref

EXAMPLES = settings(max_examples=max(5, int(settings.default.max_examples / 4)))


@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 9), form=st.sampled_from(["morison", "kirchhoff"]))
def test_core_matches_the_reference_on_random_trees_in_moving_water(seed: int, n: int, form: str) -> None:
    """Both added-mass forms: the reference computes Kirchhoff's terms otherwise (a turning
    added-mass tensor per slice, by Gauss-Legendre quadrature; the core: closed-form moments)."""
    rng = np.random.default_rng(seed)
    robot = random_robot(rng, n, base_body=bool(rng.random() < 0.8), axial=bool(rng.random() < 0.5))
    samples = 20
    q, qd, qdd = rng.uniform(-3, 3, (samples, n)), rng.uniform(-2, 2, (samples, n)), rng.uniform(-5, 5, (samples, n))
    motion = motion_arguments(rng, samples)
    current, current_acceleration = rng.normal(size=(samples, 3)), rng.normal(size=(samples, 3))
    density, gravity = rng.uniform(990, 1040), rng.uniform(9.7, 9.9)
    # Per-evaluation coefficients half of the time (circular segments take one per segment).
    cd = cm = None
    if rng.random() < 0.5:
        circular = np.array([s.section == "circular" for s in robot.segments], dtype=bool)
        cd = rng.uniform(0.5, 2.5, (len(robot.segments), 2))
        cm = rng.uniform(0.1, 1.5, (len(robot.segments), 2))
        cd[circular, 1], cm[circular, 1] = cd[circular, 0], cm[circular, 0]
    result = robot.hydro(
        q, qd, qdd, cd=cd, cm=cm, water=uwml.Water(density, gravity), base_motion=uwml.BaseMotion(**motion), current=current,
        current_acceleration=current_acceleration, added_mass=form,
    )  # fmt: skip
    expected = ref.robot_hydro(
        robot.joints, robot.links, robot.base, q, qd, qdd, cd=cd, cm=cm, density=density, gravity=gravity,
        current=current, current_acceleration=current_acceleration, added_mass=form, **motion,
    )  # fmt: skip
    assert_matches_reference(result, expected)


def assert_matches_reference(result: uwml.Torques, expected: dict[str, np.ndarray]) -> None:
    actual = {name: getattr(result, name) for name in COMPONENTS} | {f"base_{name}": getattr(result.base, name) for name in COMPONENTS}
    scale = np.maximum.reduce([np.max(np.abs(expected[k]), axis=1) for k in actual]) + 1e-300
    for key, value in actual.items():
        assert_close(value, expected[key], scale, RTOL_REFERENCE, key)


@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 9), form=st.sampled_from(["morison", "kirchhoff"]))
def test_core_matches_the_reference_on_random_trees_on_a_base_at_rest_in_still_water(seed: int, n: int, form: str) -> None:
    """A base at rest (tilted) in still water, where the core skips the products with the zero
    motion of the base and of the joints' first links; axes along coordinate axes half of the
    time, where the body frames of parent and child agree or differ by a quarter turn."""
    rng = np.random.default_rng(seed)
    robot = random_robot(rng, n, base_body=bool(rng.random() < 0.8), axes="mixed")
    samples = 20
    q, qd, qdd = rng.uniform(-3, 3, (samples, n)), rng.uniform(-2, 2, (samples, n)), rng.uniform(-5, 5, (samples, n))
    orientation = random_quaternions(rng, 1) if rng.random() < 0.5 else np.array([[1.0, 0.0, 0.0, 0.0]])
    result = robot.hydro(q, qd, qdd, base_motion=uwml.BaseMotion(orientation=orientation[0]), added_mass=form)
    expected = ref.robot_hydro(
        robot.joints, robot.links, robot.base, q, qd, qdd, density=robot.water.density, gravity=robot.water.gravity,
        orientation=orientation[0], added_mass=form,
    )  # fmt: skip
    assert_matches_reference(result, expected)


def test_joints_and_links_may_be_any_iterables() -> None:
    leg = uwml.paper_leg()
    robot = uwml.Robot((j for j in leg.joints), iter(leg.links), losses=uwml.JointLosses())
    assert robot.joints == leg.joints and len(robot.losses) == 3
    named = uwml.Joint((0, 0, 0), (0, 0, 1), name="knee")
    with pytest.raises(ValueError, match="joint names must be unique; 'knee' is given more than once"):
        uwml.Robot((j for j in (named, named)), iter(leg.links[:2]))


def test_a_cylinder_dragged_broadside_by_its_base() -> None:
    # A horizontal cylinder (length L, diameter D) on a base moving at U across it: the base
    # feels −½ρ Cd D L U|U|; at rest in a current c, +½ρ Cd D L c|c|; along its axis, nothing.
    length, diameter, cd, rho = 0.8, 0.1, 1.1, 1025.0
    rod = uwml.Link(
        0.0, (0, 0, 0), 0.0, segments=[uwml.Segment((-0.4, 0, 0), (1, 0, 0), length, section="circular", diameter=diameter, cd=cd, cm=0.0)]
    )
    robot = uwml.Robot([uwml.Joint((0, 0, 0), (0, 0, 1))], [uwml.Link(0.0, (0, 0, 0), 0.0)], base=rod)
    water = uwml.Water(rho, 9.81)
    expected = -0.5 * rho * cd * diameter * length * 0.7 * 0.7
    moving = robot.hydro([0.0], [0.0], [0.0], water=water, base_motion=uwml.BaseMotion(velocity=(0, 0.7, 0)))
    np.testing.assert_allclose(moving.base.drag, [0, expected, 0, 0, 0, 0], atol=1e-12)
    drifting = robot.hydro([0.0], [0.0], [0.0], water=water, current=(0, 0.7, 0))
    np.testing.assert_allclose(drifting.base.drag, [0, -expected, 0, 0, 0, 0], atol=1e-12)
    # The base turned a quarter about z: the same current now runs along the rod.
    quarter = uwml.BaseMotion(orientation=Rotation.from_euler("z", 90, degrees=True))
    along = robot.hydro([0.0], [0.0], [0.0], water=water, base_motion=quarter, current=(0, 0.7, 0))
    np.testing.assert_allclose(along.base.drag, np.zeros(6), atol=1e-12)


def test_broadcasting_shapes_and_threads() -> None:
    rng = np.random.default_rng(4)
    robot = random_robot(rng, 4)
    q = rng.uniform(-1, 1, 4)
    single = robot.hydro(q, q, q, current=(0.1, 0.2, 0.0))
    assert single.drag.shape == (4,) and single.base.drag.shape == (6,)
    motion = motion_arguments(rng, 7)
    batch = robot.hydro(q, q, q, base_motion=uwml.BaseMotion(**motion))
    assert batch.drag.shape == (7, 4) and batch.base.total.shape == (7, 6)
    for i in (0, 6):
        one = robot.hydro(q, q, q, base_motion=uwml.BaseMotion(**{k: v[i] for k, v in motion.items()}))
        np.testing.assert_array_equal(batch.total[i], one.total)
        np.testing.assert_array_equal(batch.base.total[i], one.base.total)
    many = rng.uniform(-1, 1, (101, 4))
    motion = motion_arguments(rng, 101)
    arguments = {"base_motion": uwml.BaseMotion(**motion), "current": rng.normal(size=(101, 3))}
    one_thread = robot.hydro(many, many, many, **arguments)
    two_threads = robot.hydro(many, many, many, **arguments, threads=2)
    for name in COMPONENTS:
        np.testing.assert_array_equal(getattr(one_thread, name), getattr(two_threads, name))
        np.testing.assert_array_equal(getattr(one_thread.base, name), getattr(two_threads.base, name))


def test_orientation_as_a_scipy_rotation_or_a_quaternion() -> None:
    rng = np.random.default_rng(5)
    robot = random_robot(rng, 3)
    q = rng.uniform(-1, 1, 3)
    rotations = Rotation.random(5, random_state=3)
    by_rotation = robot.hydro(q, q, q, base_motion=uwml.BaseMotion(orientation=rotations))
    quaternions = rotations.as_quat(scalar_first=True)
    by_numbers = robot.hydro(q, q, q, base_motion=uwml.BaseMotion(orientation=quaternions))
    np.testing.assert_array_equal(by_rotation.base.total, by_numbers.base.total)
    # −q is the same rotation.
    flipped = robot.hydro(q, q, q, base_motion=uwml.BaseMotion(orientation=-quaternions))
    np.testing.assert_allclose(flipped.base.total, by_numbers.base.total, rtol=1e-13, atol=1e-12)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"base_motion": "fixed"}, "base_motion must be a uwml.BaseMotion"),
        ({"current": (0.0, 1.0)}, r"current must have shape \(3,\)"),
        ({"current": (0.0, np.nan, 0.0)}, "current must be finite"),
        ({"current_acceleration": np.zeros((2, 3)), "current": np.zeros((3, 3))}, "must agree on the number of samples"),
        ({"cd": [1.0, 2.0, 3.0]}, "cd must be None, a scalar"),
        ({"cm": -1.0}, "cm must be finite and non-negative"),
    ],
)
def test_bad_arguments_name_themselves(kwargs: dict, message: str) -> None:
    robot = random_robot(np.random.default_rng(6), 2)
    with pytest.raises((ValueError, TypeError), match=message):
        robot.hydro([0.0, 0.0], [0.0, 0.0], [0.0, 0.0], **kwargs)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"orientation": (0.0, 0.0, 0.0, 0.0)}, "unit quaternion"),
        ({"orientation": (1.0, 0.1, 0.0, 0.0)}, "unit quaternion"),
        ({"orientation": (1.0, 0.0, 0.0)}, r"orientation must have shape \(4,\)"),
        ({"velocity": (0.0, np.inf, 0.0)}, "velocity must be finite"),
        ({"angular_acceleration": np.zeros((2, 2))}, r"angular_acceleration must have shape \(3,\)"),
    ],
)
def test_bad_base_motions_name_themselves(kwargs: dict, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        uwml.BaseMotion(**kwargs)


def test_bad_robots_name_the_joint_link_or_segment() -> None:
    link = uwml.Link(1.0, (0, 0, 0), 0.001)
    with pytest.raises(ValueError, match=r"joints\[1\].parent must be -1 \(the base\) or an earlier link"):
        uwml.Robot([uwml.Joint((0, 0, 0), (0, 0, 1)), uwml.Joint((0, 0, 0), (0, 0, 1), parent=1)], [link, link])
    with pytest.raises(ValueError, match="joint.parent must be -1"):
        uwml.Joint((0, 0, 0), (0, 0, 1), parent=-2)
    with pytest.raises(ValueError, match="joint.kind must be one of"):
        uwml.Joint((0, 0, 0), (0, 0, 1), kind="spherical")
    with pytest.raises(ValueError, match="segment.section must be one of"):
        uwml.Segment((0, 0, 0), (1, 0, 0), 1.0, section="elliptic", diameter=0.1)
    with pytest.raises(ValueError, match="a circular segment needs segment.diameter"):
        uwml.Segment((0, 0, 0), (1, 0, 0), 1.0, section="circular")
    with pytest.raises(TypeError, match="circular segment must be one number"):
        uwml.Segment((0, 0, 0), (1, 0, 0), 1.0, section="circular", diameter=0.1, cd=(1.0, 2.0))
    with pytest.raises(ValueError, match="a rectangular segment needs segment.normals"):
        uwml.Segment((0, 0, 0), (1, 0, 0), 1.0)
    with pytest.raises(TypeError, match=r"link.segments\[0\] must be a uwml.Segment"):
        uwml.Link(1.0, (0, 0, 0), 0.001, segments=["rod"])
    robot = random_robot(np.random.default_rng(2), 2)
    with pytest.raises(ValueError, match=r"q must have shape \(2,\) or \(n_samples, 2\)"):
        robot.hydro([0.0], [0.0], [0.0])
    with pytest.raises(ValueError, match=r"qd\[0, 1\] is NaN: joint states must be finite"):
        robot.hydro([0.0, 0.0], [0.0, np.nan], [0.0, 0.0])


@EXAMPLES
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 8))
def test_link_wrenches_and_added_mass_matrix_match_the_reference(seed: int, n: int) -> None:
    rng = np.random.default_rng(seed)
    robot = random_robot(rng, n, base_body=bool(rng.random() < 0.8))
    samples = 6
    q, qd, qdd = rng.uniform(-3, 3, (samples, n)), rng.uniform(-2, 2, (samples, n)), rng.uniform(-5, 5, (samples, n))
    motion = motion_arguments(rng, samples)
    current = rng.normal(size=(samples, 3))
    wrenches = robot.link_wrenches(q, qd, qdd, base_motion=uwml.BaseMotion(**motion), current=current)
    expected = ref.robot_link_wrenches(robot.joints, robot.links, robot.base, q, qd, qdd, current=current, **motion)
    assert wrenches.shape == expected.shape == (samples, n + 1, 6)
    scale = np.max(np.abs(expected).reshape(samples, -1), axis=1) + 1e-300
    assert_close(wrenches, expected, scale, RTOL_REFERENCE, "link wrenches")
    matrices = robot.added_mass_matrix(q)
    expected_matrices = ref.robot_added_mass_matrix(robot.joints, robot.links, robot.base, q)
    assert matrices.shape == (samples, n + 6, n + 6)
    scale = np.max(np.abs(expected_matrices).reshape(samples, -1), axis=1) + 1e-300
    assert_close(matrices, expected_matrices, scale, RTOL_REFERENCE, "added-mass matrix")
    np.testing.assert_array_equal(matrices, np.swapaxes(matrices, 1, 2))
    assert np.all(np.linalg.eigvalsh(matrices) >= -1e-12 * scale[:, None])
    # −M_A times the accelerations is the added-mass part at zero velocity.
    still = robot.hydro(
        q,
        np.zeros_like(q),
        qdd,
        base_motion=uwml.BaseMotion(acceleration=motion["acceleration"], angular_acceleration=motion["angular_acceleration"]),
    )
    accelerations = np.concatenate([motion["acceleration"], motion["angular_acceleration"], qdd], axis=1)
    forces = np.concatenate([still.base.added_mass, still.added_mass], axis=1)
    assert_close(-np.einsum("sij,sj->si", matrices, accelerations), forces, np.max(np.abs(forces), axis=1) + scale, 1e-12, "M_A a")


def test_identifying_cd_and_cm_of_an_arm_on_a_moving_vehicle() -> None:
    # Synthetic: torques of a 3-joint arm of cylinders on a surging, pitching ROV in a current,
    # at known Cd = 1.05 and Cm = 0.85 (generated by the model itself, plus noise); least squares
    # on the regressors recovers them, and regressors times coefficients are the forces.
    rng = np.random.default_rng(12)
    cylinder = lambda axis, length, d: uwml.Segment((0, 0, 0), axis, length, section="circular", diameter=d)
    arm = uwml.Robot(
        joints=[uwml.Joint((0.6, 0, -0.3), (0, 0, 1), parent=-1), uwml.Joint((0, 0, -0.3), (0, 1, 0)), uwml.Joint((0.5, 0, 0), (0, 1, 0))],
        links=[
            uwml.Link(5.0, (0, 0, -0.15), 0.003, segments=[cylinder((0, 0, -1), 0.3, 0.12)]),
            uwml.Link(4.0, (0.25, 0, 0), 0.002, segments=[cylinder((1, 0, 0), 0.5, 0.09)]),
            uwml.Link(3.0, (0.2, 0, 0), 0.0015, segments=[cylinder((1, 0, 0), 0.4, 0.07)]),
        ],
        base=uwml.Link(300.0, (0, 0, 0), 0.29, segments=[cylinder((1, 0, 0), 1.8, 0.6)]),
    )
    t = np.linspace(0, 20, 4000)
    q = np.stack([0.8 * np.sin(0.7 * t), 0.5 * np.sin(1.1 * t + 1), 0.9 * np.sin(1.3 * t)], axis=1)
    qd = np.gradient(q, t, axis=0)
    qdd = np.gradient(qd, t, axis=0)
    pitch = 0.1 * np.sin(0.5 * t)
    motion = uwml.BaseMotion(
        orientation=np.stack([np.cos(pitch / 2), 0 * t, np.sin(pitch / 2), 0 * t], axis=1),
        velocity=np.stack([0.4 + 0.1 * np.sin(0.3 * t), 0 * t, 0 * t], axis=1),
        angular_velocity=np.stack([0 * t, 0.05 * np.cos(0.5 * t), 0 * t], axis=1),
    )
    current = (0.2, 0.1, 0.0)
    truth = arm.hydro(q, qd, qdd, cd=1.05, cm=0.85, base_motion=motion, current=current)
    regressors = arm.hydro_regressors(q, qd, qdd, base_motion=motion, current=current)
    again = regressors.torques(1.05, 0.85)
    scale = np.abs(truth.total).max()
    np.testing.assert_allclose(again.total, truth.total, rtol=0, atol=1e-12 * scale)
    np.testing.assert_allclose(again.base.total, truth.base.total, rtol=0, atol=1e-12 * np.abs(truth.base.total).max())
    measured = truth.total + rng.normal(0, 0.01 * scale, truth.total.shape)
    design = np.stack([regressors.drag.sum(axis=(-1, -2)).ravel(), regressors.added_mass.sum(axis=(-1, -2)).ravel()], axis=1)
    (cd, cm), *_ = np.linalg.lstsq(design, (measured - regressors.buoyancy).ravel(), rcond=None)
    assert abs(cd - 1.05) < 0.02 and abs(cm - 0.85) < 0.02, (cd, cm)


def test_the_example_arm_on_an_rov_matches_the_reference() -> None:
    from uwml.examples import arm_on_rov

    arm = arm_on_rov()
    assert arm.n_joints == 7 and len(arm.segments) == 15 and arm.joints[6].kind == "prismatic"
    rng = np.random.default_rng(30)
    q, qd, qdd = rng.uniform(-1, 1, (10, 7)), rng.uniform(-0.5, 0.5, (10, 7)), rng.uniform(-2, 2, (10, 7))
    motion = motion_arguments(rng, 10)
    result = arm.hydro(q, qd, qdd, base_motion=uwml.BaseMotion(**motion), current=(0.3, 0.1, 0.0))
    expected = ref.robot_hydro(arm.joints, arm.links, arm.base, q, qd, qdd, current=(0.3, 0.1, 0.0), **motion)
    for name in COMPONENTS:
        scale = np.max(np.abs(expected[f"base_{name}"]), axis=1) + 1e-300
        assert_close(getattr(result.base, name), expected[f"base_{name}"], scale, RTOL_REFERENCE, name)
    # The hull floats: buoyancy 0.29 m³ of fresh water against 300 kg, both on the base wrench.
    still = arm.hydro(np.zeros(7), np.zeros(7), np.zeros(7))
    total_mass = 300.0 + sum(link.mass for link in arm.links)
    total_volume = 0.29 + sum(link.volume for link in arm.links)
    np.testing.assert_allclose(still.base.gravity[2], -total_mass * 9.81, rtol=1e-14)
    np.testing.assert_allclose(still.base.buoyancy[2], 1000.0 * total_volume * 9.81, rtol=1e-14)


def test_the_tours_example_of_an_arm_on_a_moving_rov_runs() -> None:
    from pathlib import Path

    readme = (Path(__file__).resolve().parents[1] / "docs" / "tour.md").read_text(encoding="utf-8")
    section = readme.split("## Whole robots", 1)[1]
    code = section.split("```python\n", 1)[1].split("```", 1)[0]
    namespace: dict = {}
    exec(compile(code, "docs/tour.md", "exec"), namespace)  # noqa: S102 - the tour's own example
    result = namespace["result"]
    assert result.total.shape == (7,) and result.base.total.shape == (6,)
    assert np.all(np.isfinite(result.base.total)) and abs(result.base.total[1]) > 0.0


def test_a_circular_section_does_not_depend_on_its_normals() -> None:
    # The core's circular section has no normals at all; the reference is given two different
    # orthonormal pairs for the same cylinder (turned about its axis) and must agree with both.
    import copy

    rng = np.random.default_rng(50)
    axis = np.array([0.3, -0.5, 0.81])
    axis /= np.linalg.norm(axis)
    cylinder = uwml.Segment((0.1, 0, 0), axis, 0.7, section="circular", diameter=0.1, cd=1.1, cm=0.9)
    robot = uwml.Robot(
        [uwml.Joint((0, 0, 0), (0, 1, 0)), uwml.Joint((0.4, 0, 0), (0, 0, 1))],
        [uwml.Link(3.0, (0.2, 0, 0), 0.002), uwml.Link(2.0, (0.3, 0, 0), 0.001, segments=[cylinder])],
    )
    q, qd, qdd = rng.uniform(-1, 1, (3, 30, 2))
    motion = motion_arguments(rng, 30)
    core = robot.hydro(q, qd, qdd, base_motion=uwml.BaseMotion(**motion), current=(0.2, -0.1, 0.0))
    n0, n1 = (np.asarray(n) for n in cylinder.normals)
    for angle in (0.0, 0.7, 2.0):
        turned = copy.copy(cylinder)
        object.__setattr__(
            turned, "normals", (tuple(np.cos(angle) * n0 + np.sin(angle) * n1), tuple(-np.sin(angle) * n0 + np.cos(angle) * n1))
        )
        links = (robot.links[0], uwml.Link(2.0, (0.3, 0, 0), 0.001))
        object.__setattr__(links[1], "segments", (turned,))
        expected = ref.robot_hydro(robot.joints, links, None, q, qd, qdd, current=(0.2, -0.1, 0.0), **motion)
        scale = np.max(np.abs(expected["drag"]), axis=1) + np.max(np.abs(expected["added_mass"]), axis=1) + 1e-300
        assert_close(core.drag, expected["drag"], scale, RTOL_REFERENCE, f"drag, normals turned by {angle}")
        assert_close(core.added_mass, expected["added_mass"], scale, RTOL_REFERENCE, f"added mass, normals turned by {angle}")
