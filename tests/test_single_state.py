"""One state per call (a controller or a simulator stepping one state at a time): the native
evaluation reads a plain state (lists or tuples of numbers, or 1-D float64 arrays) without
numpy's conversions; anything else the Python package checks first and hands over as arrays. One
evaluation either way.

Held here: one state gives the same bits as its row of a batch (at every position in a batch of
SIMD groups, for every container, with coefficient arrays, with a moving base, with joint
losses); the kinds the native reading declines give the numbers of the same values as float64
arrays; every bad one-state input raises naming the argument; the result objects are ordinary
dataclasses.
"""

import math

import numpy as np
import pytest
import uwml
from chains import random_chain, random_states
from robots import COMPONENTS, motion_arguments, random_robot
from uwml.examples import arm_on_rov

PAPER = uwml.paper_leg()
STATE = {"q": [0.1, -0.4, 0.7], "qd": [0.5, -1.0, 2.0], "qdd": [1.0, 3.0, -2.0]}
ENVIRONMENT_FIELDS = (*COMPONENTS, "visc", "seal", "current")


def bits(array: np.ndarray) -> bytes:
    """The exact bits (so -0.0 and 0.0 differ)."""
    return np.ascontiguousarray(array, dtype=np.float64).tobytes()


def assert_same_bits(one: object, expected: object, fields: tuple[str, ...], row: int | None, what: str) -> None:
    for name in fields:
        got, want = getattr(one, name), getattr(expected, name)
        want = want if row is None else want[row]
        assert got.shape == want.shape and got.dtype == np.float64, f"{what}: {name} {got.shape} {got.dtype}"
        assert bits(got) == bits(want), f"{what}: {name} {got} != {want}"


def containers(values: np.ndarray) -> dict[str, object]:
    """One state's values in every container the native reading takes."""
    wide = np.zeros(2 * values.size)
    wide[::2] = values
    read_only = values.copy()
    read_only.flags.writeable = False
    return {
        "list": values.tolist(),
        "tuple": tuple(values.tolist()),
        "array": values.copy(),
        "strided array": wide[::2],
        "read-only array": read_only,
    }


def read_natively(robot: uwml.Robot, state: list, conditions: uwml.Conditions | None = None) -> bool:
    """Whether the native evaluation reads ``state`` itself (else the package checks it first)."""
    native = robot._native(conditions or uwml.Conditions())
    return robot._core.hydro(*state, native) is not None


# --------------------------------------------------------------------------------------------
# The same bits as the batch row
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("seed", range(6))
def test_one_state_hydro_is_the_batch_row_bit_for_bit(seed: int) -> None:
    rng = np.random.default_rng(seed)
    leg = PAPER if seed < 2 else random_chain(rng, [1, 3, 5, 8][seed - 2])[0]
    n, m = leg.n_joints, 9  # 9 states: every lane of two full groups of four and a last one
    q, qd, qdd = random_states(rng, m, n)
    cd, cm = (2.2, 0.5) if seed % 2 == 0 else (float(rng.uniform(0.5, 3.0)), float(rng.uniform(0.1, 1.5)))
    water = uwml.Water() if seed % 3 == 0 else uwml.Water(density=float(rng.uniform(900.0, 1100.0)), gravity=9.7)
    conditions = uwml.Conditions(cd=cd, cm=cm, water=water)
    batch = leg.hydro(q, qd, qdd, conditions)
    for s in range(m):
        forms = [containers(x[s]) for x in (q, qd, qdd)]
        for kind in forms[0]:
            args = [form[kind] for form in forms]
            assert read_natively(leg, args, conditions), kind
            one = leg.hydro(*args, conditions)
            assert type(one) is uwml.Torques
            assert_same_bits(one, batch, COMPONENTS, s, f"state {s} as {kind}")
            # The shortcuts make the same conditions.
            assert_same_bits(leg.hydro(*args, cd=cd, cm=cm, water=water), one, COMPONENTS, None, f"state {s} by keywords")


@pytest.mark.parametrize("seed", range(6))
def test_one_state_environment_is_the_batch_row_bit_for_bit(seed: int) -> None:
    rng = np.random.default_rng(100 + seed)
    leg = PAPER if seed < 3 else random_chain(rng, [2, 4, 6][seed - 3])[0]
    n, m = leg.n_joints, 9
    q, qd, qdd = random_states(rng, m, n)
    depth = rng.uniform(0.0, 6000.0, m)
    depth[0] = 0.0
    temperature = rng.uniform(0.0, 30.0, m)
    losses = [None, uwml.JointLosses(), uwml.JointLosses(oil=uwml.OilDrag(exponent=1.2), seal=None, epsilon=0.0)][seed % 3]
    sea_density = 1025.0 if seed % 2 == 0 else float(rng.uniform(1000.0, 1050.0))
    water = uwml.Water() if seed % 3 == 0 else uwml.Water(density=1020.0, gravity=9.8)
    options = {"losses": losses, "water": water, "sea_density": sea_density}
    batch = leg.environment(q, qd, qdd, depth=depth, temperature_c=temperature, **options)
    for s in range(m):
        forms = [containers(x[s]) for x in (q, qd, qdd)]
        for kind in forms[0]:
            args = [form[kind] for form in forms]
            one = leg.environment(*args, depth=float(depth[s]), temperature_c=float(temperature[s]), **options)
            assert type(one) is uwml.Torques
            assert_same_bits(one, batch, ENVIRONMENT_FIELDS, s, f"state {s} as {kind}")


def test_one_state_of_a_robot_on_a_moving_base_is_the_batch_row_bit_for_bit() -> None:
    rng = np.random.default_rng(40)
    robot = random_robot(rng, 4)
    states = rng.uniform(-1, 1, (3, 5, 4))
    motions = motion_arguments(rng, 5)
    current = rng.normal(size=(5, 3))
    batch = robot.hydro(*states, base_motion=uwml.BaseMotion(**motions), current=current)
    for i in range(5):
        motion = uwml.BaseMotion(**{k: v[i] for k, v in motions.items()})
        for convert in (list, tuple, np.asarray):
            q, qd, qdd = (convert(s[i]) for s in states)
            one = robot.hydro(q, qd, qdd, base_motion=motion, current=convert(current[i]))
            assert type(one) is uwml.Torques and type(one.base) is uwml.BaseWrench
            for name in COMPONENTS:
                np.testing.assert_array_equal(getattr(one, name), getattr(batch, name)[i])
                np.testing.assert_array_equal(getattr(one.base, name), getattr(batch.base, name)[i])
    fixed = robot.hydro(list(states[0, 0]), list(states[1, 0]), list(states[2, 0]), cd=1.1, cm=0.7)
    general = robot.hydro(states[0, :1], states[1, :1], states[2, :1], cd=1.1, cm=0.7)
    np.testing.assert_array_equal(fixed.total, general.total[0])
    np.testing.assert_array_equal(fixed.base.total, general.base.total[0])


def test_one_state_environment_of_a_robot_is_the_batch_row_bit_for_bit() -> None:
    rng = np.random.default_rng(41)
    robot = random_robot(rng, 3)
    states = rng.uniform(-1, 1, (3, 4, 3))
    motions = motion_arguments(rng, 4)
    losses = uwml.JointLosses(epsilon=0.02)
    kwargs = {"depth": 3000.0, "temperature_c": 4.0, "sea_density": 1030.0, "current": (0.2, 0.0, 0.1)}
    for per_joint in (None, losses, [None, losses, losses]):
        batch = robot.environment(*states, losses=per_joint, base_motion=uwml.BaseMotion(**motions), **kwargs)
        for i in range(4):
            motion = uwml.BaseMotion(**{k: v[i] for k, v in motions.items()})
            one = robot.environment(*(list(s[i]) for s in states), losses=per_joint, base_motion=motion, **kwargs)
            for name in ENVIRONMENT_FIELDS:
                np.testing.assert_array_equal(getattr(one, name), getattr(batch, name)[i])
            np.testing.assert_array_equal(one.base.total, batch.base.total[i])


ARM = arm_on_rov()
ARM_MOTION = uwml.BaseMotion(velocity=(0.5, 0.1, -0.2), angular_velocity=(0.02, 0.05, -0.1))


def test_a_robots_coefficient_arrays_give_the_batch_rows_bits() -> None:
    """Per segment, per segment and direction (a circular segment's two alike), one given and the
    other the segments' own, as lists, tuples or arrays."""
    rng = np.random.default_rng(7)
    n, s = ARM.n_joints, len(ARM.segments)
    circular = np.array([segment.section == "circular" for segment in ARM.segments])
    per_direction = rng.uniform(0.2, 2.5, (s, 2))
    per_direction[circular, 1] = per_direction[circular, 0]
    q, qd, qdd = random_states(rng, 5, n)
    for cd, cm in [
        (rng.uniform(0.5, 3.0, s).tolist(), rng.uniform(0.1, 1.5, s)),
        (per_direction, per_direction.tolist()),
        (None, rng.uniform(0.1, 1.5, s)),
        (tuple(rng.uniform(0.5, 3.0, s)), None),
    ]:
        conditions = uwml.Conditions(cd=cd, cm=cm, base_motion=ARM_MOTION, current=(0.3, -0.1, 0.0))
        batch = ARM.hydro(q, qd, qdd, conditions)
        for k in range(5):
            args = (q[k].tolist(), qd[k].tolist(), qdd[k].tolist())
            assert read_natively(ARM, list(args), conditions)
            one = ARM.hydro(*args, conditions)
            assert_same_bits(one, batch, COMPONENTS, k, f"state {k}")
            assert bits(one.base.total) == bits(batch.base.total[k])


def test_the_results_are_ordinary_results() -> None:
    """Built without ``__init__``, the result objects are still the dataclasses: fields, repr,
    the derived sums, fresh writable arrays (the losses of ``hydro``: zeros, read-only)."""
    one = PAPER.hydro(**STATE)
    assert vars(one).keys() == {*ENVIRONMENT_FIELDS, "base"} and one.base is None
    assert np.array_equal(one.total, one.drag + one.added_mass + one.buoyancy)
    assert repr(one).startswith("Torques(drag=array(")
    for name in COMPONENTS:
        array = getattr(one, name)
        assert array.flags.c_contiguous and array.flags.writeable
        assert not any(np.shares_memory(array, getattr(one, other)) for other in COMPONENTS if other != name)
    for name in ("visc", "seal", "current"):
        assert not getattr(one, name).flags.writeable and np.all(getattr(one, name) == 0.0)
    with pytest.raises(AttributeError):
        one.drag = np.zeros(3)  # type: ignore[misc]
    env = PAPER.environment(**STATE, depth=100.0, losses=uwml.JointLosses())
    assert np.array_equal(env.total, env.hydro + env.visc + env.seal)
    assert PAPER.hydro(**STATE, base=True).base.total.shape == (6,)


def test_a_conditions_given_alone_is_evaluated_as_any_other() -> None:
    """A ``Conditions`` given alone (a controller's loop) goes to the native call in one step:
    the same bits as the keywords' path, its base wrench where the robot has a base body (or
    ``base=True``) and none with ``base=False``, each robot its own reading of it, and the
    arguments the package checks still checked."""
    arm = arm_on_rov()
    motion = uwml.BaseMotion(velocity=(0.5, 0.0, 0.1), angular_velocity=(0.0, 0.02, 0.0))
    conditions = uwml.Conditions(base_motion=motion, current=(0.2, 0.0, 0.0), cd=1.1)
    q = [0.2, 0.4, -0.8, 0.0, 0.3, 0.0, 0.05]
    alone = arm.hydro(q, q, q, conditions)
    by_keywords = arm.hydro(q, q, q, base_motion=motion, current=(0.2, 0.0, 0.0), cd=1.1)
    assert_same_bits(alone, by_keywords, COMPONENTS, None, "alone")
    assert_same_bits(alone.base, by_keywords.base, COMPONENTS, None, "alone, base")
    assert arm.hydro(q, q, q, conditions, base=False).base is None
    still = uwml.Conditions(cd=2.0)
    assert PAPER.hydro(**STATE, conditions=still).base is None
    with_base = PAPER.hydro(**STATE, conditions=still, base=True).base
    batch = PAPER.hydro(*(np.array([STATE[k]] * 2) for k in ("q", "qd", "qdd")), still, base=True)
    assert with_base is not None and bits(with_base.total) == bits(batch.base.total[1])
    # One Conditions with two robots, in turn: each evaluated with its own water and losses.
    other = random_chain(np.random.default_rng(3), 3)[0]
    for _ in range(2):
        assert_same_bits(PAPER.environment(**STATE, conditions=still), PAPER.environment(**STATE, cd=2.0), ENVIRONMENT_FIELDS, None, "leg")
        assert_same_bits(
            other.environment(**STATE, conditions=still), other.environment(**STATE, cd=2.0), ENVIRONMENT_FIELDS, None, "chain"
        )
    for threads in (1.0, True, 0):
        with pytest.raises(ValueError, match="threads must be an integer >= 1"):
            PAPER.hydro(**STATE, conditions=still, threads=threads)


# --------------------------------------------------------------------------------------------
# Kinds the native reading declines: the numbers of the same values as float64 arrays
# --------------------------------------------------------------------------------------------

Q = np.array(STATE["q"])
MISALIGNED = np.frombuffer(b"\0" + Q.tobytes(), dtype=np.float64, count=3, offset=1)

KINDS = [
    pytest.param({"q": Q.astype(np.float32)}, False, id="float32 array"),
    pytest.param({"q": np.array([0, 1, -2])}, False, id="int array"),
    pytest.param({"q": Q.astype(">f8")}, False, id="big-endian array"),
    pytest.param({"q": MISALIGNED}, False, id="misaligned array"),
    pytest.param({"q": [True, False, True]}, False, id="bools"),
    pytest.param({"q": [np.float32(0.1), 0.2, 0.3]}, False, id="float32 scalars"),
    pytest.param({"q": [0, 1, -2]}, True, id="ints"),
    pytest.param({"q": [np.float64(0.1), 2, 0.3]}, True, id="float64 scalars and an int"),
    pytest.param({"q": [0.1, 40.0, 0.3]}, False, id="an angle beyond the joint's plausible bound"),
]


@pytest.mark.filterwarnings("ignore::uwml.PlausibilityWarning")  # a state beyond plausible on purpose
@pytest.mark.parametrize("override, read", KINDS)
def test_other_kinds_give_the_numbers_of_their_values(override: dict, read: bool) -> None:
    arguments = {**STATE, **override}
    state = [arguments[k] for k in ("q", "qd", "qdd")]
    assert read_natively(PAPER, state) == read
    one = PAPER.hydro(*state)
    as_arrays = PAPER.hydro(*(np.array(np.asarray(s, dtype=np.float64)) for s in state))
    assert_same_bits(one, as_arrays, COMPONENTS, None, str(override))


# --------------------------------------------------------------------------------------------
# Bad one-state inputs: errors naming the argument
# --------------------------------------------------------------------------------------------


def argument(name: str | None) -> str | None:
    """A regex matching ``name`` (itself a regex) as a whole word; None for no match required."""
    return None if name is None else rf"(?<![\w.]){name}(?![\w])"


BAD_HYDRO = [
    pytest.param({"q": [0.0, 0.0]}, ValueError, "q", id="q 2 entries"),
    pytest.param({"q": np.zeros(4)}, ValueError, "q", id="q 4 entries"),
    pytest.param({"q": 0.5}, ValueError, "q", id="q scalar"),
    pytest.param({"q": []}, ValueError, "q", id="q empty"),
    pytest.param({"q": (0.0,) * 4}, ValueError, "q", id="q tuple of 4"),
    pytest.param({"qd": np.zeros((2, 3))}, ValueError, "qd", id="qd 2-D with 1-D q"),
    pytest.param({"qdd": np.zeros((1, 3))}, ValueError, "qdd", id="qdd (1, 3) with 1-D q"),
    pytest.param({"q": "abc"}, TypeError, "q", id="q string"),
    pytest.param({"qd": ["a", "b", "c"]}, TypeError, "qd", id="qd strings"),
    pytest.param({"qdd": [object()] * 3}, TypeError, "qdd", id="qdd objects"),
    pytest.param({"qd": {"a": 1.0}}, TypeError, "qd", id="qd dict"),
    pytest.param({"q": [[0.0, 0.0, 0.0], [0.0, 0.0]]}, (TypeError, ValueError), "q", id="q ragged"),
    pytest.param({"qd": [1j, 0.0, 0.0]}, TypeError, "qd", id="qd complex list"),
    pytest.param({"q": np.zeros(3, dtype=complex)}, TypeError, "q", id="q complex array"),
    pytest.param({"q": None}, (TypeError, ValueError), "q", id="q None"),
    pytest.param({"q": [0.1, math.nan, 0.3]}, ValueError, r"q\[(0, )?1\]", id="q NaN in a list"),
    pytest.param({"qd": np.array([0.0, 0.0, math.inf])}, ValueError, r"qd\[(0, )?2\]", id="qd inf in an array"),
    pytest.param({"qdd": (-math.inf, 0.0, 0.0)}, ValueError, r"qdd\[(0, )?0\]", id="qdd -inf in a tuple"),
    # numpy's own OverflowError, which does not name the argument.
    pytest.param({"q": [10**400, 0.0, 0.0]}, OverflowError, None, id="q int too large"),
    pytest.param({"cd": -1.0}, ValueError, "cd", id="cd negative"),
    pytest.param({"cd": math.nan}, ValueError, "cd", id="cd NaN"),
    pytest.param({"cm": math.inf}, ValueError, "cm", id="cm inf"),
    pytest.param({"cm": -1}, ValueError, "cm", id="cm negative int"),
    pytest.param({"cd": np.ones(3)}, ValueError, "cd", id="cd 3 for 2 segments"),
    pytest.param({"cd": [1.0, -2.0]}, ValueError, "cd", id="cd per segment, one negative"),
    pytest.param({"cm": [[0.5, 0.6], [0.7, math.nan]]}, ValueError, "cm", id="cm pairs, a NaN"),
    pytest.param({"cd": [[1.0, 2.0], [1.0]]}, (TypeError, ValueError), "cd", id="cd pairs ragged"),
    pytest.param({"cd": np.ones((2, 3))}, ValueError, "cd", id="cd three per segment"),
    pytest.param({"cm": [0.5, "x"]}, (TypeError, ValueError), "cm", id="cm per segment, a string"),
    pytest.param({"cd": "big"}, TypeError, "cd", id="cd string"),
    pytest.param({"cm": 1.0 + 1.0j}, TypeError, "cm", id="cm complex"),
    pytest.param({"water": 1000.0}, TypeError, "water", id="water float"),
    pytest.param({"water": (1000.0, 9.81)}, TypeError, "water", id="water tuple"),
    pytest.param({"threads": 0}, ValueError, "threads", id="threads 0"),
    pytest.param({"threads": True}, ValueError, "threads", id="threads bool"),
    pytest.param({"threads": 1.0}, ValueError, "threads", id="threads float"),
    pytest.param({"threads": "1"}, ValueError, "threads", id="threads string"),
    pytest.param({"current": [0.0, math.inf, 0.0]}, ValueError, "current", id="current inf"),
    pytest.param({"speed": 1.0}, TypeError, "speed", id="not a condition"),
]


@pytest.mark.parametrize("override, error, name", BAD_HYDRO)
def test_bad_one_state_hydro_raises_naming_the_argument(override: dict, error: type, name: str | None) -> None:
    with pytest.raises(error, match=argument(name)):
        PAPER.hydro(**{**STATE, **override})


BAD_ENVIRONMENT = [
    *BAD_HYDRO,
    pytest.param({"depth": -5.0}, ValueError, "depth", id="depth negative"),
    pytest.param({"depth": -1}, ValueError, "depth", id="depth negative int"),
    pytest.param({"depth": math.nan}, ValueError, "depth", id="depth NaN"),
    pytest.param({"depth": math.inf}, ValueError, "depth", id="depth inf"),
    pytest.param({"depth": "deep"}, TypeError, "depth", id="depth string"),
    pytest.param({"depth": [[1.0, 2.0]]}, ValueError, "depth", id="depth 2-D"),
    pytest.param({"temperature_c": math.nan}, ValueError, "temperature_c", id="temperature NaN"),
    pytest.param({"temperature_c": [[1.0]]}, ValueError, "temperature_c", id="temperature 2-D"),
    pytest.param({"temperature_c": None}, (TypeError, ValueError), "temperature_c", id="temperature None"),
    pytest.param({"sea_density": 0.0}, ValueError, "sea_density", id="sea_density 0"),
    pytest.param({"sea_density": -1025}, ValueError, "sea_density", id="sea_density negative int"),
    pytest.param({"sea_density": math.nan}, ValueError, "sea_density", id="sea_density NaN"),
    pytest.param({"losses": [uwml.JointLosses()]}, ValueError, "losses", id="losses one entry"),
    pytest.param({"losses": 3}, TypeError, "losses", id="losses int"),
    pytest.param({"losses": [None, "seal", None]}, TypeError, r"losses\[1\]", id="losses string entry"),
    pytest.param({"losses": np.zeros((3, 21))}, TypeError, r"losses\[0\]", id="losses packed array"),
]


@pytest.mark.parametrize("override, error, name", BAD_ENVIRONMENT)
def test_bad_one_state_environment_raises_naming_the_argument(override: dict, error: type, name: str | None) -> None:
    with pytest.raises(error, match=argument(name)):
        PAPER.environment(**{**STATE, "depth": 100.0, "temperature_c": 4.0, **override})


@pytest.mark.parametrize(
    "cd",
    [
        pytest.param("unequal circular", id="a circular segment's two directions differ"),
        pytest.param("per link", id="one per link on a robot"),
        pytest.param("negative", id="a negative entry"),
    ],
)
def test_a_robots_bad_coefficient_arrays_name_cd(cd: str) -> None:
    s = len(ARM.segments)
    table = np.full((s, 2), 1.0)
    if cd == "unequal circular":
        first = next(i for i, segment in enumerate(ARM.segments) if segment.section == "circular")
        table[first] = (1.0, 2.0)
        value: object = table
    elif cd == "per link":
        value = [1.0] * ARM.n_joints
    else:
        value = [1.0] * (s - 1) + [-1.0]
    q = [0.1] * ARM.n_joints
    with pytest.raises(ValueError, match=argument("cd")):
        ARM.hydro(q, q, q, cd=value)
