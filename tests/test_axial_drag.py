"""The axial drag of a segment (docs/model.md section 12.2) from Python: ``uwml.Segment(...,
cd_axial=, axial_area=)`` checked, held against the numpy reference (``tests/test_robot.py`` on
random trees) and the closed form here, kept by the model file, given by a hydro file, in its
own column of the regressors."""

from pathlib import Path

import numpy as np
import pytest
import uwml

DATA = Path(__file__).parent / "data"


def rod(cd_axial: float, axial_area: float | None = None) -> uwml.Robot:
    """A base carrying a rod along x (no cross-flow drag) and one idle link."""
    segment = uwml.Segment(
        (-0.4, 0.0, 0.0), (1, 0, 0), 0.8, section="circular", diameter=0.16, cd=0.0, cd_axial=cd_axial, axial_area=axial_area
    )
    base = uwml.Link(0.0, (0, 0, 0), 0.0, segments=[segment])
    return uwml.Robot([uwml.Joint((0, 0, 0), (0, 0, 1))], [uwml.Link(1.0, (0, 0, 0), 0.0)], base=base)


def test_the_axial_drag_of_a_rod_surging_is_its_closed_form() -> None:
    area = np.pi * 0.16**2 / 4.0
    for robot, reference_area in ((rod(0.8), area), (rod(0.8, 0.05), 0.05)):
        for u in (1.5, -0.7):
            drag = robot.hydro([0.0], [0.0], [0.0], base_motion=uwml.BaseMotion(velocity=(u, 0.0, 0.0))).base.drag
            np.testing.assert_allclose(drag, [-0.5 * 1000.0 * 0.8 * reference_area * abs(u) * u, 0, 0, 0, 0, 0], rtol=1e-14, atol=1e-12)
    still = rod(0.0).hydro([0.0], [0.0], [0.0], base_motion=uwml.BaseMotion(velocity=(1.0, 0.0, 0.0))).base.drag
    np.testing.assert_array_equal(still, np.zeros(6))


@pytest.mark.parametrize(
    "arguments, message",
    [
        ({"cd_axial": -0.1}, "segment.cd_axial must be non-negative"),
        ({"cd_axial": float("nan")}, "segment.cd_axial must be finite"),
        ({"cd_axial": 5e3}, "segment.cd_axial must be at most 1000"),
        ({"cd_axial": 0.5, "axial_area": -1.0}, "segment.axial_area must be non-negative"),
    ],
)
def test_bad_axial_drag_is_refused(arguments: dict, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        uwml.Segment((0, 0, 0), (1, 0, 0), 1.0, section="circular", diameter=0.1, **arguments)


def test_the_model_file_keeps_the_axial_drag(tmp_path: Path) -> None:
    robot = rod(0.8, 0.05)
    path = tmp_path / "rod.toml"
    robot.save(path)
    assert "cd_axial = 0.8" in path.read_text() and "axial_area = 0.05" in path.read_text()
    assert uwml.Robot.load(path) == robot
    rod(0.0).save(path)
    assert "cd_axial" not in path.read_text() and "axial_area" not in path.read_text()


def test_a_hydro_file_gives_a_links_segments_an_axial_drag(tmp_path: Path) -> None:
    hydro = tmp_path / "h.toml"
    hydro.write_text("[links.upper_arm]\ncd_axial = 0.3\n")
    robot = uwml.Robot.from_mjcf(DATA / "arm.xml", hydro)
    upper = robot.links[0].segments
    assert upper and all(s.cd_axial == 0.3 and s.axial_area == s.area for s in upper)
    assert all(s.cd_axial == 0.0 for link in robot.links[1:] for s in link.segments)
    hydro.write_text("[links.upper_arm]\ncd_axial = -1\n")
    with pytest.raises(uwml.DescriptionError, match=r"\[links\.upper_arm\], key 'cd_axial': must be a number, 0 to 1000"):
        uwml.Robot.from_mjcf(DATA / "arm.xml", hydro)


def test_the_axial_column_times_cd_axial_is_the_axial_drag() -> None:
    robot = rod(0.8)
    q, qd, qdd = [0.3], [1.5], [0.0]
    motion = uwml.BaseMotion(velocity=(0.7, -0.2, 0.4))
    regressors = robot.hydro_regressors(q, qd, qdd, base_motion=motion)
    assert np.any(regressors.base_axial_drag != 0.0)
    forces = robot.hydro(q, qd, qdd, base_motion=motion)
    rebuilt = regressors.torques([s.cd for s in robot.segments], [s.cm for s in robot.segments], 0.8)
    np.testing.assert_allclose(rebuilt.base.drag, forces.base.drag, rtol=1e-12, atol=1e-12)
    without = regressors.torques([s.cd for s in robot.segments], [s.cm for s in robot.segments])
    assert np.max(np.abs(without.base.drag - forces.base.drag)) > 1e-3, "the axial drag is in its own column"
