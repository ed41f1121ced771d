"""The public Python API of uwml: bad input is rejected with the right exception type and a
message that names the argument; chains built from Python and single rods give the reference's
and closed-form strip theory's numbers; ``import uwml`` stays light. (The paper's preset is
``test_paper_leg.py``'s, the command line's demo ``test_cli_demo.py``'s.)

Expected numbers come from the numpy reference (``uwml.reference``), from docs/model.md (typed
here), or from closed-form strip theory worked out in the docstrings below.
"""

import math
import re
import subprocess
import sys

import numpy as np
import pytest
import uwml
import uwml.cli
from uwml import reference as ref

RHO, G = 1000.0, 9.81
RHO_M = 2700.0

PAPER = uwml.paper_leg()
M = 4  # samples in the good batch
GOOD = {"q": np.zeros((M, 3)), "qd": np.full((M, 3), 0.5), "qdd": np.ones((M, 3))}


def with_nan(name: str, index: tuple[int, int], value: float) -> dict:
    state = {key: value.copy() for key, value in GOOD.items()}
    state[name][index] = value
    return state


def argument(name: str) -> str:
    """A regex matching ``name`` as a whole word (so ``q`` does not match ``qd``)."""
    return rf"(?<![\w.]){re.escape(name)}(?![\w])"


# --------------------------------------------------------------------------------------------
# Joint states: shapes, types, non-finite values
# --------------------------------------------------------------------------------------------

BAD_STATES = [
    # (override of the good batch, exception, regex the message must match)
    pytest.param({"q": np.zeros(4)}, ValueError, argument("q"), id="q wrong length"),
    pytest.param({"q": np.zeros((M, 4))}, ValueError, argument("q"), id="q wrong last dim"),
    pytest.param({"q": np.zeros((M, 2))}, ValueError, argument("q"), id="q too few joints"),
    pytest.param(
        {"q": np.zeros((2, M, 3)), "qd": np.zeros((2, M, 3)), "qdd": np.zeros((2, M, 3))}, ValueError, argument("q"), id="3-D states"
    ),
    pytest.param({"qd": np.zeros((2, M, 3))}, ValueError, argument("qd"), id="qd 3-D"),
    pytest.param({"q": 0.5}, ValueError, argument("q"), id="q scalar"),
    pytest.param({"q": []}, ValueError, argument("q"), id="q empty list"),
    pytest.param({"qd": np.zeros((M + 1, 3))}, ValueError, argument("qd"), id="qd more samples"),
    pytest.param({"qdd": np.zeros(3)}, ValueError, argument("qdd"), id="qdd 1-D with 2-D q"),
    pytest.param({"qdd": np.zeros((M, 4))}, ValueError, argument("qdd"), id="qdd wrong last dim"),
    pytest.param({"q": np.zeros(3), "qd": np.zeros(3), "qdd": np.zeros((1, 3))}, ValueError, argument("qdd"), id="qdd (1, 3) with 1-D q"),
    pytest.param({"q": "abc"}, TypeError, argument("q"), id="q string"),
    pytest.param({"qd": [["a", "b", "c"]] * M}, TypeError, argument("qd"), id="qd strings"),
    pytest.param({"qdd": [object()] * 3}, TypeError, argument("qdd"), id="qdd objects"),
    pytest.param({"qd": {"a": 1.0}}, TypeError, argument("qd"), id="qd dict"),
    pytest.param({"q": [[0.0, 0.0, 0.0], [0.0, 0.0]]}, (TypeError, ValueError), argument("q"), id="q ragged"),
    pytest.param({"q": np.zeros((M, 3), dtype=complex)}, TypeError, argument("q"), id="q complex array"),
    pytest.param({"qd": [1j, 0.0, 0.0]}, TypeError, argument("qd"), id="qd complex list"),
    pytest.param({"qdd": np.full((M, 3), 1 + 0j)}, TypeError, argument("qdd"), id="qdd complex zero imaginary"),
    pytest.param({"q": None}, (TypeError, ValueError), argument("q"), id="q None"),
    pytest.param(with_nan("q", (2, 1), math.nan), ValueError, r"(?<!\w)q\[2, 1\]", id="q NaN at [2, 1]"),
    pytest.param(with_nan("qd", (3, 0), math.inf), ValueError, r"(?<!\w)qd\[3, 0\]", id="qd inf at [3, 0]"),
    pytest.param(with_nan("qdd", (0, 2), -math.inf), ValueError, r"(?<!\w)qdd\[0, 2\]", id="qdd -inf at [0, 2]"),
    pytest.param(
        {"q": np.array([0.1, math.nan, 0.3]), "qd": np.zeros(3), "qdd": np.zeros(3)},
        ValueError,
        r"(?<!\w)q\[(0, )?1\]",
        id="1-D q NaN at [1]",
    ),
]


@pytest.mark.parametrize("override, error, match", BAD_STATES)
@pytest.mark.parametrize("entry", ["hydro", "hydro_regressors"])
def test_bad_states_are_rejected(entry: str, override: dict, error: type, match: str) -> None:
    state = {**GOOD, **override}
    with pytest.raises(error, match=match):
        if entry == "hydro":
            PAPER.hydro(**state)
        else:
            PAPER.hydro_regressors(**state)


def test_non_finite_index_names_the_first_bad_entry_of_a_large_batch() -> None:
    rng = np.random.default_rng(0)
    q, qd, qdd = rng.normal(size=(3, 1000, 3))
    qd[617, 2] = math.nan
    qd[900, 0] = math.inf
    with pytest.raises(ValueError, match=r"(?<!\w)qd\[617, 2\]"):
        PAPER.hydro(q, qd, qdd)
    chain = uwml.Robot([uwml.Joint(origin=(0, 0, 0), axis=(0, 0, 1))] * 5, [uwml.Link(mass=1.0, com=(0.1, 0, 0), volume=0.001)] * 5)
    q5 = np.zeros((10, 5))
    q5[7, 4] = -math.inf
    with pytest.raises(ValueError, match=r"(?<!\w)q\[7, 4\]"):
        chain.hydro_regressors(q5, np.zeros((10, 5)), np.zeros((10, 5)))


# --------------------------------------------------------------------------------------------
# Coefficients (the paper's leg has two segments)
# --------------------------------------------------------------------------------------------

BAD_COEFFICIENTS = [
    pytest.param(-1.0, ValueError, id="negative"),
    pytest.param(math.nan, ValueError, id="NaN"),
    pytest.param(math.inf, ValueError, id="inf"),
    pytest.param(np.ones(1), ValueError, id="1 per segment for 2 segments"),
    pytest.param(np.ones(3), ValueError, id="3 per segment for 2 segments"),
    pytest.param(np.ones((2, 3)), ValueError, id="(2, 3)"),
    pytest.param(np.ones((3, 2)), ValueError, id="(3, 2)"),
    pytest.param(np.ones((1, 2, 2)), ValueError, id="3-D"),
    pytest.param(np.array([[1.0, 2.0], [1.0, -0.1]]), ValueError, id="one negative entry"),
    pytest.param(np.array([1.0, math.nan]), ValueError, id="NaN per segment"),
    pytest.param("big", TypeError, id="string"),
    pytest.param(1.0 + 1.0j, TypeError, id="complex"),
    pytest.param([object()] * 3, TypeError, id="objects"),
    pytest.param([[1.0, 2.0], [1.0]], (TypeError, ValueError), id="ragged"),
]


@pytest.mark.parametrize("value, error", BAD_COEFFICIENTS)
@pytest.mark.parametrize("name", ["cd", "cm"])
def test_bad_coefficients_are_rejected_by_hydro(name: str, value: object, error: type) -> None:
    """(``None`` is each segment's own coefficient, as for every robot.)"""
    with pytest.raises(error, match=argument(name)):
        PAPER.hydro(**GOOD, **{name: value})


@pytest.mark.parametrize("value, error", BAD_COEFFICIENTS)
@pytest.mark.parametrize("name", ["cd", "cm"])
def test_bad_coefficients_are_rejected_by_regressor_torques(name: str, value: object, error: type) -> None:
    regressors = PAPER.hydro_regressors(**GOOD)
    with pytest.raises(error, match=argument(name)):
        regressors.torques(**{"cd": 1.0, "cm": 1.0, name: value})


# --------------------------------------------------------------------------------------------
# Joint, Segment, Link, Robot
# --------------------------------------------------------------------------------------------

SEGMENT = {
    "start": (0.0, 0.0, 0.0),
    "axis": (1.0, 0.0, 0.0),
    "length": 1.0,
    "normals": ((0.0, 1.0, 0.0), (0.0, 0.0, 1.0)),
    "widths": (0.1, 0.2),
    "area": 0.02,
}
LINK = {"mass": 2.0, "com": (0.5, 0.0, 0.0), "volume": 0.001}

BAD_JOINTS = [
    pytest.param({"axis": (0.0, 0.0, 2.0)}, ValueError, "joint.axis", id="axis not unit"),
    pytest.param({"axis": (0.0, 0.0, 1.0 + 1e-4)}, ValueError, "joint.axis", id="axis slightly long"),
    pytest.param({"axis": (0.0, 0.0, 0.0)}, ValueError, "joint.axis", id="axis zero"),
    pytest.param({"axis": (math.nan, 0.0, 1.0)}, ValueError, "joint.axis", id="axis NaN"),
    pytest.param({"axis": (0.0, 1.0)}, ValueError, "joint.axis", id="axis 2 components"),
    pytest.param({"axis": (0.0, 0.0, 1.0, 0.0)}, ValueError, "joint.axis", id="axis 4 components"),
    pytest.param({"axis": None}, TypeError, "joint.axis", id="axis None"),
    pytest.param({"axis": 1.0}, TypeError, "joint.axis", id="axis scalar"),
    pytest.param({"axis": ("x", "y", "z")}, ValueError, "joint.axis", id="axis strings"),
    pytest.param({"origin": (0.0, 0.0)}, ValueError, "joint.origin", id="origin 2 components"),
    pytest.param({"origin": (math.inf, 0.0, 0.0)}, ValueError, "joint.origin", id="origin inf"),
    pytest.param({"origin": (0.0, math.nan, 0.0)}, ValueError, "joint.origin", id="origin NaN"),
    pytest.param({"origin": "abc"}, ValueError, "joint.origin", id="origin string"),
]


@pytest.mark.parametrize("kwargs, error, name", BAD_JOINTS)
def test_bad_joint_is_rejected(kwargs: dict, error: type, name: str) -> None:
    with pytest.raises(error, match=argument(name)):
        uwml.Joint(**{"origin": (0.0, 0.0, 0.0), "axis": (0.0, 0.0, 1.0), **kwargs})


BAD_SEGMENTS = [
    pytest.param({"axis": (1.0, 1.0, 0.0)}, ValueError, "segment.axis", id="axis not unit"),
    pytest.param({"axis": (0.0, 0.0, 0.0)}, ValueError, "segment.axis", id="axis zero"),
    pytest.param({"axis": (1.0, 0.0)}, ValueError, "segment.axis", id="axis 2 components"),
    pytest.param({"start": (0.0, math.nan, 0.0)}, ValueError, "segment.start", id="start NaN"),
    pytest.param({"start": (0.0, 0.0, 0.0, 0.0)}, ValueError, "segment.start", id="start 4 components"),
    pytest.param({"length": 0.0}, ValueError, "segment.length", id="length 0"),
    pytest.param({"length": -0.5}, ValueError, "segment.length", id="length negative"),
    pytest.param({"length": math.nan}, ValueError, "segment.length", id="length NaN"),
    pytest.param({"length": "long"}, TypeError, "segment.length", id="length string"),
    pytest.param({"normals": ((1.0, 0.0, 0.0), (0.0, 0.0, 1.0))}, ValueError, "segment.normals", id="normal along axis"),
    pytest.param({"normals": ((0.0, 1.0, 0.0), (0.0, 1.0, 0.0))}, ValueError, "segment.normals", id="normals equal"),
    pytest.param({"normals": ((0.0, 0.6, 0.6), (0.0, -0.6, 0.6))}, ValueError, "segment.normals", id="normals not unit"),
    pytest.param({"normals": ((0.0, 1.0, 0.0), (0.0, 0.0, 0.0))}, ValueError, "segment.normals", id="normal zero"),
    pytest.param({"normals": ((0.0, 1.0, 0.0), (0.0, math.nan, 1.0))}, ValueError, "segment.normals", id="normal NaN"),
    pytest.param({"normals": ((0.0, 1.0, 0.0),)}, ValueError, "segment.normals", id="one normal"),
    pytest.param({"normals": ((0.0, 1.0, 0.0), (0.0, 0.0, 1.0), (0.0, 0.0, 1.0))}, ValueError, "segment.normals", id="three normals"),
    pytest.param({"normals": ((0.0, 1.0), (0.0, 0.0, 1.0))}, ValueError, "segment.normals", id="normal 2 components"),
    pytest.param({"normals": None}, (TypeError, ValueError), "segment.normals", id="normals None"),
    pytest.param({"widths": (0.0, 0.2)}, ValueError, "segment.widths", id="width 0"),
    pytest.param({"widths": (0.1, -0.2)}, ValueError, "segment.widths", id="width negative"),
    pytest.param({"widths": (0.1, math.inf)}, ValueError, "segment.widths", id="width inf"),
    pytest.param({"widths": (0.1, 0.2, 0.3)}, ValueError, "segment.widths", id="three widths"),
    pytest.param({"widths": 0.1}, (TypeError, ValueError), "segment.widths", id="widths scalar"),
    pytest.param({"area": 0.0}, ValueError, "segment.area", id="area 0"),
    pytest.param({"area": -0.01}, ValueError, "segment.area", id="area negative"),
    pytest.param({"area": math.nan}, ValueError, "segment.area", id="area NaN"),
]


@pytest.mark.parametrize("kwargs, error, name", BAD_SEGMENTS)
def test_bad_segment_is_rejected(kwargs: dict, error: type, name: str) -> None:
    with pytest.raises(error, match=argument(name)):
        uwml.Segment(**{**SEGMENT, **kwargs})


BAD_WATER = [
    pytest.param({"density": 0.0}, ValueError, "water.density", id="density 0"),
    pytest.param({"density": -1000.0}, ValueError, "water.density", id="density negative"),
    pytest.param({"density": math.nan}, ValueError, "water.density", id="density NaN"),
    pytest.param({"density": math.inf}, ValueError, "water.density", id="density inf"),
    pytest.param({"density": "salty"}, TypeError, "water.density", id="density string"),
    pytest.param({"density": None}, TypeError, "water.density", id="density None"),
    pytest.param({"gravity": -9.81}, ValueError, "water.gravity", id="gravity negative"),
    pytest.param({"gravity": math.nan}, ValueError, "water.gravity", id="gravity NaN"),
    pytest.param({"gravity": -math.inf}, ValueError, "water.gravity", id="gravity -inf"),
    pytest.param({"gravity": [9.81]}, TypeError, "water.gravity", id="gravity list"),
]


@pytest.mark.parametrize("kwargs, error, name", BAD_WATER)
def test_bad_water_is_rejected(kwargs: dict, error: type, name: str) -> None:
    with pytest.raises(error, match=argument(name)):
        uwml.Water(**kwargs)


@pytest.mark.parametrize("water", [1000.0, {"density": 1000.0, "gravity": 9.81}, (1000.0, 9.81)], ids=["float", "dict", "tuple"])
def test_water_must_be_a_water_object(water: object) -> None:
    """(``None`` is the robot's own water.)"""
    with pytest.raises(TypeError, match=argument("water")):
        PAPER.hydro(**GOOD, water=water)
    with pytest.raises(TypeError, match=argument("water")):
        PAPER.hydro_regressors(**GOOD, water=water)


def test_water_defaults_and_zero_gravity() -> None:
    water = uwml.Water()
    assert (water.density, water.gravity) == (1000.0, 9.81)
    weightless = PAPER.hydro(**GOOD, water=uwml.Water(gravity=0.0))
    assert np.all(weightless.buoyancy == 0.0) and np.all(weightless.gravity == 0.0)


def test_model_error_is_a_value_error() -> None:
    assert issubclass(uwml.ModelError, ValueError)


BAD_LINKS = [
    pytest.param({"mass": -1.0}, ValueError, "link.mass", id="mass negative"),
    pytest.param({"mass": math.nan}, ValueError, "link.mass", id="mass NaN"),
    pytest.param({"mass": math.inf}, ValueError, "link.mass", id="mass inf"),
    pytest.param({"mass": "heavy"}, TypeError, "link.mass", id="mass string"),
    pytest.param({"volume": -0.001}, ValueError, "link.volume", id="volume negative"),
    pytest.param({"volume": math.nan}, ValueError, "link.volume", id="volume NaN"),
    pytest.param({"com": (0.5, 0.0)}, ValueError, "link.com", id="com 2 components"),
    pytest.param({"com": (0.5, math.nan, 0.0)}, ValueError, "link.com", id="com NaN"),
    pytest.param({"cob": (0.5, 0.0, math.inf)}, ValueError, "link.cob", id="cob inf"),
    pytest.param({"cob": (0.5, 0.0, 0.0, 1.0)}, ValueError, "link.cob", id="cob 4 components"),
    pytest.param({"segments": "rod"}, TypeError, "link.segments[0]", id="segments string"),
    pytest.param({"segments": [SEGMENT]}, TypeError, "link.segments[0]", id="segments dict"),
    pytest.param({"segments": 5}, TypeError, "link.segments", id="segments int"),
]


@pytest.mark.parametrize("kwargs, error, name", BAD_LINKS)
def test_bad_link_is_rejected(kwargs: dict, error: type, name: str) -> None:
    with pytest.raises(error, match=argument(name)):
        uwml.Link(**{**LINK, **kwargs})


def _joint() -> uwml.Joint:
    return uwml.Joint(origin=(0.0, 0.0, 0.1), axis=(0.0, 1.0, 0.0))


def _link() -> uwml.Link:
    return uwml.Link(**LINK, segments=(uwml.Segment(**SEGMENT),))


BAD_ROBOTS = [
    pytest.param([_joint()] * 3, [_link()] * 2, ValueError, r"joints.*links|links.*joints", id="3 joints 2 links"),
    pytest.param([_joint()] * 1, [_link()] * 2, ValueError, r"joints.*links|links.*joints", id="1 joint 2 links"),
    pytest.param([], [], ValueError, argument("joints"), id="no joints"),
    pytest.param(
        [_joint()] * (uwml.MAX_ROBOT_JOINTS + 1),
        [_link()] * (uwml.MAX_ROBOT_JOINTS + 1),
        ValueError,
        str(uwml.MAX_ROBOT_JOINTS),
        id="too many joints",
    ),
    pytest.param([_joint(), "joint"], [_link()] * 2, TypeError, argument("joints"), id="string joint"),
    pytest.param([_link()], [_link()], TypeError, argument("joints"), id="link as joint"),
    pytest.param([_joint()], [_joint()], TypeError, argument("links"), id="joint as link"),
    pytest.param([_joint()], [{"mass": 1.0}], TypeError, argument("links"), id="dict as link"),
    pytest.param([ref.RefJoint((0.0, 0.0, 0.0), (0.0, 0.0, 1.0))], [_link()], TypeError, argument("joints"), id="reference joint"),
    pytest.param(None, [_link()], TypeError, argument("joints"), id="joints None"),
    pytest.param([_joint()], 5, TypeError, argument("links"), id="links int"),
]


@pytest.mark.parametrize("joints, links, error, match", BAD_ROBOTS)
def test_bad_robot_is_rejected(joints: object, links: object, error: type, match: str) -> None:
    with pytest.raises(error, match=match):
        uwml.Robot(joints, links)


def test_a_chain_of_max_joints_works() -> None:
    n = uwml.MAX_ROBOT_JOINTS
    leg = uwml.Robot([_joint()] * n, [_link()] * n)
    assert leg.n_joints == n
    rng = np.random.default_rng(0)
    q, qd, qdd = rng.normal(size=(3, 20, n))
    out = leg.hydro(q, qd, qdd)
    expected = ref.hydro([_joint()] * n, [_link()] * n, q, qd, qdd)
    for key in ("drag", "added_mass", "buoyancy", "gravity"):
        np.testing.assert_allclose(getattr(out, key), expected[key], rtol=1e-10, atol=1e-10 * np.abs(expected[key]).max())


# --------------------------------------------------------------------------------------------
# Chains built from Python
# --------------------------------------------------------------------------------------------


def _arm() -> tuple[list, list]:
    """A hand-built 4-joint arm: yaw, a tilted shoulder, a dry wrist housing, a round forearm;
    the centre of buoyancy off the centre of mass, one link lighter than water."""
    s = math.sqrt(0.5)
    joints = [
        uwml.Joint(origin=(0.0, 0.0, 0.0), axis=(0.0, 0.0, 1.0)),
        uwml.Joint(origin=(0.05, 0.0, 0.1), axis=(0.0, s, s)),
        uwml.Joint(origin=(0.4, 0.0, 0.0), axis=(1.0, 0.0, 0.0)),
        uwml.Joint(origin=(0.0, 0.1, -0.05), axis=(0.0, 1.0, 0.0)),
    ]
    links = [
        uwml.Link(mass=5.0, com=(0.0, 0.0, 0.05), volume=0.002),
        uwml.Link(
            mass=3.0,
            com=(0.2, 0.0, 0.0),
            volume=0.004,
            cob=(0.21, 0.01, 0.0),
            segments=[
                uwml.Segment(
                    start=(0.0, 0.0, 0.0),
                    axis=(1.0, 0.0, 0.0),
                    length=0.4,
                    normals=((0.0, s, -s), (0.0, s, s)),
                    widths=(0.08, 0.12),
                    area=0.0096,
                )
            ],
        ),
        uwml.Link(mass=1.0, com=(0.0, 0.05, 0.0), volume=0.0003),
        uwml.Link(
            mass=2.0,
            com=(0.0, 0.0, -0.3),
            volume=0.0012,
            cob=(0.0, 0.005, -0.28),
            segments=[
                uwml.Segment(
                    start=(0.0, 0.0, -0.02),
                    axis=(0.0, 0.0, -1.0),
                    length=0.6,
                    normals=((1.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
                    widths=(0.07, 0.07),
                    area=math.pi * 0.035**2,
                )
            ],
        ),
    ]
    return joints, links


def test_chain_built_from_python_equals_reference() -> None:
    joints, links = _arm()
    leg = uwml.Robot(joints, links)
    assert leg.n_joints == 4 and leg.links == tuple(links)
    assert [j.origin for j in leg.joints] == [j.origin for j in joints] and [j.axis for j in leg.joints] == [j.axis for j in joints]
    rng = np.random.default_rng(2)
    q = rng.uniform(-math.pi, math.pi, (800, 4))
    qd, qdd = rng.uniform(-3.0, 3.0, (800, 4)), rng.uniform(-10.0, 10.0, (800, 4))
    for cd, cm in ((1.1, 1.0), (rng.uniform(0.5, 2.0, (4, 2)), rng.uniform(0.5, 1.5, (4, 2)))):
        # The reference's coefficients per link, the robot's per segment (links 1 and 3 have one).
        per_segment = (cd, cm) if np.ndim(cd) == 0 else (cd[[1, 3]], cm[[1, 3]])
        out = leg.hydro(q, qd, qdd, cd=per_segment[0], cm=per_segment[1], water=uwml.Water(density=1025.0, gravity=9.80665))
        expected = ref.hydro(joints, links, q, qd, qdd, cd=cd, cm=cm, density=1025.0, gravity=9.80665)
        for key in ("drag", "added_mass", "buoyancy", "gravity", "total"):
            # Relative to each sample's largest entry (not below 1e-3 of the batch's largest).
            scale = np.abs(expected[key]).max(axis=1, keepdims=True)
            scale = np.maximum(scale, 1e-3 * scale.max())
            error = np.abs(getattr(out, key) - expected[key]) / scale
            assert error.max() <= 1e-10, f"{key}: relative error {error.max():.3g}"


def test_joint_axes_are_normalized() -> None:
    joint = uwml.Joint(origin=(0, 0, 0), axis=(0.0, 0.6, 0.8 * (1 + 5e-7)))
    assert math.isclose(math.hypot(*joint.axis), 1.0, rel_tol=0, abs_tol=1e-15)
    leg = uwml.Robot([joint], [_link()])
    assert math.isclose(math.hypot(*leg.joints[0].axis), 1.0, rel_tol=0, abs_tol=1e-15)
    # Integer components are accepted and stored as floats.
    joint = uwml.Joint(origin=[0, 0, 1], axis=np.array([0, 0, 1]))
    assert joint.axis == (0.0, 0.0, 1.0) and all(type(x) is float for x in joint.axis + joint.origin)


def test_total_is_drag_plus_added_mass_plus_buoyancy() -> None:
    rng = np.random.default_rng(6)
    out = PAPER.hydro(*rng.uniform(-2.0, 2.0, (3, 100, 3)))
    np.testing.assert_array_equal(out.total, out.drag + out.added_mass + out.buoyancy)


# --------------------------------------------------------------------------------------------
# Closed-form single rods
# --------------------------------------------------------------------------------------------


def test_single_rods_against_closed_forms() -> None:
    """A rod of length 1 along x from a joint at the origin, width 0.1, area A, volume V, COM at
    (0.5, 0, 0). About z: added mass −ρ Cm A ∫ s² ds q̈ = −ρ Cm A/3 q̈, and the centripetal
    acceleration is along the rod (no normal component). About −y (lifting it): buoyancy
    ρ V g · 0.5 cos q, gravity −m g · 0.5 cos q, drag −½ ρ Cd w q̇|q̇|/4."""
    area, volume, mass = 0.00785, 0.00785, 20.0
    segment = uwml.Segment(start=(0, 0, 0), axis=(1, 0, 0), length=1.0, normals=((0, 1, 0), (0, 0, 1)), widths=(0.1, 0.1), area=area)
    link = uwml.Link(mass=mass, com=(0.5, 0, 0), volume=volume, segments=(segment,))
    yaw = uwml.Robot([uwml.Joint(origin=(0, 0, 0), axis=(0, 0, 1))], [link])
    out = yaw.hydro(q=[[0.3], [1.0], [-2.0]], qd=[[0.0], [1.0], [2.0]], qdd=[[1.0], [0.0], [-3.0]], cd=1.2, cm=1.0)
    np.testing.assert_allclose(out.added_mass[:, 0], [-RHO * area / 3.0, 0.0, 3.0 * RHO * area / 3.0], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(out.drag[:, 0], [0.0, -15.0, -60.0], rtol=1e-12, atol=1e-12)
    assert np.all(out.buoyancy == 0.0) and np.all(out.gravity == 0.0)
    lift = uwml.Robot([uwml.Joint(origin=(0, 0, 0), axis=(0, -1, 0))], [link])
    q = np.linspace(-math.pi, math.pi, 13)[:, None]
    out = lift.hydro(q=q, qd=-2.0 * np.ones_like(q), qdd=np.zeros_like(q), cd=1.2, cm=1.0)
    np.testing.assert_allclose(out.buoyancy[:, 0], RHO * volume * G * 0.5 * np.cos(q[:, 0]), rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(out.gravity[:, 0], -mass * G * 0.5 * np.cos(q[:, 0]), rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(out.drag[:, 0], 0.5 * RHO * 1.2 * 0.1 * 4.0 / 4.0, rtol=1e-12)


def test_import_uwml_loads_neither_the_reference_nor_matplotlib() -> None:
    """``import uwml`` is light: the numpy reference (for tests and checks) and matplotlib (for
    plots) are imported when used; ``uwml.reference`` still works after a bare ``import uwml``."""

    code = (
        "import sys, uwml; loaded = [m for m in ('uwml.reference', 'matplotlib') if m in sys.modules]; "
        "assert not loaded, loaded; assert uwml.reference.PAPER_L2 == 0.660; print('ok')"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=False)
    assert done.returncode == 0 and done.stdout.strip() == "ok", done.stderr
