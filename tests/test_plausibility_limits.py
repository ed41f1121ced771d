"""Warnings against a description's joint limits (``uwml.Joint.range``, ``velocity_limit``,
``effort_limit``; ``uwml.plausibility``): read from URDF and MJCF, kept by the model file, and
each warning given alike by the one-state and the batch paths, which return the same bits."""

import dataclasses
import math
import warnings
from pathlib import Path

import numpy as np
import pytest
import uwml
from uwml import plausibility
from uwml.io.modelfile import ModelFileError
from uwml.robot.files import loads

ROOT = Path(__file__).resolve().parents[1]
ARM = ROOT / "examples" / "my_arm" / "my_arm.urdf"
ARM_HYDRO = ROOT / "examples" / "my_arm" / "my_arm.hydro.toml"

URDF = """<robot name="r">
 <link name="base"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
 <link name="l1"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
  <collision><geometry><cylinder radius="0.05" length="0.4"/></geometry></collision></link>
 <link name="l2"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
 <link name="l3"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
 <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/>
  <limit lower="-1" upper="2" effort="80" velocity="3"/></joint>
 <joint name="j2" type="continuous"><parent link="l1"/><child link="l2"/><axis xyz="0 1 0"/><limit effort="0" velocity="0"/></joint>
 <joint name="j3" type="prismatic"><parent link="l2"/><child link="l3"/><axis xyz="1 0 0"/>
  <limit lower="0" upper="0.3" effort="200" velocity="0.5"/></joint>
</robot>
"""

MJCF = """<mujoco><worldbody><body name="base"><inertial pos="0 0 0" mass="1" diaginertia="1 1 1"/>
 <body name="l1"><joint name="j1" type="hinge" axis="0 0 1" range="-90 90" actuatorfrcrange="-40 60"/>
  <inertial pos="0 0 0" mass="1" diaginertia="1 1 1"/></body></body></worldbody></mujoco>
"""


def test_a_urdfs_limits_are_read(tmp_path: Path) -> None:
    path = tmp_path / "r.urdf"
    path.write_text(URDF)
    j1, j2, j3 = uwml.Robot.from_urdf(path).joints
    assert (j1.range, j1.velocity_limit, j1.effort_limit) == ((-1.0, 2.0), 3.0, 80.0)
    # A continuous joint has no range; URDF's 0 effort and velocity mean "none given".
    assert (j2.range, j2.velocity_limit, j2.effort_limit) == (None, None, None)
    assert (j3.kind, j3.range, j3.velocity_limit, j3.effort_limit) == ("prismatic", (0.0, 0.3), 0.5, 200.0)


@pytest.mark.parametrize("key", ["velocity", "effort"])
def test_a_urdf_limit_that_is_not_a_number_is_refused(key: str, tmp_path: Path) -> None:
    path = tmp_path / "r.urdf"
    path.write_text(URDF.replace(f'{key}="3"' if key == "velocity" else 'effort="80"', f'{key}="fast"', 1))
    with pytest.raises(uwml.DescriptionError, match=rf"r.urdf, line 8: joint 'j1': <limit {key}='fast'> is not a number"):
        uwml.Robot.from_urdf(path)


def test_an_mjcfs_range_and_actuator_force_range_are_read(tmp_path: Path) -> None:
    path = tmp_path / "r.xml"
    path.write_text(MJCF)
    (j1,) = uwml.Robot.from_mjcf(path).joints
    assert j1.range == pytest.approx((-math.pi / 2, math.pi / 2), rel=1e-12)  # MJCF's degrees, in radians
    assert (j1.velocity_limit, j1.effort_limit) == (None, 60.0)


def test_the_model_file_keeps_the_limits(tmp_path: Path) -> None:
    robot = uwml.Robot.from_urdf(ARM, ARM_HYDRO)
    robot.save(tmp_path / "arm.toml")
    again = uwml.Robot.load(tmp_path / "arm.toml")
    assert again.joints == robot.joints and again.joints[0].effort_limit == 100.0
    text = (tmp_path / "arm.toml").read_text()
    assert "effort_limit = 100.0" in text and "range = [-3.0, 3.0]" in text
    bad = text.replace("effort_limit = 100.0", "effort_limit = -100.0", 1)
    with pytest.raises(ModelFileError, match=r"joints\[0\]: joint.effort_limit must be positive, got -100.0"):
        loads(bad)
    bad = text.replace("range = [-3.0, 3.0]", "range = [3.0, -3.0]", 1)
    with pytest.raises(ModelFileError, match=r"joints\[0\]: joint.range must be \(lower, upper\) with lower < upper"):
        loads(bad)


@pytest.mark.parametrize(
    ("field", "value", "error", "match"),
    [
        ("range", (1.0, 1.0), ValueError, "lower < upper"),
        ("range", (0.0, math.inf), ValueError, "must be finite"),
        ("range", 1.0, TypeError, "must be a pair"),
        ("velocity_limit", 0.0, ValueError, "joint.velocity_limit must be positive"),
        ("effort_limit", math.nan, ValueError, "joint.effort_limit must be finite"),
        ("effort_limit", [80.0], TypeError, "joint.effort_limit must be a number"),
    ],
)
def test_bad_limits_are_refused(field: str, value: object, error: type[Exception], match: str) -> None:
    with pytest.raises(error, match=match):
        uwml.Joint((0, 0, 0), (0, 0, 1), **{field: value})  # type: ignore[arg-type]


def both_paths(robot: uwml.Robot, q: list[float], qd: list[float], qdd: list[float]) -> tuple[list[str], np.ndarray]:
    """The warnings of the one-state call and of the same state as a batch of one, and the
    one-state result, checked equal to the batch's bit for bit."""
    seen = []
    results = []
    for state in ((q, qd, qdd), tuple(np.array([x]) for x in (q, qd, qdd))):
        robot._bounds.warned.clear()  # a robot warns once per cause: each path as the first call
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            results.append(robot.hydro(*state).total)
        seen.append([str(w.message) for w in caught if issubclass(w.category, uwml.PlausibilityWarning)])
    assert seen[0] == seen[1]
    np.testing.assert_array_equal(results[0], results[1][0])
    return seen[0], results[0]


def test_a_speed_beyond_the_velocity_limit_warns_on_both_paths() -> None:
    robot = uwml.Robot.from_urdf(ARM, ARM_HYDRO)  # velocity limits 4 rad/s
    assert both_paths(robot, [0.1, 0.2], [5.9, -5.9], [0.0, 0.0])[0] == []  # within 1.5 times: estimated speeds overshoot
    messages, _ = both_paths(robot, [0.1, 0.2], [0.2, 6.2], [0.0, 0.0])
    assert len(messages) == 1
    assert "joint 2 ('elbow')'s speed reaches 6.2 rad/s, above 1.5 times its own velocity limit of 4 rad/s" in messages[0]
    assert "noisy log" in messages[0] and "degrees" not in messages[0] and "PlausibilityWarning" in messages[0]
    # The same speed on a joint without a limit: 30 rad/s is the bound.
    free = uwml.Robot([uwml.Joint(j.origin, j.axis, parent=j.parent, name=j.name) for j in robot.joints], robot.links)
    assert both_paths(free, [0.1, 0.2], [0.2, 6.2], [0.0, 0.0])[0] == []


def test_an_angle_beyond_two_pi_warns_on_a_joint_with_a_range() -> None:
    robot = uwml.Robot.from_urdf(ARM, ARM_HYDRO)  # ranges ±3 and ±2 rad
    assert both_paths(robot, [3.2, -6.0], [0.0, 0.0], [0.0, 0.0])[0] == []  # a little beyond the range: no unit mistake
    messages, _ = both_paths(robot, [0.1, 9.0], [0.0, 0.0], [0.0, 0.0])
    assert len(messages) == 1 and "joint 2 ('elbow')'s angle reaches 9 rad, 1.43 turns (beyond ±2π and its range)" in messages[0]
    # Without a range, two turns either way are plausible (a continuous joint).
    free = uwml.Robot([uwml.Joint(j.origin, j.axis, parent=j.parent) for j in robot.joints], robot.links)
    assert both_paths(free, [0.1, 9.0], [0.0, 0.0], [0.0, 0.0])[0] == []


def test_a_torque_beyond_the_effort_limit_warns_on_both_paths() -> None:
    arm = uwml.Robot.from_urdf(ARM, ARM_HYDRO)  # effort limits 100 and 50 N·m
    q, qd = [0.1, 0.2], [0.3, 0.3]
    assert both_paths(arm, q, qd, [1.0, 1.0])[0] == []
    _, total = both_paths(arm, q, qd, [300.0, 300.0])
    # Joint 1's limit at 90 % of what the water puts on it, joint 2's far above.
    limits = (0.9 * abs(total[0]), 2.0 * abs(total[1]) + 1.0)
    robot = uwml.Robot(
        [dataclasses.replace(j, effort_limit=e) for j, e in zip(arm.joints, limits)], arm.links, base=arm.base, water=arm.water
    )
    assert both_paths(robot, q, qd, [1.0, 1.0])[0] == []
    messages, again = both_paths(robot, q, qd, [300.0, 300.0])
    np.testing.assert_array_equal(again, total)
    assert len(messages) == 1
    assert (
        f"the environment puts up to {abs(total[0]):.4g} N·m on joint 1 ('shoulder'), beyond its effort limit of {limits[0]:.4g} N·m"
        in messages[0]
    )


def test_the_joint_losses_count_towards_the_effort() -> None:
    arm = uwml.Robot.from_urdf(ARM, ARM_HYDRO)
    q, qd, qdd = [0.1, 0.2], [0.3, 0.0], [0.0, 0.0]
    env = arm.environment(q, qd, qdd, depth=200.0, losses=uwml.JointLosses())
    water, whole = abs(env.hydro[0]), abs(env.total[0])
    assert whole > 2.0 * water  # the losses at depth outweigh the water's drag at 0.3 rad/s
    # Joint 1's limit between the water's torque alone and with the losses.
    joints = [dataclasses.replace(arm.joints[0], effort_limit=(water + whole) / 2.0), arm.joints[1]]
    robot = uwml.Robot(joints, arm.links, base=arm.base, losses=uwml.JointLosses(), water=arm.water)
    robot.hydro(q, qd, qdd)  # the water alone: within the limit
    for state in ((q, qd, qdd), tuple(np.array([x]) for x in (q, qd, qdd))):
        robot._bounds.warned.clear()  # a robot warns once per cause: each path as the first call
        with pytest.warns(uwml.PlausibilityWarning, match=rf"up to {whole:.4g} N·m on joint 1 \('shoulder'\), beyond its effort limit"):
            again = robot.environment(*state, depth=200.0)
        np.testing.assert_array_equal(np.ravel(again.total), env.total)


def test_the_bounds_follow_the_descriptions_limits() -> None:
    bounds = plausibility.joint_bounds(uwml.Robot.from_urdf(ARM, ARM_HYDRO).joints)
    assert bounds.speed == (6.0, 6.0) and bounds.angle == (2 * math.pi, 2 * math.pi) and bounds.effort == (100.0, 50.0)
    paper = plausibility.joint_bounds(uwml.paper_leg().joints)
    assert paper.speed == (30.0,) * 3 and paper.angle == (4 * math.pi,) * 3 and paper.effort == (math.inf,) * 3


def plausibility_messages(call) -> list[str]:  # type: ignore[no-untyped-def]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        call()
    return [str(w.message) for w in caught if issubclass(w.category, uwml.PlausibilityWarning)]


def test_a_robot_warns_once_per_cause_and_names_the_cause() -> None:
    robot = uwml.Robot.from_urdf(ARM, ARM_HYDRO)  # velocity limits 4 rad/s
    fast = lambda qd: lambda: robot.hydro([0.1, 0.2], qd, [0.0, 0.0])
    (first,) = plausibility_messages(fast([0.0, 6.2]))
    # Beyond its own limit but not any joint's: the limit or the estimate, not a unit.
    assert "its own velocity limit of 4 rad/s" in first and "noisy log" in first and "degrees" not in first
    assert plausibility_messages(fast([0.0, 6.2])) == []  # the same cause: said once
    assert plausibility_messages(fast([0.0, -7.0])) == []  # the same joint's speed, again
    (other,) = plausibility_messages(fast([6.5, 0.0]))  # another joint: another cause
    assert other.startswith("joint 1")
    # Beyond any joint's 30 rad/s too: degrees per second, then.
    fresh = uwml.Robot.from_urdf(ARM, ARM_HYDRO)
    (unit,) = [m for m in plausibility_messages(lambda: fresh.hydro([0.1, 0.2], [0.0, 120.0], [0.0, 0.0])) if "speed" in m]
    assert "degrees per second" in unit and "its own velocity limit" in unit
