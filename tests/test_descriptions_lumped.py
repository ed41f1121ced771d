"""Lumped models (docs/model.md section 12.1) from a hydro file: a link's ``[links.NAME.lumped]``
in its description frame, turned into uwml's link frame (its point moved, its axes turned);
``strips = false`` keeps the collision geometry's volume without its strips; errors name the
file, the table and the key.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest
import uwml

DATA = Path(__file__).parent / "data"


def matrix(rows: np.ndarray) -> str:
    return "[" + ", ".join("[" + ", ".join(repr(float(x)) for x in row) + "]" for row in rows) + "]"


def lumped_table(name: str, point: str | None, added_mass: np.ndarray, damping: np.ndarray, quadratic: list[float]) -> str:
    lines = [f"[links.{name}.lumped]"]
    if point is not None:
        lines.append(f"point = {point}")
    lines += [f"added_mass = {matrix(added_mass)}", f"linear_damping = {matrix(damping)}", f"quadratic_damping = {quadratic}"]
    return "\n".join(lines) + "\n"


def test_a_hull_described_by_its_lumped_model_instead_of_strips(tmp_path: Path) -> None:
    hydro = tmp_path / "h.toml"
    added = np.diag([6.36, 7.12, 18.68, 0.189, 0.135, 0.222])
    hydro.write_text(
        "[links.hull]\nstrips = false\n"
        + lumped_table("hull", None, added, np.diag([13.7, 0, 33, 0, 0.8, 0]), [141, 217, 190, 1.19, 0.47, 1.5])
    )
    robot = uwml.Robot.from_mjcf(DATA / "arm.xml", hydro)
    plain = uwml.Robot.from_mjcf(DATA / "arm.xml")
    assert robot.base is not None and plain.base is not None
    # The box's volume and centre stay; its strip is gone; the model sits at the centre of buoyancy.
    assert robot.base.volume == plain.base.volume and robot.base.cob == plain.base.cob
    assert plain.base.segments and not robot.base.segments
    lumped = robot.base.lumped
    assert lumped is not None and lumped.point == robot.base.cob
    np.testing.assert_array_equal(lumped.added_mass, added)
    # Surging at 1 m/s: the hull's damping alone, −(13.7 + 141) N along x (the arm at rest in
    # its own frame moves with the hull and drags too: compare with the arm alone).
    motion = uwml.BaseMotion(velocity=(1.0, 0.0, 0.0))
    q = np.zeros(robot.n_joints)
    with_hull = robot.hydro(q, q, q, base_motion=motion).base.drag
    without = uwml.Robot(robot.joints, robot.links, base=dataclasses.replace(robot.base, lumped=None)).hydro(q, q, q, base_motion=motion)
    np.testing.assert_allclose(with_hull - without.base.drag, [-(13.7 + 141.0), 0, 0, 0, 0, 0], atol=1e-12)


def test_a_lumped_model_in_a_turned_description_frame_is_the_same_model_in_uwmls(tmp_path: Path) -> None:
    """upper_arm's frame is turned 90° about z in arm.xml: a model given there is the model in
    uwml's link frame with its matrices turned (checked against one built so, without axes, for
    a model with no quadratic damping, whose diagonal would not stay one) and its point moved."""
    rng = np.random.default_rng(3)
    a = rng.normal(size=(6, 6))
    added, damping = a @ a.T, np.diag(rng.uniform(1, 5, 6))
    hydro = tmp_path / "h.toml"
    hydro.write_text(lumped_table("upper_arm", "[0.1, 0.02, -0.03]", added, damping, [0.0] * 6))
    robot = uwml.Robot.from_mjcf(DATA / "arm.xml", hydro)
    plain = uwml.Robot.from_mjcf(DATA / "arm.xml")
    link = robot.links[0]
    assert link.lumped is not None
    turn = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])  # the body's quat: 90° about z
    np.testing.assert_allclose(link.lumped.axes, turn, atol=1e-12)
    np.testing.assert_allclose(link.lumped.point, turn @ np.array([0.1, 0.02, -0.03]), atol=1e-12)
    t = np.zeros((6, 6))
    t[:3, :3] = t[3:, 3:] = turn
    by_hand = uwml.LumpedModel(point=link.lumped.point, added_mass=t @ added @ t.T, linear_damping=t @ damping @ t.T)
    links = [dataclasses.replace(plain.links[0], lumped=by_hand), *plain.links[1:]]
    built = uwml.Robot(plain.joints, links, base=plain.base)
    n = robot.n_joints
    q, qd, qdd = rng.uniform(-1, 1, (3, 5, n))
    motion = uwml.BaseMotion(velocity=(0.3, -0.2, 0.1), angular_velocity=(0.1, 0.2, -0.3), acceleration=(0.5, 0.0, 0.1))
    mine, theirs = robot.hydro(q, qd, qdd, base_motion=motion), built.hydro(q, qd, qdd, base_motion=motion)
    np.testing.assert_allclose(mine.total, theirs.total, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(mine.base.total, theirs.base.total, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(robot.added_mass_matrix(q), built.added_mass_matrix(q), rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize(
    "text, message",
    [
        (
            "[links.hull.lumped]\nadded_mass = [[1, 2], [2, 1]]\n",
            r"h\.toml: \[links\.hull\], lumped, key 'added_mass': must be 6 rows of 6 numbers",
        ),
        (
            lumped_table("hull", None, np.diag([1.0, 1, 1, 1, 1, -1]), np.zeros((6, 6)), [0.0] * 6),
            r"h\.toml: \[links\.hull\], lumped: lumped\.added_mass must be positive semi-definite",
        ),
        # Issue 31: the floating hull whose simulation diverged; a huge entry hides nothing.
        (
            lumped_table("hull", None, np.diag([1e12, -99.0, 1, 1, 1, 1]), np.zeros((6, 6)), [0.0] * 6),
            r"h\.toml: \[links\.hull\], lumped: lumped\.added_mass must be positive semi-definite .*-99, below the allowed -0\.01",
        ),
        (
            lumped_table("hull", None, np.eye(6), np.diag([1e12, -99.0, 1, 1, 1, 1]), [0.0] * 6),
            r"h\.toml: \[links\.hull\], lumped: lumped\.linear_damping must have a positive semi-definite symmetric part",
        ),
        (
            lumped_table("hull", None, np.diag([1e12, 1, 1, 1, 1, 1]) + np.eye(6, k=1) * 900.0, np.zeros((6, 6)), [0.0] * 6),
            r"h\.toml: \[links\.hull\], lumped: lumped\.added_mass must be symmetric within 0\.01",
        ),
        (
            lumped_table("hull", None, np.zeros((6, 6)), np.zeros((6, 6)), [0.0, -1.0, 0, 0, 0, 0]),
            r"h\.toml: \[links\.hull\], lumped: lumped\.quadratic_damping\[1\] must be finite and non-negative",
        ),
        ("[links.hull.lumped]\nmass = 3.0\n", r"h\.toml: \[links\.hull\], lumped, key 'mass': is not a key of this table"),
        ("[links.hull]\ndry = true\n[links.hull.lumped]\n", r"h\.toml: \[links\.hull\], key 'lumped': a dry link has no segments"),
        ("[links.hull]\nstrips = 0\n", r"h\.toml: \[links\.hull\], key 'strips': must be true or false"),
    ],
)
def test_bad_lumped_entries_name_the_file_the_table_and_the_key(tmp_path: Path, text: str, message: str) -> None:
    hydro = tmp_path / "h.toml"
    hydro.write_text(text)
    with pytest.raises(uwml.DescriptionError, match=message):
        uwml.Robot.from_mjcf(DATA / "arm.xml", hydro)


def test_two_lumped_models_on_bodies_fused_into_one_link_are_refused(tmp_path: Path) -> None:
    # In arm.urdf the hull's fixed child (if any) fuses into it; build one: the MJCF's wrist and a
    # fixed body below it would do, but the arm's bodies all move. So a URDF with a fixed link.
    urdf = tmp_path / "fused.urdf"
    urdf.write_text(
        """<robot name="fused">
  <link name="base"><inertial><mass value="5"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="can"><inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="arm"><inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="fix" type="fixed"><parent link="base"/><child link="can"/><origin xyz="0.2 0 0"/></joint>
  <joint name="turn" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"""
    )
    hydro = tmp_path / "h.toml"
    hydro.write_text(
        "[links.base.lumped]\nadded_mass = " + matrix(np.eye(6)) + "\n[links.can.lumped]\nadded_mass = " + matrix(np.eye(6)) + "\n"
    )
    with pytest.raises(uwml.DescriptionError, match=r"\[links\.base\], \[links\.can\] give lumped models to bodies fused into one link"):
        uwml.Robot.from_urdf(urdf, hydro)
    # One of them is taken, at the fused link's centre of buoyancy unless given.
    hydro.write_text("[links.can.lumped]\npoint = [0.0, 0.0, 0.1]\nadded_mass = " + matrix(np.eye(6)) + "\n")
    robot = uwml.Robot.from_urdf(urdf, hydro)
    assert robot.base is not None and robot.base.lumped is not None
    np.testing.assert_allclose(robot.base.lumped.point, [0.2, 0.0, 0.1], atol=1e-12)


def test_describe_shows_a_lumped_model(tmp_path: Path) -> None:
    from uwml.viz.describe import describe

    hydro = tmp_path / "h.toml"
    hydro.write_text(
        "[links.hull]\nstrips = false\n"
        + lumped_table(
            "hull",
            None,
            np.diag([6.36, 7.12, 18.68, 0.189, 0.135, 0.222]),
            np.diag([13.7, 0, 33, 0, 0.8, 0]),
            [141, 217, 190, 1.19, 0.47, 1.5],
        )
    )
    text = describe(uwml.Robot.from_mjcf(DATA / "arm.xml", hydro))
    assert "lumped models" in text and "M_A diag (6.36, 7.12, 18.68, 0.189, 0.135, 0.222)" in text and "D_Q (141, 217, 190" in text
    assert "lumped models" not in describe(uwml.Robot.from_mjcf(DATA / "arm.xml"))
