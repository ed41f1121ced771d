"""URDF and MJCF descriptions to uwml.Robot (uwml.io.descriptions, docs/model.md section 10)."""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest
import uwml

pytest.importorskip("mujoco")

DATA = Path(__file__).parent / "data"
STATES = [
    ([0.3, -0.4, 0.6], [0.8, 0.5, -0.7], [1.0, -2.0, 0.5]),
    ([-1.1, 0.7, -0.2], [-0.3, 1.2, 0.9], [0.4, 0.3, -1.5]),
]
MOTION = uwml.BaseMotion(
    orientation=(math.cos(0.2), 0.3 * math.sin(0.2), -0.5 * math.sin(0.2), math.sqrt(0.66) * math.sin(0.2)),
    velocity=(0.4, -0.2, 0.1),
    angular_velocity=(0.05, 0.1, -0.2),
    acceleration=(0.3, 0.1, -0.2),
    angular_acceleration=(-0.1, 0.2, 0.05),
)
CURRENT = {"current": (0.3, -0.2, 0.05), "current_acceleration": (0.02, 0.01, -0.03)}


def assert_same_forces(a: uwml.Robot, b: uwml.Robot, q: list[float], qd: list[float], qdd: list[float], **kwargs: object) -> None:
    """Every joint force and the base wrench agree to 1e-12 of the largest."""
    ta, tb = a.hydro(q, qd, qdd, base=True, **kwargs), b.hydro(q, qd, qdd, base=True, **kwargs)  # type: ignore[arg-type]
    for name in ("drag", "added_mass", "buoyancy", "gravity"):
        x = np.concatenate([getattr(ta, name), getattr(ta.base, name)])
        y = np.concatenate([getattr(tb, name), getattr(tb.base, name)])
        scale = max(1.0, float(np.max(np.abs(y))))
        assert np.max(np.abs(x - y)) <= 1e-12 * scale, (name, x, y)


@pytest.fixture(scope="module")
def paper() -> uwml.Robot:
    return uwml.paper_leg()


@pytest.mark.parametrize("loader, file", [(uwml.Robot.from_urdf, "paper_leg.urdf"), (uwml.Robot.from_mjcf, "paper_leg.xml")])
def test_paper_leg_from_descriptions(paper: uwml.Robot, loader, file: str) -> None:
    robot = loader(DATA / file, DATA / "paper_leg.hydro.toml")
    assert robot.joint_names == ("hip_yaw", "hip_roll", "knee")
    assert robot.link_names == ("hip", "thigh", "calf")
    assert [j.parent for j in robot.joints] == [-1, 0, 1]
    for link, expected in zip(robot.links, paper.links):
        assert link.mass == expected.mass and link.volume == expected.volume
        np.testing.assert_allclose(link.com, expected.com, atol=1e-15)
    for q, qd, qdd in STATES:
        assert_same_forces(robot, paper, q, qd, qdd)
        assert_same_forces(robot, paper, q, qd, qdd, base_motion=MOTION, **CURRENT)


def test_paper_leg_reference_values(paper: uwml.Robot) -> None:
    """docs/model.md section 5's table, through the URDF."""
    robot = uwml.Robot.from_urdf(DATA / "paper_leg.urdf", DATA / "paper_leg.hydro.toml")
    t = robot.hydro([0.3, -0.4, 0.6], [0.8, 0.5, -0.7], [1.0, -2.0, 0.5])
    np.testing.assert_allclose(t.drag, [-24.24084, -5.060505, -0.7383118], rtol=1e-6)
    np.testing.assert_allclose(t.added_mass, [-8.525438, 21.77596, 9.484545], rtol=1e-6)
    np.testing.assert_allclose(t.buoyancy, [0.0, 59.72457, 4.193843], rtol=1e-6, atol=1e-12)


def test_from_mujoco_model_in_memory(paper: uwml.Robot) -> None:
    import mujoco

    model = mujoco.MjModel.from_xml_string(
        (DATA / "paper_leg.xml")
        .read_text()
        .replace('<asset><mesh name="thigh_visual" file="meshes/thigh_does_not_exist.stl"/></asset>', "")
        .replace('<geom class="visual" type="mesh" mesh="thigh_visual"/>', "")
    )
    robot = uwml.Robot.from_mujoco(model, DATA / "paper_leg.hydro.toml")
    assert_same_forces(robot, paper, *STATES[0])
    with pytest.raises(TypeError, match="mujoco.MjModel"):
        uwml.Robot.from_mujoco("not a model")


def test_without_hydro_file_primitive_volumes() -> None:
    """No hydro file: volume = the boxes' volumes, COB their centroid, default coefficients."""
    robot = uwml.Robot.from_urdf(DATA / "paper_leg.urdf")
    thigh, calf = robot.links[1], robot.links[2]
    assert thigh.volume == pytest.approx(0.66 * 0.238 * 0.131, rel=1e-15)
    np.testing.assert_allclose(thigh.cob, (0.33, 0.0, 0.0), atol=1e-15)
    np.testing.assert_allclose(calf.cob, (0.0, 0.0, -0.357), atol=1e-15)
    assert robot.links[0].volume == 0.0
    assert thigh.segments[0].cd == uwml.model.RECTANGULAR_DEFAULTS[:1] * 2


def rpy(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """URDF's fixed-axis roll, pitch, yaw: Rz(yaw) Ry(pitch) Rx(roll) (scipy's extrinsic xyz)."""
    from scipy.spatial.transform import Rotation

    return Rotation.from_euler("xyz", [roll, pitch, yaw]).as_matrix()


def t(v: np.ndarray) -> tuple[float, float, float]:
    return (float(v[0]), float(v[1]), float(v[2]))


def hand_built_arm() -> uwml.Robot:
    """arm.urdf with arm.hydro.toml, built by hand in uwml's base-parallel frames."""
    x, y, z = np.eye(3)
    hull = uwml.Link(
        50.0,
        (0, 0, -0.05),
        1.2 * 0.8 * 0.4,
        cob=(0, 0, 0),
        segments=[uwml.Segment((-0.6, 0, 0), (1, 0, 0), 1.2, normals=((0, 1, 0), (0, 0, 1)), widths=(0.4, 0.8), area=0.32, cd=(2.0, 2.1))],
    )
    r1 = rpy(0, 0, math.pi / 2)
    o1 = np.array([0.5, 0, -0.2])
    upper = uwml.Link(
        3.0,
        t(r1 @ (0.2 * x)),
        math.pi * 0.05**2 * 0.4,
        segments=[uwml.Segment(t(r1 @ (0.2 * x) - 0.2 * (r1 @ x)), t(r1 @ x), 0.4, section="circular", diameter=0.1, cd=1.1, cm=0.9)],
    )
    r2 = r1 @ rpy(0.3, 0.2, -0.4)
    o2 = o1 + r1 @ (0.4 * x)
    r3 = r2 @ rpy(0, 0, 0.5)
    p3 = o2 + r2 @ (0.3 * x)
    fore_com, wrist_com = r2 @ (0.15 * x), p3 - o2
    cylinder_volume = math.pi * 0.04**2 * 0.3
    wrist_cob = p3 - o2 + r3 @ (0.01 * x)
    fore = uwml.Link(
        2.5,
        t((2.0 * fore_com + 0.5 * wrist_com) / 2.5),
        cylinder_volume + 0.0006,
        cob=t((cylinder_volume * fore_com + 0.0006 * wrist_cob) / (cylinder_volume + 0.0006)),
        segments=[uwml.Segment(t(r2 @ (0.15 * x) - 0.15 * (r2 @ x)), t(r2 @ x), 0.3, section="circular", diameter=0.08)],
    )
    o4 = p3 + r3 @ (0.05 * x)
    fingers = [
        uwml.Segment(t(r3 @ (side * 0.03 * y)), t(r3 @ x), 0.1, normals=(t(r3 @ z), t(r3 @ y)), widths=(0.02, 0.04), area=0.04 * 0.02)
        for side in (1.0, -1.0)
    ]
    finger = uwml.Link(0.3, t(r3 @ (0.05 * x)), 2 * 0.1 * 0.02 * 0.04, segments=fingers)
    joints = [
        uwml.Joint(t(o1), (0, 0, 1), parent=-1),
        uwml.Joint(t(o2 - o1), t(r2 @ y), parent=0),
        uwml.Joint(t(o4 - o2), t(r3 @ y), parent=1, kind="prismatic"),
    ]
    return uwml.Robot(joints, [upper, fore, finger], base=hull)


ARM_STATES = [([0.4, -0.7, 0.01], [0.6, -0.9, 0.05], [1.5, 0.4, -0.3]), ([-1.2, 2.0, -0.015], [-0.2, 0.3, -0.08], [0.2, -1.0, 0.6])]


def test_arm_urdf_and_mjcf_are_the_same_robot_as_built_by_hand() -> None:
    urdf = uwml.Robot.from_urdf(DATA / "arm.urdf", DATA / "arm.hydro.toml")
    mjcf = uwml.Robot.from_mjcf(DATA / "arm.xml", DATA / "arm.hydro.toml")
    by_hand = hand_built_arm()
    for robot in (urdf, mjcf):
        assert robot.joint_names == ("shoulder", "elbow", "gripper")
        assert robot.link_names == ("upper_arm", "forearm", "finger")
        assert robot.base is not None and robot.base.name == "hull"
        assert [j.kind for j in robot.joints] == ["revolute", "revolute", "prismatic"]
        assert len(robot.segments) == 5
        for q, qd, qdd in ARM_STATES:
            assert_same_forces(robot, by_hand, q, qd, qdd)
            assert_same_forces(robot, by_hand, q, qd, qdd, base_motion=MOTION, **CURRENT)
    for q, qd, qdd in ARM_STATES:
        assert_same_forces(urdf, mjcf, q, qd, qdd, base_motion=MOTION, **CURRENT)


def test_tree_through_both_formats() -> None:
    urdf = uwml.Robot.from_urdf(DATA / "biped.urdf")
    mjcf = uwml.Robot.from_mjcf(DATA / "biped.xml")
    for robot in (urdf, mjcf):
        assert robot.joint_names == ("left_hip", "left_knee", "right_hip", "right_knee")
        assert [j.parent for j in robot.joints] == [-1, 0, -1, 2]
        shin = robot.links[1]
        assert shin.volume == pytest.approx(math.pi * 0.03**2 * 0.3 + 4 / 3 * math.pi * 0.04**3, rel=1e-14)
        assert len(shin.segments) == 1 and shin.segments[0].section == "circular"
    np.testing.assert_allclose(urdf.joints[0].axis, (0.0, math.cos(0.2), math.sin(0.2)), atol=1e-15)
    q, qd, qdd = [0.3, -0.5, -0.2, 0.8], [0.5, -1.0, 0.7, 0.2], [1.0, 0.5, -0.4, 2.0]
    assert_same_forces(urdf, mjcf, q, qd, qdd)
    assert_same_forces(urdf, mjcf, q, qd, qdd, base_motion=MOTION, **CURRENT)


MESH_URDF = """<robot name="m">
  <link name="base"/>
  <link name="hand"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><mesh filename="hand_absent.stl"/></geometry></collision></link>
  <joint name="j" type="continuous"><parent link="base"/><child link="hand"/><axis xyz="0 0 1"/></joint>
</robot>"""


def test_errors_name_the_file_and_element(tmp_path: Path) -> None:
    bad = tmp_path / "bad.urdf"
    bad.write_text('<robot name="x"><link name="a"></robot>')
    with pytest.raises(
        uwml.DescriptionError, match=r"bad\.urdf: not a readable URDF file: not well-formed XML \(mismatched tag\) at line 1"
    ):
        uwml.Robot.from_urdf(bad)
    with pytest.raises(uwml.DescriptionError, match=r"absent\.xml: the MJCF file cannot be read: no such file"):
        uwml.Robot.from_mjcf(tmp_path / "absent.xml")
    ball = tmp_path / "ball.xml"
    ball.write_text(
        '<mujoco><worldbody><body name="b"><geom size="0.1"/><body name="c"><joint name="shoulder_ball" type="ball"/><geom size="0.1"/></body></body></worldbody></mujoco>'
    )
    with pytest.raises(uwml.DescriptionError, match=r"ball\.xml: joint 'shoulder_ball' is a ball joint"):
        uwml.Robot.from_mjcf(ball)
    mesh = tmp_path / "mesh.urdf"
    mesh.write_text(MESH_URDF)
    with pytest.raises(uwml.DescriptionError, match=r"mesh\.urdf: link 'hand' has a collision mesh .*\[links\.hand\]"):
        uwml.Robot.from_urdf(mesh)
    hydro = tmp_path / "hand.toml"
    hydro.write_text(
        '[links.hand]\nvolume = 0.001\ncob = [0.0, 0.0, 0.1]\n\n[[links.hand.segments]]\nsection = "circular"\nstart = [0.0, 0.0, 0.0]\naxis = [0.0, 0.0, 1.0]\nlength = 0.2\ndiameter = 0.05\narea = 0.002\ncd = [1.0, 1.0]\ncm = [1.0, 1.0]\n'
    )
    robot = uwml.Robot.from_urdf(mesh, hydro)  # the mesh link described by the hydro file loads
    assert robot.links[0].volume == 0.001 and robot.links[0].cob == (0.0, 0.0, 0.1) and len(robot.segments) == 1
    dry = tmp_path / "dry.toml"
    dry.write_text("[links.hand]\ndry = true\n")
    assert uwml.Robot.from_urdf(mesh, dry).links[0].volume == 0.0


@pytest.mark.parametrize(
    "text, message",
    [
        ("[links.calfx]\nvolume = 0.1\n", r"h\.toml: \[links\.calfx\]: .*paper_leg\.urdf has no link \(body\) named 'calfx'"),
        ("[links.calf]\nvolum = 0.1\n", r"h\.toml: \[links\.calf\], key 'volum': is not a key of this table"),
        ('[links.calf]\nvolume = "big"\n', r"h\.toml: \[links\.calf\], key 'volume': must be a volume"),
        ("[links.calf]\ncob = [0.0, 0.0, 0.0]\n", r"h\.toml: \[links\.calf\], key 'cob': needs volume"),
        ("[links.calf]\ndry = true\ncd = 1.0\n", r"h\.toml: \[links\.calf\], key 'cd': a dry link"),
        (
            "[links.calf]\nsegment_cd = [1.0, 2.0]\n",
            r"h\.toml: \[links\.calf\], key 'segment_cd': must have one entry per segment of the link \(1\), got 2",
        ),
        ('[[links.calf.segments]]\nsection = "circular"\n', r"h\.toml: \[links\.calf\], segments\[0\], key 'start': is missing"),
        (
            '[[links.calf.segments]]\nsection = "circular"\nstart = [0.0, 0.0, 0.0]\naxis = [0.0, 0.0, 1.0]\nlength = 0.2\narea = 0.002\ncd = [1.0, 1.0]\ncm = [1.0, 1.0]\ndiameter = 0.05\nwidths = [0.05, 0.05]\n',
            r"h\.toml: \[links\.calf\], segments\[0\], key 'widths': is not a key of a circular section \(a circular section takes diameter\)",
        ),
        (
            '[[links.calf.segments]]\nsection = "rectangular"\nstart = [0.0, 0.0, 0.0]\naxis = [0.0, 0.0, 1.0]\nlength = 0.2\narea = 0.002\ncd = [1.0, 1.0]\ncm = [1.0, 1.0]\nnormals = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]\nwidths = [0.05, 0.08]\ndiameter = 0.05\n',
            r"h\.toml: \[links\.calf\], segments\[0\], key 'diameter': is not a key of a rectangular section \(a rectangular section takes normals and widths\)",
        ),
        ("[joints.knee]\nseal = 1\n", r"h\.toml: \[joints\.knee\], seal: must be a table, got int"),
        (
            "[joints.kne]\nepsilon = 0.01\n",
            r"h\.toml: \[joints\.kne\]: no joint of that name in the description \(its joints: hip_yaw, hip_roll, knee\)",
        ),
        ("[joints.knee]\nepsilon = 0.01\n[joints.knee.seal]\nc0 = 1.0\n", r"h\.toml: \[joints\.knee\], seal, key 'c1_per_mpa': is missing"),
        (
            "[water]\ndensity = 1.025\n",
            r"h\.toml: \[water\], key 'density': must be a density \[kg/m³\], 900 to 1300, got 1\.025 \(outside .*g/cm³",
        ),
        (
            "[water]\ngravity = 32.2\n",
            r"h\.toml: \[water\], key 'gravity': must be an acceleration \[m/s²\], 9\.7 to 9\.9, got 32\.2 \(.*ft/s²",
        ),
        ("[water]\nsalinity = 35.0\n", r"h\.toml: \[water\], key 'salinity': is not a key of this table \(allowed: density, gravity\)"),
        ("water = 1025.0\n", r"h\.toml: \[water\]: must be a table, got float"),
        ("[links.calf\n", r"h\.toml: not valid TOML"),
    ],
)
def test_hydro_file_errors(tmp_path: Path, text: str, message: str) -> None:
    hydro = tmp_path / "h.toml"
    hydro.write_text(text)
    with pytest.raises(uwml.DescriptionError, match=message):
        uwml.Robot.from_urdf(DATA / "paper_leg.urdf", hydro)


def test_missing_hydro_file(tmp_path: Path) -> None:
    with pytest.raises(uwml.DescriptionError, match=r"nothing\.toml: the hydro file cannot be read"):
        uwml.Robot.from_urdf(DATA / "paper_leg.urdf", tmp_path / "nothing.toml")


def test_hydro_segment_coefficients_per_segment(tmp_path: Path) -> None:
    hydro = tmp_path / "h.toml"
    hydro.write_text("[links.finger]\nsegment_cd = [[1.0, 1.5], 2.0]\nsegment_cm = [0.7, [0.8, 0.9]]\n")
    finger = uwml.Robot.from_urdf(DATA / "arm.urdf", hydro).links[2]
    assert [s.cd for s in finger.segments] == [(1.0, 1.5), (2.0, 2.0)]
    assert [s.cm for s in finger.segments] == [(0.7, 0.7), (0.8, 0.9)]


def test_joint_losses_from_the_hydro_file(tmp_path: Path) -> None:
    hydro = tmp_path / "h.toml"
    seal = uwml.Seal()
    seal_lines = "\n".join(
        f"{name} = {getattr(seal, name)!r}" for name in ("c0", "c1_per_mpa", "s0", "s1_per_mpa", "d0", "d1_per_mpa", "stribeck_speed")
    )
    hydro.write_text((DATA / "paper_leg.hydro.toml").read_text() + f"\n[joints.knee]\nepsilon = 0.02\n\n[joints.knee.seal]\n{seal_lines}\n")
    robot = uwml.Robot.from_urdf(DATA / "paper_leg.urdf", hydro)
    knee = uwml.JointLosses(oil=None, seal=seal, epsilon=0.02)
    assert robot.losses == (None, None, knee)
    q, qd = [0.3, -0.4, 0.6], [0.5, -0.8, 1.1]
    own = robot.environment(q, qd, [0.0] * 3, depth=3000.0, temperature_c=4.0)
    given = uwml.paper_leg().environment(q, qd, [0.0] * 3, depth=3000.0, temperature_c=4.0, losses=[None, None, knee])
    np.testing.assert_allclose(own.seal, given.seal, rtol=1e-14)
    assert own.seal[2] * qd[2] < 0.0 and own.seal[0] == 0.0
    # The model file keeps them.
    path = tmp_path / "leg.toml"
    robot.save(path)
    assert uwml.Robot.load(path).losses == robot.losses
    # Without epsilon, the smooth sign's width is the default the format page states: 1e-3 rad/s.
    hydro.write_text((DATA / "paper_leg.hydro.toml").read_text() + f"\n[joints.knee.seal]\n{seal_lines}\n")
    assert uwml.Robot.from_urdf(DATA / "paper_leg.urdf", hydro).losses[2] == uwml.JointLosses(oil=None, seal=seal, epsilon=1e-3)


def test_water_from_the_hydro_file(tmp_path: Path) -> None:
    """``[water]`` sets the robot's water: every evaluation uses it unless given another, and
    the model file keeps it. Buoyancy is proportional to the density (docs/model.md section 10,
    "Base motion and current"), so the sea-water robot's buoyancy is 1025/1000 of the fresh-water
    one's."""
    hydro = tmp_path / "h.toml"
    hydro.write_text((DATA / "paper_leg.hydro.toml").read_text() + "\n[water]\ndensity = 1025.0\ngravity = 9.80665\n")
    sea = uwml.Robot.from_urdf(DATA / "paper_leg.urdf", hydro)
    fresh = uwml.Robot.from_urdf(DATA / "paper_leg.urdf", DATA / "paper_leg.hydro.toml")
    assert sea.water == uwml.Water(density=1025.0, gravity=9.80665) and fresh.water == uwml.Water()
    q, qd, qdd = STATES[0]
    own, given = sea.hydro(q, qd, qdd), fresh.hydro(q, qd, qdd, water=uwml.Water(density=1025.0, gravity=9.80665))
    for name in ("drag", "added_mass", "buoyancy", "gravity"):
        np.testing.assert_array_equal(getattr(own, name), getattr(given, name))
    np.testing.assert_array_equal(own.base.total, given.base.total)
    plain = fresh.hydro(q, qd, qdd, water=uwml.Water(density=1000.0, gravity=9.80665))
    np.testing.assert_allclose(own.buoyancy, 1.025 * plain.buoyancy, rtol=1e-14)
    # Given water wins over the robot's own.
    np.testing.assert_array_equal(sea.hydro(q, qd, qdd, water=uwml.Water()).buoyancy, fresh.hydro(q, qd, qdd).buoyancy)
    path = tmp_path / "leg.toml"
    sea.save(path)
    loaded = uwml.Robot.load(path)
    assert loaded == sea and loaded.water == sea.water and loaded != fresh


def test_the_documented_example_hydro_file_reads() -> None:
    """examples/hydro.toml, the format's documented example, is a valid hydro file."""
    from uwml.io.hydrofile import read_hydro

    file = read_hydro(Path(__file__).resolve().parents[1] / "examples" / "hydro.toml")
    assert set(file.links) == {"upper_arm", "wrist", "camera", "hull"} and file.links["camera"].dry
    assert file.links["hull"].segments[0].diameter == 0.6 and file.links["wrist"].cob == (0.01, 0.0, 0.0)
    assert file.joints["elbow"].seal is not None and file.joints["elbow"].seal.c0 == 16.0 and file.joints["elbow"].oil is None
    assert file.water == uwml.Water(1025.0, 9.81)


def test_the_readme_own_robot_section_runs(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The tour's "Your own robot, from its URDF" (docs/tour.md): its URDF and hydro file and its
    Python, run as written, the numbers checked."""
    readme = (Path(__file__).resolve().parents[1] / "docs" / "tour.md").read_text(encoding="utf-8")
    section = readme.split("## Your own robot, from its URDF", 1)[1].split("\n## ", 1)[0]

    def block(language: str) -> str:
        return section.split(f"```{language}\n", 1)[1].split("```", 1)[0]

    (tmp_path / "examples" / "my_arm").mkdir(parents=True)
    (tmp_path / "examples" / "my_arm" / "my_arm.urdf").write_text(block("xml"))
    (tmp_path / "examples" / "my_arm" / "my_arm.hydro.toml").write_text(block("toml"))
    monkeypatch.chdir(tmp_path)
    namespace: dict = {}
    exec(compile(block("python"), "docs/tour.md", "exec"), namespace)  # noqa: S102 - the tour's own example
    arm, tau = namespace["arm"], namespace["tau"]
    assert arm.joint_names == ("shoulder", "elbow") and arm.link_names == ("upper_arm", "forearm")
    assert arm.water == uwml.Water(1025.0) and arm.base is not None and arm.base.volume == pytest.approx(0.48, rel=1e-14)
    # The hull's buoyancy, up, in the base wrench (fixed base): ρ V g of everything, less the weight.
    volume = 0.48 + math.pi * 0.04**2 * 0.4 + math.pi * 0.03**2 * 0.3
    np.testing.assert_allclose(tau.base.buoyancy[2], 1025.0 * volume * 9.81, rtol=1e-12)
    assert uwml.Robot.load(tmp_path / "my_arm.toml") == arm
    # Its command-line block: run line by line by tests/test_readme.py.


@pytest.mark.parametrize(
    ("files", "hydro", "message"),
    [
        ({"bad.urdf": '<robot name="x"><link name="a"></robot>'}, None, r"bad\.urdf: not a readable URDF file"),
        ({}, None, r"absent\.xml: the MJCF file cannot be read"),
        (
            {
                "ball.xml": '<mujoco><worldbody><body name="b"><geom size="0.1"/><body name="c"><joint name="wrist" type="ball"/><geom size="0.1"/></body></body></worldbody></mujoco>'
            },
            None,
            r"ball\.xml: joint 'wrist' is a ball joint",
        ),
        ({"mesh.urdf": MESH_URDF}, None, r"mesh\.urdf: link 'hand' has a collision mesh"),
        (
            {"mesh.urdf": MESH_URDF, "h.toml": "[links.palm]\ndry = true\n"},
            "h.toml",
            r"h\.toml: \[links\.palm\]: .*no link \(body\) named 'palm'",
        ),
        (
            {"mesh.urdf": MESH_URDF, "h.toml": "[links.hand]\ndry = true\n[joints.k]\nepsilon = 0.01\n"},
            "h.toml",
            r"h\.toml: \[joints\.k\]: no joint of that name",
        ),
    ],
)
def test_the_command_line_names_the_file_and_element_and_exits_2(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], files: dict[str, str], hydro: str | None, message: str
) -> None:
    from uwml.cli import main

    for name, text in files.items():
        (tmp_path / name).write_text(text)
    description = next((name for name in files if name.endswith((".urdf", ".xml"))), "absent.xml")
    arguments = ["--robot", str(tmp_path / description)] + ([] if hydro is None else ["--hydro", str(tmp_path / hydro)])
    for command in (["describe"], ["export", "--c"]):
        assert main(command + arguments) == 2
        err = capsys.readouterr().err
        assert err.startswith("uwml: error: ") and re.search(message, err), err


def test_a_mesh_link_given_only_a_volume_warns_that_it_has_no_drag(tmp_path: Path) -> None:
    pytest.importorskip("mujoco")
    urdf = tmp_path / "mesh.urdf"
    urdf.write_text(MESH_URDF)
    hydro = tmp_path / "h.toml"
    hydro.write_text("[links.hand]\nvolume = 0.001\n")
    with pytest.warns(uwml.PlausibilityWarning, match=r"h\.toml: \[links\.hand\] gives the mesh link 'hand' a volume but no segments"):
        robot = uwml.Robot.from_urdf(urdf, hydro)
    assert robot.links[0].volume == 0.001 and not robot.links[0].segments
    # With a segment, or out of the water: nothing to say (the tests turn warnings into errors).
    hydro.write_text(
        '[links.hand]\nvolume = 0.001\n[[links.hand.segments]]\nsection = "circular"\nstart = [0.0, 0.0, 0.0]\n'
        "axis = [1.0, 0.0, 0.0]\nlength = 0.1\ndiameter = 0.05\narea = 0.002\ncd = [1.2, 1.2]\ncm = [1.0, 1.0]\n"
    )
    uwml.Robot.from_urdf(urdf, hydro)
    hydro.write_text("[links.hand]\ndry = true\n")
    uwml.Robot.from_urdf(urdf, hydro)
