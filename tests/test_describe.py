"""``uwml describe`` and ``uwml.viz.describe``: a robot's parts and net buoyancy in words, and its
picture at q = 0; numbers checked against hand computations."""

from pathlib import Path

import numpy as np
import pytest
import uwml
from uwml.cli import main
from uwml.examples import arm_on_rov
from uwml.viz.describe import describe, frame_origins


def test_frame_origins_add_along_the_tree() -> None:
    robot = uwml.Robot(
        [
            uwml.Joint((1, 0, 0), (0, 0, 1)),
            uwml.Joint((0, 2, 0), (0, 0, 1)),
            uwml.Joint((0, 0, 3), (1, 0, 0), parent=0),
            uwml.Joint((5, 0, 0), (0, 1, 0), parent=-1),
        ],
        [uwml.Link(1.0, (0, 0, 0), 0.0)] * 4,
    )
    np.testing.assert_array_equal(frame_origins(robot), [[1, 0, 0], [1, 2, 0], [1, 0, 3], [5, 0, 0]])


def test_the_description_states_masses_volumes_and_net_buoyancy() -> None:
    text = describe(arm_on_rov(), uwml.Water(density=1025.0, gravity=9.81))
    # The hull: 1025 · 0.29 · 9.81 = 2916 N of buoyancy, net (1025 · 0.29 − 300) · 9.81 = −26.98 N;
    # link 0: net (1025 · 0.004 − 12) · 9.81 = −77.50 N.
    assert "base             mass       300 kg  volume      0.29 m³  buoyancy      2916 N  net     -26.98 N" in text
    assert "net      -77.5 N" in text
    assert "net buoyancy" not in text and "buoyancy = ρ V g, the water's; net = ρ V g − m g" in text
    assert "joint6           prismatic parent link5" in text
    assert "circular, D 0.6 m" in text and "Cd (2, 2.1)" in text
    assert "   14 link6" in text


def test_uwml_describe_prints_and_draws(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "arm.toml"
    arm_on_rov().save(path)
    picture = tmp_path / "arm.png"
    assert main(["describe", "--robot", str(path), "--plot", str(picture), "--density", "1025"]) == 0
    out = capsys.readouterr().out
    assert "7 joints, 15 segments" in out and "buoyancy" in out and " net " in out
    assert picture.stat().st_size > 10_000 and picture.read_bytes()[:4] == b"\x89PNG"
    assert main(["describe"]) == 0
    assert "3 joints, 2 segments" in capsys.readouterr().out
    assert main(["describe", "--robot", str(tmp_path / "missing.toml")]) == 2
    assert "missing.toml: the model file cannot be read: no such file" in capsys.readouterr().err
    assert main(["describe", "--robot", str(tmp_path / "arm.stl")]) == 2
    assert "--robot takes a uwml model file (.toml), a URDF" in capsys.readouterr().err


def test_uwml_describe_reads_urdf_and_mjcf_with_their_hydro_files(capsys: pytest.CaptureFixture[str]) -> None:
    pytest.importorskip("mujoco")
    data = Path(__file__).parent / "data"
    for description in ("paper_leg.urdf", "paper_leg.xml"):
        assert main(["describe", "--robot", str(data / description), "--hydro", str(data / "paper_leg.hydro.toml")]) == 0
        out = capsys.readouterr().out
        # Table II: the thigh's 19.261 kg at 2700 kg/m³, net buoyancy (1000 V − m) g = −118.98 N.
        assert "3 joints, 2 segments" in out and "mass     19.26 kg" in out and "-119 N" in out
        # The limits as read: the URDF's range, velocity and effort; the MJCF gives none.
        knee = next(line for line in out.splitlines() if line.strip().startswith("knee"))
        if description.endswith(".urdf"):
            assert "limits: range [-3, 3] rad, velocity 10 rad/s, effort 530 N·m" in knee
        else:
            assert "limits" not in knee
    assert main(["describe", "--robot", str(data / "paper_leg.urdf"), "--hydro", str(data / "missing.toml")]) == 2
    assert "missing.toml" in capsys.readouterr().err


def test_rounding_residues_show_as_zero_and_bodies_without_drag_are_named() -> None:
    joint = uwml.Joint((0.0, 0.0, 0.0), (0.0, 0.0, 1.0))
    segment = uwml.Segment((0.0, 0.0, -1.665e-17), (1.0, 0.0, 2.22e-16), 0.5, section="circular", diameter=0.1)
    robot = uwml.Robot(
        [joint, joint], [uwml.Link(1.0, (0.25, 0, 0), 0.004, segments=[segment]), uwml.Link(0.5, (0, 0, 0), 0.001, name="can")]
    )
    text = describe(robot)
    assert "start (0, 0, 0)" in text and "e-17" not in text and "e-16" not in text
    assert "in the water without drag or added mass (a volume, no segment, no lumped model): can" in text


def test_the_picture_draws_boxes_with_a_legend(tmp_path: Path) -> None:
    from uwml.viz.describe import _box

    segment = uwml.Segment((0, 0, 0), (1, 0, 0), 2.0, normals=((0, 1, 0), (0, 0, 1)), widths=(0.4, 0.2), area=0.08)
    corners = _box(np.zeros(3), np.array([1.0, 0.0, 0.0]), segment)
    # Flow along y sees widths[0] = 0.4, the extent along z; flow along z sees 0.2, along y.
    np.testing.assert_allclose(np.ptp(corners, axis=0), [2.0, 0.2, 0.4])


def test_a_joint_that_mujoco_split_is_named_as_the_planar_joint_it_was(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    pytest.importorskip("mujoco")
    path = tmp_path / "split.xml"
    path.write_text(
        '<mujoco><worldbody><body name="base"><body name="arm"><joint name="j3_elbow_TX" type="slide" axis="1 0 0"/>'
        '<joint name="j3_elbow_TY" type="slide" axis="0 1 0"/><geom type="sphere" size="0.05" mass="1"/></body></body></worldbody></mujoco>'
    )
    assert main(["describe", "--robot", str(path)]) == 2
    err = capsys.readouterr().err
    assert "joint 'j3_elbow' is a planar or floating joint" in err and "uwml takes revolute, continuous and prismatic joints" in err


def test_the_picture_draws_a_lumped_hull_its_thrusters_and_names_every_body() -> None:
    pytest.importorskip("mujoco")
    import matplotlib.pyplot as plt
    from uwml.robot.files import from_urdf
    from uwml.viz.describe import _lumped_surface, figure

    example = Path(__file__).parent.parent / "examples" / "bluerov2"
    robot = from_urdf(example / "bluerov2_arm.urdf", example / "bluerov2_arm.hydro.toml")
    fig = figure(robot)
    try:
        (ax,) = fig.axes  # type: ignore[attr-defined]
        assert {"hull", "upper_arm", "forearm"} <= {t.get_text().strip() for t in ax.texts}
        labels = [t.get_text() for t in ax.get_legend().get_texts()]
        assert any("lumped body" in label for label in labels) and any("thruster" in label for label in labels)
        gids = [c.get_gid() or "" for c in ax.collections]
        assert gids.count("lumped hull") == 1 and sum(g.startswith("thruster") for g in gids) == 8
        # The hull's sphere holds its volume, about the lumped model's point.
        x, _, z = _lumped_surface(robot.base, np.zeros(3))
        diameter = 2.0 * (3.0 * robot.base.volume / (4.0 * np.pi)) ** (1.0 / 3.0)
        np.testing.assert_allclose([np.ptp(x), np.ptp(z)], diameter, rtol=0.05)
        np.testing.assert_allclose([np.mean([z.max(), z.min()])], robot.base.lumped.point[2], atol=1e-12)
    finally:
        plt.close(fig)  # type: ignore[arg-type]


def test_a_lumped_hull_from_a_description_is_drawn_as_its_collision_box() -> None:
    """``uwml describe`` of a URDF and its hydro file: the hull described by its lumped model
    (``strips = false``) is drawn as its collision box (the description's shape, kept for the
    picture), not the sphere of its volume."""
    pytest.importorskip("mujoco")
    import uwml.examples
    from uwml.io.descriptions import urdf_parts
    from uwml.viz.describe import figure

    rov = uwml.examples.path("bluerov2")
    parts = urdf_parts(rov / "bluerov2_arm.urdf", rov / "bluerov2_arm.hydro.toml")
    (box,) = parts.outlines
    assert box.link == "hull" and box.kind == "box" and box.size == pytest.approx((0.457 / 2, 0.575 / 2, 0.254 / 2))
    fig = figure(parts.build(uwml.Robot), outlines=parts.outlines)
    try:
        (ax,) = fig.axes  # type: ignore[attr-defined]
        edges = [line for line in ax.lines if line.get_gid() == "outline hull"]
        assert len(edges) == 12
        xs = np.concatenate([line.get_data_3d()[0] for line in edges])
        np.testing.assert_allclose([xs.min(), xs.max()], [-0.2285, 0.2285])
        assert not any((c.get_gid() or "").startswith("lumped") for c in ax.collections)  # no sphere beside it
        assert any("its collision shape" in t.get_text() for t in ax.get_legend().get_texts())
    finally:
        import matplotlib.pyplot as plt

        plt.close(fig)  # type: ignore[arg-type]
