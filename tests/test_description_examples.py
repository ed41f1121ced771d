"""Two robots written twice, as URDF and as MJCF (tests/data): a 6-joint arm of cylinders on a
vehicle with a box hull (rov_manipulator: rotated frames, fixed joints, a gripper of boxes on
prismatic joints, visuals pointing to absent meshes) and a six-legged body (hexapod: a tree of 18
joints). Both forms must be the same uwml robot: the same names, tree and forces. What the mapping
must give is worked out here by hand from the files' numbers (docs/model.md section 10), not taken from the
code under test."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import uwml

pytest.importorskip("mujoco")

DATA = Path(__file__).parent / "data"
MOTION = uwml.BaseMotion(
    orientation=(math.cos(0.15), 0.2 * math.sin(0.15), math.sqrt(0.92) * math.sin(0.15), -0.2 * math.sin(0.15)),
    velocity=(0.6, -0.1, 0.05),
    angular_velocity=(0.02, -0.05, 0.1),
    acceleration=(0.2, 0.05, -0.1),
    angular_acceleration=(0.01, 0.03, -0.02),
)
CURRENT = {"current": (0.25, 0.1, -0.02), "current_acceleration": (0.01, -0.02, 0.0)}


def rz(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def rx(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def assert_same_forces(a: uwml.Robot, b: uwml.Robot, rng: np.random.Generator, n: int = 4) -> None:
    """Every joint force component and the base wrench agree to 1e-12 of the largest, on n
    random states, fixed base and on a moving base in a current."""
    q, qd, qdd = (rng.uniform(-1.0, 1.0, (n, a.n_joints)) for _ in range(3))
    q[:, [j for j, joint in enumerate(a.joints) if joint.kind == "prismatic"]] *= 0.03
    for kwargs in ({}, {"base_motion": MOTION, **CURRENT}):
        ta, tb = a.hydro(q, qd, qdd, **kwargs), b.hydro(q, qd, qdd, **kwargs)  # type: ignore[arg-type]
        for name in ("drag", "added_mass", "buoyancy", "gravity"):
            x = np.concatenate([getattr(ta, name), getattr(ta.base, name)], axis=1)
            y = np.concatenate([getattr(tb, name), getattr(tb.base, name)], axis=1)
            scale = max(1.0, float(np.max(np.abs(y))))
            assert np.max(np.abs(x - y)) <= 1e-12 * scale, (name, kwargs.keys())
            assert np.max(np.abs(y)) > 0.0, name


@pytest.fixture(scope="module")
def manipulator() -> tuple[uwml.Robot, uwml.Robot]:
    return uwml.Robot.from_urdf(DATA / "rov_manipulator.urdf"), uwml.Robot.from_mjcf(DATA / "rov_manipulator.xml")


@pytest.fixture(scope="module")
def hexapod() -> tuple[uwml.Robot, uwml.Robot]:
    return uwml.Robot.from_urdf(DATA / "hexapod.urdf"), uwml.Robot.from_mjcf(DATA / "hexapod.xml")


def test_the_manipulator_forms_are_one_robot(manipulator: tuple[uwml.Robot, uwml.Robot]) -> None:
    urdf, mjcf = manipulator
    for robot in (urdf, mjcf):
        assert robot.joint_names == (
            "shoulder_yaw",
            "shoulder_pitch",
            "elbow",
            "wrist_roll",
            "wrist_pitch",
            "wrist_yaw",
            "finger_left",
            "finger_right",
        )
        # The bracket is fused into the hull, the camera into wrist_1, the palm into the hand.
        assert robot.link_names == ("turret", "upper_arm", "forearm", "wrist_1", "wrist_2", "hand", "finger_left", "finger_right")
        assert [j.parent for j in robot.joints] == [-1, 0, 1, 2, 3, 4, 5, 5]
        assert [j.kind for j in robot.joints] == ["revolute"] * 6 + ["prismatic"] * 2
        assert [[s.section for s in link.segments] for link in robot.links] == [
            ["circular"],
            ["circular"],
            ["circular"],
            ["circular"],
            ["circular"],
            ["circular", "rectangular"],
            ["rectangular"],
            ["rectangular"],
        ]
    assert_same_forces(urdf, mjcf, np.random.default_rng(5))


def test_the_manipulator_maps_by_the_rules(manipulator: tuple[uwml.Robot, uwml.Robot]) -> None:
    for robot in manipulator:
        # Frames: the bracket turns 0.3 rad about z, the turret does not turn, the upper arm
        # rolls 0.2 rad: its pitch axis is Rz(0.3) Rx(0.2) y; the wrist roll axis is Rz(0.3)
        # Rx(0.2) x; the right finger slides opposite to the left one.
        shoulder = rz(0.3) @ rx(0.2)
        np.testing.assert_allclose(robot.joints[0].axis, (0.0, 0.0, 1.0), atol=1e-15)
        np.testing.assert_allclose(robot.joints[1].axis, shoulder @ (0.0, 1.0, 0.0), atol=1e-15)
        np.testing.assert_allclose(robot.joints[3].axis, shoulder @ (1.0, 0.0, 0.0), atol=1e-15)
        np.testing.assert_allclose(robot.joints[7].axis, -np.asarray(robot.joints[6].axis), atol=1e-15)
        # The turret's anchor is the bracket's origin (0.7, 0, -0.3) plus Rz(0.3)(0, 0, -0.05).
        np.testing.assert_allclose(robot.joints[0].origin, (0.7, 0.0, -0.35), atol=1e-15)
        # Base: the hull box and the bracket box; mass 302 kg, COM mass-weighted.
        base = robot.base
        assert base is not None and len(base.segments) == 2 and base.mass == pytest.approx(302.0, rel=1e-15)
        assert base.volume == pytest.approx(1.6 * 1.0 * 0.6 + 0.12 * 0.1 * 0.05, rel=1e-14)
        np.testing.assert_allclose(base.com, (2.0 * 0.7 / 302.0, 0.0, (300.0 * 0.05 + 2.0 * -0.325) / 302.0), atol=1e-15)
        hull = base.segments[0]
        # The hull box 1.6 × 1.0 × 0.6: along x, n0 along y, n1 along z, widths (0.6, 1.0).
        np.testing.assert_allclose(hull.axis, (1.0, 0.0, 0.0), atol=1e-15)
        assert hull.widths == pytest.approx((0.6, 1.0), rel=1e-15) and hull.area == pytest.approx(0.6, rel=1e-15)
        assert hull.length == pytest.approx(1.6, rel=1e-15)
        # Volumes: a cylinder πr²L; wrist_1 with the camera's sphere; the hand with the palm box.
        turret, wrist_1, hand = robot.links[0], robot.links[3], robot.links[5]
        assert turret.volume == pytest.approx(math.pi * 0.06**2 * 0.12, rel=1e-14)
        assert turret.segments[0].diameter == pytest.approx(0.12, rel=1e-15)
        assert wrist_1.volume == pytest.approx(math.pi * 0.035**2 * 0.08 + 4.0 / 3.0 * math.pi * 0.03**3, rel=1e-14)
        assert wrist_1.mass == pytest.approx(1.3, rel=1e-15) and hand.mass == pytest.approx(1.3, rel=1e-15)
        assert hand.volume == pytest.approx(math.pi * 0.04**2 * 0.05 + 0.04 * 0.12 * 0.08, rel=1e-14)
        # The hull displaces more water than the vehicle weighs.
        assert base.volume * 1000.0 > base.mass


def test_visual_meshes_are_absent_and_do_not_stop_the_load() -> None:
    for name in ("rov_manipulator.urdf", "rov_manipulator.xml", "hexapod.urdf", "hexapod.xml"):
        text = (DATA / name).read_text()
        meshes = [part.split('"', 1)[0] for part in text.split('filename="')[1:]] + [
            part.split('"', 1)[0] for part in text.split('file="')[1:]
        ]
        assert meshes, name
        for mesh in meshes:
            assert not (DATA / mesh.replace("package://", "")).exists(), mesh


def test_the_hexapod_forms_are_one_tree(hexapod: tuple[uwml.Robot, uwml.Robot]) -> None:
    urdf, mjcf = hexapod
    legs = ["front_left", "middle_left", "rear_left", "front_right", "middle_right", "rear_right"]
    for robot in (urdf, mjcf):
        assert robot.n_joints == 18
        assert robot.joint_names == tuple(f"{leg}_{part}" for leg in legs for part in ("coxa_yaw", "femur_pitch", "tibia_pitch"))
        assert [j.parent for j in robot.joints] == [p for k in range(6) for p in (-1, 3 * k, 3 * k + 1)]
        # Mount angles: front left 30°, so its femur pitches about Rz(30°) y.
        np.testing.assert_allclose(robot.joints[1].axis, (-math.sin(math.pi / 6), math.cos(math.pi / 6), 0.0), atol=1e-15)
        np.testing.assert_allclose(robot.joints[13].axis, (math.sin(math.pi / 2), 0.0, 0.0), atol=1e-15)
        base = robot.base
        assert base is not None and base.mass == pytest.approx(15.0, rel=1e-15)
        assert base.volume == pytest.approx(0.8 * 0.5 * 0.15 + math.pi * 0.06**2 * 0.4, rel=1e-14)
        # The tibia with its foot (a sphere: volume only): COM mass-weighted, straight down.
        tibia = robot.links[2]
        assert tibia.mass == pytest.approx(0.6, rel=1e-15) and len(tibia.segments) == 1
        assert tibia.volume == pytest.approx(math.pi * 0.02**2 * 0.3 + 4.0 / 3.0 * math.pi * 0.03**3, rel=1e-14)
        np.testing.assert_allclose(tibia.com, (0.0, 0.0, -(0.5 * 0.15 + 0.1 * 0.3) / 0.6), atol=1e-15)
    assert_same_forces(urdf, mjcf, np.random.default_rng(6))


def test_a_mirrored_hexapod_state_puts_no_sideways_wrench_on_the_body(hexapod: tuple[uwml.Robot, uwml.Robot]) -> None:
    """The legs are mirror images about the body's x–z plane (right leg k at −θ_k, y → −y). Under
    that mirror a yaw (about z) joint's angle changes sign and a pitch joint's does not (its axis
    Rz(θ) y maps to minus the mirror leg's, and an angular velocity is an axial vector). So with
    each right leg in the mirrored state of its left leg, the whole robot is mirror-symmetric: on a
    fixed base in still water the body feels no sideways force and no roll or yaw moment, and
    each right yaw torque is minus its left one, each pitch torque equal."""
    rng = np.random.default_rng(7)
    left = rng.uniform(-0.8, 0.8, (3, 5, 9))
    mirror = np.array([-1.0, 1.0, 1.0] * 3)
    states = [np.concatenate([x, x * mirror], axis=1) for x in left]
    for robot in hexapod:
        result = robot.hydro(*states)
        wrench = result.base.total
        scale = float(np.max(np.abs(wrench)))
        assert scale > 1.0
        np.testing.assert_allclose(wrench[:, [1, 3, 5]], 0.0, atol=1e-12 * scale)
        np.testing.assert_allclose(
            result.total[:, 9:], result.total[:, :9] * mirror, rtol=1e-12, atol=1e-12 * float(np.max(np.abs(result.total)))
        )
        # Not trivially zero: a state that is not mirrored does push sideways.
        skew = robot.hydro(*[np.concatenate([x, x], axis=1) for x in left]).base.total
        assert np.max(np.abs(skew[:, [1, 3, 5]])) > 1e-3 * scale
