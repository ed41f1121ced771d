"""URDF and MJCF descriptions to uwml.Robot (uwml.descriptions, MODEL.md section 10)."""

from __future__ import annotations

import math
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
    ta, tb = a.hydro(q, qd, qdd, **kwargs), b.hydro(q, qd, qdd, **kwargs)  # type: ignore[arg-type]
    for name in ("drag", "added_mass", "buoyancy", "gravity"):
        x = np.concatenate([getattr(ta, name), getattr(ta.base, name)])
        y = np.concatenate([getattr(tb, name), getattr(tb.base, name)])
        scale = max(1.0, float(np.max(np.abs(y))))
        assert np.max(np.abs(x - y)) <= 1e-12 * scale, (name, x, y)


@pytest.fixture(scope="module")
def paper() -> uwml.Robot:
    return uwml.Robot.from_leg(uwml.Leg.paper())


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
    """MODEL.md section 5's table, through the URDF."""
    robot = uwml.Robot.from_urdf(DATA / "paper_leg.urdf", DATA / "paper_leg.hydro.toml")
    t = robot.hydro([0.3, -0.4, 0.6], [0.8, 0.5, -0.7], [1.0, -2.0, 0.5])
    np.testing.assert_allclose(t.drag, [-24.24084, -5.060505, -0.7383118], rtol=1e-6)
    np.testing.assert_allclose(t.added_mass, [-8.525438, 21.77596, 9.484545], rtol=1e-6)
    np.testing.assert_allclose(t.buoyancy, [0.0, 59.72457, 4.193843], rtol=1e-6, atol=1e-12)


def test_from_mujoco_model_in_memory(paper: uwml.Robot) -> None:
    import mujoco

    model = mujoco.MjModel.from_xml_string((DATA / "paper_leg.xml").read_text().replace('<asset><mesh name="thigh_visual" file="meshes/thigh_does_not_exist.stl"/></asset>', "").replace('<geom class="visual" type="mesh" mesh="thigh_visual"/>', ""))
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
