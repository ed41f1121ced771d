"""``uwml.Robot`` (the Rust path) held against the numpy reference ``uwml.reference.robot_hydro``
on random trees, base motions and currents, against ``uwml.Leg`` on serial chains, and checked
for its inputs: shapes, broadcasting, orientations, errors that name the argument.

Expected values come from the reference (an independent numpy implementation) or from numbers
written here; ``uwml.Leg`` (a Robot too, through the chain convenience of the core) must give the
robot's values.
"""

import numpy as np
import pytest
import uwml
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation
from uwml import reference as ref

#: Tolerance of the core against the reference, relative to the largest entry of a sample.
RTOL_REFERENCE = 1e-10
EXAMPLES = settings(max_examples=max(5, int(settings.default.max_examples / 4)))
COMPONENTS = ("drag", "added_mass", "buoyancy", "gravity")


def random_robot(rng: np.random.Generator, n: int, *, base_body: bool = True, axes: str = "any", axial: bool = False) -> uwml.Robot:
    """A random tree of ``n`` joints: random parents, kinds, axes; every body with one or two
    segments, rectangular or circular, with their own coefficients. ``axes="mixed"``: each joint
    axis along a coordinate axis (either sign) half of the time, so that parents and children
    share axes or meet at right angles, as in most real robots. ``axial``: about half the segments
    with an axial drag (docs/model.md section 12.2), half of those with their own area."""

    def unit() -> np.ndarray:
        v = rng.normal(size=3)
        return v / np.linalg.norm(v)

    def joint_axis() -> np.ndarray:
        if axes == "mixed" and rng.random() < 0.5:
            return np.eye(3)[rng.integers(0, 3)] * rng.choice([-1.0, 1.0])
        return unit()

    def segments() -> list[uwml.Segment]:
        out = []
        for _ in range(rng.integers(0, 3)):
            axis = unit()
            n0 = np.cross(axis, unit())
            n0 /= np.linalg.norm(n0)
            start, length = rng.uniform(-0.2, 0.2, 3), rng.uniform(0.1, 1.0)
            if rng.random() < 0.5:
                out.append(
                    uwml.Segment(
                        start,
                        axis,
                        length,
                        section="circular",
                        diameter=rng.uniform(0.03, 0.2),
                        cd=rng.uniform(0.5, 2),
                        cm=rng.uniform(0.2, 1.5),
                        cd_axial=rng.uniform(0.1, 1.0) if axial and rng.random() < 0.5 else 0.0,
                    )
                )
            else:
                out.append(
                    uwml.Segment(
                        start,
                        axis,
                        length,
                        normals=(n0, np.cross(axis, n0)),
                        widths=rng.uniform(0.03, 0.3, 2),
                        area=rng.uniform(0.005, 0.05),
                        cd=tuple(rng.uniform(0.5, 2.5, 2)),
                        cm=tuple(rng.uniform(0.1, 1.5, 2)),
                        cd_axial=rng.uniform(0.1, 1.0) if axial and rng.random() < 0.5 else 0.0,
                        axial_area=rng.uniform(0.001, 0.05) if rng.random() < 0.5 else None,
                    )
                )
        return out

    def body() -> uwml.Link:
        return uwml.Link(
            rng.uniform(1, 20), rng.uniform(-0.4, 0.4, 3), rng.uniform(0.0005, 0.02), cob=rng.uniform(-0.4, 0.4, 3), segments=segments()
        )

    joints = [
        uwml.Joint(
            rng.uniform(-0.5, 0.5, 3),
            joint_axis(),
            parent=int(rng.integers(-1, i)) if i else -1,
            kind="prismatic" if rng.random() < 0.3 else "revolute",
        )
        for i in range(n)
    ]
    links = [body() for _ in range(n)]
    return uwml.Robot(joints, links, base=body() if base_body else None)


def random_quaternions(rng: np.random.Generator, n: int) -> np.ndarray:
    q = rng.normal(size=(n, 4))
    return q / np.linalg.norm(q, axis=1, keepdims=True)


def motion_arguments(rng: np.random.Generator, n: int) -> dict[str, np.ndarray]:
    return {
        "orientation": random_quaternions(rng, n),
        "velocity": rng.normal(size=(n, 3)),
        "angular_velocity": rng.normal(size=(n, 3)),
        "acceleration": rng.normal(size=(n, 3)),
        "angular_acceleration": rng.normal(size=(n, 3)),
    }


def assert_close(actual: np.ndarray, expected: np.ndarray, scale: np.ndarray, rtol: float, what: str) -> None:
    error = np.max(np.abs(actual - expected).reshape(len(scale), -1), axis=1) / scale
    worst = int(np.argmax(error))
    assert error[worst] <= rtol, f"{what}: sample {worst} off by {error[worst]:.3g} relative\n{actual[worst]}\n{expected[worst]}"


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


def assert_matches_reference(result: uwml.RobotTorques, expected: dict[str, np.ndarray]) -> None:
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


def test_a_serial_chain_as_a_robot_is_the_leg() -> None:
    leg = uwml.Leg.paper()
    robot = uwml.Robot.from_leg(leg)
    rng = np.random.default_rng(1)
    q, qd, qdd = rng.uniform(-3, 3, (500, 3)), rng.uniform(-2, 2, (500, 3)), rng.uniform(-5, 5, (500, 3))
    a, b = robot.hydro(q, qd, qdd), leg.hydro(q, qd, qdd)
    for name in COMPONENTS:
        scale = np.max(np.abs(getattr(b, name)), axis=1) + 1e-300
        assert_close(getattr(a, name), getattr(b, name), scale, 1e-14, name)
    # docs/model.md section 5.
    t = robot.hydro([0.3, -0.4, 0.6], [0.8, 0.5, -0.7], [1.0, -2.0, 0.5])
    np.testing.assert_allclose(t.drag, [-24.24084, -5.060505, -0.7383118], rtol=2e-7)
    np.testing.assert_allclose(t.added_mass, [-8.525438, 21.77596, 9.484545], rtol=2e-7)
    np.testing.assert_allclose(t.buoyancy, [0.0, 59.72457, 4.193843], rtol=2e-7, atol=1e-12)


def test_joints_and_links_may_be_any_iterables() -> None:
    leg = uwml.Leg.paper()
    robot = uwml.Robot((j for j in leg.joints), iter(leg.links), losses=uwml.JointLosses())
    assert robot.joints == uwml.Robot.from_leg(leg).joints and len(robot.losses) == 3
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
    with pytest.raises(ValueError, match="either as segment="):
        s1 = uwml.Segment((0, 0, 0), (1, 0, 0), 1.0, section="circular", diameter=0.1)
        uwml.Link(1.0, (0, 0, 0), 0.001, segment=s1, segments=[s1, s1])
    with pytest.raises(ValueError, match="use uwml.Robot"):
        uwml.Leg([uwml.Joint((0, 0, 0), (0, 0, 1), kind="prismatic")], [link])
    with pytest.raises(ValueError, match="use uwml.Robot"):
        uwml.Leg([uwml.Joint((0, 0, 0), (0, 0, 1))], [uwml.Link(1.0, (0, 0, 0), 0.001, segment=s1)])
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


def test_environment_is_hydro_plus_the_legs_losses() -> None:
    # The losses of each joint depend on its speed only: a robot's environment is its hydro
    # plus what uwml.Leg.environment adds for the same joint speeds, depth and temperature.
    leg = uwml.Leg.paper()
    robot = uwml.Robot.from_leg(leg)
    rng = np.random.default_rng(8)
    q, qd, qdd = rng.uniform(-2, 2, (40, 3)), rng.uniform(-1, 1, (40, 3)), rng.uniform(-3, 3, (40, 3))
    depth, temperature = rng.uniform(0, 6000, 40), rng.uniform(0, 20, 40)
    losses = [None, uwml.JointLosses(), uwml.JointLosses()]
    motion = uwml.BaseMotion(velocity=(0.3, 0.0, 0.1))
    env = robot.environment(q, qd, qdd, depth=depth, temperature_c=temperature, losses=losses, base_motion=motion, threads=2)
    hydro = robot.hydro(q, qd, qdd, base_motion=motion)
    reference = leg.environment(q, qd, qdd, depth=depth, temperature_c=temperature, losses=losses, water=robot.water)
    for name in ("visc", "seal", "current"):
        np.testing.assert_array_equal(getattr(env, name), getattr(reference, name))
    assert np.all(env.seal[:, 0] == 0.0) and np.all(env.seal[:, 1:] * qd[:, 1:] <= 0.0)
    np.testing.assert_array_equal(env.hydro, hydro.total)
    np.testing.assert_array_equal(env.base.total, hydro.base.total)
    np.testing.assert_array_equal(env.total, hydro.total + env.visc + env.seal)
    with pytest.raises(ValueError, match="depth must be finite and from 0 to 11000 m"):
        robot.environment(q[0], qd[0], qdd[0], depth=-1.0)
    with pytest.raises(ValueError, match="losses must have one entry per joint"):
        robot.environment(q[0], qd[0], qdd[0], losses=[None])


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


def test_jacobians_of_a_robot_are_the_slopes_and_the_legs_for_a_chain() -> None:
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
    # A chain: the joint blocks are uwml.Leg's.
    leg = uwml.Leg.paper()
    chain = uwml.Robot.from_leg(leg)
    Q = rng.uniform(-2, 2, (4, 3))
    a = chain.jacobians(Q, Q, Q, depth=1000.0, losses=uwml.JointLosses(epsilon=0.01))
    b = leg.jacobians(Q, Q, Q, depth=1000.0, losses=uwml.JointLosses(epsilon=0.01), water=chain.water)
    tol = 1e-12 * np.abs(b.d_q).max()
    np.testing.assert_allclose(a.d_q[:, 6:, :], b.d_q, atol=tol)
    np.testing.assert_allclose(a.d_velocity[:, 6:, 6:], b.d_qd, atol=tol)
    np.testing.assert_allclose(a.added_mass_matrix[:, 6:, 6:], b.added_mass_matrix, atol=1e-12 * np.abs(b.added_mass_matrix).max())


def test_the_example_arm_on_an_rov_matches_the_reference() -> None:
    from uwml.robot.examples import arm_on_rov

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


def test_one_state_is_the_batch_row_bit_for_bit_and_errors_are_the_general_paths() -> None:
    rng = np.random.default_rng(40)
    robot = random_robot(rng, 4)
    states = rng.uniform(-1, 1, (3, 5, 4))
    motions = motion_arguments(rng, 5)
    current = rng.normal(size=(5, 3))
    batch = robot.hydro(*states, base_motion=uwml.BaseMotion(**motions), current=current)
    for i in range(5):
        motion = uwml.BaseMotion(**{k: v[i] for k, v in motions.items()})
        for convert in (list, tuple, np.asarray):
            q, qd, qdd = (convert(s[i]) for s in states)
            one = robot.hydro(q, qd, qdd, base_motion=motion, current=convert(current[i]))
            assert type(one) is uwml.RobotTorques and type(one.base) is uwml.BaseWrench
            for name in COMPONENTS:
                np.testing.assert_array_equal(getattr(one, name), getattr(batch, name)[i])
                np.testing.assert_array_equal(getattr(one.base, name), getattr(batch.base, name)[i])
    fixed = robot.hydro(list(states[0, 0]), list(states[1, 0]), list(states[2, 0]), cd=1.1, cm=0.7)
    general = robot.hydro(states[0, :1], states[1, :1], states[2, :1], cd=1.1, cm=0.7)
    np.testing.assert_array_equal(fixed.total, general.total[0])
    np.testing.assert_array_equal(fixed.base.total, general.base.total[0])
    # The short path declines what it does not take; the general path raises as always.
    with pytest.raises(ValueError, match=r"qd\[0, 1\] is NaN"):
        robot.hydro([0.0] * 4, [0.0, np.nan, 0.0, 0.0], [0.0] * 4)
    with pytest.raises(ValueError, match="current must be finite"):
        robot.hydro([0.0] * 4, [0.0] * 4, [0.0] * 4, current=[0.0, np.inf, 0.0])
    with pytest.raises(ValueError, match="cm must be finite and non-negative"):
        robot.hydro([0.0] * 4, [0.0] * 4, [0.0] * 4, cm=-0.5)
    with pytest.raises(ValueError, match=r"q must have shape \(4,\)"):
        robot.hydro([0.0] * 3, [0.0] * 3, [0.0] * 3)


def test_one_state_environment_is_the_batch_row_bit_for_bit() -> None:
    rng = np.random.default_rng(41)
    robot = random_robot(rng, 3)
    states = rng.uniform(-1, 1, (3, 4, 3))
    motions = motion_arguments(rng, 4)
    losses = uwml.JointLosses(epsilon=0.02)
    kwargs = {"depth": 3000.0, "temperature_c": 4.0, "sea_density": 1030.0, "current": (0.2, 0.0, 0.1)}
    for per_joint in (None, losses, [None, losses, losses]):
        batch = robot.environment(*states, losses=per_joint, base_motion=uwml.BaseMotion(**motions), **kwargs)
        for i in range(4):
            motion = uwml.BaseMotion(**{k: v[i] for k, v in motions.items()})
            one = robot.environment(*(list(s[i]) for s in states), losses=per_joint, base_motion=motion, **kwargs)
            assert type(one) is uwml.RobotEnvironment
            for name in (*COMPONENTS, "visc", "seal", "current"):
                np.testing.assert_array_equal(getattr(one, name), getattr(batch, name)[i])
            np.testing.assert_array_equal(one.base.total, batch.base.total[i])
    with pytest.raises(ValueError, match="depth must be finite and from 0 to 11000 m"):
        robot.environment([0.0] * 3, [0.0] * 3, [0.0] * 3, depth=-5.0)


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


def test_kirchhoff_regressors_and_jacobians_are_its_forces() -> None:
    """``added_mass="kirchhoff"`` everywhere a robot evaluates added mass: the regressors at the
    segments' coefficients give ``hydro``'s forces; the jacobians' value is ``environment``'s
    total and their velocity derivative matches central differences; ``M_A`` is the Morison one."""
    from uwml.robot.examples import arm_on_rov

    robot = arm_on_rov()
    rng = np.random.default_rng(12)
    q, qd, qdd = rng.uniform(-1, 1, (3, 7)), rng.uniform(-1, 1, (3, 7)), rng.uniform(-1, 1, (3, 7))
    motion = uwml.BaseMotion(**motion_arguments(rng, 3))
    current = rng.normal(size=(3, 3))
    forces = robot.hydro(q, qd, qdd, base_motion=motion, current=current, added_mass="kirchhoff")
    morison = robot.hydro(q, qd, qdd, base_motion=motion, current=current)
    assert np.max(np.abs(forces.added_mass - morison.added_mass)) > 1e-3
    cd = np.array([s.cd for s in robot.segments])
    cm = np.array([s.cm for s in robot.segments])
    columns = robot.hydro_regressors(q, qd, qdd, base_motion=motion, current=current, added_mass="kirchhoff").torques(cd, cm)
    for name in COMPONENTS:
        np.testing.assert_allclose(getattr(columns, name), getattr(forces, name), rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(getattr(columns.base, name), getattr(forces.base, name), rtol=1e-12, atol=1e-12)
    one = uwml.BaseMotion(
        **{
            k: np.asarray(getattr(motion, k))[0]
            for k in ("orientation", "velocity", "angular_velocity", "acceleration", "angular_acceleration")
        }
    )
    jac = robot.jacobians(q[0], qd[0], qdd[0], base_motion=one, current=current[0], added_mass="kirchhoff")
    env = robot.environment(q[0], qd[0], qdd[0], base_motion=one, current=current[0], added_mass="kirchhoff")
    np.testing.assert_allclose(jac.value, np.concatenate([env.base.total, env.total]), rtol=1e-12, atol=1e-12)
    np.testing.assert_array_equal(
        jac.added_mass_matrix, robot.jacobians(q[0], qd[0], qdd[0], base_motion=one, current=current[0]).added_mass_matrix
    )
    h = 1e-6
    for j in range(7):
        step = np.zeros(7)
        step[j] = h
        plus = robot.environment(q[0], qd[0] + step, qdd[0], base_motion=one, current=current[0], added_mass="kirchhoff")
        minus = robot.environment(q[0], qd[0] - step, qdd[0], base_motion=one, current=current[0], added_mass="kirchhoff")
        fd = (np.concatenate([plus.base.total, plus.total]) - np.concatenate([minus.base.total, minus.total])) / (2 * h)
        np.testing.assert_allclose(jac.d_velocity[:, 6 + j], fd, rtol=1e-6, atol=1e-6 * np.max(np.abs(fd)))
    with pytest.raises(ValueError, match="added_mass must be one of morison, kirchhoff"):
        robot.hydro(q, qd, qdd, added_mass="potential")


def test_the_leg_takes_kirchhoffs_added_mass_too() -> None:
    """``Leg.hydro``, ``environment``, ``jacobians``, ``hydro_regressors`` with
    ``added_mass="kirchhoff"``: the leg as a robot's forces; at zero velocity the Morison ones."""
    leg = uwml.Leg.paper()
    robot = uwml.Robot.from_leg(leg)
    rng = np.random.default_rng(13)
    q, qd, qdd = rng.uniform(-1, 1, (4, 3)), rng.uniform(-1, 1, (4, 3)), rng.uniform(-2, 2, (4, 3))
    cd, cm = rng.uniform(0.5, 2.5, (3, 2)), rng.uniform(0.2, 1.5, (3, 2))
    k = leg.hydro(q, qd, qdd, cd=cd, cm=cm, added_mass="kirchhoff")
    r = robot.hydro(q, qd, qdd, cd=cd[1:], cm=cm[1:], added_mass="kirchhoff")
    for name in COMPONENTS:
        np.testing.assert_array_equal(getattr(k, name), getattr(r, name))
    at_rest = leg.hydro(q, 0 * qd, qdd, cd=cd, cm=cm, added_mass="kirchhoff")
    np.testing.assert_allclose(at_rest.added_mass, leg.hydro(q, 0 * qd, qdd, cd=cd, cm=cm).added_mass, rtol=1e-12, atol=1e-12)
    assert np.max(np.abs(k.added_mass - leg.hydro(q, qd, qdd, cd=cd, cm=cm).added_mass)) > 1e-3
    losses = uwml.JointLosses()
    fresh = uwml.Water()
    env = leg.environment(q, qd, qdd, depth=2000.0, temperature_c=4.0, losses=losses, cd=cd, cm=cm, water=fresh, added_mass="kirchhoff")
    np.testing.assert_array_equal(env.added_mass, k.added_mass)
    np.testing.assert_array_equal(
        env.seal, leg.environment(q, qd, qdd, depth=2000.0, temperature_c=4.0, losses=losses, cd=cd, cm=cm, water=fresh).seal
    )
    jac = leg.jacobians(q, qd, qdd, depth=2000.0, temperature_c=4.0, losses=losses, cd=cd, cm=cm, water=fresh, added_mass="kirchhoff")
    np.testing.assert_allclose(jac.value, env.total, rtol=1e-12, atol=1e-10)
    np.testing.assert_allclose(
        jac.added_mass_matrix, leg.jacobians(q, qd, qdd, cd=cd, cm=cm, water=fresh).added_mass_matrix, rtol=1e-12, atol=1e-12
    )
    regressors = leg.hydro_regressors(q, qd, qdd, per="direction", added_mass="kirchhoff")
    np.testing.assert_allclose(regressors.torques(cd, cm).added_mass, k.added_mass, rtol=1e-12, atol=1e-12)
    one = leg.hydro_regressors(q, qd, qdd, added_mass="kirchhoff").torques(2.2, 0.5)
    np.testing.assert_allclose(one.added_mass, leg.hydro(q, qd, qdd, added_mass="kirchhoff").added_mass, rtol=1e-12, atol=1e-12)
    with pytest.raises(ValueError, match="added_mass must be one of morison, kirchhoff"):
        leg.hydro(q, qd, qdd, added_mass="Kirchhoff")


def test_one_coefficient_given_takes_the_segments_own_for_the_other() -> None:
    """``cd`` per segment with ``cm`` None (and the reverse): the other is each segment's own, as
    when both are None (the native batch once refused it, asking for both tables)."""
    leg = uwml.Leg.paper()
    robot = uwml.Robot(leg.joints, leg.links)
    state = ([0.1, -0.4, 0.7], [0.5, -1.0, 2.0], [1.0, 3.0, -2.0])
    own_cd = np.array([s.cd for s in robot.segments])
    own_cm = np.array([s.cm for s in robot.segments])
    both = robot.hydro(*state, cd=own_cd * 1.5, cm=own_cm)
    np.testing.assert_array_equal(robot.hydro(*state, cd=own_cd * 1.5).total, both.total)
    both = robot.hydro(*state, cd=own_cd, cm=own_cm * 0.5)
    np.testing.assert_array_equal(robot.hydro(*state, cm=own_cm * 0.5).total, both.total)
    # The leg's per-link layout, too: link 0 has no segment.
    np.testing.assert_array_equal(leg.hydro(*state, cd=[9.0, 3.3, 3.3]).total, robot.hydro(*state, cd=3.3).total)


def test_a_leg_is_a_robot_that_does_not_load_descriptions() -> None:
    """A Leg is a Robot (its evaluations are the robot's), but a description loads as a Robot:
    the inherited loaders say so instead of failing inside the description reader."""
    leg = uwml.Leg.paper()
    assert isinstance(leg, uwml.Robot)
    for load in (uwml.Leg.from_urdf, uwml.Leg.from_mjcf, uwml.Leg.from_mujoco):
        with pytest.raises(TypeError, match=r"loads as a uwml\.Robot"):
            load("anything")  # type: ignore[arg-type]
    state = ([0.1, -0.4, 0.7], [0.5, -1.0, 2.0], [1.0, 3.0, -2.0])
    np.testing.assert_array_equal(leg.hydro(*state).total, uwml.Robot(leg.joints, leg.links).hydro(*state).total)
