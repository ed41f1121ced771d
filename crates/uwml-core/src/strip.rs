//! Exact strip integrals over one straight link (MODEL.md section 3).
//!
//! Along a link, a slice's normal velocity `h(s) = v0 + v1·s` and normal acceleration
//! `a0 + a1·s` are affine in the arc length `s`, and so is every joint's moment arm. Each
//! joint's torque is therefore a linear combination of two moments of the integrand, which
//! these functions return exactly, for any inputs, with a fixed amount of work.

use nalgebra::SimdRealField;

use crate::model::constant;

/// `(∫ h|h| ds, ∫ s·h|h| ds)` over `[start, start + width]` by 2-point Gauss-Legendre, exact
/// where `h = v0 + v1·s` keeps its sign (the integrands are then a quadratic and a cubic).
#[inline(always)]
fn gauss_legendre_2<T: SimdRealField + Copy>(v0: T, v1: T, start: T, width: T) -> (T, T) {
    // The nodes at the fractions (1 ∓ 1/√3)/2 of the interval, each weighted by half its width.
    let (s1, s2) =
        (start + width * constant(0.211_324_865_405_187_1), start + width * constant(0.788_675_134_594_812_9));
    let (h1, h2) = (v0 + v1 * s1, v0 + v1 * s2);
    let (f1, f2) = (h1 * h1.simd_abs(), h2 * h2.simd_abs());
    let half = width * constant(0.5);
    (half * (f1 + f2), half * (s1 * f1 + s2 * f2))
}

/// Where `h(s) = v0 + v1·s` changes sign inside `[0, L]`: the root `s* = L·h(0)/(h(0) − h(L))`,
/// whose denominator is the larger in magnitude, so nothing is divided by a small number;
/// otherwise `L`.
#[inline(always)]
fn sign_change<T: SimdRealField + Copy>(v0: T, v1: T, length: T) -> T {
    let end = v0 + v1 * length;
    // Strictly opposite signs. Where the product underflows, the root is so close to an end
    // that ignoring it changes nothing in the integrals.
    (length * (v0 / (v0 - end))).select((v0 * end).simd_lt(T::zero()), length)
}

/// `(∫₀ᴸ h|h| ds, ∫₀ᴸ s·h|h| ds)` for `h(s) = v0 + v1·s`, exactly (up to rounding): 2-point
/// Gauss-Legendre on both sides of the [sign change](sign_change), where the second side is
/// empty if there is none.
#[inline]
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
pub fn drag_moments<T: SimdRealField + Copy>(v0: T, v1: T, length: T) -> (T, T) {
    let root = sign_change(v0, v1, length);
    let (a0, a1) = gauss_legendre_2(v0, v1, T::zero(), root);
    let (b0, b1) = gauss_legendre_2(v0, v1, root, length - root);
    (a0 + b0, a1 + b1)
}

/// [`drag_moments`] for two normal directions at once: the same operations side by side, which
/// the compiler pairs into SIMD instructions.
#[inline(always)]
pub(crate) fn drag_moments_2<T: SimdRealField + Copy>([v0, w0]: [T; 2], [v1, w1]: [T; 2], length: T) -> [(T, T); 2] {
    let roots = [sign_change(v0, v1, length), sign_change(w0, w1, length)];
    let each = |piece: &dyn Fn(T, T, T) -> (T, T)| [piece(v0, v1, roots[0]), piece(w0, w1, roots[1])];
    let before = each(&|v0, v1, root| gauss_legendre_2(v0, v1, T::zero(), root));
    // Always both pieces (the second empty where there is no sign change): no branch on the
    // data, which mispredicts on varied states at a cost above the arithmetic's.
    let after = each(&|v0, v1, root| gauss_legendre_2(v0, v1, root, length - root));
    let sum = |(a0, a1): (T, T), (b0, b1): (T, T)| (a0 + b0, a1 + b1);
    [sum(before[0], after[0]), sum(before[1], after[1])]
}

/// `(∫₀ᴸ (a0 + a1 s) ds, ∫₀ᴸ s (a0 + a1 s) ds)` in closed form.
#[inline]
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
pub fn added_mass_moments<T: SimdRealField + Copy>(a0: T, a1: T, length: T) -> (T, T) {
    let l2 = length * length * constant::<T>(0.5);
    let l3 = length * length * length * constant::<T>(1.0 / 3.0);
    (a0 * length + a1 * l2, a0 * l2 + a1 * l3)
}
