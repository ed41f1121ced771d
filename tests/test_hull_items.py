"""A hydro file's point items, mass override and the warning for a link fused into a lumped body
(docs/model.md section 13): the robot's masses, volumes and centres against hand computations,
the MuJoCo model made from the description carrying the same masses, refusals naming the file,
the table and the key, and ``uwml describe``'s listing."""

from __future__ import annotations

import math
import warnings
from pathlib import Path

import numpy as np
import pytest
import uwml

mujoco = pytest.importorskip("mujoco")

from uwml.cli import main
from uwml.io.descriptions import urdf_parts
from uwml.robot.files import model_and_robot
from uwml.viz.describe import describe

G, RHO = 9.81, 1000.0
#: A hull (10 kg, its COM at its origin, a 0.4 × 0.3 × 0.2 m box), a camera fixed to it turned a
#: quarter turn about z (a cylinder, fused into the hull), and an arm on a pitch joint.
ROV = """<robot name="rov">
  <link name="hull">
    <inertial><origin xyz="0 0 0"/><mass value="10"/><inertia ixx="0.2" iyy="0.3" izz="0.4" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.4 0.3 0.2"/></geometry></collision>
  </link>
  <link name="camera">
    <inertial><origin xyz="0 0 0"/><mass value="0.5"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0 0 0" rpy="0 1.5707963267948966 0"/><geometry><cylinder radius="0.03" length="0.1"/></geometry></collision>
  </link>
  <joint name="camera_mount" type="fixed">
    <parent link="hull"/><child link="camera"/><origin xyz="0.2 0 0.05" rpy="0 0 1.5707963267948966"/>
  </joint>
  <link name="arm">
    <inertial><origin xyz="0.1 0 0"/><mass value="1"/><inertia ixx="1e-3" iyy="4e-3" izz="4e-3" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0.1 0 0" rpy="0 1.5707963267948966 0"/><geometry><cylinder radius="0.02" length="0.2"/></geometry></collision>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="hull"/><child link="arm"/><origin xyz="0.25 0 -0.1"/><axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" effort="50" velocity="2"/>
  </joint>
</robot>
"""
BOX = 0.4 * 0.3 * 0.2
CAMERA = math.pi * 0.03**2 * 0.1
LUMPED = """
[links.hull.lumped]
added_mass = [[5, 0, 0, 0, 0, 0], [0, 6, 0, 0, 0, 0], [0, 0, 7, 0, 0, 0], [0, 0, 0, 0.1, 0, 0], [0, 0, 0, 0, 0.1, 0], [0, 0, 0, 0, 0, 0.1]]
linear_damping = [[10, 0, 0, 0, 0, 0], [0, 10, 0, 0, 0, 0], [0, 0, 10, 0, 0, 0], [0, 0, 0, 1, 0, 0], [0, 0, 0, 0, 1, 0], [0, 0, 0, 0, 0, 1]]
quadratic_damping = [100.0, 100.0, 100.0, 1.0, 1.0, 1.0]
"""


@pytest.fixture
def rov(tmp_path: Path) -> Path:
    path = tmp_path / "rov.urdf"
    path.write_text(ROV)
    return path


def hydro(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "rov.hydro.toml"
    path.write_text(text)
    return path


def body_inertia(model: object, name: str) -> tuple[float, np.ndarray, np.ndarray]:
    """A compiled body's mass, centre of mass and inertia about it, in its own frame."""
    i = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, name)
    rotation = np.zeros(9)
    mujoco.mju_quat2Mat(rotation, model.body_iquat[i])  # type: ignore[attr-defined]
    r = rotation.reshape(3, 3)
    return float(model.body_mass[i]), np.array(model.body_ipos[i]), r @ np.diag(model.body_inertia[i]) @ r.T  # type: ignore[attr-defined]


def test_an_item_adds_its_mass_at_its_place_by_the_parallel_axis_theorem(rov: Path, tmp_path: Path) -> None:
    file = hydro(tmp_path, '[[links.hull.items]]\nname = "lead"\nmass = 2.0\nvolume = 0.0\nposition = [0.1, 0.0, 0.0]\n')
    model, robot = model_and_robot(rov, file)
    mass, com, inertia = body_inertia(model, "hull")
    # 12 kg at (10·0 + 2·0.1)/12 = 1/60 m; about the new COM, iyy and izz gain the reduced mass
    # 10·2/12 kg times 0.1² m²: 0.016667 kg·m²; about the old one (the origin) 2·0.1² = 0.02.
    assert mass == pytest.approx(12.0, rel=1e-15)
    np.testing.assert_allclose(com, [1.0 / 60.0, 0.0, 0.0], rtol=1e-14, atol=1e-16)
    np.testing.assert_allclose(inertia, np.diag([0.2, 0.3 + 20.0 / 12.0 * 0.01, 0.4 + 20.0 / 12.0 * 0.01]), rtol=1e-12, atol=1e-15)
    about_origin = inertia + mass * (com @ com * np.eye(3) - np.outer(com, com))
    np.testing.assert_allclose(about_origin, np.diag([0.2, 0.32, 0.42]), rtol=1e-12, atol=1e-15)
    # The robot the core evaluates: the hull with its camera fused in (0.5 kg at (0.2, 0, 0.05)).
    assert robot.base is not None
    assert robot.base.mass == pytest.approx(12.5, rel=1e-15)
    np.testing.assert_allclose(robot.base.com, np.array([0.2 + 0.1, 0.0, 0.025]) / 12.5, rtol=1e-12, atol=1e-16)
    assert robot.base.volume == pytest.approx(BOX + CAMERA, rel=1e-14)  # no volume: the buoyancy unchanged


def test_an_items_own_inertia_adds_about_its_place(rov: Path, tmp_path: Path) -> None:
    text = "[[links.hull.items]]\nmass = 2.0\nvolume = 0.0\nposition = [0.0, 0.0, 0.0]\ninertia = [0.01, 0.02, 0.03]\n"
    model, _ = model_and_robot(rov, hydro(tmp_path, text))
    mass, com, inertia = body_inertia(model, "hull")
    assert mass == pytest.approx(12.0) and np.allclose(com, 0.0)
    np.testing.assert_allclose(inertia, np.diag([0.21, 0.32, 0.43]), rtol=1e-12)


def test_buoyancy_and_centre_of_buoyancy_are_volume_weighted(rov: Path, tmp_path: Path) -> None:
    text = '[[links.hull.items]]\nname = "foam"\nmass = 0.5\nvolume = 0.002\nposition = [0.0, 0.1, 0.15]\n'
    robot = uwml.Robot.from_urdf(rov, hydro(tmp_path, text))
    plain = uwml.Robot.from_urdf(rov)
    assert robot.base is not None and plain.base is not None
    camera_centre = np.array([0.2, 0.0, 0.05])
    assert robot.base.volume == pytest.approx(BOX + CAMERA + 0.002, rel=1e-14)
    expected = (CAMERA * camera_centre + 0.002 * np.array([0.0, 0.1, 0.15])) / (BOX + CAMERA + 0.002)
    np.testing.assert_allclose(robot.base.cob, expected, rtol=1e-12, atol=1e-16)
    np.testing.assert_allclose(plain.base.cob, CAMERA * camera_centre / (BOX + CAMERA), rtol=1e-12, atol=1e-16)


def test_the_net_weight_and_buoyancy_shift_by_the_items_at_their_places(rov: Path, tmp_path: Path) -> None:
    """At rest, the base wrench's gravity and buoyancy shift by exactly ``−m g`` and ``ρ V g``
    (upwards) at the hull's item, and the shoulder's torque by the arm item's ``(ρ V − m) g``
    times its lever arm about the pitch axis: ``−0.2 cos q``."""
    m_hull, v_hull, r_hull = 3.0, 0.001, np.array([-0.1, 0.05, 0.08])
    m_arm, v_arm = 0.3, 0.0005
    text = (
        f"[[links.hull.items]]\nmass = {m_hull}\nvolume = {v_hull}\nposition = {r_hull.tolist()}\n"
        f"[[links.arm.items]]\nmass = {m_arm}\nvolume = {v_arm}\nposition = [0.2, 0.0, 0.0]\n"
    )
    robot = uwml.Robot.from_urdf(rov, hydro(tmp_path, text))
    plain = uwml.Robot.from_urdf(rov)
    q = np.array([0.7])
    zero = np.zeros(1)
    mine, theirs = robot.hydro(q, zero, zero, base=True), plain.hydro(q, zero, zero, base=True)
    assert mine.base is not None and theirs.base is not None
    weight, lift = np.array([0.0, 0.0, -m_hull * G]), np.array([0.0, 0.0, RHO * v_hull * G])
    # The arm item at the shoulder (0.25, 0, -0.1) plus (0.2 cos q, 0, −0.2 sin q).
    r_arm = np.array([0.25 + 0.2 * math.cos(0.7), 0.0, -0.1 - 0.2 * math.sin(0.7)])
    arm_weight, arm_lift = np.array([0.0, 0.0, -m_arm * G]), np.array([0.0, 0.0, RHO * v_arm * G])
    gravity = np.concatenate([weight + arm_weight, np.cross(r_hull, weight) + np.cross(r_arm, arm_weight)])
    buoyancy = np.concatenate([lift + arm_lift, np.cross(r_hull, lift) + np.cross(r_arm, arm_lift)])
    np.testing.assert_allclose(mine.base.gravity - theirs.base.gravity, gravity, atol=1e-12)
    np.testing.assert_allclose(mine.base.buoyancy - theirs.base.buoyancy, buoyancy, atol=1e-12)
    net = (RHO * v_arm - m_arm) * G
    shift = (mine.gravity + mine.buoyancy) - (theirs.gravity + theirs.buoyancy)
    np.testing.assert_allclose(shift, [-0.2 * math.cos(0.7) * net], rtol=1e-12)


def test_an_item_on_a_fused_turned_link_is_placed_in_that_links_frame(rov: Path, tmp_path: Path) -> None:
    # The camera's frame: at (0.2, 0, 0.05), turned a quarter turn about z: its x is the hull's y.
    text = '[[links.camera.items]]\nname = "DVL"\nmass = 1.5\nvolume = 0.0008\nposition = [0.05, 0.0, 0.0]\n'
    parts = urdf_parts(rov, hydro(tmp_path, text))
    robot = parts.build(uwml.Robot)
    assert robot.base is not None
    place = np.array([0.2, 0.05, 0.05])
    assert robot.base.mass == pytest.approx(12.0)
    np.testing.assert_allclose(robot.base.com, (0.5 * np.array([0.2, 0.0, 0.05]) + 1.5 * place) / 12.0, rtol=1e-12, atol=1e-16)
    total = BOX + CAMERA + 0.0008
    np.testing.assert_allclose(robot.base.cob, (CAMERA * np.array([0.2, 0.0, 0.05]) + 0.0008 * place) / total, rtol=1e-12, atol=1e-16)
    (item,) = parts.items
    assert (item.body, item.link, item.name) == ("camera", "hull", "DVL")
    np.testing.assert_allclose(item.position, place, atol=1e-15)


def test_the_simulated_model_carries_the_same_masses_as_the_robot(rov: Path, tmp_path: Path) -> None:
    text = (
        "[links.hull]\nmass = 11.0\n"
        "[[links.hull.items]]\nmass = 2.0\nvolume = 0.001\nposition = [0.1, 0.0, -0.05]\n"
        "[[links.camera.items]]\nmass = 0.25\nvolume = 0.0\nposition = [0.0, 0.02, 0.0]\n"
        "[[links.arm.items]]\nmass = 0.4\nvolume = 0.0\nposition = [0.15, 0.0, 0.01]\n"
    )
    model, robot = model_and_robot(rov, hydro(tmp_path, text), floating=True)
    assert robot.base is not None
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    hull, camera, arm = (mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, n) for n in ("hull", "camera", "arm"))
    assert model.body_mass[hull] + model.body_mass[camera] == pytest.approx(robot.base.mass, rel=1e-14)
    assert robot.base.mass == pytest.approx(11.0 + 2.0 + 0.5 + 0.25, rel=1e-14)
    assert model.body_mass[arm] == pytest.approx(robot.links[0].mass, rel=1e-14) and robot.links[0].mass == pytest.approx(1.4)
    # Centres of mass agree (the root at the world origin, unturned: base frame = world frame).
    com = (model.body_mass[hull] * data.xipos[hull] + model.body_mass[camera] * data.xipos[camera]) / robot.base.mass
    np.testing.assert_allclose(com, robot.base.com, atol=1e-14)
    shoulder = np.array([0.25, 0.0, -0.1])
    np.testing.assert_allclose(data.xipos[arm], shoulder + np.array(robot.links[0].com), atol=1e-14)
    np.testing.assert_allclose(robot.links[0].com, (np.array([0.1, 0.0, 0.0]) + 0.4 * np.array([0.15, 0.0, 0.01])) / 1.4, atol=1e-15)


def test_a_mass_override_replaces_the_descriptions_inertial_before_the_items(rov: Path, tmp_path: Path) -> None:
    full = "[links.hull]\nmass = 12.0\ncom = [0.0, 0.0, -0.02]\ninertia = [0.3, 0.4, 0.5]\n"
    model, robot = model_and_robot(rov, hydro(tmp_path, full))
    mass, com, inertia = body_inertia(model, "hull")
    assert mass == 12.0
    np.testing.assert_allclose(com, [0.0, 0.0, -0.02], atol=1e-16)
    np.testing.assert_allclose(inertia, np.diag([0.3, 0.4, 0.5]), rtol=1e-12)
    assert robot.base is not None and robot.base.mass == pytest.approx(12.5)
    # Mass alone: the description's centre of mass, its inertia scaled by 12/10.
    model, _ = model_and_robot(rov, hydro(tmp_path, "[links.hull]\nmass = 12.0\n"))
    mass, com, inertia = body_inertia(model, "hull")
    np.testing.assert_allclose(inertia, 1.2 * np.diag([0.2, 0.3, 0.4]), rtol=1e-12)
    assert mass == 12.0 and np.allclose(com, 0.0)
    # Then the items: 12 kg at (0, 0, −0.02) and 3 kg at (0, 0, 0.08): 15 kg at (0, 0, 0).
    with_item = full + "[[links.hull.items]]\nmass = 3.0\nvolume = 0.0\nposition = [0.0, 0.0, 0.08]\n"
    parts = urdf_parts(rov, hydro(tmp_path, with_item))
    model, _ = model_and_robot(rov, tmp_path / "rov.hydro.toml")
    mass, com, inertia = body_inertia(model, "hull")
    assert mass == 15.0
    np.testing.assert_allclose(com, 0.0, atol=1e-16)
    np.testing.assert_allclose(inertia, np.diag([0.3 + 12 * 0.02**2 + 3 * 0.08**2, 0.4 + 12 * 0.02**2 + 3 * 0.08**2, 0.5]), rtol=1e-12)
    (override,) = parts.overrides
    assert (override.body, override.described_mass, override.mass, override.inertia_given) == ("hull", 10.0, 12.0, True)
    np.testing.assert_allclose(override.com, [0.0, 0.0, -0.02], atol=1e-16)


def test_a_link_the_description_leaves_massless_takes_an_override_with_its_inertia(tmp_path: Path) -> None:
    urdf = tmp_path / "bare.urdf"
    urdf.write_text(
        '<robot name="bare"><link name="base"><inertial><mass value="5"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/>'
        '</inertial></link><link name="tool"><collision><geometry><sphere radius="0.05"/></geometry></collision></link>'
        '<joint name="slide" type="prismatic"><parent link="base"/><child link="tool"/><axis xyz="1 0 0"/>'
        '<limit lower="0" upper="1" effort="1" velocity="1"/></joint></robot>'
    )
    with pytest.raises(uwml.DescriptionError, match=r"link 'tool' is moved by joint 'slide' but has no <inertial>"):
        uwml.Robot.from_urdf(urdf)
    with pytest.raises(uwml.DescriptionError, match=r"\[links\.tool\], key 'mass': the description gives this link no mass .*give inertia"):
        uwml.Robot.from_urdf(urdf, hydro(tmp_path, "[links.tool]\nmass = 0.8\n"))
    model, robot = model_and_robot(
        urdf, hydro(tmp_path, "[links.tool]\nmass = 0.8\ncom = [0.01, 0.0, 0.0]\ninertia = [1e-3, 1e-3, 1e-3]\n")
    )
    assert robot.links[0].mass == 0.8 and robot.links[0].com == pytest.approx((0.01, 0.0, 0.0))
    assert body_inertia(model, "tool")[0] == 0.8


@pytest.mark.parametrize(
    "text, message",
    [
        ("[links.hull]\nmass = 0.0\n", r"\[links\.hull\], key 'mass': must be a mass \[kg\], above 0.*positive"),
        ("[links.hull]\nmass = -2.0\n", r"\[links\.hull\], key 'mass': must be a mass .*between 0 and 1e\+09 kg"),
        ("[links.hull]\nmass = nan\n", r"\[links\.hull\], key 'mass': must be a mass"),
        ("[links.hull]\nmass = 1.0\ninertia = [0.1, 0.1, 0.3]\n", r"key 'inertia': .*izz at most the sum of the other two"),
        ("[links.hull]\nmass = 1.0\ninertia = [0.1, 0.0, 0.1]\n", r"key 'inertia': .*each moment finite, above 0"),
        ("[links.hull]\nmass = 1.0\ninertia = [0.1, 0.1]\n", r"key 'inertia': .*not an array of 3 numbers"),
        ("[links.hull]\ncom = [0.0, 0.0, 0.0]\n", r"\[links\.hull\], key 'com': needs mass"),
        ("[links.hull]\ninertia = [1.0, 1.0, 1.0]\n", r"\[links\.hull\], key 'inertia': needs mass"),
        (
            "[links.hull]\nballast = 1.0\n",
            r"\[links\.hull\], key 'ballast': is not a key of this table \(allowed: .*mass, com, inertia, items, thrusters\)",
        ),
        (
            "[[links.hull.items]]\nweight = 1.0\n",
            r"\[links\.hull\], items\[0\], key 'weight': is not a key of this table \(allowed: name, mass, volume, position, inertia\)",
        ),
        ("[[links.hull.items]]\nmass = 1.0\nposition = [0.0, 0.0, 0.0]\n", r"\[links\.hull\], items\[0\], key 'volume': is missing"),
        ("[[links.hull.items]]\nmass = 1.0\nvolume = 0.0\n", r"items\[0\], key 'position': is missing"),
        ("[[links.hull.items]]\nmass = -1.0\nvolume = 0.0\nposition = [0, 0, 0]\n", r"items\[0\], key 'mass': must be a mass"),
        ("[[links.hull.items]]\nmass = 1.0\nvolume = -0.1\nposition = [0, 0, 0]\n", r"items\[0\], key 'volume': must be a volume"),
        ("[[links.hull.items]]\nmass = 1.0\nvolume = 0.0\nposition = [0, 0, 1e5]\n", r"items\[0\], key 'position': .*at most 10000 m"),
        ("[[links.hull.items]]\nmass = 1.0\nvolume = 0.0\nposition = [0, 0, 0]\nname = 3\n", r"items\[0\], key 'name': .*not a string"),
        (
            "[[links.hull.items]]\nmass = 0.0\nvolume = 0.001\nposition = [0, 0, 0]\ninertia = [1.0, 1.0, 1.0]\n",
            r"items\[0\], key 'inertia': needs a mass above 0",
        ),
        (
            "[[links.hull.items]]\nmass = 1.0\nvolume = 0.0\nposition = [0, 0, 0]\ninertia = [1.0, 1.0, 3.0]\n",
            r"items\[0\], key 'inertia': .*triangle inequality",
        ),
        ("[links.hull]\nitems = 3\n", r"\[links\.hull\], key 'items': must be an array of tables"),
        ("[links.camera]\ndry = true\n[[links.camera.items]]\nmass = 1.0\nvolume = 0.001\nposition = [0, 0, 0]\n", r"a dry link has none"),
    ],
)
def test_bad_masses_and_items_are_refused_naming_the_file_table_and_key(rov: Path, tmp_path: Path, text: str, message: str) -> None:
    with pytest.raises(uwml.DescriptionError, match=r"rov\.hydro\.toml: " + message if message.startswith(r"\[") else message):
        uwml.Robot.from_urdf(rov, hydro(tmp_path, text))


def test_items_are_capped_per_link(rov: Path, tmp_path: Path) -> None:
    item = "[[links.hull.items]]\nmass = 0.1\nvolume = 0.0\nposition = [0.0, 0.0, 0.0]\n"
    assert len(urdf_parts(rov, hydro(tmp_path, item * 64)).items) == 64
    with pytest.raises(uwml.DescriptionError, match=r"key 'items': has 65 entries; a link takes at most 64 items"):
        uwml.Robot.from_urdf(rov, hydro(tmp_path, item * 65))


def test_a_dry_link_takes_masses_without_volume(rov: Path, tmp_path: Path) -> None:
    text = "[links.camera]\ndry = true\nmass = 1.0\n[[links.camera.items]]\nmass = 0.5\nvolume = 0.0\nposition = [0.0, 0.0, 0.0]\n"
    robot = uwml.Robot.from_urdf(rov, hydro(tmp_path, text))
    assert robot.base is not None
    assert robot.base.mass == pytest.approx(11.5) and robot.base.volume == pytest.approx(BOX)


def test_a_compiled_model_refuses_masses_it_would_not_carry(rov: Path, tmp_path: Path) -> None:
    model, _ = model_and_robot(rov)
    with pytest.raises(uwml.DescriptionError, match=r"\[links\.hull\] gives a mass override, which a compiled mujoco\.MjModel cannot take"):
        uwml.Robot.from_mujoco(model, hydro(tmp_path, "[links.hull]\nmass = 12.0\n"))
    foam = "[[links.hull.items]]\nmass = 0.0\nvolume = 0.001\nposition = [0.0, 0.0, 0.1]\n"
    robot = uwml.Robot.from_mujoco(model, hydro(tmp_path, foam))  # buoyancy alone: the model's masses stay right
    assert robot.base is not None and robot.base.volume == pytest.approx(BOX + CAMERA + 0.001)


def test_a_lumped_models_point_stays_where_the_body_alone_puts_it(rov: Path, tmp_path: Path) -> None:
    base = "[links.hull]\nstrips = false\n[links.camera]\ndry = true\n" + LUMPED
    plain = uwml.Robot.from_urdf(rov, hydro(tmp_path, base))
    item = "[[links.hull.items]]\nmass = 1.0\nvolume = 0.003\nposition = [0.1, 0.1, 0.1]\n"
    robot = uwml.Robot.from_urdf(rov, hydro(tmp_path, base + item))
    assert plain.base is not None and robot.base is not None and robot.base.lumped is not None and plain.base.lumped is not None
    assert robot.base.cob != plain.base.cob
    np.testing.assert_allclose(robot.base.lumped.point, plain.base.lumped.point, atol=1e-16)


def test_a_link_fused_into_a_lumped_body_warns_naming_it_and_what_it_adds(rov: Path, tmp_path: Path) -> None:
    with pytest.warns(uwml.DescriptionWarning) as caught:
        robot = uwml.Robot.from_urdf(rov, hydro(tmp_path, "[links.hull]\nstrips = false\n" + LUMPED))
    (warning,) = [w for w in caught if issubclass(w.category, uwml.DescriptionWarning)]
    text = str(warning.message)
    litres = f"{1000 * CAMERA:.4g} L"
    assert "link 'camera' is fused into link 'hull'" in text and "[links.hull]" in text
    assert litres in text and f"{RHO * G * CAMERA:.4g} N of buoyancy" in text and "1 strip segment with the default coefficients" in text
    assert "dry = true in [links.camera]" in text and "strips = false" in text
    assert issubclass(uwml.DescriptionWarning, uwml.PlausibilityWarning) and issubclass(uwml.DescriptionWarning, UserWarning)
    assert robot.base is not None and len(robot.base.segments) == 1  # the camera's strip, as warned
    for fix in ("[links.camera]\ndry = true\n", "[links.camera]\nstrips = false\n"):
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            quiet = uwml.Robot.from_urdf(rov, hydro(tmp_path, "[links.hull]\nstrips = false\n" + fix + LUMPED))
        assert quiet.base is not None and not quiet.base.segments
    # Items alone on the fused link say nothing of its water: still warned.
    items = "[[links.camera.items]]\nmass = 0.1\nvolume = 0.0\nposition = [0.0, 0.0, 0.0]\n"
    with pytest.warns(uwml.DescriptionWarning, match="link 'camera' is fused into link 'hull'"):
        uwml.Robot.from_urdf(rov, hydro(tmp_path, "[links.hull]\nstrips = false\n" + items + LUMPED))
    # Without a lumped model, fusing is the rule (docs/model.md section 10) and nothing is said.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        uwml.Robot.from_urdf(rov)


def test_describe_lists_items_and_overrides(rov: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    text = (
        "[links.hull]\nmass = 12.0\n"
        '[[links.hull.items]]\nname = "lead"\nmass = 2.0\nvolume = 0.0002\nposition = [0.1, 0.0, -0.05]\n'
        "[[links.camera.items]]\nmass = 0.1\nvolume = 0.0003\nposition = [0.05, 0.0, 0.0]\n"
    )
    file = hydro(tmp_path, text)
    parts = urdf_parts(rov, file)
    listing = describe(parts.build(uwml.Robot), items=parts.items, overrides=parts.overrides)
    # lead: ρ V g = 1000 · 0.0002 · 9.81 = 1.962 N up, m g = 19.62 N down: net −17.66 N.
    lead = next(line for line in listing.splitlines() if " lead " in line)
    assert lead.split()[:2] == ["base", "lead"] and "mass         2 kg" in lead and "buoyancy     1.962 N" in lead
    assert "net     -17.66 N" in lead and "at (0.1, 0, -0.05)" in lead
    # The camera's item, unnamed, placed in the hull's frame: (0.2, 0.05, 0.05); net (0.3 − 0.1) · 9.81.
    camera = next(line for line in listing.splitlines() if "item 1" in line)
    assert "net     +1.962 N" in camera and "at (0.2, 0.05, 0.05)" in camera and "(of camera, fused into hull)" in camera
    assert "mass        12 kg (the description's 10 kg)  COM (0, 0, 0)  its inertia the description's, scaled" in listing
    assert main(["describe", "--robot", str(rov), "--hydro", str(file)]) == 0
    out = capsys.readouterr().out
    assert "point items" in out and lead in out and "mass overrides" in out
    # Without items or overrides, no such section.
    plain = describe(uwml.Robot.from_urdf(rov))
    assert "point items" not in plain and "mass overrides" not in plain


def test_the_documented_example_hydro_file_has_an_item() -> None:
    from uwml.io.hydrofile import read_hydro

    (lead,) = read_hydro(Path(__file__).resolve().parents[1] / "examples" / "hydro.toml").links["hull"].items
    assert (lead.name, lead.mass, lead.volume, lead.position, lead.inertia) == ("lead", 1.2, 0.000106, (0.0, 0.0, -0.2), None)
