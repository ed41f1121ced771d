//! Exact strip integrals over one straight link (MODEL.md section 3).
//!
//! Along a link, a slice's normal velocity `h(s) = v0 + v1·s` and normal acceleration
//! `a0 + a1·s` are affine in the arc length `s`, and so is every joint's moment arm. Each
//! joint's torque is therefore a linear combination of two moments of the integrand, which
//! these functions return exactly, for any inputs, with a fixed amount of work.

use nalgebra::RealField;

use crate::model::constant;

/// `(∫ h|h| ds, ∫ s·h|h| ds)` over `[a, b]` by 2-point Gauss-Legendre, exact where `h` keeps
/// its sign (the integrands are then a quadratic and a cubic).
#[inline]
fn gauss_legendre_2<T: RealField + Copy>(v0: T, v1: T, a: T, b: T) -> (T, T) {
    let half = constant::<T>(0.5);
    let radius = (b - a) * half;
    let centre = (a + b) * half;
    let offset = radius * constant::<T>(0.577_350_269_189_625_8); // 1/√3
    let (s1, s2) = (centre - offset, centre + offset);
    let (h1, h2) = (v0 + v1 * s1, v0 + v1 * s2);
    let (f1, f2) = (h1 * h1.abs(), h2 * h2.abs());
    (radius * (f1 + f2), radius * (s1 * f1 + s2 * f2))
}

/// `(∫₀ᴸ h|h| ds, ∫₀ᴸ s·h|h| ds)` for `h(s) = v0 + v1·s`, exactly (up to rounding).
///
/// If `h` changes sign inside `[0, L]` the interval is split at the root
/// `s* = L·h(0)/(h(0) − h(L))`, whose denominator is the larger in magnitude, so nothing is
/// divided by a small number; otherwise the second piece is empty. Always four evaluations.
#[inline]
pub fn drag_moments<T: RealField + Copy>(v0: T, v1: T, length: T) -> (T, T) {
    let zero = T::zero();
    let end = v0 + v1 * length;
    let crosses = (v0 > zero && end < zero) || (v0 < zero && end > zero);
    let root = if crosses { length * (v0 / (v0 - end)) } else { length };
    let (a0, a1) = gauss_legendre_2(v0, v1, zero, root);
    let (b0, b1) = gauss_legendre_2(v0, v1, root, length);
    (a0 + b0, a1 + b1)
}

/// `(∫₀ᴸ (a0 + a1 s) ds, ∫₀ᴸ s (a0 + a1 s) ds)` in closed form.
#[inline]
pub fn added_mass_moments<T: RealField + Copy>(a0: T, a1: T, length: T) -> (T, T) {
    let l2 = length * length * constant::<T>(0.5);
    let l3 = length * length * length * constant::<T>(1.0 / 3.0);
    (a0 * length + a1 * l2, a0 * l2 + a1 * l3)
}
