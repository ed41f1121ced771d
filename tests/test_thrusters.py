"""Thrusters (docs/model.md section 13.1): thrust curves against hand values, the allocation matrix
``B`` against ``(d, r × d)`` worked by hand (on the base and on a moved link), the model file and
the hydro file carrying them (a description's link frame turned into uwml's), and the simulation
applying them: the same step as the wrench worked by hand from ``B``'s geometry, the lag's exact
first-order response, and refusals."""

from __future__ import annotations

import math
import textwrap
from pathlib import Path

import numpy as np
import pytest
import uwml
from uwml import ThrustCurve, Thruster
from uwml.robot.files import from_urdf

EXAMPLE = Path(__file__).parent.parent / "examples" / "bluerov2"
URDF, HYDRO = EXAMPLE / "bluerov2_arm.urdf", EXAMPLE / "bluerov2_arm.hydro.toml"


# --- curves and thrusters ------------------------------------------------------------------


def test_a_table_interpolates_linearly_and_holds_its_ends() -> None:
    curve = ThrustCurve.table([-1.0, -0.1, 0.1, 1.0], [-40.0, 0.0, 0.0, 50.0])
    np.testing.assert_allclose(curve([-2.0, -1.0, -0.55, 0.0, 0.55, 1.0, 3.0]), [-40.0, -40.0, -20.0, 0.0, 25.0, 50.0, 50.0])


def test_a_polynomial_per_sign_with_a_dead_band() -> None:
    # Forward 10 (u - 0.1)^2, reverse -(2 (|u| - 0.1) + 5 (|u| - 0.1)^2), zero within 0.1.
    curve = ThrustCurve.polynomial(forward=[0.0, 0.0, 10.0], reverse=[0.0, 2.0, 5.0], dead_band=0.1)
    np.testing.assert_allclose(curve([-0.6, -0.1, 0.05, 0.1, 0.6]), [-(2 * 0.5 + 5 * 0.25), 0.0, 0.0, 0.0, 10 * 0.25])


def test_the_t200_curve_gives_the_published_full_command_thrusts() -> None:
    curve = ThrustCurve.t200()
    np.testing.assert_allclose(curve([-1.0, -0.0625, 0.0, 0.0625, 1.0]), [-40.2, 0.0, 0.0, 0.0, 51.5], rtol=1e-14, atol=1e-12)
    # Forward exceeds reverse at every command past the dead band (about 1.28 times).
    u = np.linspace(0.1, 1.0, 10)
    assert np.all(curve(u) > -curve(-u)) and np.allclose(curve(u) / -curve(-u), 51.5 / 40.2)


def test_a_thruster_normalizes_its_direction_and_limits_its_thrust() -> None:
    thruster = Thruster((0.1, 0.2, 0.3), (3.0, 4.0, 0.0), max_forward=20.0, max_reverse=10.0)
    assert thruster.direction == pytest.approx((0.6, 0.8, 0.0))
    np.testing.assert_allclose(thruster.thrust([-1.0, 0.5, 1.0]), [-10.0, ThrustCurve.t200()(0.5), 20.0])
    assert thruster.moment_arm == pytest.approx(tuple(np.cross((0.1, 0.2, 0.3), (0.6, 0.8, 0.0))))


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (lambda: ThrustCurve.table([0.0, 0.0], [1.0, 2.0]), "must increase strictly"),
        (lambda: ThrustCurve.table([0.0], [1.0]), "at least 2 points"),
        (lambda: ThrustCurve.table([0.0, 1.0], [0.0, math.nan]), "must be finite"),
        (lambda: ThrustCurve.polynomial([]), "needs its forward coefficients"),
        (lambda: ThrustCurve.polynomial([1.0], dead_band=-0.1), "dead_band must be non-negative"),
        (lambda: ThrustCurve("spline"), "kind must be 'table' or 'polynomial'"),
        (lambda: Thruster((0, 0, 0), (0, 0, 0)), "nonzero vector"),
        (lambda: Thruster((0, 0, 0), (1, 0, 0), max_forward=-1.0), "max_forward must be a non-negative"),
        (lambda: Thruster((0, 0, 0), (1, 0, 0), time_constant=math.inf), "time_constant must be finite"),
    ],
)
def test_bad_curves_and_thrusters_are_refused(make, message: str) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises((TypeError, ValueError), match=message):
        make()


# --- the allocation matrix -------------------------------------------------------------------


def two_thruster_robot() -> uwml.Robot:
    base = uwml.Link(10.0, (0, 0, 0), 0.01, thrusters=[Thruster((0.2, 0.1, 0.0), (1, 0, 0)), Thruster((0.0, 0.0, 0.1), (0, 0, 1))])
    link = uwml.Link(1.0, (0.1, 0, 0), 0.001, thrusters=[Thruster((0.5, 0.0, 0.0), (0, 1, 0))])
    return uwml.Robot([uwml.Joint((0.3, 0, 0), (0, 0, 1))], [link], base=base)


def test_allocation_columns_are_direction_and_moment_arm() -> None:
    robot = two_thruster_robot()
    assert [body for body, _ in robot.thrusters] == [-1, -1, 0]
    B = robot.thruster_allocation([math.pi / 2])
    # Base: (1,0,0) at (0.2,0.1,0): moment (0, 0, -0.1); (0,0,1) at (0,0,0.1): no moment.
    np.testing.assert_allclose(B[:, 0], [1, 0, 0, 0, 0, -0.1], atol=1e-15)
    np.testing.assert_allclose(B[:, 1], [0, 0, 1, 0, 0, 0], atol=1e-15)
    # The link turned 90° about z at (0.3, 0, 0): the point (0.5, 0, 0) at (0.3, 0.5, 0), the
    # direction (0, 1, 0) along (-1, 0, 0): moment (0.3, 0.5, 0) × (-1, 0, 0) = (0, 0, 0.5).
    np.testing.assert_allclose(B[:, 2], [-1, 0, 0, 0, 0, 0.5], atol=1e-15)
    with pytest.raises(ValueError, match="give the joint positions q"):
        robot.thruster_allocation()
    with pytest.raises(ValueError, match="q must be 1 finite joint positions"):
        robot.thruster_allocation([0.0, 1.0])


def test_the_bluerov2_heavy_has_eight_thrusters_that_reach_every_direction() -> None:
    pytest.importorskip("mujoco")
    robot = from_urdf(URDF, HYDRO)
    B = robot.thruster_allocation()
    assert B.shape == (6, 8) and np.linalg.matrix_rank(B) == 6
    # The front-right horizontal thruster, as the hydro file gives it (hull frame = base frame).
    r, d = np.array([0.156, -0.111, -0.085]), np.array([1.0, 1.0, 0.0]) / math.sqrt(2.0)
    np.testing.assert_allclose(B[:, 0], np.concatenate([d, np.cross(r, d)]), atol=1e-15)


# --- files -----------------------------------------------------------------------------------


def test_a_model_file_keeps_thrusters_and_their_curves(tmp_path: Path) -> None:
    lagging = Thruster((0.2, 0.1, 0.0), (1, 0, 0), ThrustCurve.table([-1, 0, 1], [-30, 0, 40]), 35.0, 25.0, 0.08, "t1")
    base = uwml.Link(10.0, (0, 0, 0), 0.01, thrusters=[lagging, Thruster((0, 0, 0.1), (0, 0, 1))])
    robot = uwml.Robot(
        [uwml.Joint((0.3, 0, 0), (0, 0, 1))], [uwml.Link(1.0, (0.1, 0, 0), 0.001, thrusters=[Thruster((0.5, 0, 0), (0, 1, 0))])], base=base
    )
    path = tmp_path / "robot.toml"
    robot.save(path)
    loaded = uwml.Robot.load(path)
    assert loaded == robot
    assert loaded.thrusters[0][1] == lagging and loaded.thrusters[2][0] == 0


URDF_TURNED = """\
<robot name="turned">
  <link name="hull">
    <inertial><mass value="10"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <link name="boom">
    <inertial><origin xyz="0.1 0 0"/><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="swing" type="revolute">
    <parent link="hull"/><child link="boom"/>
    <origin xyz="0.3 0 0" rpy="0 0 1.0"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="10" velocity="3"/>
  </joint>
</robot>
"""


def turned_description(tmp_path: Path, extra: str = "") -> tuple[Path, Path]:
    urdf, hydro = tmp_path / "turned.urdf", tmp_path / "turned.hydro.toml"
    urdf.write_text(URDF_TURNED)
    hydro.write_text(
        textwrap.dedent(
            """\
            [links.hull]
            dry = true
            [links.boom]
            dry = true
            [[links.boom.thrusters]]
            name = "tip"
            position = [0.5, 0.0, 0.0]
            direction = [0.0, 1.0, 0.0]
            time_constant = 0.05
            [links.boom.thrusters.curve]
            kind = "table"
            commands = [-1.0, 1.0]
            thrusts = [-20.0, 20.0]
            """
        )
        + extra
    )
    return urdf, hydro


def test_a_hydro_files_thruster_is_turned_into_the_links_uwml_frame(tmp_path: Path) -> None:
    pytest.importorskip("mujoco")
    robot = from_urdf(*turned_description(tmp_path))
    ((body, thruster),) = robot.thrusters
    # The boom's URDF frame is turned 1 rad about z; uwml's link frame is parallel to the base's.
    c, s = math.cos(1.0), math.sin(1.0)
    assert body == 0 and thruster.name == "tip" and thruster.time_constant == 0.05
    np.testing.assert_allclose(thruster.position, [0.5 * c, 0.5 * s, 0.0], atol=1e-12)
    np.testing.assert_allclose(thruster.direction, [-s, c, 0.0], atol=1e-12)


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        ("[[links.hull.thrusters]]\nposition = [0, 0, 0]\ndirection = [1, 0, 0]\nrpm = 3\n", r"key 'rpm'.*allowed: name, position"),
        ("[[links.hull.thrusters]]\nposition = [0, 0, 0]\n", r"key 'direction'.*is missing"),
        ("[[links.hull.thrusters]]\nposition = [0, 0, 0]\ndirection = [0, 0, 0]\n", "nonzero vector"),
        ("".join("[[links.hull.thrusters]]\nposition = [0, 0, 0]\ndirection = [1, 0, 0]\n" for _ in range(65)), "at most 64 thrusters"),
    ],
)
def test_bad_thrusters_in_a_hydro_file_are_refused(tmp_path: Path, extra: str, message: str) -> None:
    pytest.importorskip("mujoco")
    with pytest.raises(uwml.DescriptionError, match=message):
        from_urdf(*turned_description(tmp_path, extra))


# --- simulation ------------------------------------------------------------------------------


def test_a_thrust_step_is_the_hand_worked_wrench_on_the_hull() -> None:
    mujoco = pytest.importorskip("mujoco")
    from uwml.sim.mujoco import Simulation

    command = np.array([0.6, -0.4, 0.3, 0.9, -0.2, 0.5, 0.1, -0.7])
    pushed, handed = (Simulation.from_file(URDF, HYDRO) for _ in range(2))
    pushed.command_thrusters(command)
    robot = handed.robot
    thrust = np.array([t.thrust(u) for (_, t), u in zip(robot.thrusters, command, strict=True)])
    np.testing.assert_allclose(pushed.thrust, thrust)
    hull = mujoco.mj_name2id(handed.model, mujoco.mjtObj.mjOBJ_BODY, "hull")
    # B T in the hull's frame about its origin, then about its centre of mass; in world axes each step.
    wrench, com = robot.thruster_allocation() @ thrust, handed.model.body_ipos[hull]
    force, moment = wrench[:3], wrench[3:] - np.cross(com, wrench[:3])
    for _ in range(200):
        turn = np.zeros(9)
        mujoco.mju_quat2Mat(turn, handed.data.qpos[3:7])  # the hull's pose at the step's start
        turn = turn.reshape(3, 3)
        handed.step(wrenches={"hull": np.concatenate([turn @ force, turn @ moment])})
        pushed.step()
    np.testing.assert_allclose(pushed.data.qpos, handed.data.qpos, rtol=0, atol=1e-12)
    np.testing.assert_allclose(pushed.data.qvel, handed.data.qvel, rtol=0, atol=1e-10)
    assert np.abs(pushed.data.qvel[:6]).max() > 0.05  # it moved
    # xfrc_applied is as it was after every step.
    assert not np.any(pushed.data.xfrc_applied)


def test_a_thruster_on_a_turned_link_pushes_where_its_link_is(tmp_path: Path) -> None:
    mujoco = pytest.importorskip("mujoco")
    from uwml.sim.mujoco import Simulation

    urdf, hydro = turned_description(tmp_path)
    pushed, handed = (Simulation.from_file(urdf, hydro) for _ in range(2))
    for sim in (pushed, handed):
        sim.data.qpos[:] = 0.4
        mujoco.mj_forward(sim.model, sim.data)
    pushed.command_thrusters([0.5])
    ((_, thruster),) = handed.robot.thrusters
    for _ in range(20):  # the thrust lags: each step's is the thrust at its start
        q = handed.data.qpos.copy()
        at = handed.robot.forward_kinematics(q, 0, thruster.position)
        direction = handed.robot.forward_kinematics(q, 0, np.add(thruster.position, thruster.direction)) - at
        force = pushed.thrust[0] * direction
        com = handed.robot.forward_kinematics(q, 0, handed.robot.links[0].com)
        handed.step(wrenches={"boom": np.concatenate([force, np.cross(at - com, force)])})
        pushed.step()
    np.testing.assert_allclose(pushed.data.qvel, handed.data.qvel, rtol=0, atol=1e-12)
    assert abs(pushed.data.qvel[0]) > 1e-3


def test_the_lag_is_the_exact_first_order_response(tmp_path: Path) -> None:
    pytest.importorskip("mujoco")
    from uwml.sim.mujoco import Simulation

    sim = Simulation.from_file(*turned_description(tmp_path))
    h, tau = sim.model.opt.timestep, 0.05
    sim.command_thrusters([0.5])  # the table's 10 N, reached through the lag
    assert sim.thrust[0] == 0.0
    for n in range(1, 41):
        sim.step()
        assert sim.thrust[0] == pytest.approx(10.0 * (1.0 - math.exp(-n * h / tau)), rel=1e-12)
    sim.command_thrusters([0.0])
    before = sim.thrust[0]
    sim.step()
    assert sim.thrust[0] == pytest.approx(before * math.exp(-h / tau), rel=1e-12)


def test_bad_commands_are_refused(tmp_path: Path) -> None:
    pytest.importorskip("mujoco")
    from uwml.sim.mujoco import Simulation

    sim = Simulation.from_file(URDF, HYDRO)
    with pytest.raises(ValueError, match="8 finite numbers"):
        sim.command_thrusters([0.1] * 7)
    with pytest.raises(ValueError, match="8 finite numbers"):
        sim.command_thrusters([0.1] * 7 + [math.nan])
    np.testing.assert_array_equal(sim.thrust, np.zeros(8))


def test_a_thruster_without_a_lag_acts_at_once_beside_one_with_a_lag(tmp_path: Path) -> None:
    """Mixed lags: the new command of a thruster without a lag is its thrust in the very next
    step, whatever the others' lags (it was one step late when another thruster lagged)."""
    pytest.importorskip("mujoco")
    from uwml.sim.mujoco import Simulation

    extra = "[[links.hull.thrusters]]\nposition = [0.0, 0.0, 0.0]\ndirection = [1.0, 0.0, 0.0]\n"
    sim = Simulation.from_file(*turned_description(tmp_path, extra))
    assert [t.time_constant for _, t in sim.robot.thrusters] == [0.0, 0.05]  # base first
    sim.command_thrusters([1.0, 0.5])
    assert sim.thrust[0] == pytest.approx(51.5) and sim.thrust[1] == 0.0  # at once; the lagging one not yet
