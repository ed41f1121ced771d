"""``uwml.Conditions``: what an evaluation takes besides the robot and its state, one frozen value
checked once; every evaluation takes ``(q, qd, qdd, conditions)``, and the keywords of its fields
as shortcuts that make (or replace fields of) one. Held here: the checks name the field; the
shortcuts give the conditions' numbers; the robot's own water and losses stand in where the
conditions give none; the core reads a conditions value once per robot; the base wrench is
evaluated where asked for.
"""

import pickle
import typing

import numpy as np
import pytest
import uwml
from robots import random_robot
from uwml.robot.evaluation_conditions import ConditionFields

STATE = ([0.1, -0.4, 0.7], [0.5, -1.0, 2.0], [1.0, 3.0, -2.0])


@pytest.mark.parametrize(
    ("fields", "error", "message"),
    [
        ({"water": 1000.0}, TypeError, "water must be a uwml.Water"),
        ({"cd": -1.0}, ValueError, "cd must be finite and non-negative"),
        ({"cm": np.ones((2, 3))}, ValueError, r"cm must be None, a scalar, shape \(n_segments,\)"),
        ({"cd": "big"}, TypeError, "cd must be None, a real number"),
        ({"added_mass": "potential"}, ValueError, "added_mass must be one of morison, kirchhoff"),
        ({"base_motion": "fixed"}, TypeError, "base_motion must be a uwml.BaseMotion"),
        ({"current": (0.0, 1.0)}, ValueError, r"current must have shape \(3,\)"),
        ({"current_acceleration": (0.0, np.nan, 0.0)}, ValueError, "current_acceleration must be finite"),
        ({"depth": -1.0}, ValueError, "depth must be finite and from 0 to 11000 m"),
        ({"depth": [[1.0]]}, ValueError, "depth must be a scalar or have one entry per sample"),
        ({"temperature_c": -300.0}, ValueError, "above absolute zero"),
        ({"losses": 3}, TypeError, "losses must be a uwml.JointLosses"),
        ({"losses": [None, "seal"]}, TypeError, r"losses\[1\] must be a uwml.JointLosses"),
        ({"sea_density": 0.0}, ValueError, "sea_density must be finite and positive"),
        ({"current": np.zeros((2, 3)), "depth": np.zeros(3)}, ValueError, "current: 2, depth: 3"),
    ],
)
def test_bad_conditions_name_the_field(fields: dict, error: type, message: str) -> None:
    with pytest.raises(error, match=message):
        uwml.Conditions(**fields)


def test_conditions_are_frozen_and_replaced_field_by_field() -> None:
    conditions = uwml.Conditions(cd=2.0, current=(0.1, 0.0, 0.0))
    with pytest.raises(AttributeError):
        conditions.cd = 1.0  # type: ignore[misc]
    assert not conditions.current.flags.writeable
    moved = conditions.replace(cm=0.7)
    assert float(moved.cd) == 2.0 and float(moved.cm) == 0.7 and conditions.cm is None
    np.testing.assert_array_equal(moved.current, conditions.current)
    with pytest.raises(TypeError, match="unknown conditions 'speed'"):
        conditions.replace(speed=1.0)  # type: ignore[call-arg]
    assert repr(moved) == "Conditions(cd=2.0, cm=0.7, current=[0.1, 0.0, 0.0])"
    assert uwml.Conditions().n_samples is None and uwml.Conditions(depth=np.zeros(4)).n_samples == 4


def test_the_keywords_of_an_evaluation_are_the_fields() -> None:
    names = [field.name for field in __import__("dataclasses").fields(uwml.Conditions)]
    assert list(typing.get_type_hints(ConditionFields)) == names


def test_shortcuts_give_the_numbers_of_the_conditions_they_make() -> None:
    robot = random_robot(np.random.default_rng(3), 3)
    q = np.random.default_rng(4).uniform(-1, 1, (5, 3))
    fields = {"cd": 1.3, "water": uwml.Water(1025.0), "current": (0.2, 0.0, 0.1), "added_mass": "kirchhoff"}
    conditions = uwml.Conditions(**fields)
    by_keywords = robot.hydro(q, q, q, **fields)
    by_value = robot.hydro(q, q, q, conditions)
    for name in ("drag", "added_mass", "buoyancy", "gravity"):
        np.testing.assert_array_equal(getattr(by_keywords, name), getattr(by_value, name))
    # Given with a conditions value, the keywords replace its fields.
    replaced = robot.hydro(q, q, q, conditions, cd=0.5)
    np.testing.assert_array_equal(replaced.drag, robot.hydro(q, q, q, conditions.replace(cd=0.5)).drag)
    with pytest.raises(TypeError, match="conditions must be a uwml.Conditions or None, got float"):
        robot.hydro(q, q, q, 2.2)  # type: ignore[arg-type]


def test_one_coefficient_given_takes_the_segments_own_for_the_other() -> None:
    """``cd`` per segment with ``cm`` None (and the reverse): the other is each segment's own, as
    when both are None."""
    robot = uwml.paper_leg()
    own_cd = np.array([s.cd for s in robot.segments])
    own_cm = np.array([s.cm for s in robot.segments])
    both = robot.hydro(*STATE, cd=own_cd * 1.5, cm=own_cm)
    np.testing.assert_array_equal(robot.hydro(*STATE, cd=own_cd * 1.5).total, both.total)
    both = robot.hydro(*STATE, cd=own_cd, cm=own_cm * 0.5)
    np.testing.assert_array_equal(robot.hydro(*STATE, cm=own_cm * 0.5).total, both.total)
    np.testing.assert_array_equal(robot.hydro(*STATE, cd=own_cd, cm=own_cm).total, robot.hydro(*STATE).total)


def test_the_robots_own_water_and_losses_where_the_conditions_give_none() -> None:
    leg = uwml.paper_leg()
    losses = uwml.JointLosses()
    robot = uwml.Robot(leg.joints, leg.links, losses=losses, water=uwml.Water(1025.0))
    conditions = uwml.Conditions(depth=2000.0, temperature_c=4.0)
    own = robot.environment(*STATE, conditions)
    given = leg.environment(*STATE, conditions, water=uwml.Water(1025.0), losses=losses)
    for name in ("drag", "buoyancy", "visc", "seal", "current"):
        np.testing.assert_array_equal(getattr(own, name), getattr(given, name))
    assert np.any(own.seal != 0.0)
    # The robot's own, unless the conditions give others ([None] * n: none).
    none = robot.environment(*STATE, conditions, losses=[None] * 3)
    assert np.all(none.seal == 0.0) and np.all(none.visc == 0.0)


def test_the_core_reads_a_conditions_value_once_per_robot() -> None:
    leg, other = uwml.paper_leg(), uwml.paper_leg()
    conditions = uwml.Conditions(cd=2.0)
    first = leg._native(conditions)
    assert leg._native(conditions) is first
    assert other._native(conditions) is not first
    # Pickled (sent to a worker), a conditions value leaves the core's reading behind.
    copy = pickle.loads(pickle.dumps(conditions))
    assert "_native" not in vars(copy) and float(copy.cd) == 2.0
    np.testing.assert_array_equal(leg.hydro(*STATE, copy).total, leg.hydro(*STATE, conditions).total)


def test_the_base_wrench_is_evaluated_where_asked_for() -> None:
    """By default where the robot has a base body or the conditions move its base; ``base=``
    says otherwise. The joints' forces do not depend on it."""
    leg = uwml.paper_leg()
    assert leg.hydro(*STATE).base is None
    moving = uwml.BaseMotion(velocity=(0.3, 0.0, 0.0))
    assert leg.hydro(*STATE, base_motion=moving).base is not None
    assert leg.hydro(*STATE, base_motion=moving, base=False).base is None
    asked = leg.hydro(*STATE, base=True)
    np.testing.assert_array_equal(asked.total, leg.hydro(*STATE).total)
    # The weight of the whole leg on its base, upright: −m g along z.
    np.testing.assert_allclose(asked.base.gravity[2], -9.81 * sum(link.mass for link in leg.links), rtol=1e-14)
    robot = random_robot(np.random.default_rng(8), 2)
    assert robot.base is not None and robot.hydro([0.1, 0.2], [0.0, 0.0], [0.0, 0.0]).base is not None


def test_the_same_keywords_call_after_call_make_their_conditions_once() -> None:
    """A controller passing the same keywords every call has them checked and read by the core
    once; a list or an array changed in place between calls is seen (compared by value)."""
    leg = uwml.paper_leg()
    cd, cm = [2.0, 2.0], np.array([0.5, 0.5])
    first = leg.hydro(*STATE, cd=cd, cm=cm, current=(0.1, 0.0, 0.0))
    made = leg._last_shortcuts[2]
    again = leg.hydro(*STATE, cd=[2.0, 2.0], cm=cm.copy(), current=(0.1, 0.0, 0.0))
    assert leg._last_shortcuts[2] is made
    np.testing.assert_array_equal(again.total, first.total)
    cd[0] = 3.0
    cm[1] = 1.0
    changed = leg.hydro(*STATE, cd=cd, cm=cm, current=(0.1, 0.0, 0.0))
    assert leg._last_shortcuts[2] is not made
    expected = leg.hydro(*STATE, uwml.Conditions(cd=[3.0, 2.0], cm=[0.5, 1.0], current=(0.1, 0.0, 0.0)))
    np.testing.assert_array_equal(changed.total, expected.total)
    assert not np.array_equal(changed.total, first.total)
