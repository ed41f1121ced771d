"""Tests of ``uwml.sea.oil``: Walther / ASTM D341 viscosity, its derivative, Barus, and a_T."""

import math

import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st
from pure import load

oil = load("sea.oil")
VG32 = oil.ISO_VG32


def _walther(nu: float) -> float:
    return math.log10(math.log10(nu + 0.7))


@st.composite
def viscosity_laws(draw: st.DrawFn) -> tuple[float, float, float, float]:
    """Two reference points of a plausible mineral oil: Walther slopes B of 2.5-4.5 (VG32: 3.75)."""
    t1 = draw(st.floats(0.0, 50.0))
    t2 = t1 + draw(st.floats(20.0, 80.0))
    nu1 = draw(st.floats(10.0, 500.0))
    slope = draw(st.floats(2.5, 4.5))
    w2 = _walther(nu1) - slope * (math.log10(t2 + 273.15) - math.log10(t1 + 273.15))
    return nu1, t1, 10.0 ** (10.0**w2) - 0.7, t2


@given(viscosity_laws())
def test_reproduces_its_reference_points(points: tuple[float, float, float, float]) -> None:
    nu1, t1, nu2, t2 = points
    law = oil.OilViscosity(nu1, t1, nu2, t2)
    np.testing.assert_allclose(law.kinematic_viscosity([t1, t2]), [nu1, nu2], rtol=1e-9)


def test_vg32_reference_points_and_documented_figures() -> None:
    np.testing.assert_allclose(VG32.kinematic_viscosity([40.0, 100.0]), [32.0, 5.4], rtol=1e-12)
    # docs/losses.md, "The deep-sea temperature effect": about 65 cSt at 25 °C and 290 cSt at
    # 2 °C. The preset gives 65.4 and 287.1 cSt.
    assert float(VG32.kinematic_viscosity(25.0)) == pytest.approx(65.0, rel=0.02)
    assert float(VG32.kinematic_viscosity(2.0)) == pytest.approx(290.0, rel=0.02)


@given(viscosity_laws(), st.floats(-5.0, 120.0), st.floats(-5.0, 120.0), st.floats(-5.0, 120.0))
def test_walther_is_a_straight_line_in_log_log_temperature(points, a: float, b: float, c: float) -> None:
    law = oil.OilViscosity(*points)
    t = np.array(sorted((a, b, c)))
    assume(np.min(np.diff(t)) >= 1.0)
    w = np.array([_walther(nu) for nu in law.kinematic_viscosity(t)])
    x = np.log10(t + 273.15)
    slopes = np.diff(w) / np.diff(x)
    assert slopes[0] == pytest.approx(slopes[1], rel=1e-7)


@given(viscosity_laws(), st.floats(-5.0, 120.0), st.floats(0.1, 20.0))
def test_viscosity_falls_with_temperature(points, t: float, dt: float) -> None:
    law = oil.OilViscosity(*points)
    assert law.kinematic_viscosity(t + dt) < law.kinematic_viscosity(t)


@given(viscosity_laws(), st.floats(-5.0, 120.0))
def test_sensitivity_matches_finite_differences(points, t: float) -> None:
    law = oil.OilViscosity(*points)
    h = 1e-3  # K; central difference error ~ h² · (third derivative), far below the tolerance
    numeric = -(math.log(law.kinematic_viscosity(t + h)) - math.log(law.kinematic_viscosity(t - h))) / (2.0 * h)
    assert float(law.temperature_sensitivity_per_k(t)) == pytest.approx(numeric, rel=1e-6)


def test_viscosity_ratio() -> None:
    assert float(VG32.viscosity_ratio(40.0, 100.0)) == pytest.approx(32.0 / 5.4, rel=1e-12)
    np.testing.assert_allclose(
        VG32.viscosity_ratio([10.0, 30.0], 30.0), [VG32.kinematic_viscosity(10.0) / VG32.kinematic_viscosity(30.0), 1.0]
    )


def test_barus() -> None:
    assert float(oil.barus_factor(10.0, 20.0)) == pytest.approx(math.exp(0.2), rel=1e-15)
    # docs/losses.md, "The deep-sea temperature effect": α = 15 to 40 GPa⁻¹ gives ×1.16 to ×1.49 at 10 MPa.
    np.testing.assert_allclose(oil.barus_factor(10.0, 15.0), 1.1618, rtol=1e-4)
    np.testing.assert_allclose(oil.barus_factor(10.0, 40.0), 1.4918, rtol=1e-4)
    np.testing.assert_array_equal(oil.barus_factor([0.0, 5.0], 0.0), [1.0, 1.0])


def test_drag_temperature_sensitivity() -> None:
    local = oil.drag_temperature_sensitivity("ISO_VG32", 20.0)
    assert local == pytest.approx(float(VG32.temperature_sensitivity_per_k(20.0)), rel=1e-15)
    # The secant reproduces Walther's ratio exactly between its two temperatures.
    secant = oil.drag_temperature_sensitivity("ISO_VG32", 20.0, to_temperature_c=2.0)
    assert math.exp(secant * 18.0) == pytest.approx(float(VG32.viscosity_ratio(2.0, 20.0)), rel=1e-12)
    # ln ν is convex in θ, so the secant toward the cold exceeds the local value at 20 °C.
    assert secant > local
    # The vortex regime (T ∝ μ^0.5) halves it.
    assert oil.drag_temperature_sensitivity(VG32, 20.0, viscosity_power=0.5) == pytest.approx(0.5 * local, rel=1e-15)


def test_deep_sea_cold_beats_pressure_for_vg32() -> None:
    # docs/losses.md: from 20 °C to 2 °C VG32 thickens ×3.33; 0 to 10 MPa at α = 15-40 GPa⁻¹ gives
    # ×1.16-1.49.
    cold = float(VG32.viscosity_ratio(2.0, 20.0))
    assert cold == pytest.approx(3.33, abs=0.01)
    assert cold > float(oil.barus_factor(10.0, 40.0))


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda: oil.OilViscosity(5.0, 40.0, 32.0, 100.0), "viscosity must fall"),
        (lambda: oil.OilViscosity(32.0, 40.0, 5.4, 40.0), "t1_c and t2_c"),
        (lambda: oil.OilViscosity(0.2, 40.0, 0.1, 100.0), "nu1_cst"),
        (lambda: oil.OilViscosity(32.0, -300.0, 5.4, 100.0), "t1_c"),
        (lambda: VG32.kinematic_viscosity(float("nan")), "t_c"),
        (lambda: oil.barus_factor(-1.0, 20.0), "pressure_mpa"),
        (lambda: oil.barus_factor(1.0, -20.0), "alpha_per_gpa"),
        (lambda: oil.drag_temperature_sensitivity("VG999"), "oil"),
        (lambda: oil.drag_temperature_sensitivity(VG32, 20.0, to_temperature_c=20.0), "to_temperature_c"),
        (lambda: oil.drag_temperature_sensitivity(VG32, 20.0, viscosity_power=2.0), "viscosity_power"),
    ],
)
def test_bad_inputs(call, name: str) -> None:
    with pytest.raises(ValueError, match=f"^{name}"):
        call()
