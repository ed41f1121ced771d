"""Two robots, each written as URDF and as MJCF (tests/data), read by uwml.io.descriptions (docs/model.md section 10).

rov_arm6: a 6-joint arm of cylinders (a capsule on wrist_2) on a vehicle whose hull is a box, with
a skid and a bracket on fixed joints, rotated joint frames (yaw 25°, roll 15°, rpy (20°, −10°,
35°), a camera pitched −20°, a finger frame rolled 180°), a camera on the wrist and a palm box on
fixed joints, two finger boxes on prismatic joints, visuals naming absent meshes, and a hydro file
(rov_arm6.hydro.toml) used for both forms. The MJCF gives its angles in degrees with the intrinsic
z-y'-x'' sequence and moves the forearm's body frame off the elbow axis (the joint's ``pos`` puts
the axis back).

hexapod: a box body with a battery cylinder (the base; a free root in MJCF), six legs of three
revolute joints (coxa yaw, femur pitch, tibia pitch) mounted at ±30°, ±90°, ±150° about z, leg
links cylinders, feet spheres (volume only) on fixed joints.

Both forms of a robot must be the same uwml robot: the same names, tree and forces. What the
mapping must give (counts, kinds, volumes, masses, COMs, axes, origins) is worked out here by hand
from the files' numbers, not taken from the code under test."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("mujoco")

import uwml

DATA = Path(__file__).parent / "data"
ARM = ("rov_arm6.urdf", "rov_arm6.xml")
HYDRO = DATA / "rov_arm6.hydro.toml"
HEXAPOD = ("hexapod.urdf", "hexapod.xml")
G = 9.81
DEG = math.pi / 180.0

# A moving base in a current, with no symmetry (for comparing the two forms).
MOTION = uwml.BaseMotion(
    orientation=(math.cos(0.3), -0.4 * math.sin(0.3), 0.5 * math.sin(0.3), math.sqrt(0.59) * math.sin(0.3)),
    velocity=(0.5, 0.2, -0.15),
    angular_velocity=(-0.08, 0.04, 0.12),
    acceleration=(0.25, -0.1, 0.08),
    angular_acceleration=(0.05, -0.02, 0.04),
)
CURRENT = {"current": (0.2, -0.15, 0.04), "current_acceleration": (-0.02, 0.03, 0.01)}


# --- rotations, written out (URDF rpy = Rz(yaw) Ry(pitch) Rx(roll)) ---------------------------


def rx(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def ry(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def rz(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def rpy(roll: float, pitch: float, yaw: float) -> np.ndarray:
    return rz(yaw) @ ry(pitch) @ rx(roll)


X, Y, Z = np.eye(3)


def cylinder(r: float, length: float) -> float:
    return math.pi * r**2 * length


def sphere(r: float) -> float:
    return 4.0 / 3.0 * math.pi * r**3


def load(name: str, hydro: Path | None = None) -> uwml.Robot:
    path = DATA / name
    return uwml.Robot.from_urdf(path, hydro) if name.endswith(".urdf") else uwml.Robot.from_mjcf(path, hydro)


# --- comparing two robots ------------------------------------------------------------------------


def assert_same_forces(a: uwml.Robot, b: uwml.Robot, seed: int, n: int = 5) -> None:
    """Every joint force component (drag, added mass, buoyancy, gravity) and the base wrench agree
    to 1e-12 of the largest, on n seeded random states, fixed base in still water and on a moving
    base in a current. Every component must also be nonzero somewhere (no vacuous pass)."""
    rng = np.random.default_rng(seed)
    q, qd, qdd = (rng.uniform(-1.2, 1.2, (n, a.n_joints)) for _ in range(3))
    prismatic = [j for j, joint in enumerate(a.joints) if joint.kind == "prismatic"]
    q[:, prismatic] *= 0.015  # fingers within a couple of centimetres
    for kwargs in ({}, {"base_motion": MOTION, **CURRENT}):
        ta, tb = a.hydro(q, qd, qdd, **kwargs), b.hydro(q, qd, qdd, **kwargs)  # type: ignore[arg-type]
        for name in ("drag", "added_mass", "buoyancy", "gravity"):
            x = np.concatenate([getattr(ta, name), getattr(ta.base, name)], axis=1)
            y = np.concatenate([getattr(tb, name), getattr(tb.base, name)], axis=1)
            scale = float(np.max(np.abs(y)))
            assert scale > 1e-6, (name, kwargs.keys())
            assert np.max(np.abs(x - y)) <= 1e-12 * scale, (name, kwargs.keys(), np.max(np.abs(x - y)) / scale)


def midpoint(segment: uwml.Segment) -> np.ndarray:
    return np.asarray(segment.start) + 0.5 * segment.length * np.asarray(segment.axis)


def assert_parallel(axis: object, expected: np.ndarray) -> None:
    """A segment's axis along the expected line (either sense: a segment may be written either way)."""
    assert abs(abs(float(np.dot(axis, expected))) - 1.0) < 1e-14, (axis, expected)


def assert_same_links(a: uwml.Robot, b: uwml.Robot) -> None:
    """Link by link (base included): mass, COM, volume, COB, and every segment's section, size,
    midpoint, lines (axis, and a box's normals; either sense) and coefficients."""
    assert a.base is not None and b.base is not None
    for la, lb in zip((a.base, *a.links), (b.base, *b.links), strict=True):
        assert la.name == lb.name
        assert la.mass == pytest.approx(lb.mass, rel=1e-14) and la.volume == pytest.approx(lb.volume, rel=1e-14)
        np.testing.assert_allclose(la.com, lb.com, atol=1e-14)
        np.testing.assert_allclose(la.cob, lb.cob, atol=1e-14)
        assert len(la.segments) == len(lb.segments), la.name
        for sa, sb in zip(la.segments, lb.segments):
            assert sa.section == sb.section and sa.length == pytest.approx(sb.length, rel=1e-14)
            assert sa.area == pytest.approx(sb.area, rel=1e-14)
            np.testing.assert_allclose(sa.widths, sb.widths, rtol=1e-14)
            np.testing.assert_allclose(midpoint(sa), midpoint(sb), atol=1e-14)
            assert_parallel(sa.axis, np.asarray(sb.axis))
            if sa.section == "rectangular":  # a circular section's normals are any perpendicular pair
                for na, nb in zip(sa.normals, sb.normals, strict=True):
                    assert_parallel(na, np.asarray(nb))
            assert sa.cd == sb.cd and sa.cm == sb.cm


# --- the ROV arm ---------------------------------------------------------------------------------

# Orientations at q = 0 relative to the hull (products of the fixed rotations down the tree).
R_BRACKET = rz(25 * DEG)
R_ARM = R_BRACKET @ rx(15 * DEG)  # upper_arm, forearm, wrist_1
R_CAMERA = R_ARM @ ry(-20 * DEG)
R_WRIST = R_ARM @ rpy(20 * DEG, -10 * DEG, 35 * DEG)  # wrist_2, hand, palm, finger_left
R_RIGHT = R_WRIST @ rx(math.pi)  # finger_right

# Joint anchors in the hull frame at q = 0.
O_TURRET = np.array([0.6, 0.1, -0.25]) + R_BRACKET @ (0.0, 0.0, -0.06)
O_UPPER = O_TURRET + R_BRACKET @ (0.0, 0.0, -0.1)
O_FORE = O_UPPER + R_ARM @ (0.45, 0.0, 0.0)
O_WRIST1 = O_FORE + R_ARM @ (0.38, 0.0, 0.0)
O_WRIST2 = O_WRIST1 + R_ARM @ (0.07, 0.0, 0.0)
O_HAND = O_WRIST2 + R_WRIST @ (0.07, 0.0, 0.0)
O_PALM = O_HAND + R_WRIST @ (0.04, 0.0, 0.0)
O_LEFT = O_PALM + R_WRIST @ (0.03, 0.025, 0.0)
O_RIGHT = O_PALM + R_WRIST @ (0.03, -0.025, 0.0)

V_HULL = 1.4 * 0.9 * 0.5
V_SKID = cylinder(0.05, 1.2)
V_BRACKET = 0.1 * 0.08 * 0.06
V_TURRET = cylinder(0.055, 0.1)
V_UPPER = cylinder(0.04, 0.45)
V_FORE = cylinder(0.035, 0.38)
V_WRIST1 = cylinder(0.03, 0.07) + cylinder(0.02, 0.06) + sphere(0.02)  # with the camera
V_WRIST2 = cylinder(0.028, 0.05) + sphere(0.028)  # a capsule (no hydro file)
V_HAND = cylinder(0.035, 0.04) + 0.03 * 0.1 * 0.07  # with the palm
V_FINGER = 0.07 * 0.012 * 0.025


@pytest.fixture(scope="module")
def arm() -> tuple[uwml.Robot, uwml.Robot]:
    return load(ARM[0], HYDRO), load(ARM[1], HYDRO)


@pytest.fixture(scope="module")
def arm_dry() -> tuple[uwml.Robot, uwml.Robot]:
    """Without the hydro file: primitive volumes and default coefficients."""
    return load(ARM[0]), load(ARM[1])


def test_arm_forms_have_the_same_tree(arm: tuple[uwml.Robot, uwml.Robot]) -> None:
    for robot in arm:
        assert robot.n_joints == 8
        assert robot.joint_names == (
            "shoulder_yaw", "shoulder_pitch", "elbow", "wrist_roll", "wrist_pitch", "wrist_yaw", "finger_left", "finger_right",
        )  # fmt: skip
        # skid and bracket fuse into the hull (the base), the camera into wrist_1, the palm into the hand.
        assert robot.link_names == ("turret", "upper_arm", "forearm", "wrist_1", "wrist_2", "hand", "finger_left", "finger_right")
        assert robot.base is not None and robot.base.name == "hull"
        assert [j.parent for j in robot.joints] == [-1, 0, 1, 2, 3, 4, 5, 5]
        assert [j.kind for j in robot.joints] == ["revolute"] * 6 + ["prismatic"] * 2
        # Cylinders (and the capsule's cylinder) are circular; boxes rectangular; spheres none.
        assert [[s.section for s in link.segments] for link in robot.links] == [
            ["circular"],  # turret
            ["circular"],  # upper_arm
            ["circular"],  # forearm
            ["circular", "circular"],  # wrist_1 + the camera housing (its dome: volume only)
            ["circular"],  # wrist_2: a capsule
            ["circular", "rectangular"],  # hand + palm
            ["rectangular"],
            ["rectangular"],
        ]
        assert [s.section for s in robot.base.segments] == ["rectangular", "circular", "rectangular"]  # hull, skid, bracket
        assert robot.water.density == 1025.0


# Random states over wide ranges: beyond the description's velocity limits (0.1 m/s for the fingers).
@pytest.mark.filterwarnings("ignore::uwml.PlausibilityWarning")
def test_arm_forms_are_the_same_robot(arm: tuple[uwml.Robot, uwml.Robot], arm_dry: tuple[uwml.Robot, uwml.Robot]) -> None:
    assert_same_links(*arm)
    assert_same_links(*arm_dry)
    for ja, jb in zip(arm[0].joints, arm[1].joints, strict=True):
        np.testing.assert_allclose(ja.origin, jb.origin, atol=1e-14)
        np.testing.assert_allclose(ja.axis, jb.axis, atol=1e-14)
    assert_same_forces(*arm, seed=11)
    assert_same_forces(*arm_dry, seed=12)


def test_arm_joint_frames_by_hand(arm: tuple[uwml.Robot, uwml.Robot]) -> None:
    """Axes are the fixed rotations applied to the local axis; origins are anchor differences.
    The elbow's MJCF body frame is 0.05 m beyond the axis (joint pos −0.05): its origin must
    still be R_arm (0.45, 0, 0) from the shoulder, and the wrist's R_arm (0.38, 0, 0) from it."""
    axes = [Z, R_ARM @ Y, R_ARM @ Y, R_ARM @ X, R_WRIST @ Y, R_WRIST @ Z, R_WRIST @ Y, -(R_WRIST @ Y)]
    anchors = [O_TURRET, O_UPPER, O_FORE, O_WRIST1, O_WRIST2, O_HAND, O_LEFT, O_RIGHT]
    parents = [None, 0, 1, 2, 3, 4, 5, 5]
    origins = [anchors[i] - (anchors[p] if p is not None else 0.0) for i, p in enumerate(parents)]
    for robot in arm:
        for joint, axis, origin in zip(robot.joints, axes, origins, strict=True):
            np.testing.assert_allclose(joint.axis, axis, atol=1e-14, err_msg=joint.name)
            np.testing.assert_allclose(joint.origin, origin, atol=1e-14, err_msg=joint.name)
        # Spelled out: the turret's anchor (0.6, 0.1, −0.31); the shoulder pitch axis Rz(25°) Rx(15°) y.
        np.testing.assert_allclose(robot.joints[0].origin, (0.6, 0.1, -0.31), atol=1e-15)
        c25, s25, c15, s15 = math.cos(25 * DEG), math.sin(25 * DEG), math.cos(15 * DEG), math.sin(15 * DEG)
        np.testing.assert_allclose(robot.joints[1].axis, (-s25 * c15, c25 * c15, s15), atol=1e-15)
        # The wrist-roll axis is in the horizontal plane at the bracket's 25°.
        np.testing.assert_allclose(robot.joints[3].axis, (c25, s25, 0.0), atol=1e-15)


def test_arm_base_by_hand(arm: tuple[uwml.Robot, uwml.Robot]) -> None:
    """The hull (250 kg, COM (0.02, 0, 0.04)), the skid (6 kg at (0, 0, −0.3)) and the bracket
    (1.5 kg at (0.6, 0.1, −0.25) + Rz(25°)(0, 0, −0.03)) fused: masses summed, COM mass-weighted,
    volume the three primitives, COB their volume-weighted centroid."""
    bracket_centre = np.array([0.6, 0.1, -0.28])
    com = (250.0 * np.array([0.02, 0.0, 0.04]) + 6.0 * np.array([0.0, 0.0, -0.3]) + 1.5 * bracket_centre) / 257.5
    volume = V_HULL + V_SKID + V_BRACKET
    cob = (V_SKID * np.array([0.0, 0.0, -0.3]) + V_BRACKET * bracket_centre) / volume
    for robot in arm:
        base = robot.base
        assert base is not None
        assert base.mass == pytest.approx(257.5, rel=1e-15)
        np.testing.assert_allclose(base.com, com, atol=1e-15)
        assert base.volume == pytest.approx(volume, rel=1e-14)
        np.testing.assert_allclose(base.cob, cob, atol=1e-15)
        hull, skid, bracket = base.segments
        # The hull box 1.4 × 0.9 × 0.5: along x, n0 along y, n1 along z: widths (0.5, 0.9).
        assert_parallel(hull.axis, X)
        assert hull.length == pytest.approx(1.4, rel=1e-15)
        assert hull.widths == pytest.approx((0.5, 0.9), rel=1e-15) and hull.area == pytest.approx(0.45, rel=1e-15)
        np.testing.assert_allclose(midpoint(hull), (0.0, 0.0, 0.0), atol=1e-15)
        assert_parallel(hull.normals[1], Z)
        # The skid: a cylinder of diameter 0.1 along x, 1.2 long, centred 0.3 m below; cd 0.8 (hydro file).
        assert_parallel(skid.axis, X)
        assert skid.length == pytest.approx(1.2, rel=1e-15) and skid.diameter == pytest.approx(0.1, rel=1e-15)
        np.testing.assert_allclose(midpoint(skid), (0.0, 0.0, -0.3), atol=1e-15)
        assert skid.cd == (0.8, 0.8)
        # The bracket box 0.1 × 0.08 × 0.06, turned 25° about z: along Rz(25°) x, widths (0.06, 0.08).
        assert_parallel(bracket.axis, R_BRACKET @ X)
        assert bracket.length == pytest.approx(0.1, rel=1e-15)
        assert bracket.widths == pytest.approx((0.06, 0.08), rel=1e-15)
        np.testing.assert_allclose(midpoint(bracket), bracket_centre, atol=1e-15)
        # The vehicle floats: its hull displaces more sea water than it weighs.
        assert 1025.0 * base.volume > base.mass


def test_arm_links_by_hand(arm: tuple[uwml.Robot, uwml.Robot], arm_dry: tuple[uwml.Robot, uwml.Robot]) -> None:
    for robot in arm:
        turret, upper, fore, wrist_1, wrist_2, hand, left, right = robot.links
        # Cylinders: πr²L, the segment's diameter 2r, centred on the primitive.
        assert turret.volume == pytest.approx(V_TURRET, rel=1e-14) and turret.mass == 2.5
        assert turret.segments[0].diameter == pytest.approx(0.11, rel=1e-15)
        np.testing.assert_allclose(midpoint(turret.segments[0]), (0.0, 0.0, -0.05), atol=1e-15)
        assert upper.volume == pytest.approx(V_UPPER, rel=1e-14)
        np.testing.assert_allclose(upper.com, R_ARM @ (0.225, 0.0, 0.0), atol=1e-15)
        assert upper.segments[0].cd == (1.1, 1.1) and upper.segments[0].cm == (0.9, 0.9)  # hydro file
        # The forearm, measured from the elbow axis (the MJCF body frame is not on it).
        assert fore.volume == pytest.approx(V_FORE, rel=1e-14)
        np.testing.assert_allclose(fore.com, R_ARM @ (0.19, 0.0, 0.0), atol=1e-15)
        np.testing.assert_allclose(midpoint(fore.segments[0]), R_ARM @ (0.19, 0.0, 0.0), atol=1e-15)
        assert fore.segments[0].length == pytest.approx(0.38, rel=1e-15)
        assert_parallel(fore.segments[0].axis, R_ARM @ X)
        # wrist_1 with the camera fused: 0.9 + 0.3 kg, COM mass-weighted; the camera's
        # housing along its own pitched x axis; its dome adds volume only.
        camera_com = np.array([0.03, 0.0, 0.05]) + ry(-20 * DEG) @ (0.01, 0.0, 0.0)
        assert wrist_1.mass == pytest.approx(1.2, rel=1e-15)
        np.testing.assert_allclose(wrist_1.com, R_ARM @ ((0.9 * np.array([0.035, 0.0, 0.0]) + 0.3 * camera_com) / 1.2), atol=1e-15)
        assert wrist_1.volume == pytest.approx(V_WRIST1, rel=1e-14)
        housing = wrist_1.segments[1]
        assert_parallel(housing.axis, R_CAMERA @ X)
        assert housing.length == pytest.approx(0.06, rel=1e-15) and housing.diameter == pytest.approx(0.04, rel=1e-15)
        np.testing.assert_allclose(midpoint(housing), R_ARM @ camera_com, atol=1e-15)
        # wrist_2: the hydro file's volume and COB (in wrist_2's own, rotated frame).
        assert wrist_2.volume == 0.0003
        np.testing.assert_allclose(wrist_2.cob, R_WRIST @ (0.03, 0.0, 0.005), atol=1e-15)
        capsule = wrist_2.segments[0]  # its cylinder part
        assert capsule.length == pytest.approx(0.05, rel=1e-15) and capsule.diameter == pytest.approx(0.056, rel=1e-15)
        # The hand with the palm: 0.6 + 0.4 kg, COM at (0.6·0.02 + 0.4·0.055) = 0.034 along R_wrist x.
        assert hand.mass == pytest.approx(1.0, rel=1e-15)
        np.testing.assert_allclose(hand.com, R_WRIST @ (0.034, 0.0, 0.0), atol=1e-15)
        assert hand.volume == pytest.approx(V_HAND, rel=1e-14)
        palm = hand.segments[1]
        # The palm box 0.03 × 0.1 × 0.07: along its y, n0 along z, n1 along x: widths (0.03, 0.07).
        assert_parallel(palm.axis, R_WRIST @ Y)
        assert palm.widths == pytest.approx((0.03, 0.07), rel=1e-15) and palm.area == pytest.approx(0.0021, rel=1e-14)
        assert_parallel(palm.normals[0], R_WRIST @ Z)
        assert palm.cd == (1.3, 1.6) and palm.cm == (1.0, 0.8)  # the fused palm's own hydro entry
        # The fingers: boxes 0.07 × 0.012 × 0.025 along the palm's x.
        for finger in (left, right):
            assert finger.volume == pytest.approx(V_FINGER, rel=1e-14) and finger.mass == 0.08
            assert_parallel(finger.segments[0].axis, R_WRIST @ X)
            assert finger.segments[0].widths == pytest.approx((0.012, 0.025), rel=1e-15)
            np.testing.assert_allclose(finger.com, R_WRIST @ (0.035, 0.0, 0.0), atol=1e-15)
    for robot in arm_dry:
        # Without the hydro file: the capsule's volume (cylinder + two half spheres), its centre the COB.
        wrist_2 = robot.links[4]
        assert wrist_2.volume == pytest.approx(V_WRIST2, rel=1e-14)
        np.testing.assert_allclose(wrist_2.cob, R_WRIST @ (0.035, 0.0, 0.0), atol=1e-15)
        assert robot.water.density == 1000.0


def test_arm_static_wrench_is_total_buoyancy_and_weight(arm: tuple[uwml.Robot, uwml.Robot]) -> None:
    """At rest (qd = qdd = 0) on a fixed upright base in still water, whatever q: no drag, no added
    mass; the base force of buoyancy is ρ g V_total up and that of gravity g m_total down, with
    V_total, m_total summed by hand (wrist_2's volume from the hydro file, sea water)."""
    volume = V_HULL + V_SKID + V_BRACKET + V_TURRET + V_UPPER + V_FORE + V_WRIST1 + 0.0003 + V_HAND + 2 * V_FINGER
    mass = 257.5 + 2.5 + 3.5 + 2.8 + 1.2 + 0.8 + 1.0 + 2 * 0.08
    q = np.random.default_rng(3).uniform(-1.5, 1.5, (4, 8))
    q[:, 6:] *= 0.01
    zero = np.zeros_like(q)
    for robot in arm:
        t = robot.hydro(q, zero, zero)
        for name in ("drag", "added_mass"):
            assert np.all(getattr(t, name) == 0.0) and np.all(getattr(t.base, name) == 0.0), name
        np.testing.assert_allclose(t.base.buoyancy[:, :3], np.tile([0.0, 0.0, 1025.0 * G * volume], (4, 1)), rtol=1e-13, atol=1e-10)
        np.testing.assert_allclose(t.base.gravity[:, :3], np.tile([0.0, 0.0, -G * mass], (4, 1)), rtol=1e-13, atol=1e-10)
        assert np.max(np.abs(t.buoyancy)) > 0.1 and np.max(np.abs(t.gravity)) > 0.1


# --- the hexapod ---------------------------------------------------------------------------------

LEGS = ("front_left", "middle_left", "rear_left", "front_right", "middle_right", "rear_right")
MOUNT_ANGLE = (30.0, 90.0, 150.0, -30.0, -90.0, -150.0)  # degrees about z
MOUNT_POS = ((0.35, 0.2, 0.0), (0.0, 0.25, 0.0), (-0.35, 0.2, 0.0), (0.35, -0.2, 0.0), (0.0, -0.25, 0.0), (-0.35, -0.2, 0.0))
V_BODY = 0.8 * 0.5 * 0.15 + cylinder(0.06, 0.4)  # box + battery
V_COXA = cylinder(0.03, 0.08)
V_FEMUR = cylinder(0.025, 0.24)
V_TIBIA = cylinder(0.02, 0.3) + sphere(0.03)  # with the foot


@pytest.fixture(scope="module")
def hexapod() -> tuple[uwml.Robot, uwml.Robot]:
    return load(HEXAPOD[0]), load(HEXAPOD[1])


def test_hexapod_forms_have_the_same_tree(hexapod: tuple[uwml.Robot, uwml.Robot]) -> None:
    for robot in hexapod:
        assert robot.n_joints == 18
        assert robot.joint_names == tuple(f"{leg}_{part}" for leg in LEGS for part in ("coxa_yaw", "femur_pitch", "tibia_pitch"))
        assert robot.link_names == tuple(f"{leg}_{part}" for leg in LEGS for part in ("coxa", "femur", "tibia"))
        assert [j.parent for j in robot.joints] == [-1, 0, 1, -1, 3, 4, -1, 6, 7, -1, 9, 10, -1, 12, 13, -1, 15, 16]
        assert [j.kind for j in robot.joints] == ["revolute"] * 18
        assert [[s.section for s in link.segments] for link in robot.links] == [["circular"]] * 18  # feet: volume only
        assert robot.base is not None and robot.base.name == "body"
        assert [s.section for s in robot.base.segments] == ["rectangular", "circular"]


def test_hexapod_forms_are_the_same_robot(hexapod: tuple[uwml.Robot, uwml.Robot]) -> None:
    assert_same_links(*hexapod)
    assert_same_forces(*hexapod, seed=21)


def test_hexapod_by_hand(hexapod: tuple[uwml.Robot, uwml.Robot]) -> None:
    """Leg k mounted at angle θ_k about z: the coxa yaws about z, the femur and tibia pitch about
    Rz(θ) y = (−sin θ, cos θ, 0); the femur is 0.08 m out along Rz(θ) x, the tibia 0.24 m further.
    The base: the body box and the battery (15 kg, COM (0, 0, (12·0.01 − 3·0.14)/15) = −0.02)."""
    for robot in hexapod:
        for k, (angle, pos) in enumerate(zip(MOUNT_ANGLE, MOUNT_POS, strict=True)):
            t = angle * DEG
            out, pitch = np.array([math.cos(t), math.sin(t), 0.0]), np.array([-math.sin(t), math.cos(t), 0.0])
            coxa, femur, tibia = robot.joints[3 * k : 3 * k + 3]
            np.testing.assert_allclose(coxa.axis, Z, atol=1e-15)
            np.testing.assert_allclose(femur.axis, pitch, atol=1e-15)
            np.testing.assert_allclose(tibia.axis, pitch, atol=1e-15)
            np.testing.assert_allclose(coxa.origin, pos, atol=1e-15)
            np.testing.assert_allclose(femur.origin, 0.08 * out, atol=1e-15)
            np.testing.assert_allclose(tibia.origin, 0.24 * out, atol=1e-15)
            links = robot.links[3 * k : 3 * k + 3]
            for link, volume, mass in zip(links, (V_COXA, V_FEMUR, V_TIBIA), (0.4, 0.8, 0.6), strict=True):
                assert link.volume == pytest.approx(volume, rel=1e-14) and link.mass == pytest.approx(mass, rel=1e-15)
            # The femur cylinder: along the leg, 0.24 long, diameter 0.05, centred 0.12 out.
            segment = links[1].segments[0]
            assert_parallel(segment.axis, out)
            assert segment.length == pytest.approx(0.24, rel=1e-15) and segment.diameter == pytest.approx(0.05, rel=1e-15)
            np.testing.assert_allclose(midpoint(segment), 0.12 * out, atol=1e-15)
            # The tibia with its foot (0.5 kg at 0.15 down, 0.1 kg at 0.3 down), straight down.
            np.testing.assert_allclose(links[2].com, (0.0, 0.0, -(0.5 * 0.15 + 0.1 * 0.3) / 0.6), atol=1e-15)
            cob = -(cylinder(0.02, 0.3) * 0.15 + sphere(0.03) * 0.3) / V_TIBIA
            np.testing.assert_allclose(links[2].cob, (0.0, 0.0, cob), atol=1e-15)
        base = robot.base
        assert base is not None
        assert base.mass == pytest.approx(15.0, rel=1e-15) and base.volume == pytest.approx(V_BODY, rel=1e-14)
        np.testing.assert_allclose(base.com, (0.0, 0.0, -0.02), atol=1e-15)
        box, battery = base.segments
        assert box.widths == pytest.approx((0.15, 0.5), rel=1e-15) and box.length == pytest.approx(0.8, rel=1e-15)
        assert_parallel(battery.axis, X)
        np.testing.assert_allclose(midpoint(battery), (0.0, 0.0, -0.14), atol=1e-15)


def test_hexapod_static_wrench_is_total_buoyancy_and_weight(hexapod: tuple[uwml.Robot, uwml.Robot]) -> None:
    """At rest, fixed base, still water, any q: the base force is ρ g V_total up (buoyancy) and
    g m_total down (gravity), summed by hand over the body, battery and six legs with their feet.
    At q = 0 the robot is symmetric about the x–z and y–z planes (front and rear legs at ±30°,
    ±150° from x = ±0.35; the battery under the centre), so both moments vanish there too."""
    volume = V_BODY + 6 * (V_COXA + V_FEMUR + V_TIBIA)
    mass = 15.0 + 6 * (0.4 + 0.8 + 0.6)
    q = np.random.default_rng(4).uniform(-1.0, 1.0, (3, 18))
    q[0] = 0.0
    zero = np.zeros_like(q)
    for robot in hexapod:
        t = robot.hydro(q, zero, zero)
        np.testing.assert_allclose(t.base.buoyancy[:, :3], np.tile([0.0, 0.0, 1000.0 * G * volume], (3, 1)), rtol=1e-13, atol=1e-11)
        np.testing.assert_allclose(t.base.gravity[:, :3], np.tile([0.0, 0.0, -G * mass], (3, 1)), rtol=1e-13, atol=1e-11)
        np.testing.assert_allclose(t.base.buoyancy[0, 3:], 0.0, atol=1e-13)
        np.testing.assert_allclose(t.base.gravity[0, 3:], 0.0, atol=1e-13)
        assert np.max(np.abs(t.base.buoyancy[1:, 3:])) > 1e-3  # a bent leg does turn the body


# --- visuals -------------------------------------------------------------------------------------


def mesh_files(name: str) -> list[str]:
    """The mesh files a description names: URDF <mesh filename>, MJCF <asset><mesh file>."""
    root = ET.parse(DATA / name).getroot()
    if name.endswith(".urdf"):
        return [m.attrib["filename"] for m in root.iter("mesh")]
    return [m.attrib["file"] for m in root.iter("mesh") if "file" in m.attrib]


@pytest.mark.parametrize("name", [*ARM, *HEXAPOD])
def test_absent_visual_meshes_do_not_stop_the_load(name: str) -> None:
    """Every mesh the description names is absent, so MuJoCo alone refuses the file when it keeps
    the visuals (MJCF always; URDF with discardvisual="false"), and uwml loads it all the same:
    visuals are dropped before MuJoCo compiles."""
    import mujoco  # type: ignore[import-untyped]

    meshes = mesh_files(name)
    assert len(meshes) >= (5 if name in ARM else 2)
    for mesh in meshes:
        for candidate in (DATA / mesh, DATA / mesh.removeprefix("package://"), Path(mesh)):
            assert not candidate.exists(), mesh
    text = (DATA / name).read_text()
    if name.endswith(".urdf"):
        text = text.replace("</robot>", '<mujoco><compiler discardvisual="false"/></mujoco></robot>')
    with pytest.raises(ValueError, match="(?i)file"):
        mujoco.MjModel.from_xml_string(text)
    robot = load(name)
    assert robot.n_joints == (8 if name in ARM else 18)
