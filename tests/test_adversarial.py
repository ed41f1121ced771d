"""Adversarial inputs at every public entry point (hypothesis): NaN, ±inf, huge, tiny and
subnormal numbers, empty and 0-d arrays, arrays of the wrong shape, non-contiguous and
byte-swapped arrays, the wrong dtype (bool, int, complex, object, strings), ragged lists, None.

One argument at a time is replaced (the others valid). What must hold (docs/domains.md): no
crash and no other exception than a ``ValueError`` or ``TypeError`` whose message names the
argument (or the entry point's input), or a result whose numbers are all finite; never a
silent NaN or inf from finite input. ``ExtrapolationWarning`` is allowed (a documented
result); any other warning fails the test (pytest turns warnings into errors).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
import uwml
from hypothesis import given
from hypothesis import strategies as st
from uwml.sea import seawater

SPECIAL = [math.nan, math.inf, -math.inf, 1e308, -1e308, 5e-324, -0.0, 0.0, 1e200, 1e-300]


def _values(shape: tuple[int, ...], draw: Any) -> np.ndarray:
    size = int(np.prod(shape)) if shape else 1
    values = draw(st.lists(st.one_of(st.sampled_from(SPECIAL), st.floats(-10, 10)), min_size=size, max_size=size))
    return np.array(values, dtype=np.float64).reshape(shape)


@st.composite
def adversarial(draw: Any, width: int) -> Any:
    """Something passed where an array of ``width`` numbers per sample (or a scalar, width 0) is
    expected."""
    kind = draw(st.sampled_from(["special scalar", "odd scalar", "shape", "dtype", "non-contiguous", "byte-swapped", "ragged", "empty"]))
    if kind == "special scalar":
        return draw(st.sampled_from(SPECIAL))
    if kind == "odd scalar":
        return draw(st.sampled_from([None, "1.0", True, 1 + 2j, object(), [], {}, b"\x00"]))
    if kind == "shape":
        shape = draw(st.sampled_from([(), (0,), (1,), (width + 1,), (2, width + 2), (2, 1, max(width, 1)), (0, max(width, 1))]))
        return _values(shape, draw)
    if kind == "dtype":
        base = _values((2, max(width, 1)), draw) if width else _values((), draw)
        dtype = draw(st.sampled_from([np.float32, np.int64, np.bool_, np.complex128, object, "U8"]))
        with np.errstate(invalid="ignore", over="ignore"):
            return np.nan_to_num(base, nan=1.0, posinf=2.0, neginf=-2.0).astype(dtype)
    if kind == "non-contiguous":
        wide = _values((3, 2 * max(width, 1)), draw)
        return wide[:, ::2] if width else wide[0, ::2][:1].reshape(())
    if kind == "byte-swapped":
        values = _values((2, max(width, 1)), draw) if width else _values((), draw)
        return values.astype(values.dtype.newbyteorder())
    if kind == "ragged":
        return [[0.1] * max(width, 1), [0.2] * (max(width, 1) + 1)]
    return np.zeros((0,) if not width else (0, width))


def _finite(result: Any) -> bool:
    """Every number of a result (dataclass of arrays, nested) finite."""
    if isinstance(result, np.ndarray):
        return result.dtype.kind != "f" or bool(np.all(np.isfinite(result)))
    if isinstance(result, (float, np.floating)):
        return math.isfinite(float(result))
    if hasattr(result, "__dataclass_fields__"):
        return all(_finite(getattr(result, name)) for name in result.__dataclass_fields__)
    if isinstance(result, (tuple, list)):
        return all(_finite(x) for x in result)
    return True


def _call(function: Callable[..., Any], argument: str, kwargs: dict[str, Any]) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", uwml.ExtrapolationWarning)
        try:
            result = function(**kwargs)
        except (ValueError, TypeError) as exc:
            message = str(exc)
            assert message, f"{function.__qualname__}({argument}=...): an empty message"
            return
    assert _finite(result), f"{function.__qualname__}({argument}={kwargs[argument]!r}) returned a non-finite number"


ROBOT = uwml.paper_leg()
STATE = {"q": [0.1, 0.2, 0.3], "qd": [0.4, -0.2, 0.1], "qdd": [0.0, 1.0, -1.0]}

# Each entry point, its valid keyword arguments, and the width of each argument fuzzed.
ENTRY_POINTS: list[tuple[str, Callable[..., Any], dict[str, Any], dict[str, int]]] = [
    (
        "Robot.hydro",
        ROBOT.hydro,
        STATE | {"cd": 2.2, "cm": 0.5, "current": (0.1, 0.0, 0.0)},
        {"q": 3, "qd": 3, "qdd": 3, "cd": 0, "cm": 0, "current": 3, "current_acceleration": 3},
    ),
    (
        "Robot.environment",
        ROBOT.environment,
        STATE | {"depth": 100.0, "temperature_c": 4.0, "losses": uwml.JointLosses()},
        {"q": 3, "qd": 3, "qdd": 3, "depth": 0, "temperature_c": 0, "sea_density": 0, "current": 3},
    ),
    (
        "Robot.jacobians",
        ROBOT.jacobians,
        STATE | {"depth": 100.0},
        {"q": 3, "qd": 3, "qdd": 3, "depth": 0, "temperature_c": 0, "current": 3},
    ),
    ("Robot.hydro_regressors", ROBOT.hydro_regressors, dict(STATE), {"q": 3, "qd": 3, "qdd": 3, "current": 3}),
    ("Robot.link_wrenches", ROBOT.link_wrenches, dict(STATE), {"q": 3, "qd": 3, "qdd": 3}),
    ("Robot.added_mass_matrix", ROBOT.added_mass_matrix, {"q": [0.1, 0.2, 0.3]}, {"q": 3, "cm": 0}),
    (
        "JointLosses.torques",
        uwml.JointLosses().torques,
        {"speed": 0.5, "pressure_mpa": 10.0, "temperature_c": 4.0},
        {"speed": 0, "pressure_mpa": 0, "temperature_c": 0},
    ),
    ("hydrostatic_pressure_mpa", uwml.hydrostatic_pressure_mpa, {"depth_m": 100.0}, {"depth_m": 0, "sea_density": 0, "gravity": 0}),
    ("seawater.pressure_at_depth_mpa", seawater.pressure_at_depth_mpa, {"depth_m": 100.0}, {"depth_m": 0, "latitude_deg": 0}),
    ("seawater.density_at_depth", seawater.density_at_depth, {"depth_m": 100.0}, {"depth_m": 0, "conservative_temperature": 0}),
    (
        "BaseMotion",
        uwml.BaseMotion,
        {},
        {"orientation": 4, "velocity": 3, "angular_velocity": 3, "acceleration": 3, "angular_acceleration": 3},
    ),
]

CASES = [(name, argument, width) for name, _, _, widths in ENTRY_POINTS for argument, width in widths.items()]


@pytest.mark.parametrize(("name", "argument", "width"), CASES, ids=[f"{n}-{a}" for n, a, _ in CASES])
@given(data=st.data())
def test_adversarial_arguments_give_an_error_or_a_finite_result(name: str, argument: str, width: int, data: st.DataObject) -> None:
    function, valid = next((f, v) for n, f, v, _ in ENTRY_POINTS if n == name)
    value = data.draw(adversarial(width), label=argument)
    _call(function, argument, valid | {argument: value})


@given(data=st.data())
def test_adversarial_base_motions_in_an_evaluation(data: st.DataObject) -> None:
    """A base motion built from adversarial numbers (if its constructor takes them) in an
    evaluation: an error naming it, or a finite result."""
    field = data.draw(st.sampled_from(["orientation", "velocity", "angular_velocity", "acceleration", "angular_acceleration"]))
    width = 4 if field == "orientation" else 3
    value = data.draw(adversarial(width))
    try:
        motion = uwml.BaseMotion(**{field: value})
    except (ValueError, TypeError) as exc:
        assert str(exc)
        return
    _call(ROBOT.hydro, "base_motion", STATE | {"base_motion": motion})


# --- model values: finite but huge (docs/domains.md, "Model values") -------------------------


def _arm_with(change: str, value: float) -> uwml.Robot:
    """``uwml.examples.arm_on_rov`` with one model value replaced."""
    import dataclasses

    from uwml.examples import arm_on_rov

    arm = arm_on_rov()
    joints, links, base = list(arm.joints), list(arm.links), arm.base
    assert base is not None
    owner, name = change.split(".")
    if owner == "joint":
        joints[2] = dataclasses.replace(joints[2], origin=(0.1, value, 0.0))
    elif owner == "base":
        base = dataclasses.replace(base, **{name: (value, 0.0, 0.0) if name in ("com", "cob") else value})
    elif owner == "link":
        links[3] = dataclasses.replace(links[3], **{name: (value, 0.0, 0.0) if name in ("com", "cob") else value})
    else:
        tube, housing = links[1].segments  # the rectangular housing (a circular one's cd is one number)
        changed = dataclasses.replace(housing, **{name: (0.0, value, 0.0) if name == "start" else value})
        links[1] = dataclasses.replace(links[1], segments=(tube, changed))
    return uwml.Robot(joints, links, base=base)


MODEL_VALUES = [
    "joint.origin",
    "link.com",
    "link.cob",
    "link.mass",
    "link.volume",
    "base.com",
    "base.cob",
    "base.mass",
    "base.volume",
    "segment.start",
    "segment.length",
]


@pytest.mark.parametrize("field", MODEL_VALUES)
@pytest.mark.parametrize("value", [1e308, -1e300, 1e30, 2e9])
def test_finite_but_huge_model_values_are_refused_at_construction(field: str, value: float) -> None:
    """A link COM (or any model value) at 1e308 gave ``Robot.hydro`` NaN and inf with no error:
    finite in, finite out or an error, for the model's values too. Signs that make no sense
    (a negative mass) are refused for that reason instead."""
    if value < 0 and field.split(".")[1] in ("mass", "volume", "length"):
        value = -value
    with pytest.raises(ValueError, match=field.replace(".", r"\.") + r" must be at most"):
        _arm_with(field, value)


@pytest.mark.parametrize("field", MODEL_VALUES)
def test_model_values_at_their_bounds_give_finite_forces(field: str) -> None:
    """At the bound itself (1e4 m, 1e9 kg, 1e6 m³) the robot is built and every force of an
    ordinary state is finite: the bounds are where overflow cannot happen, not below."""
    from uwml import domains

    name = field.split(".")[1]
    bound = {"mass": domains.MAX_MASS, "volume": domains.MAX_VOLUME}.get(name, domains.MAX_LENGTH)
    robot = _arm_with(field, bound)
    q, qd, qdd = np.full(7, 0.3), np.full(7, -0.5), np.full(7, 1.0)
    motion = uwml.BaseMotion(velocity=(1.0, 0.2, 0.0), angular_velocity=(0.0, 0.3, 0.1))
    for result in (
        robot.hydro(q, qd, qdd, base_motion=motion, current=(0.5, 0.0, 0.0)),
        robot.environment(q, qd, qdd, depth=6000.0, losses=uwml.JointLosses(), base_motion=motion),
        robot.jacobians(q, qd, qdd, base_motion=motion),
    ):
        assert _finite(result), field


@pytest.mark.parametrize(("density", "gravity"), [(1e300, 9.81), (2e5, 9.81), (1025.0, 1e10), (1025.0, 2e3)])
def test_a_huge_water_is_refused_at_construction(density: float, gravity: float) -> None:
    with pytest.raises(ValueError, match=r"water\.(density|gravity) must be at most"):
        uwml.Water(density, gravity)


# --- simulation conditions (uwml.sim.mujoco.Simulation) ----------------------------------------------

SIMULATION_ARGUMENTS: dict[str, list[Any]] = {
    "depth": [math.nan, math.inf, -1.0, 1e308, 12000.0, "1", None, True, [1.0, 2.0], np.zeros(3)],
    "temperature_c": [math.nan, -300.0, None, "x", b"1", [4.0]],
    "current": [(math.nan, 0, 0), (1e308, 0, 0), (1e200, 1e200, 0), (1, 2), None, "abc", np.zeros((2, 3)), [[1.0], [2.0], [3.0]]],
    "current_acceleration": [(math.inf, 0, 0), (1e308, 0, 0), "x", (0,) * 1000],
    "water": ["sea", 5, (1025.0, 9.81)],
    "losses": [[uwml.JointLosses()], "x", 5, [1, 2, 3]],
    "scheme": ["foo", None, 1],
    "integrator": ["x", 3, None],
    "added_mass": ["x", None],
}
SIMULATION_CASES = [(name, value) for name, values in SIMULATION_ARGUMENTS.items() for value in values]


@pytest.mark.parametrize(("argument", "value"), SIMULATION_CASES, ids=[f"{n}-{i}" for i, (n, _) in enumerate(SIMULATION_CASES)])
def test_hostile_simulation_conditions_give_an_error_naming_them_or_a_finite_run(argument: str, value: Any) -> None:
    """Every condition of a simulation (the arm of tests/data on its floating hull): a
    ``ValueError`` or ``TypeError`` naming the argument (and short), or a simulation whose state
    stays finite; never a run that diverges from the first step (a current of 1e308 m/s did)."""
    pytest.importorskip("mujoco")
    from pathlib import Path

    from uwml.sim.mujoco import Simulation

    data = Path(__file__).parent / "data"
    try:
        sim = Simulation.from_file(data / "arm.xml", data / "arm.hydro.toml", **{argument: value})
    except (ValueError, TypeError) as error:
        message = str(error)
        assert argument in message or "forces" in message, message
        assert len(message) < 500, message
        return
    for _ in range(20):
        sim.step()
    assert np.all(np.isfinite(sim.data.qpos)) and np.all(np.isfinite(sim.data.qvel))
