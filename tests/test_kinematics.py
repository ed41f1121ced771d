"""Forward kinematics, the geometric Jacobian, the paper leg's inverse kinematics and the walking gait.

Nothing expected here is produced by the code under test: expected values are the closed form
of docs/model.md section 2 typed below, a numpy forward kinematics of a general chain written in this
file (Rodrigues rotations), central finite differences, numbers typed from the gait's definition
(stance speed, height), or relations between evaluations (periodicity, continuity, IK∘FK).
"""

import math

import numpy as np
import pytest
import uwml
from hypothesis import given, settings
from hypothesis import strategies as st
from uwml import WalkingGait, _core, paper_leg_foot, paper_leg_ik

# docs/model.md section 2 (Table II).
L2, L3 = 0.660, 0.714
PAPER = uwml.paper_leg()


def closed_form_foot(q: np.ndarray, s: float = L3) -> np.ndarray:
    """``L2 u2 + s u3`` of docs/model.md section 2, typed from it."""
    q1, q2, q3 = q[..., 0], q[..., 1], q[..., 2]
    e_r = np.stack([np.cos(q1), np.sin(q1), np.zeros_like(q1)], axis=-1)
    z = np.array([0.0, 0.0, 1.0])
    u2 = np.cos(q2)[..., None] * e_r + np.sin(q2)[..., None] * z
    u3 = np.sin(q2 + q3)[..., None] * e_r - np.cos(q2 + q3)[..., None] * z
    return L2 * u2 + s * u3


def rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    """Rodrigues' rotation about a unit axis."""
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + math.sin(angle) * k + (1 - math.cos(angle)) * (k @ k)


def numpy_frames(leg: uwml.Robot, q: np.ndarray) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """World (rotation, origin, axis) of every link frame: the chain's convention, written here."""
    frames = []
    rot, origin = np.eye(3), np.zeros(3)
    for joint, angle in zip(leg.joints, q):
        origin = origin + rot @ np.array(joint.origin)
        axis = rot @ np.array(joint.axis)
        rot = rot @ rotation(np.array(joint.axis), angle)
        frames.append((rot, origin, axis))
    return frames


def random_leg(rng: np.random.Generator, n: int) -> uwml.Robot:
    """A chain of ``n`` joints with random axes and offsets; every other link has a segment."""
    joints, links = [], []
    for i in range(n):
        axis = rng.normal(size=3)
        axis /= np.linalg.norm(axis)
        joints.append(uwml.Joint(origin=tuple(rng.uniform(-0.5, 0.5, 3)), axis=tuple(axis)))
        segment = None
        if i % 2 == 1:
            basis, _ = np.linalg.qr(rng.normal(size=(3, 3)))
            segment = uwml.Segment(
                start=tuple(rng.uniform(-0.2, 0.2, 3)),
                axis=tuple(basis[:, 0]),
                length=float(rng.uniform(0.1, 0.8)),
                normals=(tuple(basis[:, 1]), tuple(basis[:, 2])),
                widths=(0.1, 0.1),
                area=0.01,
            )
        links.append(uwml.Link(mass=1.0, com=(0.0, 0.0, 0.0), volume=0.0, segments=() if segment is None else (segment,)))
    return uwml.Robot(joints, links)


angles = st.lists(st.floats(-math.pi, math.pi), min_size=3, max_size=3).map(np.array)


# ---------------------------------------------------------------- forward kinematics, Jacobian


@given(q=angles)
def test_paper_foot_and_knee_match_the_closed_form(q):
    np.testing.assert_allclose(PAPER.forward_kinematics(q), closed_form_foot(q), atol=1e-14)
    np.testing.assert_allclose(PAPER.forward_kinematics(q, link=2), closed_form_foot(q), atol=1e-14)
    np.testing.assert_allclose(PAPER.forward_kinematics(q, link=-1, point=(0, 0, -0.3)), closed_form_foot(q, 0.3), atol=1e-14)
    # Link 1's default point is the thigh's tip, the knee; link 0 has no segment: its origin, the hip.
    np.testing.assert_allclose(PAPER.forward_kinematics(q, link=-2), closed_form_foot(q, 0.0), atol=1e-14)
    np.testing.assert_allclose(PAPER.forward_kinematics(q, link=0), np.zeros(3), atol=0)
    np.testing.assert_allclose(paper_leg_foot(q), closed_form_foot(q), atol=1e-14)


def test_forward_kinematics_keeps_the_leading_shape():
    q = np.random.default_rng(1).uniform(-3, 3, (2, 4, 5, 3))
    p, jac = PAPER.point_jacobian(q)
    assert p.shape == (2, 4, 5, 3) and jac.shape == (2, 4, 5, 6, 3)
    np.testing.assert_allclose(p, closed_form_foot(q), atol=1e-14)
    assert PAPER.forward_kinematics(q[0, 0, 0]).shape == (3,)
    assert PAPER.forward_kinematics(np.zeros((0, 3))).shape == (0, 3)


def test_paper_jacobian_angular_rows_are_the_typed_axes():
    q = np.random.default_rng(2).uniform(-3, 3, (50, 3))
    _, jac = PAPER.point_jacobian(q)
    q1 = q[:, 0]
    minus_e_t = np.stack([np.sin(q1), -np.cos(q1), np.zeros_like(q1)], axis=-1)
    np.testing.assert_allclose(jac[:, 3:, 0], np.broadcast_to([0, 0, 1.0], (50, 3)), atol=1e-15)
    np.testing.assert_allclose(jac[:, 3:, 1], minus_e_t, atol=1e-15)
    np.testing.assert_allclose(jac[:, 3:, 2], minus_e_t, atol=1e-15)
    # The knee does not move the thigh.
    _, knee_jac = PAPER.point_jacobian(q, link=1)
    assert np.all(knee_jac[:, :, 2] == 0.0)


def finite_difference_jacobian(leg: uwml.Robot, q: np.ndarray, link: int, point, step: float) -> np.ndarray:
    columns = []
    for j in range(leg.n_joints):
        dq = np.zeros(leg.n_joints)
        dq[j] = step
        columns.append((leg.forward_kinematics(q + dq, link, point) - leg.forward_kinematics(q - dq, link, point)) / (2 * step))
    return np.stack(columns, axis=-1)


@given(q=angles)
def test_paper_jacobian_matches_finite_differences(q):
    step = 1e-6
    for link in range(3):
        _, jac = PAPER.point_jacobian(q, link)
        np.testing.assert_allclose(jac[:3], finite_difference_jacobian(PAPER, q, link, None, step), atol=1e-3 * math.sqrt(step))


@settings(max_examples=50)
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 8))
def test_random_chain_jacobian_matches_numpy_kinematics_and_finite_differences(seed, n):
    rng = np.random.default_rng(seed)
    leg = random_leg(rng, n)
    q = rng.uniform(-math.pi, math.pi, n)
    frames = numpy_frames(leg, q)
    step = 1e-6
    for link in range(n):
        point = rng.uniform(-0.5, 0.5, 3)
        p, jac = leg.point_jacobian(q, link - n if link % 2 else link, point)
        rot, origin, _ = frames[link]
        np.testing.assert_allclose(p, origin + rot @ point, atol=1e-12)
        np.testing.assert_allclose(jac[:3], finite_difference_jacobian(leg, q, link, point, step), atol=1e-3 * math.sqrt(step))
        for j in range(n):
            if j <= link:
                _, o_j, z_j = frames[j]
                np.testing.assert_allclose(jac[3:, j], z_j, atol=1e-12)
                np.testing.assert_allclose(jac[:3, j], np.cross(z_j, p - o_j), atol=1e-12)
            else:
                assert np.all(jac[:, j] == 0.0)
        # The default point: the segment's tip, or the frame origin.
        segment = leg.links[link].segments[0] if leg.links[link].segments else None
        local = np.zeros(3) if segment is None else np.array(segment.start) + segment.length * np.array(segment.axis)
        np.testing.assert_allclose(leg.forward_kinematics(q, link), origin + rot @ local, atol=1e-12)


# ---------------------------------------------------------------- inverse kinematics

reach = st.floats(abs(L2 - L3) + 1e-3, L2 + L3 - 1e-3)
direction = st.tuples(st.floats(-math.pi, math.pi), st.floats(-1.5, 1.5))  # azimuth, elevation off the axis


def target(r: float, azimuth: float, elevation: float) -> np.ndarray:
    return r * np.array([math.cos(elevation) * math.cos(azimuth), math.cos(elevation) * math.sin(azimuth), math.sin(elevation)])


@given(r=reach, d=direction)
def test_fk_of_ik_is_the_identity_for_both_branches(r, d):
    foot = target(r, *d)
    up, down = paper_leg_ik(foot, "up"), paper_leg_ik(foot, "down")
    for q in (up, down):
        np.testing.assert_allclose(closed_form_foot(q), foot, atol=1e-12)
        assert np.all(np.abs(q) <= math.pi)
    assert math.cos(up[2]) >= -1e-12 and math.cos(down[2]) <= 1e-12
    # The two branches differ (the knee is mirrored about the hip-foot line), away from the boundary.
    knee_up, knee_down = closed_form_foot(up, 0.0), closed_form_foot(down, 0.0)
    sin_q3 = (r**2 - L2**2 - L3**2) / (2 * L2 * L3)
    assert np.linalg.norm(knee_up - knee_down) == pytest.approx(2 * L2 * L3 * math.sqrt(1 - sin_q3**2) / r, rel=1e-6, abs=1e-9)


@given(
    q1=st.floats(-3.1, 3.1),
    q2=st.floats(-3.1, 3.1),
    q3=st.floats(-3.1, 3.1),
)
def test_ik_of_fk_is_the_identity_on_its_branch(q1, q2, q3):
    q = np.array([q1, q2, q3])
    foot = closed_form_foot(q)
    rho = math.hypot(foot[0], foot[1])
    # Conventions of paper_leg_ik: the foot on the e_r side (rho > 0 along e_r), branch by sign of cos q3.
    along = foot[0] * math.cos(q1) + foot[1] * math.sin(q1)
    if rho < 1e-3 or along <= 0 or abs(math.cos(q3)) < 1e-3:
        return
    solved = paper_leg_ik(foot, "up" if math.cos(q3) > 0 else "down")
    np.testing.assert_allclose(np.angle(np.exp(1j * (solved - q))), 0.0, atol=1e-8)


def test_ik_is_vectorized_and_takes_other_lengths():
    rng = np.random.default_rng(3)
    q = np.stack([rng.uniform(-1, 1, (4, 6)), rng.uniform(-1, 1, (4, 6)), rng.uniform(0.1, 1.4, (4, 6))], axis=-1)
    lengths = (0.4, 0.5)
    a, b = q[..., 1], q[..., 1] + q[..., 2]
    rho = 0.4 * np.cos(a) + 0.5 * np.sin(b)
    q = q[rho > 0.05]
    foot = paper_leg_foot(q, lengths)
    np.testing.assert_allclose(paper_leg_ik(foot, "up", lengths), q, atol=1e-10)


def test_boundary_targets_give_one_solution():
    for r in (L2 + L3, L3 - L2):
        foot = np.array([r * math.cos(0.3), 0.0, -r * math.sin(0.3)])
        up, down = paper_leg_ik(foot, "up"), paper_leg_ik(foot, "down")
        np.testing.assert_allclose(up, down, atol=1e-6)
        np.testing.assert_allclose(closed_form_foot(up), foot, atol=1e-9)


@pytest.mark.parametrize(
    "foot, reason",
    [
        ((1.4, 0.0, 0.0), "out of reach"),
        ((0.0, 0.02, -0.02), "out of reach"),
        ((0.0, 0.0, -0.8), "yaw axis"),
        ((np.nan, 0.0, -0.8), "not finite"),
    ],
)
def test_unreachable_targets_raise_naming_them(foot, reason):
    with pytest.raises(ValueError, match=reason) as info:
        paper_leg_ik(foot)
    assert str(list(map(float, foot)))[1:6] in str(info.value)
    batch = np.array([[0.7, 0.0, -0.6], [0.7, 0.1, -0.5], foot])
    with pytest.raises(ValueError, match=r"foot\[2\]"):
        paper_leg_ik(batch)
    with pytest.raises(ValueError, match=r"foot\[1, 0\]"):
        paper_leg_ik(batch.reshape(3, 1, 3)[1:])


# ---------------------------------------------------------------- gait

GAIT = WalkingGait()
# A gait off the leg's x axis, so that the hip yaw moves (q1 and its rate vary).
SIDEWAYS = WalkingGait(period=1.3, duty_factor=0.75, step_length=0.2, step_height=0.05, nominal_foot=(0.6, 0.2, -0.7))
EPS = 1e-9


def derivative_bound(f, t0: float, t1: float) -> float:
    """Largest |df/dt| on [t0, t1], from finite differences on a fine grid, with a safety factor of 4."""
    t = np.linspace(t0, t1, 20001)
    values = f(t)
    return 4 * float(np.max(np.abs(np.diff(values, axis=0)) / (t[1] - t[0])))


@pytest.mark.parametrize("gait", [GAIT, SIDEWAYS], ids=["default", "sideways"])
def test_gait_is_continuous_to_the_acceleration_at_both_phase_changes(gait):
    functions = [gait.foot, gait.foot_velocity, gait.foot_acceleration]
    derivatives = [gait.foot_velocity, gait.foot_acceleration, lambda t: np.gradient(gait.foot_acceleration(t), t, axis=0)]
    changes = [gait.stance_duration, gait.period, 0.0, 3 * gait.period + gait.stance_duration]
    for f, df in zip(functions, derivatives):
        for t in changes:
            bound = max(derivative_bound(df, t - 1e-3, t - 1e-6), derivative_bound(df, t + 1e-6, t + 1e-3), 1.0)
            left, right = f(t - EPS), f(t + EPS)
            assert np.max(np.abs(right - left)) <= 2 * EPS * bound + 1e-12, (f.__name__, t, left, right)
    # The analytic derivatives are the derivatives (so continuity of each means C² of the foot).
    t = np.linspace(0.0, 2 * gait.period, 997)
    step = 1e-6
    for f, df in ((gait.foot, gait.foot_velocity), (gait.foot_velocity, gait.foot_acceleration)):
        numeric = (f(t + step) - f(t - step)) / (2 * step)
        scale = np.max(np.abs(df(t)))
        np.testing.assert_allclose(df(t), numeric, atol=math.sqrt(step) * 1e-2 * scale)


def test_gait_stance_swing_and_period():
    t = np.linspace(-3.0, 7.0, 2001)
    foot = GAIT.foot(t)
    np.testing.assert_allclose(GAIT.foot(t + 2.0), foot, atol=1e-12)
    np.testing.assert_allclose(GAIT.foot_velocity(t - 4.0), GAIT.foot_velocity(t), atol=1e-10)
    np.testing.assert_allclose(GAIT.foot_acceleration(t + 6.0), GAIT.foot_acceleration(t), atol=1e-8)
    phase = np.mod(t, 2.0)
    stance = phase < 1.2
    # Stance: on the ground line at 0.3 m / 1.2 s backward, from x = 0.85 to 0.55.
    np.testing.assert_allclose(
        foot[stance], np.stack([0.85 - 0.25 * phase[stance], np.zeros(stance.sum()), np.full(stance.sum(), -0.6)], -1), atol=1e-12
    )
    np.testing.assert_allclose(GAIT.foot_velocity(t[stance]), np.broadcast_to([-0.25, 0, 0], (stance.sum(), 3)), atol=1e-12)
    # Swing: lifted, 0.1 m at mid-swing, forward on the whole.
    assert np.all(foot[~stance, 2] >= -0.6 - 1e-12) and np.all(foot[:, 1] == 0.0)
    np.testing.assert_allclose(GAIT.foot(1.6), [0.7, 0.0, -0.5], atol=1e-12)
    assert GAIT.foot(np.zeros((2, 3))).shape == (2, 3, 3)
    assert GAIT.foot(0.5).shape == (3,)


@pytest.mark.parametrize("knee", ["up", "down"])
@pytest.mark.parametrize("gait", [GAIT, SIDEWAYS], ids=["default", "sideways"])
def test_joint_states_are_consistent_with_finite_differences(gait, knee):
    GAIT = gait  # the same checks for both gaits
    t = np.linspace(0.0, GAIT.period, 401)
    q, qd, qdd = GAIT.joint_states(t, knee=knee)
    np.testing.assert_allclose(PAPER.forward_kinematics(q), GAIT.foot(t), atol=1e-12)
    # The Rust Jacobian maps qd to the foot velocity.
    _, jac = PAPER.point_jacobian(q)
    np.testing.assert_allclose(np.einsum("nij,nj->ni", jac[:, :3], qd), GAIT.foot_velocity(t), atol=1e-12)
    step = 1e-5
    q_plus, qd_plus, _ = GAIT.joint_states(t + step, knee=knee)
    q_minus, qd_minus, _ = GAIT.joint_states(t - step, knee=knee)
    # Tolerance ~ sqrt(step) relative everywhere; 100 times tighter away from the phase changes,
    # where the jerk jumps and a central difference of qd straddling the change is off by O(step).
    tol = math.sqrt(step)
    smooth = (np.abs(t - GAIT.stance_duration) > 2 * step) & (np.abs(t % GAIT.period) > 2 * step) & (np.abs(t - GAIT.period) > 2 * step)
    qd_numeric, qdd_numeric = (q_plus - q_minus) / (2 * step), (qd_plus - qd_minus) / (2 * step)
    assert np.count_nonzero(~smooth) == 3
    for analytic, numeric, scale in ((qd, qd_numeric, np.max(np.abs(qd))), (qdd, qdd_numeric, np.max(np.abs(qdd)))):
        np.testing.assert_allclose(analytic, numeric, atol=tol * scale)
        np.testing.assert_allclose(analytic[smooth], numeric[smooth], atol=1e-2 * tol * scale)
    np.testing.assert_allclose(qdd[smooth], ((q_plus - 2 * q + q_minus) / step**2)[smooth], atol=0.1 * tol * np.max(np.abs(qdd)))
    # Both branches, both exact: the knee branch shows in q3.
    assert np.all(np.cos(q[:, 2]) > 0) if knee == "up" else np.all(np.cos(q[:, 2]) < 0)


# ---------------------------------------------------------------- bad inputs


def test_bad_inputs_to_the_jacobian_and_forward_kinematics():
    for method in (PAPER.point_jacobian, PAPER.forward_kinematics):
        with pytest.raises(ValueError, match="link"):
            method(np.zeros(3), link=3)
        with pytest.raises(ValueError, match="link"):
            method(np.zeros(3), link=-4)
        with pytest.raises(TypeError, match="link"):
            method(np.zeros(3), link=1.0)
        with pytest.raises(TypeError, match="link"):
            method(np.zeros(3), link=True)
        with pytest.raises(ValueError, match="q"):
            method(np.zeros(4))
        with pytest.raises(ValueError, match="q"):
            method(np.float64(0.0))
        with pytest.raises(ValueError, match=r"q\[1, 2\]"):
            method(np.array([[0, 0, 0], [0, 0, np.inf]]))
        with pytest.raises(TypeError, match="q"):
            method([[0, 0], [0]])
        with pytest.raises(TypeError, match="q"):
            method(np.zeros(3, complex))
        with pytest.raises(ValueError, match="point"):
            method(np.zeros(3), point=(0, 0))
        with pytest.raises(ValueError, match="point"):
            method(np.zeros(3), point=(0, 0, np.nan))
        with pytest.raises(TypeError, match="point"):
            method(np.zeros(3), point=(0, 0, 1j))
    assert PAPER.forward_kinematics(np.zeros(3), link=np.int64(1)).shape == (3,)


def test_bad_inputs_to_the_binding():
    chain = _core.Robot.paper_leg()
    q, point = np.zeros((2, 3)), np.zeros(3)
    for link in (-1, 3, 2**40):
        with pytest.raises(ValueError, match="link"):
            chain.point_jacobian(q, link, point)
    with pytest.raises(ValueError, match="q"):
        chain.point_jacobian(np.zeros((2, 4)), 0, point)
    with pytest.raises(ValueError, match="point"):
        chain.point_jacobian(q, 0, np.zeros(4))
    with pytest.raises(ValueError, match="point"):
        chain.point_jacobian(q, 0, np.array([0.0, np.nan, 0.0]))
    p, jac = chain.point_jacobian(q, 2, np.array([0.0, 0.0, -L3]))
    assert jac.shape == (2, 6, 3)
    np.testing.assert_allclose(p, np.broadcast_to([L2, 0.0, -L3], (2, 3)), atol=1e-15)


def test_bad_inputs_to_ik_and_gait():
    with pytest.raises(ValueError, match="knee"):
        paper_leg_ik((0.7, 0.0, -0.6), knee="sideways")
    with pytest.raises(ValueError, match="lengths"):
        paper_leg_ik((0.7, 0.0, -0.6), lengths=(0.6, -0.1))
    with pytest.raises(ValueError, match="lengths"):
        paper_leg_foot(np.zeros(3), lengths=(0.6,))
    with pytest.raises(ValueError, match="foot"):
        paper_leg_ik((0.7, 0.0))
    with pytest.raises(TypeError, match="foot"):
        paper_leg_ik("far")
    with pytest.raises(ValueError, match="q"):
        paper_leg_foot(np.zeros(2))
    for kwargs, name, error in [
        ({"period": 0.0}, "period", ValueError),
        ({"period": np.inf}, "period", ValueError),
        ({"period": [1.0, 2.0]}, "period", TypeError),
        ({"duty_factor": 1.0}, "duty_factor", ValueError),
        ({"duty_factor": 0.0}, "duty_factor", ValueError),
        ({"step_length": -0.1}, "step_length", ValueError),
        ({"step_height": np.nan}, "step_height", ValueError),
        ({"step_height": "high"}, "step_height", TypeError),
        ({"nominal_foot": (0.7, 0.0)}, "nominal_foot", ValueError),
        ({"lengths": (0.0, 1.0)}, "lengths", ValueError),
    ]:
        with pytest.raises(error, match=name):
            WalkingGait(**kwargs)
    with pytest.raises(ValueError, match="t must be finite"):
        GAIT.foot([0.0, np.nan])
    with pytest.raises(TypeError, match="t"):
        GAIT.foot_velocity("now")
    with pytest.raises(ValueError, match="knee"):
        GAIT.joint_states(0.0, knee="left")
    with pytest.raises(ValueError, match="unreachable"):
        WalkingGait(nominal_foot=(1.3, 0.0, -0.3)).joint_states(np.linspace(0, 2, 11))
