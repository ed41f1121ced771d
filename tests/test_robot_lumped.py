"""Fossen's lumped model of a body (``uwml.LumpedModel``, docs/model.md section 12.1) through
``uwml.Robot`` (the Rust core) held against the independent numpy reference on random trees with
lumped models on random bodies, beside their segments, in moving water; its added-mass matrix;
the model file's round trip; the checks of ``LumpedModel``; and what is not available yet for a
robot with lumped models (regressors), refused rather than answered wrongly.
"""

import dataclasses

import numpy as np
import pytest
import uwml
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation
from test_robot import RTOL_REFERENCE, assert_close, assert_matches_reference, motion_arguments, random_robot
from uwml import reference as ref

EXAMPLES = settings(max_examples=max(5, int(settings.default.max_examples / 4)))


def moving_water_states(rng: np.random.Generator, n: int, samples: int) -> tuple:  # type: ignore[type-arg]
    """Random joint states of ``n`` joints, a base motion's arguments and a current, ``samples`` each."""
    q, qd, qdd = rng.uniform(-3, 3, (samples, n)), rng.uniform(-2, 2, (samples, n)), rng.uniform(-5, 5, (samples, n))
    motion = motion_arguments(rng, samples)
    return q, qd, qdd, motion, rng.normal(size=(samples, 3)), rng.normal(size=(samples, 3))


def random_lumped(rng: np.random.Generator) -> uwml.LumpedModel:
    """A lumped model with a full (random, positive semi-definite) added mass, a linear damping
    with a positive semi-definite symmetric part and a skew part, and quadratic damping."""
    a = rng.normal(size=(6, 6)) * rng.uniform(0.5, 5.0)
    skew = rng.normal(size=(6, 6))
    damping = rng.normal(size=(6, 4))
    axes = Rotation.random(random_state=rng).as_matrix() if rng.random() < 0.5 else np.eye(3)
    return uwml.LumpedModel(
        point=rng.uniform(-0.3, 0.3, 3) if rng.random() < 0.7 else None,
        axes=axes,
        added_mass=a @ a.T,
        linear_damping=damping @ damping.T + (skew - skew.T),
        quadratic_damping=rng.uniform(0.0, 20.0, 6),
    )


def with_lumped(robot: uwml.Robot, rng: np.random.Generator) -> uwml.Robot:
    """``robot`` with a lumped model on its base (if it has a body) and on about half its links."""
    links = [dataclasses.replace(link, lumped=random_lumped(rng)) if rng.random() < 0.5 else link for link in robot.links]
    base = None if robot.base is None else dataclasses.replace(robot.base, lumped=random_lumped(rng))
    return uwml.Robot(robot.joints, links, base=base)


@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 8), form=st.sampled_from(["morison", "kirchhoff"]))
def test_core_matches_the_reference_with_lumped_models_in_moving_water(seed: int, n: int, form: str) -> None:
    rng = np.random.default_rng(seed)
    robot = with_lumped(random_robot(rng, n, base_body=bool(rng.random() < 0.8)), rng)
    samples = 12
    q, qd, qdd, motion, current, current_acceleration = moving_water_states(rng, n, samples)
    result = robot.hydro(
        q, qd, qdd, base_motion=uwml.BaseMotion(**motion), current=current, current_acceleration=current_acceleration,
        added_mass=form,
    )  # fmt: skip
    expected = ref.robot_hydro(
        robot.joints, robot.links, robot.base, q, qd, qdd, current=current, current_acceleration=current_acceleration,
        added_mass=form, **motion,
    )  # fmt: skip
    assert_matches_reference(result, expected)
    # One state at a time (the native one-state path) gives the batch's rows.
    one = robot.hydro(q[0], qd[0], qdd[0], base_motion=uwml.BaseMotion(**{k: v[0] for k, v in motion.items()}),
                      current=current[0], current_acceleration=current_acceleration[0], added_mass=form)  # fmt: skip
    np.testing.assert_array_equal(one.total, result.total[0])


@EXAMPLES
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 6))
def test_added_mass_matrix_and_link_wrenches_with_lumped_models_match_the_reference(seed: int, n: int) -> None:
    rng = np.random.default_rng(seed)
    robot = with_lumped(random_robot(rng, n), rng)
    samples = 5
    q, qd, qdd = rng.uniform(-3, 3, (samples, n)), rng.uniform(-2, 2, (samples, n)), rng.uniform(-5, 5, (samples, n))
    matrices = robot.added_mass_matrix(q)
    expected = ref.robot_added_mass_matrix(robot.joints, robot.links, robot.base, q)
    scale = np.max(np.abs(expected).reshape(samples, -1), axis=1)
    assert_close(matrices, expected, scale, RTOL_REFERENCE, "added-mass matrix")
    np.testing.assert_array_equal(matrices, np.swapaxes(matrices, 1, 2))
    assert np.all(np.linalg.eigvalsh(matrices) >= -1e-12 * scale[:, None])
    motion = motion_arguments(rng, samples)
    current = rng.normal(size=(samples, 3))
    wrenches = robot.link_wrenches(q, qd, qdd, base_motion=uwml.BaseMotion(**motion), current=current)
    expected_wrenches = ref.robot_link_wrenches(robot.joints, robot.links, robot.base, q, qd, qdd, current=current, **motion)
    assert_close(wrenches, expected_wrenches, np.max(np.abs(expected_wrenches).reshape(samples, -1), axis=1), RTOL_REFERENCE, "wrenches")


def test_a_lumped_models_point_defaults_to_its_bodys_centre_of_buoyancy() -> None:
    model = uwml.LumpedModel(added_mass=np.eye(6))
    assert model.point is None
    link = uwml.Link(2.0, (0.1, 0.0, 0.0), 0.001, cob=(0.0, 0.2, 0.0), lumped=model)
    assert link.lumped is not None and link.lumped.point == (0.0, 0.2, 0.0)
    assert uwml.Link(2.0, (0.1, 0.0, 0.0), 0.001, lumped=model).lumped.point == (0.1, 0.0, 0.0)  # cob is com
    kept = uwml.Link(2.0, (0.1, 0.0, 0.0), 0.001, lumped=uwml.LumpedModel(point=(1.0, 2.0, 3.0)))
    assert kept.lumped is not None and kept.lumped.point == (1.0, 2.0, 3.0)


def test_a_robot_with_lumped_models_round_trips_through_its_model_file(tmp_path) -> None:
    rng = np.random.default_rng(4)
    robot = with_lumped(random_robot(rng, 4), rng)
    path = tmp_path / "robot.toml"
    robot.save(path)
    assert "[base.lumped]" in path.read_text() and "quadratic_damping" in path.read_text()
    loaded = uwml.Robot.load(path)
    assert loaded == robot
    q = rng.uniform(-1, 1, (3, 4))
    np.testing.assert_array_equal(loaded.hydro(q, q, q).total, robot.hydro(q, q, q).total)


@pytest.mark.parametrize(
    "arguments, message",
    [
        ({"added_mass": np.eye(5)}, r"lumped.added_mass must be a 6×6 matrix, got shape \(5, 5\)"),
        (
            {"added_mass": np.triu(np.ones((6, 6)))},
            r"lumped.added_mass must be symmetric within 1e-09 .*: \[0\]\[1\] = 1.0 but \[1\]\[0\] = 0.0",
        ),
        ({"added_mass": np.diag([1.0, 1.0, -1.0, 1.0, 1.0, 1.0])}, r"lumped.added_mass must be positive semi-definite .* -1"),
        ({"added_mass": np.ones((6, 6)) + np.diag([0, 0, 0, 0, 0, -2.0])}, r"lumped.added_mass must be positive semi-definite"),
        ({"linear_damping": -np.eye(6)}, r"lumped.linear_damping must have a positive semi-definite symmetric part"),
        ({"linear_damping": np.full((6, 6), np.nan)}, r"lumped.linear_damping\[0\]\[0\] must be finite"),
        ({"added_mass": np.eye(6) * 1e13}, r"lumped.added_mass\[0\]\[0\] must be at most 1e\+12"),
        ({"quadratic_damping": [1, 1, 1, 1, 1]}, r"lumped.quadratic_damping must be 6 numbers, got 5"),
        ({"quadratic_damping": [1, 1, -1, 1, 1, 1]}, r"lumped.quadratic_damping\[2\] must be finite and non-negative"),
        ({"point": (0.0, np.inf, 0.0)}, r"lumped.point must be 3 finite numbers"),
        ({"axes": np.diag([1.0, 1.0, -1.0])}, r"lumped.axes must be a rotation"),
        ({"axes": 2.0 * np.eye(3)}, r"lumped.axes must be a rotation"),
        ({"axes": np.eye(4)}, r"lumped.axes must be a 3×3 rotation matrix"),
    ],
)
def test_bad_lumped_models_are_refused_naming_the_entry(arguments: dict, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        uwml.LumpedModel(**arguments)


def _diag(*head: float) -> np.ndarray:
    """A diagonal 6×6 matrix starting with ``head``, ones after."""
    return np.diag([*head, *[1.0] * (6 - len(head))])


def _asymmetric(scale: float, asymmetry: float) -> np.ndarray:
    """diag(scale, 1, …) with [0][1] = ``asymmetry`` and [1][0] = 0 (positive definite either way)."""
    matrix = _diag(scale)
    matrix[0, 1] = asymmetry
    return matrix


def _singular_at(rng: np.random.Generator, scale: float, rank: int) -> np.ndarray:
    """A random positive semi-definite matrix of ``rank`` whose largest diagonal entry is ``scale``
    (rounded to float64: its zero eigenvalues come out as ±rounding)."""
    if rank == 0:
        return np.zeros((6, 6))
    a = rng.normal(size=(6, rank))
    matrix = a @ a.T
    return 0.5 * (matrix + matrix.T) * (scale / float(np.max(np.diag(matrix))) * 0.999_999)  # not above the cap by rounding


class _Duck:
    """A duck-typed body for the numpy reference: no segments, the given lumped model."""

    def __init__(self, lumped: object) -> None:
        self.mass, self.com, self.volume, self.cob, self.segments, self.lumped = 1.0, (0.0, 0.0, 0.0), 0.0, None, (), lumped


@pytest.mark.parametrize(
    "arguments, message",
    [
        # Issue 31: a 1e12 entry no longer hides a −99 eigenvalue (the relative tolerance alone
        # allowed −100) nor an asymmetry of 900 (it allowed 1000, then averaged it away).
        (
            {"added_mass": _diag(1e12, -99.0)},
            (
                r"lumped.added_mass must be positive semi-definite .*smallest eigenvalue is -99, "
                r"below the allowed -0\.01 \(-min\(1e-10 × 1e\+12 its largest diagonal entry, 0\.01\)\)"
            ),
        ),
        (
            {"added_mass": _asymmetric(1e12, 900.0)},
            (
                r"lumped.added_mass must be symmetric within 0\.01 \(min\(1e-09 × 1e\+12 its largest entry, 0\.01\)\): "
                r"\[0\]\[1\] = 900.0 but \[1\]\[0\] = 0.0"
            ),
        ),
        (
            {"linear_damping": _diag(1e12, -99.0)},
            r"lumped.linear_damping must have a positive semi-definite symmetric part .*smallest eigenvalue is -99, below the allowed -0\.01",
        ),
        ({"added_mass": _diag(1e9, -0.1)}, r"lumped.added_mass must be positive semi-definite"),
        ({"added_mass": _asymmetric(1e9, 0.1)}, r"lumped.added_mass must be symmetric within 0\.01"),
    ],
)
def test_a_huge_entry_hides_no_negative_eigenvalue_or_asymmetry(arguments: dict, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        uwml.LumpedModel(**arguments)


def test_rounding_in_huge_entries_is_still_taken() -> None:
    """The absolute floor stays above float64's rounding at the 1e12 cap: singular semi-definite
    matrices of every rank at 1e12, their asymmetric rounding, and a damping's skew part are taken
    by the Python check, the core (through ``uwml.Robot``) and the reference alike."""
    rng = np.random.default_rng(31)
    joint, link = uwml.Joint((0.0, 0.0, 0.0), (0.0, 0.0, 1.0)), uwml.Link(1.0, (0.0, 0.0, 0.0), 0.0)
    for scale in (1e-3, 1.0, 1e6, 1e9, 1e11, 1e12):
        for rank in range(6):
            matrix = _singular_at(rng, scale, rank)
            rounded = matrix.copy()
            if rank:
                rounded[0, 3] = np.nextafter(rounded[0, 3], np.inf)  # an asymmetry of one ulp
            skew = rng.normal(size=(6, 6)) * scale * 1e-3
            model = uwml.LumpedModel(added_mass=rounded, linear_damping=matrix + (skew - skew.T))
            robot = uwml.Robot([joint], [link], base=uwml.Link(1.0, (0.0, 0.0, 0.0), 0.0, lumped=model))
            q = np.zeros((1, 1))
            ref.robot_hydro(robot.joints, robot.links, _Duck(model), q, q, q)


def test_the_reference_refuses_what_the_model_refuses() -> None:
    """The numpy reference checks a duck-typed lumped model by the same rule (docs/model.md section
    12.1): what ``uwml.LumpedModel`` refuses, it refuses."""
    import types

    joint, link = uwml.Joint((0.0, 0.0, 0.0), (0.0, 0.0, 1.0)), uwml.Link(1.0, (0.0, 0.0, 0.0), 0.0)
    q = np.zeros((1, 1))
    zero = np.zeros((6, 6))
    for fields, message in [
        ({"added_mass": _diag(1e12, -99.0)}, r"base.lumped.added_mass must be positive semi-definite"),
        ({"added_mass": _asymmetric(1e12, 900.0)}, r"base.lumped.added_mass must be symmetric within 0\.01"),
        ({"linear_damping": _diag(1e12, -99.0)}, r"base.lumped.linear_damping must have a positive semi-definite symmetric part"),
        ({"quadratic_damping": [0.0, 0.0, -1.0, 0.0, 0.0, 0.0]}, r"base.lumped.quadratic_damping\[2\] must be >= 0"),
    ]:
        given = {"point": None, "axes": None, "added_mass": zero, "linear_damping": zero, "quadratic_damping": np.zeros(6), **fields}
        with pytest.raises(ValueError, match=message):
            ref.robot_hydro([joint], [link], _Duck(types.SimpleNamespace(**given)), q, q, q)


def test_the_tolerances_are_one_rule_in_the_core_the_model_and_the_reference() -> None:
    """docs/model.md section 12.1: one relative tolerance per check and one absolute floor, named
    once per language (the core's ``uwml_core::LUMPED_*``, ``uwml.model.lumped``'s, the
    reference's); each states the same numbers."""
    import re
    from pathlib import Path

    from uwml.model import lumped
    from uwml.reference import _inputs

    source = (Path(__file__).resolve().parents[1] / "crates/uwml-core/src/bounds.rs").read_text()
    core = {name: float(value) for name, value in re.findall(r"pub const (LUMPED_\w+_TOLERANCE): f64 = ([-+.\deE_]+);", source)}
    python = {name: getattr(lumped, name) for name in core}
    reference = {name: getattr(_inputs, f"_{name}") for name in core}
    assert set(core) == {"LUMPED_SYMMETRY_TOLERANCE", "LUMPED_EIGENVALUE_TOLERANCE", "LUMPED_ABSOLUTE_TOLERANCE"}
    assert core == python == reference


def test_the_floating_case_of_the_issue_is_refused_at_load(tmp_path) -> None:
    """Issue 31: a floating robot whose hull had diag(1e12, −99, …) loaded and its simulation
    diverged; now its model file is refused at load, naming the table and the entry's rule."""
    hull = uwml.Link(50.0, (0.0, 0.0, 0.0), 0.05, lumped=uwml.LumpedModel(added_mass=_diag(1e12, 2.0)))
    robot = uwml.Robot([uwml.Joint((0.3, 0.0, 0.0), (0.0, 0.0, 1.0))], [uwml.Link(1.0, (0.1, 0.0, 0.0), 0.001)], base=hull)
    path = tmp_path / "floating.toml"
    robot.save(path)
    text = path.read_text()
    assert "[0.0, 2.0, 0.0," in text
    path.write_text(text.replace("[0.0, 2.0, 0.0,", "[0.0, -99.0, 0.0,"))
    with pytest.raises(uwml.ModelFileError, match=r"floating\.toml: base, lumped: lumped.added_mass must be positive semi-definite .*-99"):
        uwml.Robot.load(path)


def test_a_link_takes_only_a_lumped_model() -> None:
    with pytest.raises(TypeError, match="link.lumped must be a uwml.LumpedModel or None, got dict"):
        uwml.Link(1.0, (0, 0, 0), 0.0, lumped={"added_mass": np.eye(6)})


def test_too_many_lumped_models_are_refused() -> None:
    n = uwml.MAX_LUMPED_BODIES + 1
    links = [uwml.Link(1.0, (0.1, 0, 0), 0.0, lumped=uwml.LumpedModel()) for _ in range(n)]
    joints = [uwml.Joint((0.1, 0, 0), (0, 0, 1)) for _ in range(n)]
    with pytest.raises(ValueError, match=f"up to {n - 1} lumped models"):
        uwml.Robot(joints, links)


@EXAMPLES
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 6), form=st.sampled_from(["morison", "kirchhoff"]))
def test_regressors_times_every_coefficient_are_the_references_forces(seed: int, n: int, form: str) -> None:
    """docs/model.md section 12.1: linear in each entry of M_A, D_L and D_Q (in the model's own
    axes), and 12.2 in cd_axial: the columns times the robot's own coefficients are the numpy
    reference's drag and added mass on every joint and on the base, on a moving base in a
    current."""
    rng = np.random.default_rng(seed)
    robot = with_lumped(random_robot(rng, n, base_body=bool(rng.random() < 0.8), axial=True), rng)
    samples = 6
    q, qd, qdd, motion, current, current_acceleration = moving_water_states(rng, n, samples)
    regressors = robot.hydro_regressors(
        q, qd, qdd, base_motion=uwml.BaseMotion(**motion), current=current, current_acceleration=current_acceleration,
        added_mass=form,
    )  # fmt: skip
    m = len(robot.lumped_models)
    assert regressors.lumped.shape == (samples, n, m, 63) and regressors.base_lumped.shape == (samples, 6, m, 63)
    assert regressors.axial_drag.shape == (samples, n, len(robot.segments))
    cd = np.array([s.cd for s in robot.segments]).reshape(-1, 2)
    cm = np.array([s.cm for s in robot.segments]).reshape(-1, 2)
    forces = regressors.torques(
        cd, cm, [s.cd_axial for s in robot.segments], np.array([model.coefficients() for _, model in robot.lumped_models]).reshape(m, 63)
    )
    expected = ref.robot_hydro(
        robot.joints, robot.links, robot.base, q, qd, qdd, current=current, current_acceleration=current_acceleration,
        added_mass=form, **motion,
    )  # fmt: skip
    assert_matches_reference(forces, expected)
    # A lumped model's damping columns carry no added mass, its added-mass columns no drag:
    # the damping half alone is the reference's drag without the segments.
    damping_only = regressors.torques(
        0.0, 0.0, 0.0, np.array([np.r_[np.zeros(21), model.coefficients()[21:]] for _, model in robot.lumped_models]).reshape(m, 63)
    )
    assert np.all(damping_only.added_mass == 0.0) and np.all(damping_only.base.added_mass == 0.0)


def test_regressors_name_their_lumped_coefficients_and_check_their_shapes() -> None:
    from uwml.model.lumped import LUMPED_COEFFICIENTS

    assert len(LUMPED_COEFFICIENTS) == 63 and len(set(LUMPED_COEFFICIENTS)) == 63
    assert LUMPED_COEFFICIENTS[:2] == ("added_mass[0][0]", "added_mass[0][1]") and LUMPED_COEFFICIENTS[20] == "added_mass[5][5]"
    assert LUMPED_COEFFICIENTS[21] == "linear_damping[0][0]" and LUMPED_COEFFICIENTS[-1] == "quadratic_damping[5]"
    model = uwml.LumpedModel(added_mass=np.diag([1.0, 2, 3, 4, 5, 6]), quadratic_damping=[7.0, 0, 0, 0, 0, 8])
    values = dict(zip(LUMPED_COEFFICIENTS, model.coefficients(), strict=True))
    assert values["added_mass[2][2]"] == 3.0 and values["added_mass[0][1]"] == 0.0 and values["quadratic_damping[5]"] == 8.0
    rng = np.random.default_rng(2)
    robot = with_lumped(random_robot(rng, 2), rng)
    regressors = robot.hydro_regressors([0.1, 0.2], [0.0, 0.0], [0.0, 0.0])
    with pytest.raises(ValueError, match=r"lumped must have shape \(\d+, 63\)"):
        regressors.torques(2.0, 1.0, 0.0, np.zeros((len(robot.lumped_models) + 1, 63)))
    with pytest.raises(ValueError, match="cd_axial must be a scalar or"):
        regressors.torques(2.0, 1.0, [0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0][: len(robot.segments) + 1])
