"""Tests of ``uwml.sea.seawater`` (TEOS-10 via gsw) against the core's uniform sea ``p = ρ g z``.

The bound docs/losses.md states is measured here, over every latitude and depths from 1 m: the
uniform sea (ρ = 1025 kg/m³, g = 9.81 m/s²) is below TEOS-10 by at most 0.77 % down to 1000 m
and 1.92 % down to 6000 m (at the poles). The usual rule of thumb, within about 0.5 % down to 1 km,
holds up to about 45° of latitude.
"""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from pure import load

seawater = load("sea.seawater")
ref = load("reference")

LATITUDES = np.linspace(-90.0, 90.0, 37)[:, None]


def _relative_gap(max_depth: float, latitudes: np.ndarray = LATITUDES) -> np.ndarray:
    """(uniform sea − TEOS-10) / TEOS-10 on a grid of latitudes × depths in [1 m, max_depth]."""
    depths = np.geomspace(1.0, max_depth, 400)[None, :]
    teos = seawater.pressure_at_depth_mpa(depths, latitudes)
    uniform = ref.hydrostatic_pressure_mpa(depths)
    return (uniform - teos) / teos


@pytest.mark.parametrize(("max_depth", "bound", "floor"), [(1000.0, 0.0077, 0.0076), (6000.0, 0.0193, 0.0192)])
def test_uniform_sea_within_measured_bound(max_depth: float, bound: float, floor: float) -> None:
    worst = float(np.abs(_relative_gap(max_depth)).max())
    assert worst <= bound
    assert worst >= floor  # the documented bound is tight, not a loose guess


def test_uniform_sea_underestimates() -> None:
    # Sea water below the surface is denser than 1025 kg/m³ and gravity exceeds 9.81 m/s² away
    # from the equator; only in the top metres at the equator is the uniform sea ahead, by < 1e-6.
    assert float(_relative_gap(6000.0).max()) < 1e-6


def test_model_claim_half_percent_to_1km_at_mid_latitudes() -> None:
    mid = np.linspace(-45.0, 45.0, 19)[:, None]
    assert float(np.abs(_relative_gap(1000.0, mid)).max()) <= 0.0052
    assert float(np.abs(_relative_gap(1000.0, np.array([[90.0]]))).max()) > 0.0075  # not at the poles


def test_pressure_basics() -> None:
    assert seawater.pressure_at_depth_mpa(0.0) == pytest.approx(0.0, abs=1e-12)
    # 1000 m of sea is about 10 MPa (the paper's "10 MPa, about 1 km").
    assert 10.0 < float(seawater.pressure_at_depth_mpa(1000.0)) < 10.2
    assert seawater.pressure_at_depth_mpa([0.0, 10.0]).shape == (2,)


@given(st.floats(0.0, 10000.0), st.floats(1.0, 1000.0), st.floats(-90.0, 90.0))
def test_pressure_grows_with_depth(depth: float, step: float, latitude: float) -> None:
    assert seawater.pressure_at_depth_mpa(depth + step, latitude) > seawater.pressure_at_depth_mpa(depth, latitude)


def test_pressure_grows_toward_the_poles() -> None:
    p = seawater.pressure_at_depth_mpa(1000.0, np.array([0.0, 30.0, 60.0, 90.0]))
    assert np.all(np.diff(p) > 0.0)
    assert seawater.pressure_at_depth_mpa(1000.0, -60.0) == pytest.approx(float(p[2]), rel=1e-12)


def test_density_physics() -> None:
    surface, deep = seawater.density_at_depth([0.0, 1000.0])
    assert 1020.0 < surface < 1030.0
    # Compressibility of sea water is about 4.4e-10 /Pa: 10 MPa squeezes it by about 0.44 %.
    assert 0.003 < (deep - surface) / surface < 0.006
    cold, warm = seawater.density_at_depth(0.0, conservative_temperature=[2.0, 20.0])
    assert cold > warm
    fresh, salty = seawater.density_at_depth(0.0, absolute_salinity=[0.0, 35.0])
    assert salty - fresh == pytest.approx(27.0, abs=2.0)  # about 0.78 kg/m³ per g/kg


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda: seawater.pressure_at_depth_mpa(-1.0), "depth_m"),
        (lambda: seawater.pressure_at_depth_mpa(float("nan")), "depth_m"),
        (lambda: seawater.pressure_at_depth_mpa(10.0, 91.0), "latitude_deg"),
        (lambda: seawater.pressure_at_depth_mpa(10.0, float("inf")), "latitude_deg"),
        (lambda: seawater.density_at_depth(10.0, absolute_salinity=-1.0), "absolute_salinity"),
        (lambda: seawater.density_at_depth(10.0, conservative_temperature=float("nan")), "conservative_temperature"),
    ],
)
def test_bad_inputs_name_the_argument(call, name: str) -> None:
    with pytest.raises(ValueError, match=f"^{name} "):
        call()
