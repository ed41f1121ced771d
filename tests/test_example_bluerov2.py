"""examples/bluerov2: the BlueROV2 Heavy with its published parameters (von Benzon et al., J. Mar.
Sci. Eng. 10 (2022) 1898) carrying a small arm. The hull's lumped damping reproduces the paper's
terminal speeds per axis (the closed form of ``d u + q u² = F``), in the evaluation and in a
simulation; the README's section runs as written."""

import dataclasses
import math
import os
import re
from pathlib import Path

import numpy as np
import pytest
import uwml

ROOT = Path(__file__).resolve().parents[1]
URDF, HYDRO = ROOT / "examples/bluerov2/bluerov2_arm.urdf", ROOT / "examples/bluerov2/bluerov2_arm.hydro.toml"
#: The published damping (magnitudes), (x, y, z, roll, pitch, yaw).
LINEAR = [13.7, 0.0, 33.0, 0.0, 0.8, 0.0]
QUADRATIC = [141.0, 217.0, 190.0, 1.19, 0.47, 1.5]


def terminal(axis: int, push: float) -> float:
    d, q = LINEAR[axis], QUADRATIC[axis]
    return (-d + math.sqrt(d * d + 4.0 * q * push)) / (2.0 * q)


def test_the_example_is_the_published_vehicle() -> None:
    robot = uwml.Robot.from_urdf(URDF, HYDRO)
    assert robot.base is not None and robot.base.lumped is not None
    assert robot.base.mass == 13.5 and robot.base.volume == 0.0134 and robot.base.cob == (0.0, 0.0, 0.01)
    assert not robot.base.segments  # strips = false: the lumped model alone
    lumped = robot.base.lumped
    np.testing.assert_array_equal(np.diag(lumped.added_mass), [6.36, 7.12, 18.68, 0.189, 0.135, 0.222])
    np.testing.assert_array_equal(np.diag(lumped.linear_damping), LINEAR)
    np.testing.assert_array_equal(lumped.quadratic_damping, QUADRATIC)
    assert robot.water == uwml.Water(1000.0, 9.81)


@pytest.mark.parametrize("axis", range(6))
def test_the_hulls_damping_balances_a_push_at_the_papers_terminal_speed(axis: int) -> None:
    # The base moving along (or turning about) one axis at the terminal speed of a 20 N push (2 N·m
    # about an axis), its centre of buoyancy (the model's point) not translating: the hull's
    # damping is the push, reversed, and nothing else.
    robot = uwml.Robot.from_urdf(URDF, HYDRO)
    assert robot.base is not None
    without = uwml.Robot(robot.joints, robot.links, base=dataclasses.replace(robot.base, lumped=None), water=robot.water)
    push = 20.0 if axis < 3 else 2.0
    u = terminal(axis, push)
    twist = np.zeros(6)
    twist[axis] = u
    point = np.array(robot.base.cob)
    velocity = twist[:3] - np.cross(twist[3:], point)
    motion = uwml.BaseMotion(velocity=velocity, angular_velocity=twist[3:])
    q = np.zeros(robot.n_joints)
    drag = robot.hydro(q, q, q, base_motion=motion).base.drag - without.hydro(q, q, q, base_motion=motion).base.drag
    expected = np.zeros(6)
    expected[axis] = -push
    # About the base origin: the force acts at the point (a moment point × force besides).
    expected[3:] += np.cross(point, expected[:3])
    np.testing.assert_allclose(drag, expected, atol=1e-9 * push)


def test_a_pushed_vehicle_reaches_the_papers_surge_speed_in_simulation() -> None:
    """20 N of surge thrust through the centre of buoyancy along the hull's x, gravity off (the
    model's weight and buoyancy apart), the arm held straight ahead (its tubes along the surge,
    where strips feel nothing): the surge speed settles at the closed form's (to 1e-3: the last
    of the pitch the arm's mass gave the hull while it sped up still turns it, slowly)."""
    mujoco = pytest.importorskip("mujoco")
    from uwml.robot.files import model_and_robot
    from uwml.sim.mujoco import Simulation
    from uwml.sim.prescribed import Trajectory

    model, robot = model_and_robot(URDF, HYDRO)  # floating: the hydro file's [base]
    model.opt.gravity[:] = 0.0
    sim = Simulation(model, robot, water=uwml.Water(1000.0, 0.0))
    sim.prescribe(["shoulder", "elbow"], Trajectory.of(lambda t: (np.zeros(2), np.zeros(2), np.zeros(2)), joints=2))
    hull = mujoco.mj_name2id(sim.model, mujoco.mjtObj.mjOBJ_BODY, "hull")
    push = 20.0
    for _ in range(8000):
        # The force at the centre of buoyancy: at the centre of mass, with its moment.
        mujoco.mj_kinematics(sim.model, sim.data)
        mujoco.mj_comPos(sim.model, sim.data)
        cob = sim.data.xpos[hull] + sim.data.xmat[hull].reshape(3, 3) @ np.array([0.0, 0.0, 0.01])
        force = sim.data.xmat[hull].reshape(3, 3) @ np.array([push, 0.0, 0.0])
        moment = np.cross(cob - sim.data.xipos[hull], force)
        sim.step(wrenches={"hull": np.concatenate([force, moment])})
    # In the hull's own axes: the arm's mass below and ahead makes the hull pitch while it speeds
    # up (and nothing restores it without gravity), so the thrust turns with it.
    rotation = sim.data.xmat[hull].reshape(3, 3)
    speed = (rotation.T @ sim.data.qvel[0:3])[0]
    assert abs(speed - terminal(0, push)) <= 1e-3 * terminal(0, push), (speed, terminal(0, push))


def test_the_readme_section_runs_as_written(monkeypatch: pytest.MonkeyPatch) -> None:
    pytest.importorskip("mujoco")
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    section = readme.split("## A vehicle and its arm: BlueROV2 Heavy", 1)[1].split("\n## ", 1)[0]
    code = re.search(r"```python\n(.*?)```", section, re.DOTALL)
    assert code is not None
    monkeypatch.chdir(ROOT)
    namespace: dict[str, object] = {}
    exec(compile(code.group(1), "README.md", "exec"), namespace)  # noqa: S102 - the README's own example
    sim = namespace["sim"]
    assert np.all(np.isfinite(sim.data.qvel)) and abs(sim.data.qvel[0]) > 0.01  # type: ignore[attr-defined]
    assert os.path.basename(str(namespace["urdf"])) == "bluerov2_arm.urdf"
