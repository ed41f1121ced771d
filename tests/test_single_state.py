"""One state per call: ``Leg.hydro`` and ``Leg.environment`` with 1-D states take a native fast
path (a Leg is a Robot: the robot's ``hydro_one`` / ``environment_one``) for plain arguments, and
the general path for everything else.

Held here: the fast path gives the same bits as the batch path's row for the same state (at every
position in a batch of SIMD groups, for every container it takes); it is taken for the plain
kinds and declines the rest, which the general path then answers with the same numbers; and every
bad one-state input raises exactly what the general path raises (type and message), naming the
argument.
"""

import math

import numpy as np
import pytest
import uwml
from test_hydro import random_chain, random_states
from uwml.robot import BaseWrench, RobotEnvironment, RobotTorques
from uwml.robot._arguments import one_state_losses
from uwml.robot.examples import arm_on_rov

PAPER = uwml.Leg.paper()
STATE = {"q": [0.1, -0.4, 0.7], "qd": [0.5, -1.0, 2.0], "qdd": [1.0, 3.0, -2.0]}
HYDRO_FIELDS = ("drag", "added_mass", "buoyancy", "gravity")
ENVIRONMENT_FIELDS = (*HYDRO_FIELDS, "visc", "seal", "current")


class _GeneralOnly:
    """A native robot whose one-state calls always decline: the general path alone."""

    def __init__(self, core: object) -> None:
        self._native = core

    def hydro_one(self, *args: object, **options: object) -> None:
        return None

    def environment_one(self, *args: object, **options: object) -> None:
        return None

    def __getattr__(self, name: str) -> object:
        return getattr(self._native, name)


def general_only(leg: uwml.Robot) -> uwml.Robot:
    """``leg`` (or any robot) without the fast path (what ``Leg.hydro`` did before it)."""
    other = type(leg).__new__(type(leg))
    other.__dict__.update(leg.__dict__)
    other._core = _GeneralOnly(leg._core)
    return other


STILL = (0.0, 0.0, 0.0)


def native_hydro(leg: uwml.Leg, state: list, cd: object, cm: object, density: float, gravity: float, threads: object) -> object:
    """The native one-state hydro of a leg on its fixed base in still water, coefficient arrays per
    link (None: declined)."""
    return leg._core.hydro_one(
        RobotTorques, BaseWrench, *state, cd, cm, density, gravity, None, STILL, STILL, threads, False, per_link=True
    )


def native_environment(leg: uwml.Leg, state: list, depth: object, temperature: object, packed: object, cd: object, cm: object,
                       density: float, gravity: float, sea_density: object) -> object:  # fmt: skip
    """The native one-state environment, as :func:`native_hydro`."""
    return leg._core.environment_one(
        RobotEnvironment,
        BaseWrench,
        *state,
        depth,
        temperature,
        packed,
        cd,
        cm,
        density,
        gravity,
        sea_density,
        None,
        STILL,
        STILL,
        1,
        False,
        per_link=True,
    )


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
    """One state's values in every container the fast path takes."""
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


# --------------------------------------------------------------------------------------------
# The same bits as the batch path
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("seed", range(6))
def test_one_state_hydro_is_the_batch_row_bit_for_bit(seed: int) -> None:
    rng = np.random.default_rng(seed)
    leg = PAPER if seed < 2 else random_chain(rng, [1, 3, 5, uwml.MAX_JOINTS][seed - 2])[0]
    n, m = leg.n_joints, 9  # 9 states: every lane of two full groups of four and a last one
    q, qd, qdd = random_states(rng, m, n)
    cd, cm = (2.2, 0.5) if seed % 2 == 0 else (float(rng.uniform(0.5, 3.0)), float(rng.uniform(0.1, 1.5)))
    water = uwml.Water() if seed % 3 == 0 else uwml.Water(density=float(rng.uniform(900.0, 1100.0)), gravity=9.7)
    batch = leg.hydro(q, qd, qdd, cd=cd, cm=cm, water=water)
    for s in range(m):
        forms = [containers(x[s]) for x in (q, qd, qdd)]
        for kind in forms[0]:
            args = [form[kind] for form in forms]
            assert native_hydro(leg, args, cd, cm, water.density, water.gravity, 1) is not None, kind
            one = leg.hydro(*args, cd=cd, cm=cm, water=water)
            assert type(one) is RobotTorques
            assert_same_bits(one, batch, HYDRO_FIELDS, s, f"state {s} as {kind}")
        # A batch of that one state, 1-D (the general path), too.
        assert_same_bits(
            leg.hydro(q[s], qd[s], qdd[s], cd=cd, cm=cm, water=water),
            general_only(leg).hydro(q[s], qd[s], qdd[s], cd=cd, cm=cm, water=water),
            HYDRO_FIELDS,
            None,
            f"state {s}",
        )


@pytest.mark.parametrize("seed", range(6))
def test_one_state_environment_is_the_batch_row_bit_for_bit(seed: int) -> None:
    rng = np.random.default_rng(100 + seed)
    leg = PAPER if seed < 3 else random_chain(rng, [2, 4, 6][seed - 3])[0]
    n, m = leg.n_joints, 9
    q, qd, qdd = random_states(rng, m, n)
    depth = rng.uniform(0.0, 6000.0, m)
    depth[0] = 0.0
    temperature = rng.uniform(-2.0, 40.0, m)
    losses = [None, uwml.JointLosses(), uwml.JointLosses(oil=uwml.OilDrag(exponent=1.2), seal=None, epsilon=0.0)][seed % 3]
    sea_density = 1025.0 if seed % 2 == 0 else float(rng.uniform(1000.0, 1050.0))
    cd, cm = (2.2, 0.5) if seed % 2 == 0 else (float(rng.uniform(0.5, 3.0)), float(rng.uniform(0.1, 1.5)))
    water = uwml.Water() if seed % 3 == 0 else uwml.Water(density=1020.0, gravity=9.8)
    options = {"losses": losses, "cd": cd, "cm": cm, "water": water, "sea_density": sea_density}
    batch = leg.environment(q, qd, qdd, depth=depth, temperature_c=temperature, **options)
    for s in range(m):
        forms = [containers(x[s]) for x in (q, qd, qdd)]
        for kind in forms[0]:
            args = [form[kind] for form in forms]
            one = leg.environment(*args, depth=float(depth[s]), temperature_c=float(temperature[s]), **options)
            assert type(one) is RobotEnvironment
            assert_same_bits(one, batch, ENVIRONMENT_FIELDS, s, f"state {s} as {kind}")
        packed = None if losses is None else one_state_losses(leg, losses, n)
        fast = native_environment(
            leg, [q[s], qd[s], qdd[s]], float(depth[s]), float(temperature[s]), packed, cd, cm, water.density, water.gravity, sea_density
        )
        assert fast is not None


def test_the_fast_results_are_ordinary_results() -> None:
    """Built without ``__init__``, the result objects are still the dataclasses: fields, repr,
    equality, the derived sums, fresh writable arrays."""
    one = PAPER.hydro(**STATE)
    assert vars(one).keys() == {*HYDRO_FIELDS, "base"}
    assert np.array_equal(one.total, one.drag + one.added_mass + one.buoyancy)
    assert repr(one).startswith("RobotTorques(drag=array(")
    for name in HYDRO_FIELDS:
        array = getattr(one, name)
        assert array.flags.c_contiguous and array.flags.writeable
        # Fresh: no field shares memory with another (they may be views of one fresh buffer).
        assert not any(np.shares_memory(array, getattr(one, other)) for other in HYDRO_FIELDS if other != name)
    with pytest.raises(AttributeError):
        one.drag = np.zeros(3)  # type: ignore[misc]
    env = PAPER.environment(**STATE, depth=100.0, losses=uwml.JointLosses())
    assert vars(env).keys() == {*ENVIRONMENT_FIELDS, "base"}
    assert np.array_equal(env.total, env.hydro + env.visc + env.seal)
    general = general_only(PAPER).environment(**STATE, depth=100.0, losses=uwml.JointLosses())
    assert_same_bits(env, general, ENVIRONMENT_FIELDS, None, "environment")


# --------------------------------------------------------------------------------------------
# Declined kinds: the general path answers, with the same numbers
# --------------------------------------------------------------------------------------------

Q = np.array(STATE["q"])
MISALIGNED = np.frombuffer(b"\0" + Q.tobytes(), dtype=np.float64, count=3, offset=1)

DECLINED = [
    pytest.param({"q": Q.astype(np.float32)}, False, id="float32 array"),
    pytest.param({"q": np.array([0, 1, -2])}, False, id="int array"),
    pytest.param({"q": Q.astype(">f8")}, False, id="big-endian array"),
    pytest.param({"q": MISALIGNED}, False, id="misaligned array"),
    pytest.param({"q": [True, False, True]}, False, id="bools"),
    pytest.param({"q": [np.float32(0.1), 0.2, 0.3]}, False, id="float32 scalars"),
    pytest.param({"q": [0, 1, -2]}, True, id="ints"),
    pytest.param({"q": [np.float64(0.1), 2, 0.3]}, True, id="float64 scalars and an int"),
    pytest.param({"cd": [1.0, 2.0, 3.0]}, True, id="cd per link"),
    pytest.param({"cd": (1.0, 2.0, 3.0)}, True, id="cd per link, tuple"),
    pytest.param({"cd": np.array([1.0, 2.0, 3.0])}, True, id="cd per link, array"),
    pytest.param({"cm": np.full((3, 2), 0.7)}, True, id="cm per direction"),
    pytest.param({"cm": [[0.5, 0.6], (0.7, 0.8), np.array([0.9, 1.0])]}, True, id="cm pairs"),
    pytest.param({"cd": np.full((3, 2), 0.7)[:, ::-1]}, True, id="cd per direction, strided"),
    pytest.param({"cd": np.ones((3, 2), dtype=np.float32)}, False, id="cd per direction float32"),
    pytest.param({"cd": [1.0, np.float32(2.0), 3.0]}, False, id="cd per link, a float32"),
    pytest.param({"cd": np.float32(1.5)}, False, id="cd float32"),
    pytest.param({"cd": 2}, True, id="cd int"),
    pytest.param({"threads": np.int64(2)}, False, id="threads numpy int"),
    pytest.param({"threads": 2}, True, id="threads 2"),
]


def outcome(call, fields: tuple[str, ...]) -> tuple:
    """What ``call()`` gives: its fields' bits, or its error's type and message."""
    try:
        result = call()
    except Exception as error:  # noqa: BLE001 - compared, not handled
        return (type(error), str(error))
    return tuple(bits(getattr(result, name)) for name in fields)


@pytest.mark.parametrize("override, taken", DECLINED)
def test_other_kinds_give_the_general_paths_numbers(override: dict, taken: bool) -> None:
    """The same numbers (or, for a misaligned array, the same error: the batch path does not
    take those either)."""
    arguments = {**STATE, **override}
    fast = outcome(lambda: PAPER.hydro(**arguments), HYDRO_FIELDS)
    assert fast == outcome(lambda: general_only(PAPER).hydro(**arguments), HYDRO_FIELDS)
    assert not isinstance(fast[0], type) or override.get("q") is MISALIGNED
    state = [arguments[k] for k in ("q", "qd", "qdd")]
    native = native_hydro(PAPER, state, arguments.get("cd", 2.2), arguments.get("cm", 0.5), 1000.0, 9.81, arguments.get("threads", 1))
    assert (native is not None) == taken


@pytest.mark.parametrize(
    "override, taken",
    [
        ({"depth": 0}, True),
        ({"depth": np.float64(10.0)}, True),
        ({"depth": np.array(10.0)}, False),
        ({"depth": [10.0]}, False),
        ({"temperature_c": np.float32(4.0)}, False),
        ({"sea_density": 1025}, True),
        ({"losses": [uwml.JointLosses(), None, uwml.JointLosses()]}, False),
        ({"losses": (uwml.JointLosses(),) * 3}, False),
    ],
    ids=str,
)
def test_other_environment_kinds_give_the_general_paths_numbers(override: dict, taken: bool) -> None:
    arguments = {**STATE, "depth": 50.0, "temperature_c": 10.0, **override}
    one = PAPER.environment(**arguments)
    assert_same_bits(one, general_only(PAPER).environment(**arguments), ENVIRONMENT_FIELDS, None, str(override))
    losses = arguments.get("losses")
    packed = None if losses is None else one_state_losses(PAPER, losses, 3)
    state = [arguments[k] for k in ("q", "qd", "qdd")]
    native = native_environment(
        PAPER, state, arguments["depth"], arguments["temperature_c"], packed, 2.2, 0.5, 1000.0, 9.81, arguments.get("sea_density", 1000.0)
    )
    assert (native is not None) == taken


def test_losses_are_packed_once_per_object() -> None:
    leg = uwml.Leg.paper()
    losses = uwml.JointLosses()
    first = one_state_losses(leg, losses, 3)
    assert one_state_losses(leg, losses, 3) is first
    other = uwml.JointLosses(seal=None)
    assert one_state_losses(leg, other, 3) is not first
    assert one_state_losses(leg, [losses] * 3, 3) is False
    # Another object of other values gives other torques; the first again gives the first.
    a = leg.environment(**STATE, depth=10.0, losses=losses)
    b = leg.environment(**STATE, depth=10.0, losses=other)
    c = leg.environment(**STATE, depth=10.0, losses=losses)
    assert not np.array_equal(a.seal, b.seal) and np.array_equal(a.seal, c.seal)


# --------------------------------------------------------------------------------------------
# Bad one-state inputs: the general path's errors, naming the argument
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
    # numpy's own OverflowError, which does not name the argument (nor did it before).
    pytest.param({"q": [10**400, 0.0, 0.0]}, OverflowError, None, id="q int too large"),
    pytest.param({"cd": -1.0}, ValueError, "cd", id="cd negative"),
    pytest.param({"cd": math.nan}, ValueError, "cd", id="cd NaN"),
    pytest.param({"cm": math.inf}, ValueError, "cm", id="cm inf"),
    pytest.param({"cm": -1}, ValueError, "cm", id="cm negative int"),
    pytest.param({"cd": np.ones(2)}, ValueError, "cd", id="cd 2 per link"),
    pytest.param({"cd": [1.0, -2.0, 3.0]}, ValueError, "cd", id="cd per link, one negative"),
    pytest.param({"cm": [[0.5, 0.6], [0.7, math.nan], [0.9, 1.0]]}, ValueError, "cm", id="cm pairs, a NaN"),
    pytest.param({"cd": [[1.0, 2.0], [1.0], [1.0, 1.0]]}, (TypeError, ValueError), "cd", id="cd pairs ragged"),
    pytest.param({"cd": np.ones((3, 3))}, ValueError, "cd", id="cd three per link"),
    pytest.param({"cm": [0.5, 0.5, "x"]}, (TypeError, ValueError), "cm", id="cm per link, a string"),
    pytest.param({"cd": "big"}, TypeError, "cd", id="cd string"),
    pytest.param({"cm": 1.0 + 1.0j}, TypeError, "cm", id="cm complex"),
    pytest.param({"water": 1000.0}, TypeError, "water", id="water float"),
    pytest.param({"water": (1000.0, 9.81)}, TypeError, "water", id="water tuple"),
    pytest.param({"threads": 0}, ValueError, "threads", id="threads 0"),
    pytest.param({"threads": True}, ValueError, "threads", id="threads bool"),
    pytest.param({"threads": 1.0}, ValueError, "threads", id="threads float"),
    pytest.param({"threads": "1"}, ValueError, "threads", id="threads string"),
]


def _raised(call) -> BaseException:
    with pytest.raises(Exception) as info:
        call()
    return info.value


@pytest.mark.parametrize("override, error, name", BAD_HYDRO)
def test_bad_one_state_hydro_raises_as_the_general_path(override: dict, error: type, name: str | None) -> None:
    arguments = {**STATE, **override}
    with pytest.raises(error, match=argument(name)) as fast:
        PAPER.hydro(**arguments)
    general = _raised(lambda: general_only(PAPER).hydro(**arguments))
    assert type(fast.value) is type(general) and str(fast.value) == str(general)


BAD_ENVIRONMENT = [
    *BAD_HYDRO,
    pytest.param({"depth": -5.0}, ValueError, "depth", id="depth negative"),
    pytest.param({"depth": -1}, ValueError, "depth", id="depth negative int"),
    pytest.param({"depth": math.nan}, ValueError, "depth", id="depth NaN"),
    pytest.param({"depth": math.inf}, ValueError, "depth", id="depth inf"),
    pytest.param({"depth": "deep"}, TypeError, "depth", id="depth string"),
    pytest.param({"depth": [1.0, 2.0]}, ValueError, "depth", id="depth two values"),
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
def test_bad_one_state_environment_raises_as_the_general_path(override: dict, error: type, name: str | None) -> None:
    arguments = {**STATE, "depth": 100.0, "temperature_c": 4.0, **override}
    with pytest.raises(error, match=argument(name)) as fast:
        PAPER.environment(**arguments)
    general = _raised(lambda: general_only(PAPER).environment(**arguments))
    assert type(fast.value) is type(general) and str(fast.value) == str(general)


# --------------------------------------------------------------------------------------------
# Coefficient arrays on a robot: per segment, per segment and direction
# --------------------------------------------------------------------------------------------

ARM = arm_on_rov()
ARM_MOTION = uwml.BaseMotion(velocity=(0.5, 0.1, -0.2), angular_velocity=(0.02, 0.05, -0.1))


def test_a_robots_one_state_coefficient_arrays_are_the_batch_row_bit_for_bit() -> None:
    """Per segment, per segment and direction (a circular segment's two alike), one given and the
    other the segments' own: the native one-state call takes them, with the batch row's bits."""
    rng = np.random.default_rng(7)
    n, s = ARM.n_joints, len(ARM.segments)
    circular = np.array([segment.section == "circular" for segment in ARM.segments])
    per_direction = rng.uniform(0.2, 2.5, (s, 2))
    per_direction[circular, 1] = per_direction[circular, 0]
    options = {"base_motion": ARM_MOTION, "current": (0.3, -0.1, 0.0)}
    q, qd, qdd = random_states(rng, 5, n)
    for cd, cm in [
        (rng.uniform(0.5, 3.0, s).tolist(), rng.uniform(0.1, 1.5, s)),
        (per_direction, per_direction.tolist()),
        (None, rng.uniform(0.1, 1.5, s)),
        (tuple(rng.uniform(0.5, 3.0, s)), None),
    ]:
        batch = ARM.hydro(q, qd, qdd, cd=cd, cm=cm, **options)
        for k in range(5):
            one = ARM.hydro(q[k].tolist(), qd[k].tolist(), qdd[k].tolist(), cd=cd, cm=cm, **options)
            assert_same_bits(one, batch, HYDRO_FIELDS, k, f"state {k}")
            assert bits(one.base.total) == bits(batch.base.total[k])
        motion = ARM_MOTION._one  # the arrays the native call takes for a motion of single values
        native = ARM._core.hydro_one(
            RobotTorques, BaseWrench, q[0], qd[0], qdd[0], cd, cm, 1000.0, 9.81, motion, (0.3, -0.1, 0.0), STILL, 1, False
        )
        assert native is not None


@pytest.mark.parametrize(
    "cd",
    [
        pytest.param("unequal circular", id="a circular segment's two directions differ"),
        pytest.param("per link", id="one per link on a robot"),
        pytest.param("negative", id="a negative entry"),
    ],
)
def test_a_robots_bad_coefficient_arrays_raise_as_the_general_path(cd: str) -> None:
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
    fast = _raised(lambda: ARM.hydro(q, q, q, cd=value))
    general = _raised(lambda: general_only(ARM).hydro(q, q, q, cd=value))
    assert type(fast) is type(general) is ValueError and str(fast) == str(general) and "cd" in str(fast)
