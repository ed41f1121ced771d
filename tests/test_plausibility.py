"""Warnings for likely unit mistakes (``uwml.PlausibilityWarning``, ``uwml.plausibility``): degrees
given as radians, a density in g/cm³, time in milliseconds; each says what was seen, the likely
cause and how to silence it, and changes no result."""

import math
import warnings
from pathlib import Path

import numpy as np
import pytest
import uwml
from uwml import plausibility
from uwml.io.logs import Log, read_log, write_log


def quietly(call):  # type: ignore[no-untyped-def]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", uwml.PlausibilityWarning)
        return call()


@pytest.mark.parametrize("batch", [False, True])
def test_degrees_given_as_radians_warn_and_change_nothing(batch: bool) -> None:
    leg = uwml.paper_leg()
    q, qd, qdd = np.radians([30.0, -40.0, 60.0]), np.radians([45.0, 30.0, -40.0]), np.zeros(3)
    degrees = (np.degrees(q), np.degrees(qd), qdd)
    if batch:
        degrees = tuple(np.tile(a, (5000, 1)) for a in degrees)
    with pytest.warns(
        uwml.PlausibilityWarning,
        match=r"joint 1's speed reaches 45 rad/s, above 30 rad/s .* degrees per second\? uwml takes rad/s; silence with",
    ):
        loud = leg.hydro(*degrees)
    np.testing.assert_array_equal(loud.total, quietly(lambda: leg.hydro(*degrees)).total)
    # The right units: no warning (the tests turn warnings into errors).
    leg.hydro(q, qd, qdd)
    # Angles alone in degrees (speeds right): the angle's warning.
    with pytest.warns(uwml.PlausibilityWarning, match=r"joint 1's angle reaches 30 rad, 4.77 turns: are the angles in degrees\?"):
        leg.hydro(np.degrees(q), qd, qdd)


def test_a_prismatic_joint_in_mm_per_second_warns() -> None:
    robot = uwml.Robot([uwml.Joint((0, 0, 0), (1, 0, 0), kind="prismatic")], [uwml.Link(1.0, (0, 0, 0), 0.0)])
    with pytest.warns(
        uwml.PlausibilityWarning, match=r"joint 1 \(prismatic\) moves at up to 250 m/s, above 10 m/s: are the speeds in mm/s\?"
    ):
        robot.hydro([0.1], [250.0], [0.0])
    robot.hydro([120.0], [0.25], [0.0])  # a long travel is no angle


def test_a_density_in_grams_per_cubic_centimetre_warns() -> None:
    with pytest.warns(
        uwml.PlausibilityWarning, match=r"a water density of 1.025 kg/m³ is outside 500 to 1100 kg/m³ .*\(1.025 is sea water in g/cm³\)"
    ):
        uwml.Water(density=1.025)
    uwml.Water(density=1025.0)
    uwml.Water(density=998.2)


def test_a_log_in_milliseconds_warns(tmp_path: Path) -> None:
    n = 200
    t = np.arange(n) * 1.0  # 1 kHz in milliseconds
    log = Log(time=t, q=np.zeros((n, 3)), qd=np.zeros((n, 3)), qdd=np.zeros((n, 3)))
    path = tmp_path / "ms.csv"
    write_log(log, path)
    with pytest.warns(
        uwml.PlausibilityWarning, match=r"ms.csv: the median time step is 1 s \(1 Hz\): is time in milliseconds\? uwml takes seconds"
    ):
        read_log(path)
    write_log(Log(time=t * 1e-3, q=log.q), path)
    read_log(path)


def test_a_batch_is_checked_on_rows_spread_over_it() -> None:
    q = np.zeros((100_000, 3))
    qd = np.full((100_000, 3), 0.5)
    qd[:, 1] = 80.0  # every row: a unit mistake shows in all of them
    with pytest.warns(uwml.PlausibilityWarning, match="joint 2's speed reaches 80 rad/s"):
        plausibility.check_states(q, qd, plausibility.joint_bounds(uwml.paper_leg().joints))
    assert plausibility.CHECKED_ROWS <= 1024 and math.isclose(plausibility.PLAUSIBLE_ANGLE, 4 * math.pi)
