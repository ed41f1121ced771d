//! The exact strip integrals: special cases with closed forms, and dense quadrature; the
//! circular sections' speed moments (docs/model.md section 10, "The circular strip integral") too.
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing, clippy::expect_used)]

use uwml_core::nalgebra::Vector3;
use uwml_core::strip::{added_mass_moments, circular_speed_moments, drag_moments};

mod common;
use common::Rng;

/// `|a − b| ≤ rel · scale`.
fn assert_close(a: f64, b: f64, scale: f64, rel: f64, what: &str) {
    assert!((a - b).abs() <= rel * scale, "{what}: {a} vs {b} (scale {scale})");
}

/// Composite Gauss-Legendre (2 points) on `pieces` sub-intervals of f over [0, L]: a dense,
/// independent quadrature whose error shrinks as pieces⁻⁴ away from the kink at the root.
fn dense(v0: f64, v1: f64, length: f64, pieces: usize) -> (f64, f64) {
    let f = |s: f64| {
        let h = v0 + v1 * s;
        h * h.abs()
    };
    let (mut i0, mut i1) = (0.0, 0.0);
    let step = length / pieces as f64;
    let offset = 0.5 * step / 3f64.sqrt();
    for k in 0..pieces {
        let mid = (k as f64 + 0.5) * step;
        for s in [mid - offset, mid + offset] {
            i0 += 0.5 * step * f(s);
            i1 += 0.5 * step * s * f(s);
        }
    }
    (i0, i1)
}

fn close(a: f64, b: f64, rel: f64, scale: f64) -> bool {
    (a - b).abs() <= rel * scale.max(f64::MIN_POSITIVE)
}

#[test]
fn root_at_the_start() {
    // h = v1·s: ∫ h|h| = v1|v1| L³/3, ∫ s h|h| = v1|v1| L⁴/4.
    for v1 in [2.5, -0.7] {
        let (i0, i1) = drag_moments(0.0, v1, 0.8);
        let k = v1 * f64::abs(v1);
        assert!(close(i0, k * 0.8f64.powi(3) / 3.0, 1e-14, i0.abs()), "{i0}");
        assert!(close(i1, k * 0.8f64.powi(4) / 4.0, 1e-14, i1.abs()), "{i1}");
    }
}

#[test]
fn root_at_the_end() {
    // h = v1 (s − L): h|h| = −v1|v1| (L − s)² for v1 > 0; ∫ = −v1|v1| L³/3, ∫ s·(...) = −v1|v1| L⁴/12.
    let (v1, length) = (1.3f64, 0.6);
    let (i0, i1) = drag_moments(-v1 * length, v1, length);
    let k = v1 * v1;
    assert!(close(i0, -k * length.powi(3) / 3.0, 1e-14, i0.abs()), "{i0}");
    assert!(close(i1, -k * length.powi(4) / 12.0, 1e-14, i1.abs()), "{i1}");
}

#[test]
fn root_in_the_middle() {
    // h antisymmetric about L/2: ∫ h|h| = 0, and ∫ s h|h| = 2 ∫_{L/2}^{L} (s − L/2) h|h| = v1² L⁴/32.
    let (v1, length) = (2.0f64, 1.0);
    let (i0, i1) = drag_moments(-v1 * length / 2.0, v1, length);
    assert!(i0.abs() < 1e-15, "{i0}");
    assert!(close(i1, v1 * v1 * length.powi(4) / 32.0, 1e-14, i1.abs()), "{i1}");
}

#[test]
fn uniform_flow() {
    // v1 = 0: h constant.
    let (i0, i1) = drag_moments(-1.5, 0.0, 0.7);
    assert!(close(i0, -2.25 * 0.7, 1e-15, 1.0));
    assert!(close(i1, -2.25 * 0.49 / 2.0, 1e-15, 1.0));
    assert_eq!(drag_moments(0.0, 0.0, 0.7), (0.0, 0.0));
}

#[test]
fn extreme_magnitudes_scale_exactly() {
    // h|h| is homogeneous of degree 2 in (v0, v1): scaling by 2^k scales the moments by 4^k
    // exactly in binary floating point, far into the tiny and huge ranges.
    let base = drag_moments(0.37, -1.1, 0.9);
    for k in [-250, -100, -20, 20, 100, 250] {
        let scale = 2f64.powi(k);
        let (i0, i1) = drag_moments(0.37 * scale, -1.1 * scale, 0.9);
        let expected = (base.0 * scale * scale, base.1 * scale * scale);
        assert!(close(i0, expected.0, 1e-15, expected.0.abs()), "k = {k}: {i0} vs {:?}", expected.0);
        assert!(close(i1, expected.1, 1e-15, expected.1.abs()), "k = {k}: {i1} vs {:?}", expected.1);
    }
    // A root extremely close to either end is handled without blow-up.
    for v0 in [1e-300, -1e-300, 1e-17] {
        let (i0, i1) = drag_moments(v0, -1.0, 1.0);
        assert!(close(i0, -1.0 / 3.0, 1e-12, 1.0) && close(i1, -0.25, 1e-12, 1.0), "{v0}: {i0} {i1}");
    }
}

#[test]
fn agrees_with_dense_quadrature() {
    let mut seed = 0x2545_f491_4f6c_dd1d_u64;
    let mut next = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    for _ in 0..200 {
        let (v0, v1, length) = (3.0 * next(), 5.0 * next(), 0.1 + next().abs());
        let exact = drag_moments(v0, v1, length);
        let reference = dense(v0, v1, length, 20_000);
        let scale = (v0.abs() + v1.abs() * length).powi(2) * length * (1.0 + length);
        assert!(close(exact.0, reference.0, 1e-9, scale), "{v0} {v1} {length}: {exact:?} vs {reference:?}");
        assert!(close(exact.1, reference.1, 1e-9, scale), "{v0} {v1} {length}: {exact:?} vs {reference:?}");
    }
}

#[test]
fn works_in_f32() {
    let (i0, i1) = drag_moments(0.0f32, 2.0, 1.0);
    assert!((i0 - 4.0 / 3.0).abs() < 1e-6 && (i1 - 1.0).abs() < 1e-6);
}

#[test]
fn added_mass_moments_are_polynomial_integrals() {
    // ∫₀ᴸ (a0 + a1 s) ds and ∫₀ᴸ s (a0 + a1 s) ds with L = 2: 2 a0 + 2 a1, 2 a0 + 8/3 a1.
    let (j0, j1) = added_mass_moments(1.5, -0.5, 2.0);
    assert!(close(j0, 3.0 - 1.0, 1e-15, 1.0));
    assert!(close(j1, 3.0 - 4.0 / 3.0, 1e-15, 1.0));
}

#[test]
fn non_finite_inputs_do_not_panic() {
    let (i0, _) = drag_moments(f64::NAN, 1.0, 1.0);
    assert!(i0.is_nan());
    let (i0, _) = drag_moments(f64::INFINITY, -1.0, 1.0);
    assert!(!i0.is_finite());
}

// The circular sections' speed moments (docs/model.md section 10, "The circular strip integral"):
// the cross-flow drag integral.

/// `(∫ s^k |p + s r| ds)_{k=0,1,2}` by composite 8-point Gauss-Legendre, 16 panels between
/// breakpoints graded geometrically (ratio 4) about the minimum of the speed, from its miss
/// distance `c` out to the ends: the integrand bends on the scale `c` there (a kink at `c = 0`).
fn dense_moments(p: &Vector3<f64>, r: &Vector3<f64>, length: f64) -> [f64; 3] {
    let nodes = [
        (0.183_434_642_495_649_8, 0.362_683_783_378_362),
        (0.525_532_409_916_329, 0.313_706_645_877_887_3),
        (0.796_666_477_413_626_7, 0.222_381_034_453_374_5),
        (0.960_289_856_497_536_3, 0.101_228_536_290_376_3),
    ];
    let rr = r.dot(r);
    let mut breaks = vec![0.0, length];
    if rr > 0.0 {
        let minimum = -p.dot(r) / rr;
        let miss = (p.cross(r).norm() / rr).max(length * 1e-300);
        breaks.push(minimum);
        let mut width = miss / 4.0;
        while width < 4.0 * length {
            breaks.extend([minimum - width, minimum + width]);
            width *= 4.0;
        }
    }
    breaks.retain(|s| (0.0..=length).contains(s));
    breaks.sort_by(f64::total_cmp);
    let mut out = [0.0; 3];
    for pair in breaks.windows(2) {
        let panels = 16;
        let h = (pair[1] - pair[0]) / panels as f64;
        for i in 0..panels {
            let (middle, half) = (pair[0] + h * (i as f64 + 0.5), h / 2.0);
            for (x, w) in nodes {
                for s in [middle - half * x, middle + half * x] {
                    let f = (p + r * s).norm() * w * half;
                    out[0] += f;
                    out[1] += s * f;
                    out[2] += s * s * f;
                }
            }
        }
    }
    out
}

#[test]
fn circular_speed_moments_match_dense_quadrature() {
    let mut rng = Rng(5);
    let mut worst: f64 = 0.0;
    for trial in 0..1200 {
        let length = 0.05 + 2.0 * rng.next().abs();
        let r = rng.vector::<3>(3.0) * 10f64.powf(2.0 * rng.next());
        let p = match trial % 5 {
            // The speed passes through zero inside the segment, exactly.
            0 => -r * (length * rng.next().abs()),
            // Nearly: a small miss distance.
            1 => {
                -r * (length * rng.next().abs()) + rng.vector::<3>(1.0) * 10f64.powf(-8.0 * rng.next().abs()) * r.norm()
            }
            // Nearly uniform speed.
            2 => rng.vector::<3>(100.0) + r * 50.0,
            // Zero crossing just outside either end.
            3 => -r * (length * (1.0 + 0.01 * rng.next())),
            _ => rng.vector::<3>(3.0),
        };
        let exact = dense_moments(&p, &r, length);
        let fast = circular_speed_moments(&p, &r, length);
        for (a, e) in fast.iter().zip(exact.iter()) {
            let relative = (a - e).abs() / e.abs();
            worst = worst.max(relative);
            assert!(relative <= 1e-12, "trial {trial}: {a} vs {e} ({relative:e}); p {p:?}, r {r:?}, L {length}");
        }
    }
    // Zero velocity everywhere: zero moments, not NaN.
    assert_eq!(circular_speed_moments(&Vector3::zeros(), &Vector3::zeros(), 1.0), [0.0; 3]);
    // Uniform speed: exactly |p| L^(k+1)/(k+1).
    let [i0, i1, i2] = circular_speed_moments(&Vector3::new(3.0, 4.0, 0.0), &Vector3::zeros(), 2.0);
    assert_close(i0, 10.0, 10.0, 1e-15, "uniform I0");
    assert_close(i1, 10.0, 10.0, 1e-15, "uniform I1");
    assert_close(i2, 5.0 * 8.0 / 3.0, 13.4, 1e-15, "uniform I2");
    // Through zero at the start: |r| L^(k+2)/(k+2).
    let [i0, i1, i2] = circular_speed_moments(&Vector3::zeros(), &Vector3::new(0.0, 2.0, 0.0), 1.5);
    assert_close(i0, 2.0 * 1.5f64.powi(2) / 2.0, 3.0, 1e-15, "linear I0");
    assert_close(i1, 2.0 * 1.5f64.powi(3) / 3.0, 3.0, 1e-15, "linear I1");
    assert_close(i2, 2.0 * 1.5f64.powi(4) / 4.0, 3.0, 1e-15, "linear I2");
    eprintln!("circular speed moments: worst relative error {worst:e} over 1200 cases");
}
