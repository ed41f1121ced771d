"""Viscosity of the compensation oil against temperature and pressure.

What the deep sea's cold and pressure do to the oil, and so to a joint's losses:
docs/losses.md, "The deep-sea temperature effect".

Temperature: ASTM D341 in Walther's form, ``log10(log10(ν + 0.7)) = A − B·log10(T)`` with ν the
kinematic viscosity [cSt = mm²/s] and T the absolute temperature [K]; A and B follow from two
reference viscosities (:class:`OilViscosity`). The plain ``+ 0.7`` is D341's form for
ν ≥ 2 cSt; below that D341 adds small correction terms, which are left out here (the oils of a
compensated joint stay far above 2 cSt in the sea).

Pressure: Barus, ``μ(p) = μ0 · exp(α p)`` (:func:`barus_factor`), α ≈ 15-40 GPa⁻¹ for mineral
oils.

:func:`drag_temperature_sensitivity` turns a named oil's viscosity law into the
``temperature_sensitivity_per_k`` (a_T) of :class:`uwml.model.losses.OilDrag`.

Pure numpy; no compiled code.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._checks import finite_array

__all__ = ["ISO_VG32", "OILS", "OilViscosity", "barus_factor", "drag_temperature_sensitivity"]

Array = NDArray[np.float64]

#: 0 °C in kelvin.
_KELVIN = 273.15
#: Walther's offset [cSt] (ASTM D341, ν ≥ 2 cSt).
_WALTHER_OFFSET = 0.7
_LN10 = math.log(10.0)


def _temperature(value: ArrayLike, name: str) -> Array:
    t = finite_array(value, name)
    if np.any(t <= -_KELVIN):
        raise ValueError(f"{name} must be above absolute zero (-273.15 °C), got minimum {t.min()}")
    return t


def _scalar(value: float, name: str) -> float:
    a = finite_array(value, name)
    if a.shape != ():
        raise ValueError(f"{name} must be a single number, got shape {a.shape}")
    return float(a)


class OilViscosity:
    """Kinematic viscosity of an oil against temperature, by ASTM D341 / Walther.

    ``log10(log10(ν + 0.7)) = A − B·log10(T)``, T in kelvin, with A and B fixed by two
    reference points ``(t1_c, nu1_cst)`` and ``(t2_c, nu2_cst)`` (usually 40 °C and 100 °C, as
    on a data sheet).

    Parameters
    ----------
    nu1_cst, nu2_cst : float
        Kinematic viscosities at the two reference temperatures [cSt = mm²/s], > 0.3 (so that
        ``log10(ν + 0.7) > 0``), the colder one the more viscous.
    t1_c, t2_c : float
        The reference temperatures [°C], distinct, above absolute zero.

    Raises
    ------
    ValueError
        On non-finite, out-of-range or inconsistent reference points (viscosity not falling
        with temperature).
    """

    def __init__(self, nu1_cst: float, t1_c: float, nu2_cst: float, t2_c: float) -> None:
        nu1, nu2 = _scalar(nu1_cst, "nu1_cst"), _scalar(nu2_cst, "nu2_cst")
        t1, t2 = float(_temperature(_scalar(t1_c, "t1_c"), "t1_c")), float(_temperature(_scalar(t2_c, "t2_c"), "t2_c"))
        for name, nu in (("nu1_cst", nu1), ("nu2_cst", nu2)):
            if nu <= 1.0 - _WALTHER_OFFSET:
                raise ValueError(f"{name} must be > {1.0 - _WALTHER_OFFSET} cSt for Walther's law, got {nu}")
        if t1 == t2:
            raise ValueError(f"t1_c and t2_c must differ, got {t1} twice")
        if (nu1 - nu2) * (t1 - t2) >= 0.0:
            raise ValueError(f"viscosity must fall as temperature rises, got {nu1} cSt at {t1} °C and {nu2} cSt at {t2} °C")
        self.nu1_cst, self.t1_c, self.nu2_cst, self.t2_c = nu1, t1, nu2, t2
        w1, w2 = self._walther(nu1), self._walther(nu2)
        x1, x2 = math.log10(t1 + _KELVIN), math.log10(t2 + _KELVIN)
        #: Walther slope B [-].
        self.slope = (w1 - w2) / (x2 - x1)
        #: Walther intercept A [-].
        self.intercept = w1 + self.slope * x1

    @staticmethod
    def _walther(nu: float) -> float:
        return math.log10(math.log10(nu + _WALTHER_OFFSET))

    def __repr__(self) -> str:
        return f"OilViscosity(nu1_cst={self.nu1_cst}, t1_c={self.t1_c}, nu2_cst={self.nu2_cst}, t2_c={self.t2_c})"

    def _log10_z(self, t_c: ArrayLike) -> Array:
        """``log10(ν + 0.7)`` at ``t_c``."""
        t_k = _temperature(t_c, "t_c") + _KELVIN
        return 10.0 ** (self.intercept - self.slope * np.log10(t_k))

    def kinematic_viscosity(self, t_c: ArrayLike) -> Array:
        """Kinematic viscosity ν [cSt] at temperature ``t_c`` [°C] (vectorized).

        Raises
        ------
        ValueError
            If ``t_c`` is not finite or not above absolute zero.
        """
        return 10.0 ** self._log10_z(t_c) - _WALTHER_OFFSET

    def temperature_sensitivity_per_k(self, t_c: ArrayLike) -> Array:
        """``−d ln ν / dθ`` [1/K] at ``t_c`` [°C], analytic (vectorized).

        With ``Z = ν + 0.7`` and ``L = log10 Z = 10^(A − B log10 T)``:
        ``dν/dT = −B · ln(10) · Z · L / T``, so ``−d ln ν/dθ = B ln(10) Z L / (T ν)``.
        """
        t_k = _temperature(t_c, "t_c") + _KELVIN
        log10_z = self._log10_z(t_c)
        z = 10.0**log10_z
        return self.slope * _LN10 * z * log10_z / (t_k * (z - _WALTHER_OFFSET))

    def viscosity_ratio(self, t_c: ArrayLike, t_ref_c: ArrayLike) -> Array:
        """``ν(t_c) / ν(t_ref_c)`` [-] (vectorized, broadcasting)."""
        return self.kinematic_viscosity(t_c) / self.kinematic_viscosity(t_ref_c)


#: A typical ISO VG 32 mineral hydraulic oil (viscosity index about 100): 32 cSt at 40 °C,
#: 5.4 cSt at 100 °C. Gives 65.4 cSt at 25 °C, 86.3 cSt at 20 °C and 287 cSt at 2 °C.
ISO_VG32 = OilViscosity(32.0, 40.0, 5.4, 100.0)

#: Named oils for :func:`drag_temperature_sensitivity`.
OILS: dict[str, OilViscosity] = {"ISO_VG32": ISO_VG32}


def barus_factor(pressure_mpa: ArrayLike, alpha_per_gpa: float) -> Array:
    """Barus's pressure-viscosity factor ``μ(p)/μ(0) = exp(α p)`` [-].

    Parameters
    ----------
    pressure_mpa : array_like
        Gauge pressure [MPa], ≥ 0.
    alpha_per_gpa : float
        Pressure-viscosity coefficient α [1/GPa], ≥ 0 (about 15-40 for mineral oils).

    Raises
    ------
    ValueError
        If ``pressure_mpa`` is negative or not finite, or ``alpha_per_gpa`` is negative or not
        finite.
    """
    p = finite_array(pressure_mpa, "pressure_mpa")
    if np.any(p < 0.0):
        raise ValueError(f"pressure_mpa must be >= 0, got minimum {p.min()}")
    alpha = _scalar(alpha_per_gpa, "alpha_per_gpa")
    if alpha < 0.0:
        raise ValueError(f"alpha_per_gpa must be >= 0, got {alpha}")
    return np.exp(alpha * 1e-3 * p)


def drag_temperature_sensitivity(
    oil: str | OilViscosity = "ISO_VG32",
    temperature_c: float = 20.0,
    *,
    to_temperature_c: float | None = None,
    viscosity_power: float = 1.0,
) -> float:
    """``temperature_sensitivity_per_k`` (a_T) of :class:`uwml.model.losses.OilDrag` for an oil.

    The drag torque goes as ``μ^m`` (m = 1 laminar Couette flow, 0.5 with Taylor vortices) and
    the model writes the temperature effect as ``exp(−a_T (θ − θ_ref))``. Without
    ``to_temperature_c`` this returns the local value ``a_T = m · (−d ln ν/dθ)`` at
    ``temperature_c``; with it, the secant value ``m · ln(ν(θ2)/ν(θ1)) / (θ1 − θ2)``, which
    makes the exponential reproduce Walther's viscosity ratio exactly between the two
    temperatures (use this when the model is referenced at one temperature and run at another:
    Walther's ``ln ν`` is convex in θ, so the local value at either end is off over 18 K).
    Kinematic viscosity stands for dynamic: the oil's thermal expansion (about 7e-4 /K) is
    neglected next to its viscosity change (about 7e-2 /K for VG32 at 10 °C).

    Parameters
    ----------
    oil : str or OilViscosity
        A name in :data:`OILS` (e.g. ``"ISO_VG32"``) or a viscosity law.
    temperature_c : float
        Where the sensitivity is wanted (the model's reference temperature) [°C].
    to_temperature_c : float, optional
        The other end of the secant (the operating temperature) [°C], ≠ ``temperature_c``.
    viscosity_power : float
        m in ``T ∝ μ^m``, in (0, 1].

    Returns
    -------
    float
        a_T [1/K], ≥ 0.

    Raises
    ------
    ValueError
        On an unknown oil name, out-of-range temperatures or ``viscosity_power``.
    """
    if isinstance(oil, str):
        if oil not in OILS:
            raise ValueError(f"oil must be one of {sorted(OILS)} or an OilViscosity, got {oil!r}")
        oil = OILS[oil]
    power = _scalar(viscosity_power, "viscosity_power")
    if not 0.0 < power <= 1.0:
        raise ValueError(f"viscosity_power must lie in (0, 1], got {power}")
    theta1 = float(_temperature(_scalar(temperature_c, "temperature_c"), "temperature_c"))
    if to_temperature_c is None:
        return power * float(oil.temperature_sensitivity_per_k(theta1))
    theta2 = float(_temperature(_scalar(to_temperature_c, "to_temperature_c"), "to_temperature_c"))
    if theta2 == theta1:
        raise ValueError(f"to_temperature_c must differ from temperature_c = {theta1}")
    return power * math.log(float(oil.viscosity_ratio(theta2, theta1))) / (theta1 - theta2)
