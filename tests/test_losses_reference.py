"""Tests of the joint-loss functions of the numpy reference (docs/losses.md, "The models").

The modules are loaded from the source tree (``pure.load``), without the compiled extension.
Expected values are worked out here by hand from the formulas of docs/losses.md or from exact identities
(a 3-4-5 triangle, ``exp(−1)``), never taken from the code under test.
"""

import math
import re
from types import SimpleNamespace

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from pure import load

ref = load("reference")
losses = load("model.losses")

RPM = 2.0 * math.pi / 60.0
OIL, SEAL, DRIVE = losses.OilDrag(), losses.Seal(), losses.Drive()

speeds = st.floats(-5.0, 5.0, allow_nan=False)
pressures = st.floats(0.0, 12.0, allow_nan=False)
temperatures = st.floats(-2.0, 40.0, allow_nan=False)
epsilons = st.floats(0.0, 0.5, allow_nan=False)


@st.composite
def seals(draw: st.DrawFn) -> object:
    """Physically ordered seal parameters: S ≥ C ≥ 0, D ≥ 0, ω_s > 0."""
    c0, c1 = draw(st.floats(0.0, 50.0)), draw(st.floats(0.0, 10.0))
    return losses.Seal(
        c0=c0,
        c1_per_mpa=c1,
        s0=c0 + draw(st.floats(0.0, 50.0)),
        s1_per_mpa=c1 + draw(st.floats(0.0, 10.0)),
        d0=draw(st.floats(0.0, 5.0)),
        d1_per_mpa=draw(st.floats(0.0, 1.0)),
        stribeck_speed=draw(st.floats(0.005, 1.0)),
    )


@st.composite
def oils(draw: st.DrawFn) -> object:
    return losses.OilDrag(
        k_oil=draw(st.floats(0.0, 1e-2)),
        exponent=draw(st.floats(1.0, 2.0)),
        pressure_sensitivity_per_mpa=draw(st.floats(0.0, 0.05)),
        temperature_sensitivity_per_k=draw(st.floats(0.0, 0.1)),
    )


# --------------------------------------------------------------------------------------------
# Smooth sign
# --------------------------------------------------------------------------------------------


def test_smooth_sign_exact_values() -> None:
    assert ref.smooth_sign(3.0, 4.0) == pytest.approx(0.6, rel=1e-15)
    assert ref.smooth_sign(-3.0, 4.0) == pytest.approx(-0.6, rel=1e-15)
    np.testing.assert_array_equal(ref.smooth_sign([-2.0, 0.0, 5.0], 0.0), [-1.0, 0.0, 1.0])


@given(st.floats(0.0, 10.0))
def test_smooth_sign_of_zero_is_zero(epsilon: float) -> None:
    assert ref.smooth_sign(0.0, epsilon) == 0.0


# |x| ≥ 1e-300: below, x/ε may underflow to 0 (5e-324 / 2 rounds to 0).
@given(st.floats(-100.0, 100.0).filter(lambda x: abs(x) >= 1e-300), st.floats(1e-3, 10.0))
def test_smooth_sign_odd_and_inside_unit_interval(x: float, epsilon: float) -> None:
    s = ref.smooth_sign(x, epsilon)
    assert ref.smooth_sign(-x, epsilon) == -s
    assert 0.0 < abs(s) < 1.0
    assert np.sign(s) == np.sign(x)


@given(st.floats(-100.0, 100.0).filter(lambda x: abs(x) > 1e-6))
def test_smooth_sign_tends_to_sign(x: float) -> None:
    # |sgn_ε(x) − sgn(x)| ≈ ε²/(2x²): it vanishes as ε → 0, monotonically.
    gaps = [abs(ref.smooth_sign(x, e * abs(x)) - math.copysign(1.0, x)) for e in (1.0, 0.1, 0.01, 1e-3)]
    assert gaps == sorted(gaps, reverse=True)
    assert gaps[-1] <= 1e-6
    assert ref.smooth_sign(x, 0.0) == math.copysign(1.0, x)


# --------------------------------------------------------------------------------------------
# Seal: Stribeck values
# --------------------------------------------------------------------------------------------


@given(seals(), pressures)
def test_seal_stribeck_values(seal: object, p: float) -> None:
    running = seal.c0 + seal.c1_per_mpa * p
    breakaway = seal.s0 + seal.s1_per_mpa * p
    viscous = seal.d0 + seal.d1_per_mpa * p
    w_s = seal.stribeck_speed
    tiny = 1e-12 * w_s
    # ω → 0⁺ (hard sign): the breakaway level S(p).
    assert ref.seal_torque(seal, tiny, p) == pytest.approx(breakaway, rel=1e-9, abs=1e-9)
    assert ref.seal_torque(seal, -tiny, p) == pytest.approx(-breakaway, rel=1e-9, abs=1e-9)
    # At ω_s: C + (S − C)/e + D ω_s.
    expected = running + (breakaway - running) / math.e + viscous * w_s
    assert ref.seal_torque(seal, w_s, p) == pytest.approx(expected, rel=1e-12, abs=1e-12)
    # Far above ω_s (exp(−30²) underflows next to C): C + D ω.
    far = 30.0 * w_s
    assert ref.seal_torque(seal, far, p) == pytest.approx(running + viscous * far, rel=1e-12, abs=1e-12)
    # Standing still with the hard sign: nothing.
    assert ref.seal_torque(seal, 0.0, p) == 0.0


@given(seals(), oils(), st.floats(0.01, 5.0), st.floats(0.0, 10.0), st.floats(0.0, 2.0), temperatures)
def test_losses_grow_with_pressure(seal: object, oil: object, speed: float, p: float, dp: float, theta: float) -> None:
    assert ref.seal_torque(seal, speed, p + dp) >= ref.seal_torque(seal, speed, p)
    assert ref.oil_drag_torque(oil, 160.0 * speed, p + dp, theta) >= ref.oil_drag_torque(oil, 160.0 * speed, p, theta)


# --------------------------------------------------------------------------------------------
# Oil drag
# --------------------------------------------------------------------------------------------


def test_oil_drag_by_hand() -> None:
    oil = losses.OilDrag(
        k_oil=2e-3,
        exponent=1.5,
        pressure_sensitivity_per_mpa=0.03,
        temperature_sensitivity_per_k=0.05,
        reference_pressure_mpa=1.0,
        reference_temperature_c=25.0,
    )
    # 2e-3 · e^{0.03·(6 − 1)} · e^{−0.05·(5 − 25)} · 100^1.5 = 2 · e^{0.15} · e^{1}
    expected = 2.0 * math.exp(0.15) * math.exp(1.0)
    assert ref.oil_drag_torque(oil, 100.0, 6.0, 5.0) == pytest.approx(expected, rel=1e-14)
    assert ref.oil_drag_torque(oil, -100.0, 6.0, 5.0) == pytest.approx(-expected, rel=1e-14)
    # With ε: scaled by 100/sqrt(100² + 75²) = 0.8.
    assert ref.oil_drag_torque(oil, 100.0, 6.0, 5.0, 75.0) == pytest.approx(0.8 * expected, rel=1e-14)


@given(oils(), st.floats(0.1, 500.0), st.floats(0.1, 3.0), pressures, temperatures)
def test_oil_drag_is_homogeneous_of_degree_n(oil: object, omega_m: float, factor: float, p: float, theta: float) -> None:
    base = ref.oil_drag_torque(oil, omega_m, p, theta)
    scaled = ref.oil_drag_torque(oil, factor * omega_m, p, theta)
    assert scaled == pytest.approx(factor**oil.exponent * base, rel=1e-12, abs=1e-300)


# --------------------------------------------------------------------------------------------
# Current, sign and the whole joint
# --------------------------------------------------------------------------------------------


def test_loss_current_by_hand() -> None:
    # Default drive: K_t = 0.4, N η K_t = 160 · 0.8 · 0.4 = 51.2.
    assert ref.loss_current(DRIVE, 0.4, 51.2) == pytest.approx(2.0, rel=1e-15)
    np.testing.assert_allclose(ref.loss_current(DRIVE, [0.2, -0.4], [0.0, -25.6]), [0.5, -1.5], rtol=1e-15)


@given(seals(), oils(), speeds, pressures, temperatures, epsilons)
def test_losses_oppose_motion(seal: object, oil: object, speed: float, p: float, theta: float, epsilon: float) -> None:
    out = ref.joint_loss_torques(DRIVE, oil, seal, speed, p, theta, epsilon)
    assert speed * out["visc"] <= 0.0
    assert speed * out["seal"] <= 0.0
    assert speed * out["current"] >= 0.0  # the motor pays for the losses in either direction


@given(seals(), oils(), speeds, pressures, temperatures, epsilons)
def test_joint_loss_torques_compose_the_parts(seal: object, oil: object, speed: float, p: float, theta: float, epsilon: float) -> None:
    n, eta, kt = DRIVE.ratio, DRIVE.efficiency, DRIVE.torque_constant
    out = ref.joint_loss_torques(DRIVE, oil, seal, speed, p, theta, epsilon)
    t_oil = ref.oil_drag_torque(oil, n * speed, p, theta, n * epsilon)
    t_seal = ref.seal_torque(seal, speed, p, epsilon)
    assert out["visc"] == pytest.approx(-n * eta * t_oil, rel=1e-12, abs=1e-300)
    assert out["seal"] == pytest.approx(-t_seal, rel=1e-12, abs=1e-300)
    assert out["current"] == pytest.approx(t_oil / kt + t_seal / (n * eta * kt), rel=1e-12, abs=1e-12)
    # The motor-side smooth sign at N ε equals the output-side one at ε.
    if epsilon > 0.0 and oil.k_oil > 0.0 and speed != 0.0:
        magnitude = ref.oil_drag_torque(oil, n * abs(speed), p, theta)
        assert t_oil == pytest.approx(magnitude * speed / math.hypot(speed, epsilon), rel=1e-12)


def test_joint_loss_torques_without_oil_or_seal() -> None:
    speed, p, theta = np.array([-1.0, 0.5, 2.0]), 4.0, 10.0
    nothing = ref.joint_loss_torques(DRIVE, None, None, speed, p, theta)
    for key in ("visc", "seal", "current"):
        np.testing.assert_array_equal(nothing[key], np.zeros(3))
    oil_only = ref.joint_loss_torques(DRIVE, OIL, None, speed, p, theta)
    np.testing.assert_array_equal(oil_only["seal"], np.zeros(3))
    seal_only = ref.joint_loss_torques(DRIVE, None, SEAL, speed, p, theta)
    np.testing.assert_array_equal(seal_only["visc"], np.zeros(3))
    both = ref.joint_loss_torques(DRIVE, OIL, SEAL, speed, p, theta)
    np.testing.assert_allclose(both["current"], oil_only["current"] + seal_only["current"], rtol=1e-14)


def test_broadcasting_and_shapes() -> None:
    out = ref.joint_loss_torques(DRIVE, OIL, SEAL, np.linspace(-1.0, 1.0, 5)[None, :], np.array([[0.0], [5.0]]), 20.0)
    assert {key: value.shape for key, value in out.items()} == {"visc": (2, 5), "seal": (2, 5), "current": (2, 5)}


def test_hydrostatic_pressure_by_hand() -> None:
    assert ref.hydrostatic_pressure_mpa(1000.0) == pytest.approx(1025.0 * 9.81 * 1000.0 / 1e6, rel=1e-15)
    np.testing.assert_allclose(ref.hydrostatic_pressure_mpa([0.0, 100.0], 1000.0, 10.0), [0.0, 1.0], rtol=1e-15)


# --------------------------------------------------------------------------------------------
# Input validation: ValueError naming the argument
# --------------------------------------------------------------------------------------------


def _duck(obj: object, **changes: float) -> SimpleNamespace:
    """A duck-typed copy of a frozen parameter object, with some attributes changed."""
    return SimpleNamespace(**{**vars(obj), **changes})


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda: ref.smooth_sign(1.0, -1.0), "epsilon"),
        (lambda: ref.smooth_sign(float("nan"), 1.0), "x"),
        (lambda: ref.oil_drag_torque(OIL, 1.0, -0.1, 20.0), "pressure_mpa"),
        (lambda: ref.oil_drag_torque(OIL, float("inf"), 1.0, 20.0), "motor_speed"),
        (lambda: ref.oil_drag_torque(OIL, 1.0, 1.0, -300.0), "temperature_c"),
        (lambda: ref.oil_drag_torque(_duck(OIL, exponent=2.5), 1.0, 1.0, 20.0), "oil.exponent"),
        (lambda: ref.oil_drag_torque(_duck(OIL, k_oil=-1.0), 1.0, 1.0, 20.0), "oil.k_oil"),
        (lambda: ref.seal_torque(SEAL, "fast", 1.0), "speed"),
        (lambda: ref.seal_torque(_duck(SEAL, s0=1.0), 1.0, 1.0), "seal.s0"),
        (lambda: ref.seal_torque(_duck(SEAL, s1_per_mpa=0.0), 1.0, 1.0), "seal.s1_per_mpa"),
        (lambda: ref.seal_torque(_duck(SEAL, stribeck_speed=0.0), 1.0, 1.0), "seal.stribeck_speed"),
        (lambda: ref.seal_torque(SEAL, 1.0, 1.0, float("nan")), "epsilon"),
        (lambda: ref.loss_current(_duck(DRIVE, efficiency=1.2), 1.0, 1.0), "drive.efficiency"),
        (lambda: ref.loss_current(_duck(DRIVE, torque_constant=0.0), 1.0, 1.0), "drive.torque_constant"),
        (lambda: ref.loss_current(DRIVE, [1.0, float("nan")], 1.0), "oil_torque"),
        (lambda: ref.joint_loss_torques(DRIVE, OIL, SEAL, 1.0, -1.0, 20.0), "pressure_mpa"),
        (lambda: ref.joint_loss_torques(DRIVE, OIL, SEAL, 1.0, 1.0, 20.0, -0.1), "epsilon"),
        (lambda: ref.hydrostatic_pressure_mpa(-1.0), "depth_m"),
        (lambda: ref.hydrostatic_pressure_mpa(1.0, sea_density=0.0), "sea_density"),
    ],
)
def test_bad_inputs_name_the_argument(call, name: str) -> None:
    with pytest.raises(ValueError, match="^" + re.escape(name) + " "):
        call()


# --------------------------------------------------------------------------------------------
# The illustrative defaults obey the paper's laws (Section IV)
# --------------------------------------------------------------------------------------------

SPEED = 10.0 * RPM  # 10 r/min at the output
PRESSURE = 10.0  # MPa
STEP = 1e-4  # relative step of the log-log central differences


def _oil_at(speed: float, p: float, theta: float = 20.0) -> float:
    return float(ref.oil_drag_torque(OIL, DRIVE.ratio * speed, p, theta))


def _seal_at(speed: float, p: float) -> float:
    return float(ref.seal_torque(SEAL, speed, p))


def _elasticity(f, x: float) -> float:
    """d ln f / d ln x by a central difference."""
    return (math.log(f(x * (1 + STEP))) - math.log(f(x * (1 - STEP)))) / (math.log(1 + STEP) - math.log(1 - STEP))


def test_defaults_oil_is_more_speed_sensitive() -> None:
    oil = _elasticity(lambda w: _oil_at(w, PRESSURE), SPEED)
    seal = _elasticity(lambda w: _seal_at(w, PRESSURE), SPEED)
    assert oil > seal > 0.0
    assert oil == pytest.approx(OIL.exponent, rel=1e-6)  # a power law's elasticity is its exponent


def test_defaults_seal_is_more_pressure_sensitive() -> None:
    oil = _elasticity(lambda p: _oil_at(SPEED, p), PRESSURE)
    seal = _elasticity(lambda p: _seal_at(SPEED, p), PRESSURE)
    assert seal > oil > 0.0


def test_defaults_breakaway_exceeds_running_friction() -> None:
    for p in (0.0, 5.0, PRESSURE):
        breakaway = _seal_at(1e-12, p)
        far = 50.0 * SEAL.stribeck_speed  # Stribeck term gone: T = C + D ω, so C = 2 T(ω) − T(2ω)
        running = 2.0 * _seal_at(far, p) - _seal_at(2.0 * far, p)
        assert breakaway > running > 0.0


def test_defaults_grow_with_pressure() -> None:
    ps = np.linspace(0.0, PRESSURE, 11)
    for torques in (
        ref.oil_drag_torque(OIL, DRIVE.ratio * SPEED, ps, 20.0),
        ref.seal_torque(SEAL, SPEED, ps),
        ref.seal_torque(SEAL, 1e-12, ps),
    ):
        assert np.all(np.diff(torques) > 0.0)


def test_defaults_total_loss_is_the_papers() -> None:
    # Paper, Section IV: 2.85 A at 10 r/min and 10 MPa, 27.4 % of the 10.4 A rated current.
    current = float(ref.joint_loss_torques(DRIVE, OIL, SEAL, SPEED, PRESSURE, 20.0)["current"])
    assert current == pytest.approx(2.85, abs=1e-3)
    assert DRIVE.rated_current == 10.4
    assert 100.0 * current / DRIVE.rated_current == pytest.approx(27.4, abs=0.05)


def test_defaults_cold_matters_more_than_pressure() -> None:
    # Deep sea: the oil cools from 20 °C to 2 °C and the pressure rises from 0 to 10 MPa.
    cold = _oil_at(SPEED, 0.0, 2.0) / _oil_at(SPEED, 0.0, 20.0)
    pressed = _oil_at(SPEED, PRESSURE, 20.0) / _oil_at(SPEED, 0.0, 20.0)
    assert cold > pressed > 1.0
