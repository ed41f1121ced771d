//! Derivatives for control: the dual numbers' chain rules, the joint block of `robot_jacobians`
//! against central finite differences (paper leg with and without joint losses, random 4-joint
//! chains), the added-mass matrix (symmetric, positive semi-definite, `added_mass(q, 0, q̈) =
//! −M_A q̈`, `∂τ/∂q̈ = −M_A`), the value against `robot_hydro`, f32 against f64, and the loss
//! derivatives (zero in `q`, diagonal in `q̇`). Trees on a moving base: tests/robot.rs.
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing, clippy::expect_used)]

use uwml_core::nalgebra::{ComplexField, RealField, SMatrix, SVector, convert};
use uwml_core::{
    Conditions, Drive, Dual, JointLosses, LossState, OilDrag, Real, Robot, RobotData, RobotJacobianData,
    RobotJacobians, Water, presets, pressure_at_depth, robot_hydro, robot_jacobians,
};

mod common;
use common::{Rng, hydro, random_chain};

/// Central difference step and the tolerance it allows, relative to the matrix's largest entry.
const H: f64 = 1e-6;
const TOLERANCE: f64 = 1e-7;

type D2 = Dual<f64, 2>;
/// A named function of one dual number.
type Rule = (&'static str, fn(D2) -> D2);

// ---------------------------------------------------------------------------------------------
// Dual numbers.

/// `f` on a dual number against the central difference of `f` on reals.
fn check_rule(name: &str, f: impl Fn(D2) -> D2, x: f64) {
    let d = f(D2::variable(x, 0));
    let g = |x: f64| f(D2::constant(x)).re;
    let fd = (g(x + H) - g(x - H)) / (2.0 * H);
    assert!((d.eps[0] - fd).abs() <= 1e-6 * fd.abs().max(1.0), "{name}({x}): {} vs {fd}", d.eps[0]);
    assert_eq!(d.eps[1], 0.0, "{name}: an unseeded direction stays zero");
    assert_eq!(d.re.to_bits(), g(x).to_bits(), "{name}: the real part is the real function's");
}

#[test]
fn every_rule_matches_finite_differences() {
    fn c(x: f64) -> D2 {
        D2::constant(x)
    }
    let rules: [Rule; 40] = [
        ("sin", |x| x.sin()),
        ("cos", |x| x.cos()),
        ("sin_cos.0", |x| ComplexField::sin_cos(x).0),
        ("sin_cos.1", |x| ComplexField::sin_cos(x).1),
        ("tan", |x| x.tan()),
        ("asin", |x| (x * c(0.3)).asin()),
        ("acos", |x| (x * c(0.3)).acos()),
        ("atan", |x| x.atan()),
        ("atan2 y", |x| x.atan2(c(0.7))),
        ("atan2 x", |x| c(0.7).atan2(x)),
        ("sinh", |x| x.sinh()),
        ("cosh", |x| x.cosh()),
        ("sinh_cosh.1", |x| x.sinh_cosh().1),
        ("tanh", |x| x.tanh()),
        ("asinh", |x| x.asinh()),
        ("acosh", |x| (x * x + c(1.5)).acosh()),
        ("atanh", |x| (x * c(0.3)).atanh()),
        ("exp", |x| x.exp()),
        ("exp2", |x| x.exp2()),
        ("exp_m1", |x| x.exp_m1()),
        ("ln", |x| (x * x + c(0.1)).ln()),
        ("ln_1p", |x| (x * x).ln_1p()),
        ("log", |x| (x * x + c(0.1)).log(c(3.0))),
        ("log base", |x| c(5.0).log(x * x + c(1.5))),
        ("log2", |x| (x * x + c(0.1)).log2()),
        ("log10", |x| (x * x + c(0.1)).log10()),
        ("powi", |x| x.powi(3)),
        ("powi negative", |x| (x * x + c(0.5)).powi(-2)),
        ("powf constant exponent", |x| (x * x + c(0.1)).powf(c(1.2))),
        ("powf variable exponent", |x| c(1.7).powf(x)),
        ("powc", |x| (x * x + c(0.1)).powc(x)),
        ("sqrt", |x| (x * x + c(0.1)).sqrt()),
        ("cbrt", |x| x.cbrt()),
        ("hypot", |x| x.hypot(c(0.4))),
        ("abs", |x| ComplexField::abs(x)),
        ("recip", |x| x.recip()),
        ("mul_add", |x| x.mul_add(x, c(2.0))),
        ("fract", |x| (x + c(3.0)).fract()),
        ("division and remainder", |x| (x * x + c(1.0)) / (x + c(3.0)) + (x + c(5.0)) % c(2.0)),
        ("max and min", |x| RealField::max(x, c(-0.2)) * RealField::min(x * x, c(2.0))),
    ];
    for (name, f) in rules {
        for x in [-0.83, -0.31, 0.27, 0.64, 1.1] {
            check_rule(name, f, x);
        }
    }
}

#[test]
fn singular_points_keep_constants_constant_and_powers_finite() {
    let (zero, c) = (D2::variable(0.0, 0), D2::constant);
    // x^n at x = 0 for a constant n ≥ 1: n·0^(n−1) (zero for n > 1, one for n = 1), finite.
    assert_eq!(zero.powf(c(1.2)).eps, [0.0, 0.0]);
    assert_eq!(zero.powf(c(1.0)).eps, [1.0, 0.0]);
    assert_eq!(zero.powf(c(2.0)).eps, [0.0, 0.0]);
    assert_eq!(zero.powi(1).eps, [1.0, 0.0]);
    assert_eq!(zero.powi(0).eps, [0.0, 0.0]);
    // sqrt and ln of a constant zero: no NaN from 0 · ∞.
    assert_eq!(c(0.0).sqrt().eps, [0.0, 0.0]);
    assert_eq!(c(0.0).ln().eps, [0.0, 0.0]);
    assert!(zero.sqrt().eps[0].is_infinite() && zero.sqrt().eps[1] == 0.0);
    // |x| at zero: derivative ±1 by the sign bit; h|h| is differentiable there (zero).
    assert_eq!((zero * ComplexField::abs(zero)).eps, [0.0, 0.0]);
    // Comparisons look at real parts only.
    assert!(D2::variable(1.0, 0) == D2::constant(1.0) && D2::variable(1.0, 1) < D2::constant(2.0));
    assert_eq!(D2::variable(1.0, 0).partial_cmp(&D2::constant(1.0)), Some(core::cmp::Ordering::Equal));
    // Out-of-range seed: a constant, no panic.
    assert_eq!(D2::variable(1.0, 7).eps, [0.0, 0.0]);
    // Constants through nalgebra's conversions.
    let pi: D2 = convert(core::f64::consts::PI);
    assert_eq!((pi.re, pi.eps), (core::f64::consts::PI, [0.0, 0.0]));
    assert!(D2::constant(2.0).is_finite() && !D2 { re: 1.0, eps: [f64::NAN, 0.0] }.is_finite());
}

// ---------------------------------------------------------------------------------------------
// Finite differences of τ_env.

/// Central differences of `f` with respect to each entry of `x`: column `j` is `∂f/∂x_j`.
fn central<const N: usize>(x: &SVector<f64, N>, f: impl Fn(&SVector<f64, N>) -> SVector<f64, N>) -> SMatrix<f64, N, N> {
    let mut m = SMatrix::<f64, N, N>::zeros();
    for j in 0..N {
        let (mut plus, mut minus) = (*x, *x);
        plus[j] += H;
        minus[j] -= H;
        m.set_column(j, &((f(&plus) - f(&minus)) / (2.0 * H)));
    }
    m
}

/// Largest entry of `a − b` relative to the larger of `b`'s largest entry and `floor`.
fn relative_error<const N: usize>(a: &SMatrix<f64, N, N>, b: &SMatrix<f64, N, N>, floor: f64) -> f64 {
    (a - b).amax() / b.amax().max(floor)
}

/// The joint block of `robot_jacobians` for a robot on a fixed base (all `N` joints used).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Jacobians<T: RealField + Copy, const N: usize> {
    /// `τ_env` (hydrodynamics and joint losses).
    value: SVector<T, N>,
    /// `∂τ_env/∂q`.
    d_q: SMatrix<T, N, N>,
    /// `∂τ_env/∂q̇`.
    d_qd: SMatrix<T, N, N>,
    /// `M_A(q)`.
    added_mass_matrix: SMatrix<T, N, N>,
}

/// `robot_jacobians` of `robot` at `(q, q̇, q̈)`, its joint rows and columns.
fn joint_jacobians<T: RealField + Real, const N: usize, const S: usize>(
    robot: &Robot<T, N, S>,
    water: &Water<T>,
    losses: &[Option<LossState<T>>; N],
    [q, qd, qdd]: [&SVector<T, N>; 3],
) -> Jacobians<T, N> {
    let m = 6 + N;
    let nan = T::zero() / T::zero();
    let (mut value, mut d_q, mut d_velocity, mut matrix) =
        (vec![nan; m], vec![nan; m * N], vec![nan; m * m], vec![nan; m * m]);
    let out = RobotJacobians {
        value: &mut value,
        d_q: &mut d_q,
        d_velocity: &mut d_velocity,
        added_mass_matrix: &mut matrix,
    };
    let state = |v: &SVector<T, N>| -> [T; N] { (*v).into() };
    let conditions = Conditions { losses: Some(losses), ..Conditions::new(*water) };
    let mut work = RobotJacobianData::new(robot);
    robot_jacobians(robot, &conditions, [&state(q), &state(qd), &state(qdd)], &mut work, out);
    Jacobians {
        value: SVector::from_fn(|i, _| value[6 + i]),
        d_q: SMatrix::from_fn(|i, j| d_q[(6 + i) * N + j]),
        d_qd: SMatrix::from_fn(|i, j| d_velocity[(6 + i) * m + 6 + j]),
        added_mass_matrix: SMatrix::from_fn(|i, j| matrix[(6 + i) * m + 6 + j]),
    }
}

/// `τ_env`: every joint's hydrodynamic force plus its losses, summed as the evaluation sums them.
fn environment<T: Real, const N: usize, const S: usize>(
    robot: &Robot<T, N, S>,
    conditions: &Conditions<'_, T, N, S>,
    [q, qd, qdd]: [&SVector<T, N>; 3],
) -> SVector<T, N> {
    let mut data = RobotData::new();
    let state = |v: &SVector<T, N>| -> [T; N] { (*v).into() };
    robot_hydro(robot, conditions, [&state(q), &state(qd), &state(qdd)], &mut data);
    SVector::from_fn(|i, _| {
        let (f, l) = (data.joint_forces()[i], data.joint_losses()[i]);
        f.total() + l.visc + l.seal
    })
}

struct Model<const N: usize, const S: usize> {
    robot: Robot<f64, N, S>,
    water: Water<f64>,
    losses: [Option<LossState<f64>>; N],
}

impl<const N: usize, const S: usize> Model<N, S> {
    fn torques(&self, q: &SVector<f64, N>, qd: &SVector<f64, N>, qdd: &SVector<f64, N>) -> SVector<f64, N> {
        let conditions = Conditions { losses: Some(&self.losses), ..Conditions::new(self.water) };
        environment(&self.robot, &conditions, [q, qd, qdd])
    }

    fn jacobians(&self, q: &SVector<f64, N>, qd: &SVector<f64, N>, qdd: &SVector<f64, N>) -> Jacobians<f64, N> {
        joint_jacobians(&self.robot, &self.water, &self.losses, [q, qd, qdd])
    }

    /// Checks every output at one state; returns the worst relative errors of `d_q` and `d_qd`.
    fn check(&self, q: &SVector<f64, N>, qd: &SVector<f64, N>, qdd: &SVector<f64, N>) -> (f64, f64) {
        let j = self.jacobians(q, qd, qdd);
        // The value is robot_hydro's, bit for bit.
        assert_eq!(j.value, self.torques(q, qd, qdd));
        let fd_q = central(q, |q| self.torques(q, qd, qdd));
        let fd_qd = central(qd, |qd| self.torques(q, qd, qdd));
        let (e_q, e_qd) = (relative_error(&j.d_q, &fd_q, 1.0), relative_error(&j.d_qd, &fd_qd, 1.0));
        assert!(e_q <= TOLERANCE, "d_q at q={q} qd={qd}:\n{}\nvs\n{fd_q}", j.d_q);
        assert!(e_qd <= TOLERANCE, "d_qd at q={q} qd={qd}:\n{}\nvs\n{fd_qd}", j.d_qd);
        // τ is linear in q̈: the central difference is exact up to rounding, ∂τ/∂q̈ = −M_A.
        let fd_qdd = central(qdd, |qdd| self.torques(q, qd, qdd));
        let m = j.added_mass_matrix;
        assert!(relative_error(&-m, &fd_qdd, 1e-3) <= 1e-7, "M_A\n{m}\nvs −∂τ/∂q̈\n{fd_qdd}");
        self.check_added_mass_matrix(q, &m);
        (e_q, e_qd)
    }

    /// `M_A` symmetric, positive semi-definite, and `added_mass(q, 0, q̈) = −M_A q̈`.
    fn check_added_mass_matrix(&self, q: &SVector<f64, N>, m: &SMatrix<f64, N, N>) {
        assert_eq!(*m, m.transpose());
        let scale = m.amax();
        assert!(cholesky_succeeds(&(m + SMatrix::<f64, N, N>::identity() * (1e-12 * scale))), "not PSD:\n{m}");
        let zero = SVector::<f64, N>::zeros();
        let mut rng = Rng(77);
        for _ in 0..5 {
            let qdd = rng.vector::<N>(5.0);
            let added_mass = hydro(&self.robot, &self.water, None, q, &zero, &qdd).added_mass;
            assert!((added_mass + m * qdd).amax() <= 1e-13 * scale * qdd.amax(), "{added_mass} vs {}", -m * qdd);
        }
        // Unsymmetrized, column by column: the two triangles agree up to rounding.
        for j in 0..N {
            let mut unit = zero;
            unit[j] = 1.0;
            let column = -hydro(&self.robot, &self.water, None, q, &zero, &unit).added_mass;
            assert!((column - m.column(j)).amax() <= 1e-14 * scale, "column {j}: {column} vs {}", m.column(j));
        }
    }
}

/// Whether the Cholesky factorization of the symmetric `m` finds only positive pivots (`m`
/// positive definite); by hand, as nalgebra's eigen-decompositions need a concrete size.
fn cholesky_succeeds<const N: usize>(m: &SMatrix<f64, N, N>) -> bool {
    let mut l = SMatrix::<f64, N, N>::zeros();
    for j in 0..N {
        let pivot = m[(j, j)] - (0..j).map(|k| l[(j, k)] * l[(j, k)]).sum::<f64>();
        if pivot <= 0.0 {
            return false;
        }
        l[(j, j)] = pivot.sqrt();
        for i in j + 1..N {
            l[(i, j)] = (m[(i, j)] - (0..j).map(|k| l[(i, k)] * l[(j, k)]).sum::<f64>()) / l[(j, j)];
        }
    }
    true
}

fn paper(losses: bool) -> Model<3, 2> {
    let pressure = pressure_at_depth(1000.0, 1025.0, 9.81).unwrap();
    let state = losses.then(|| JointLosses::default().at(pressure, 4.0).unwrap());
    Model { robot: presets::paper_leg(), water: Water::new(1025.0, 9.81).unwrap(), losses: [state; 3] }
}

/// Random speeds away from the smooth sign's width, where the finite differences' third
/// derivative (∝ 1/ε³) would swamp the step.
fn speeds<const N: usize>(rng: &mut Rng, scale: f64) -> SVector<f64, N> {
    SVector::from_fn(|_, _| {
        loop {
            let v = scale * rng.next();
            if v.abs() > 0.05 {
                break v;
            }
        }
    })
}

#[test]
fn paper_leg_without_losses_matches_finite_differences() {
    let model = paper(false);
    let mut rng = Rng(11);
    let mut worst = (0.0f64, 0.0f64);
    for _ in 0..500 {
        let (q, qd, qdd) = (rng.vector::<3>(3.0), rng.vector::<3>(2.0), rng.vector::<3>(5.0));
        let (e_q, e_qd) = model.check(&q, &qd, &qdd);
        worst = (worst.0.max(e_q), worst.1.max(e_qd));
    }
    println!("paper leg, hydrodynamics: worst relative error d_q {:.1e}, d_qd {:.1e}", worst.0, worst.1);
}

#[test]
fn paper_leg_with_losses_matches_finite_differences() {
    let model = paper(true);
    let mut rng = Rng(12);
    let mut worst = (0.0f64, 0.0f64);
    for _ in 0..500 {
        let (q, qd, qdd) = (rng.vector::<3>(3.0), speeds::<3>(&mut rng, 2.0), rng.vector::<3>(5.0));
        let (e_q, e_qd) = model.check(&q, &qd, &qdd);
        worst = (worst.0.max(e_q), worst.1.max(e_qd));
    }
    println!("paper leg with losses: worst relative error d_q {:.1e}, d_qd {:.1e}", worst.0, worst.1);
}

#[test]
fn random_chains_match_finite_differences() {
    let mut rng = Rng(13);
    let seal_only = JointLosses::new(Drive::default(), None, JointLosses::default().seal, 0.02).unwrap();
    for k in 0..100 {
        let losses =
            [None, Some(JointLosses::default().at(5e6, 10.0).unwrap()), None, Some(seal_only.at(2e7, 2.0).unwrap())];
        let model = Model {
            robot: random_chain(&mut rng),
            water: Water::new(1025.0, 9.80665).unwrap(),
            losses: if k % 2 == 0 { losses } else { [None; 4] },
        };
        for _ in 0..5 {
            let (q, qd, qdd) = (rng.vector::<4>(3.0), speeds::<4>(&mut rng, 3.0), rng.vector::<4>(10.0));
            model.check(&q, &qd, &qdd);
        }
    }
}

#[test]
fn without_losses_the_jacobians_are_the_hydrodynamics_alone() {
    let model = paper(false);
    let mut rng = Rng(14);
    for _ in 0..20 {
        let (q, qd, qdd) = (rng.vector::<3>(3.0), rng.vector::<3>(2.0), rng.vector::<3>(5.0));
        let jacobians = model.jacobians(&q, &qd, &qdd);
        assert_eq!(jacobians.value, hydro(&model.robot, &model.water, None, &q, &qd, &qdd).total());
    }
}

#[test]
fn loss_derivatives_are_zero_in_q_and_diagonal_in_qd() {
    let (with, without) = (paper(true), paper(false));
    let state = with.losses[0].unwrap();
    let mut rng = Rng(15);
    for k in 0..300 {
        let (q, mut qd, qdd) = (rng.vector::<3>(3.0), rng.vector::<3>(2.0), rng.vector::<3>(5.0));
        if k % 10 == 0 {
            qd[1] = 0.0; // The smooth sign at zero speed: finite slope.
        }
        let (a, b) = (with.jacobians(&q, &qd, &qdd), without.jacobians(&q, &qd, &qdd));
        assert_eq!(a.d_q, b.d_q);
        assert_eq!(a.added_mass_matrix, b.added_mass_matrix);
        let losses = a.d_qd - b.d_qd;
        for i in 0..3 {
            for j in 0..3 {
                if i != j {
                    assert_eq!(losses[(i, j)], 0.0);
                }
            }
            // The diagonal: the slope of one joint's losses, against its own finite difference
            // (a smaller step near zero speed, where the smooth sign turns within ε = 1e-3).
            let h = if qd[i].abs() < 0.05 { 1e-8 } else { H };
            let loss = |w: f64| {
                let l = state.evaluate(w);
                l.visc + l.seal
            };
            let fd = (loss(qd[i] + h) - loss(qd[i] - h)) / (2.0 * h);
            // The diagonal is a difference of two large slopes (loss and drag): compare it to
            // the total slope's scale.
            let scale = a.d_qd.amax();
            assert!((losses[(i, i)] - fd).abs() <= 1e-6 * scale, "joint {i} at {}: {} vs {fd}", qd[i], losses[(i, i)]);
            // Past the Stribeck dip (ω_s = 0.05 rad/s), where friction falls with speed, the
            // losses' slope is negative: more speed, more opposing torque.
            if qd[i].abs() > 0.5 {
                assert!(losses[(i, i)] < 0.0, "slope {} at {}", losses[(i, i)], qd[i]);
            }
        }
    }
}

#[test]
fn the_dual_pass_computes_the_real_values_and_minus_the_added_mass_matrix_in_qdd() {
    // The whole model over Dual, q̈ seeded: what robot_jacobians does for the other inputs, in the
    // open.
    type D3 = Dual<f64, 3>;
    let leg = presets::paper_leg::<D3>();
    let water = Water::new(D3::constant(1025.0), D3::constant(9.81)).unwrap();
    let pressure = pressure_at_depth(D3::constant(1000.0), D3::constant(1025.0), D3::constant(9.81)).unwrap();
    let losses = [Some(JointLosses::<D3>::default().at(pressure, D3::constant(4.0)).unwrap()); 3];
    let model = paper(true);
    let mut rng = Rng(16);
    for _ in 0..100 {
        let (q, qd, qdd) = (rng.vector::<3>(3.0), rng.vector::<3>(2.0), rng.vector::<3>(5.0));
        let seeded = qdd.map_with_location(|i, _, x| D3::variable(x, i));
        let conditions = Conditions { losses: Some(&losses), ..Conditions::new(water) };
        let tau = environment(&leg, &conditions, [&q.map(D3::constant), &qd.map(D3::constant), &seeded]);
        let real = model.torques(&q, &qd, &qdd);
        // Real parts: the same operations as the f64 path (robot_jacobians takes its value
        // from them; this checks the open-coded pass to rounding).
        let re = tau.map(|t| t.re);
        assert!((re - real).amax() <= 1e-14 * real.amax(), "{re} vs {real}");
        let d_qdd = SMatrix::<f64, 3, 3>::from_fn(|i, j| tau[i].eps[j]);
        let m = model.jacobians(&q, &qd, &qdd).added_mass_matrix;
        assert!((d_qdd + m).amax() <= 1e-13 * m.amax(), "{d_qdd} vs {}", -m);
    }
}

#[test]
fn single_precision_agrees_with_double() {
    let model = paper(true);
    let leg = presets::paper_leg::<f32>();
    let water = Water::new(1025.0f32, 9.81).unwrap();
    let losses =
        [Some(JointLosses::<f32>::default().at(pressure_at_depth(1000.0, 1025.0, 9.81).unwrap(), 4.0).unwrap()); 3];
    let mut rng = Rng(17);
    for _ in 0..200 {
        let (q, qd, qdd) = (rng.vector::<3>(3.0), speeds::<3>(&mut rng, 2.0), rng.vector::<3>(5.0));
        let single = |v: &SVector<f64, 3>| v.map(|x| x as f32);
        let j32 = joint_jacobians(&leg, &water, &losses, [&single(&q), &single(&qd), &single(&qdd)]);
        let j64 = model.jacobians(&q, &qd, &qdd);
        let double = |m: &SMatrix<f32, 3, 3>| m.map(f64::from);
        for (a, b) in [
            (double(&j32.d_q), j64.d_q),
            (double(&j32.d_qd), j64.d_qd),
            (double(&j32.added_mass_matrix), j64.added_mass_matrix),
        ] {
            assert!(relative_error(&a, &b, 1e-3) <= 1e-3, "{a} vs {b}");
        }
    }
}

#[test]
fn laminar_and_quadratic_oil_and_a_generic_exponent_give_finite_slopes_at_rest() {
    // n = 1, 1.5 and 2 take the power's shortcuts, n = 1.2 the power function: all finite at
    // zero speed (n x^(n−1) with a constant n, never through ln 0).
    let model = paper(false);
    for exponent in [1.0, 1.2, 1.5, 2.0] {
        let oil = OilDrag::new(1.2e-3, exponent, 2e-8, 0.06, 0.0, 20.0).unwrap();
        let losses = JointLosses::new(Drive::default(), Some(oil), None, 1e-3).unwrap().at(1e7, 4.0).unwrap();
        let zero = SVector::<f64, 3>::zeros();
        let j = joint_jacobians(&model.robot, &model.water, &[Some(losses); 3], [&zero, &zero, &zero]);
        assert!(j.d_q.iter().chain(j.d_qd.iter()).all(|x| x.is_finite()), "n = {exponent}: {}", j.d_qd);
    }
}

#[test]
fn non_finite_states_give_nan_without_panic() {
    let model = paper(true);
    let ok = SVector::<f64, 3>::new(0.1, 0.2, 0.3);
    for bad in [f64::NAN, f64::INFINITY] {
        let mut q = ok;
        q[1] = bad;
        let j = model.jacobians(&q, &ok, &ok);
        assert!(j.value.iter().all(|x| x.is_nan()));
        assert!(j.d_qd.iter().any(|x| x.is_nan()) && j.added_mass_matrix.iter().all(|x| x.is_nan()));
    }
}
