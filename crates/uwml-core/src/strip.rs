//! Exact strip integrals over one straight segment (docs/model.md sections 3 and 10).
//!
//! Along a link, a slice's normal velocity `h(s) = v0 + v1·s` and normal acceleration
//! `a0 + a1·s` are affine in the arc length `s`, and so is every joint's moment arm. Each
//! joint's torque is therefore a linear combination of two moments of the integrand, which
//! these functions return exactly, for any inputs, with a fixed amount of work.

use nalgebra::{SimdBool, SimdRealField, Vector3};

use crate::algebra::dot;
use crate::check::constant;

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

/// The 8-point Gauss-Legendre rule on `[−1, 1]`: nodes `±x_i` and their weights.
const GAUSS_LEGENDRE_8: [(f64, f64); 4] = [
    (0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_5),
    (0.960_289_856_497_536_3, 0.101_228_536_290_376_3),
];

/// The Bernstein ellipse `E_ρ` (foci at the interval's ends) outside which [`GAUSS_LEGENDRE_8`]
/// is used: `ρ = 8`, semi-axes `(ρ ± 1/ρ)/2` in half-lengths of the interval. A function analytic
/// inside it is integrated with an error below `(64/15) M ρ⁻¹⁶ / (ρ² − 1) ≈ 2.4e-16 M`
/// (Trefethen, *Approximation Theory and Approximation Practice*, Thm. 19.3), `M` the largest
/// modulus on the ellipse.
const ELLIPSE_SEMI_AXES: (f64, f64) = (4.0625, 3.9375);

/// `(∫₀ᴸ |p + s r| ds, ∫₀ᴸ s |p + s r| ds, ∫₀ᴸ s² |p + s r| ds)` for vectors `p`, `r`: the moments
/// of the normal speed along a circular segment (docs/model.md section 10, "The circular strip
/// integral"), to 1e-13 relative in `f64`, at a fixed cost (both methods below are evaluated and
/// one is selected, so SIMD lanes agree).
///
/// `|p + s r| = sqrt(A t² + 2B t + C)` with `t = s − L/2` has its two branch points at
/// `t = (−B ± i|m × r|)/A` (`m = p + r L/2`, the speed at mid-length). Where they lie outside
/// the Bernstein ellipse `E_8` of the interval, the integrand is analytic inside it and the
/// 8-point Gauss-Legendre rule is exact to rounding; this covers every segment whose normal
/// speed changes by less than a fraction of itself along it, including `r = 0`. Where they lie
/// inside, the speed has a minimum `sqrt(A)·c` (`c = |m × r|/A`) at a distance of at most a few
/// segment lengths, and the closed forms, in `τ` measured from that minimum,
/// `∫ sqrt(τ² + c²) = ½(τR + c² asinh(τ/c))`, `∫ τ sqrt(τ² + c²) = R³/3` and
/// `∫ τ² sqrt(τ² + c²) = ¼τR³ − ¼c²·∫ sqrt(τ² + c²)` (`R = sqrt(τ² + c²)`) lose at most a few
/// hundred ulps: every term is within a bounded factor of the integral. At `c → 0` (the normal
/// velocity passes through zero on the segment) they stay exact: the `asinh` term is dropped
/// once `c²·asinh` is below rounding.
#[inline]
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
pub fn circular_speed_moments<T: SimdRealField + Copy>(p: &Vector3<T>, r: &Vector3<T>, length: T) -> [T; 3] {
    let half = length * constant::<T>(0.5);
    let middle = p + r * half;
    let (a, b) = (dot(r, r), dot(&middle, r));
    let cross = middle.cross(r);
    let cross2 = dot(&cross, &cross);
    let (semi_major, semi_minor) = (constant::<T>(ELLIPSE_SEMI_AXES.0), constant::<T>(ELLIPSE_SEMI_AXES.1));
    let outside = b * b / (semi_major * semi_major) + cross2 / (semi_minor * semi_minor);
    let gauss = outside.simd_ge(a * a * half * half);
    // Each method only where some lane takes it: the same operations per lane either way.
    let quadrature = || {
        // Gauss-Legendre, in t ∈ [−h, h].
        let speed = |t: T| {
            let v = middle + r * t;
            dot(&v, &v).simd_sqrt()
        };
        let (mut g0, mut g1, mut g2) = (T::zero(), T::zero(), T::zero());
        for (x, w) in GAUSS_LEGENDRE_8 {
            let (t, w) = (half * constant::<T>(x), half * constant::<T>(w));
            for t in [-t, t] {
                let (s, f) = (half + t, w * speed(t));
                g0 += f;
                g1 += s * f;
                g2 += s * s * f;
            }
        }
        [g0, g1, g2]
    };
    let closed_form = || {
        // Closed forms about the minimum of the speed at s = σ, in τ = s − σ.
        let sqrt_a = a.simd_sqrt();
        let c = cross2.simd_sqrt() / a;
        let sigma = half - b / a;
        let c2 = c * c;
        // The two ends' asinh(τ/c) enter only as their difference, ln(P(τ_hi)/P(τ_lo)) with
        // P(τ) = τ + R (R = sqrt(τ² + c²)), written c²/(R − τ) for τ < 0, where the sum
        // would cancel: one logarithm, and no division by c. The c² term vanishes below
        // rounding once c < ε²·h; dropping it there keeps the logarithm finite.
        let tiny = half * T::simd_default_epsilon() * T::simd_default_epsilon();
        let kept = c.simd_gt(tiny);
        let c2_kept = c2.select(kept, T::zero());
        let end = |tau: T| {
            let r2 = tau * tau + c2;
            let root = r2.simd_sqrt();
            let cube = r2 * root;
            let p = (tau + root).select(tau.simd_ge(T::zero()), c2 / (root - tau));
            (constant::<T>(0.5) * tau * root, cube * constant::<T>(1.0 / 3.0), tau * cube, p)
        };
        let (lo0, lo1, lo_tau_cube, lo_p) = end(-sigma);
        let (hi0, hi1, hi_tau_cube, hi_p) = end(length - sigma);
        let log_ratio = (hi_p / lo_p).select(kept, T::one()).simd_ln();
        let j0 = hi0 - lo0 + constant::<T>(0.5) * c2_kept * log_ratio;
        let j1 = hi1 - lo1;
        let j2 = constant::<T>(0.25) * (hi_tau_cube - lo_tau_cube - c2 * j0);
        [sqrt_a * j0, sqrt_a * (j1 + sigma * j0), sqrt_a * (j2 + sigma * (j1 + j1) + sigma * sigma * j0)]
    };
    if gauss.all() {
        return quadrature();
    }
    if gauss.none() {
        return closed_form();
    }
    let ([g0, g1, g2], closed) = (quadrature(), closed_form());
    [g0.select(gauss, closed[0]), g1.select(gauss, closed[1]), g2.select(gauss, closed[2])]
}
