//! The hydrodynamic torques of the core on the paper's leg (`presets::paper_leg`) and random
//! chains: the reference values and the properties of docs/model.md section 5, f32 against f64,
//! and the agreement of the torque and regressor paths.
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing, clippy::expect_used)]

use uwml_core::nalgebra::{Matrix3, SVector};
use uwml_core::{
    Conditions, KinematicsData, Robot, RobotData, SegmentCoefficients, Water, forward_kinematics, presets,
    robot_hydro_regressors,
};

mod common;
use common::{Forces, Rng, hydro, random_chain, random_coefficients};

fn paper_torques(q: [f64; 3], qd: [f64; 3], qdd: [f64; 3]) -> Forces<f64, 3> {
    let c = SegmentCoefficients::uniform(2.2, 0.5).unwrap();
    hydro(&presets::paper_leg(), &Water::default(), Some(&c), &q.into(), &qd.into(), &qdd.into())
}

/// The forces at `coefficients` from the regressors (drag and added-mass columns contracted with
/// them, buoyancy and gravity as evaluated), for a chain of 4 joints.
fn from_regressors(
    chain: &Robot<f64, 4, 4>,
    water: &Water<f64>,
    coefficients: &SegmentCoefficients<f64, 4>,
    [q, qd, qdd]: [&SVector<f64, 4>; 3],
) -> Forces<f64, 4> {
    let (columns, mut data) = (chain.regressor_column_count(), RobotData::new());
    let (mut drag, mut added_mass) = (vec![0.0; 10 * columns], vec![0.0; 10 * columns]);
    let state = |v: &SVector<f64, 4>| -> [f64; 4] { (*v).into() };
    let conditions = Conditions::new(*water);
    robot_hydro_regressors(
        chain,
        &conditions,
        [&state(q), &state(qd), &state(qdd)],
        &mut data,
        &mut drag,
        &mut added_mass,
    );
    let contract = |table: &[f64], c: &[[f64; 2]; 4]| {
        SVector::<f64, 4>::from_fn(|j, _| {
            let row = &table[(6 + j) * columns..(7 + j) * columns];
            (0..chain.segments().len()).map(|k| row[2 * k] * c[k][0] + row[2 * k + 1] * c[k][1]).sum()
        })
    };
    let each =
        |f: fn(&uwml_core::JointForces<f64>) -> f64| SVector::<f64, 4>::from_fn(|j, _| f(&data.joint_forces()[j]));
    Forces {
        drag: contract(&drag, coefficients.cd()),
        added_mass: contract(&added_mass, coefficients.cm()),
        buoyancy: each(|f| f.buoyancy),
        gravity: each(|f| f.gravity),
    }
}

fn assert_close(actual: f64, expected: f64, rel: f64) {
    assert!((actual - expected).abs() <= rel * expected.abs().max(1e-300), "{actual} vs {expected}");
}

#[test]
fn model_section_5_reference_values() {
    // docs/model.md section 5, from an independent brute-force computation (about 1e-7 relative).
    let t = paper_torques([0.3, -0.4, 0.6], [0.8, 0.5, -0.7], [1.0, -2.0, 0.5]);
    let expected = [
        (t.drag, [-24.24084, -5.060505, -0.7383118]),
        (t.added_mass, [-8.525438, 21.77596, 9.484545]),
        (t.buoyancy, [0.0, 59.72457, 4.193843]),
    ];
    for (actual, expected) in expected {
        for (a, e) in actual.iter().zip(expected) {
            if e == 0.0 {
                assert_eq!(*a, 0.0);
            } else {
                assert_close(*a, e, 2e-7);
            }
        }
    }
}

#[test]
fn paper_buoyancy_equations_17_and_21() {
    let (rho, g, rho_m) = (1000.0, 9.81, 2700.0);
    let (m2, m3, l2, lc2, lc3) = (19.261, 10.375, 0.660, 0.506, 0.560);
    let mut rng = Rng(7);
    for _ in 0..100 {
        let q = rng.vector::<3>(3.0);
        let t = paper_torques(q.into(), rng.vector::<3>(2.0).into(), rng.vector::<3>(5.0).into());
        let eq17 = (m2 * g * lc2 * q[1].cos() + m3 * g * (l2 * q[1].cos() + lc3 * (q[1] + q[2]).sin())) * rho / rho_m;
        let eq21 = m3 * g * lc3 * (q[1] + q[2]).sin() * rho / rho_m;
        assert_eq!(t.buoyancy[0], 0.0);
        assert!((t.buoyancy[1] - eq17).abs() < 1e-12 * 100.0);
        assert!((t.buoyancy[2] - eq21).abs() < 1e-12 * 100.0);
    }
}

#[test]
fn paper_equations_8_and_9_for_pure_yaw() {
    // Pure yaw: the slice normal speeds are q̇1·x·cos q2 (thigh) and q̇1·(L2 cos q2 + x sin(q2+q3))
    // (calf), both along e_t; eqs. (8) and (9) with the eq. (8) typo fixed, integrated densely.
    let (rho, cd, cm) = (1000.0, 2.2, 0.5);
    let (l2, l3, d21, d22, d31, d32) = (0.660, 0.714, 0.131, 0.238, 0.131, 0.279);
    let mut rng = Rng(11);
    for _ in 0..20 {
        let (q, qd1, qdd1) = (rng.vector::<3>(1.5), 2.0 * rng.next(), 4.0 * rng.next());
        let (c2, s23) = (q[1].cos(), (q[1] + q[2]).sin());
        let n = 20_000;
        let (mut drag, mut added_mass) = (0.0, 0.0);
        for (length, arm, width, area) in [(l2, [0.0, c2], d21, d21 * d22), (l3, [l2 * c2, s23], d31, d31 * d32)] {
            let dx = length / n as f64;
            for k in 0..n {
                let x = (k as f64 + 0.5) * dx;
                let r = arm[0] + arm[1] * x;
                let v = qd1 * r;
                drag += 0.5 * rho * cd * width * r * v * v.abs() * dx;
                added_mass += rho * cm * area * r * qdd1 * r * dx;
            }
        }
        let t = paper_torques(q.into(), [qd1, 0.0, 0.0], [qdd1, 0.0, 0.0]);
        // uwml's sign: drag = −τ_d1, added mass = −τ_m1. Midpoint rule error ~ (dx)² ≈ 1e-9.
        assert!((t.drag[0] + drag).abs() <= 1e-7 * drag.abs().max(1e-3), "{} vs {}", t.drag[0], -drag);
        assert!((t.added_mass[0] + added_mass).abs() <= 1e-7 * added_mass.abs().max(1e-3));
    }
}

#[test]
fn torque_path_equals_regressors_applied() {
    let mut rng = Rng(3);
    let water = Water::new(1025.0, 9.80665).unwrap();
    for _ in 0..200 {
        let chain = random_chain(&mut rng);
        let coefficients = random_coefficients(&mut rng);
        let (q, qd, qdd) = (rng.vector::<4>(3.0), rng.vector::<4>(3.0), rng.vector::<4>(10.0));
        let fast = hydro(&chain, &water, Some(&coefficients), &q, &qd, &qdd);
        let slow = from_regressors(&chain, &water, &coefficients, [&q, &qd, &qdd]);
        for (a, b) in [(fast.drag, slow.drag), (fast.added_mass, slow.added_mass), (fast.buoyancy, slow.buoyancy)] {
            let scale = b.amax().max(1e-12);
            assert!((a - b).amax() <= 1e-12 * scale, "{a} vs {b}");
        }
    }
}

#[test]
fn drag_is_dissipative_and_homogeneous_of_degree_two() {
    let mut rng = Rng(5);
    let water = Water::default();
    for _ in 0..300 {
        let chain = random_chain(&mut rng);
        let c = random_coefficients(&mut rng);
        let (q, qd, qdd) = (rng.vector::<4>(3.0), rng.vector::<4>(3.0), rng.vector::<4>(10.0));
        let drag = hydro(&chain, &water, Some(&c), &q, &qd, &qdd).drag;
        assert!(qd.dot(&drag) <= 1e-12 * qd.norm() * drag.norm(), "power {}", qd.dot(&drag));
        for lambda in [-2.5, -1.0, 0.3, 4.0] {
            let scaled = hydro(&chain, &water, Some(&c), &q, &(qd * lambda), &qdd).drag;
            let expected = drag * (lambda * f64::abs(lambda));
            assert!((scaled - expected).amax() <= 1e-12 * expected.amax().max(1e-12));
        }
    }
}

#[test]
fn added_mass_matrix_is_symmetric_positive_semidefinite() {
    let mut rng = Rng(9);
    let water = Water::default();
    let zero = SVector::<f64, 4>::zeros();
    for _ in 0..200 {
        let chain = random_chain(&mut rng);
        let c = random_coefficients(&mut rng);
        let q = rng.vector::<4>(3.0);
        // M_A = −∂τ_am/∂q̈ at q̇ = 0, column by column (τ_am is linear in q̈).
        let columns: [SVector<f64, 4>; 4] = core::array::from_fn(|j| {
            let mut unit = zero;
            unit[j] = 1.0;
            -hydro(&chain, &water, Some(&c), &q, &zero, &unit).added_mass
        });
        let m = uwml_core::nalgebra::Matrix4::from_columns(&columns);
        assert!((m - m.transpose()).amax() <= 1e-12 * m.amax());
        let eigen = m.symmetric_eigen();
        assert!(eigen.eigenvalues.min() >= -1e-12 * m.amax(), "{}", eigen.eigenvalues);
        // Linearity in q̈ (also with velocity terms present).
        let qd = rng.vector::<4>(2.0);
        let (a, b) = (rng.vector::<4>(5.0), rng.vector::<4>(5.0));
        let f = |qdd: &SVector<f64, 4>| {
            hydro(&chain, &water, Some(&c), &q, &qd, qdd).added_mass
                - hydro(&chain, &water, Some(&c), &q, &qd, &zero).added_mass
        };
        let lhs = f(&(a * 2.0 - b * 0.5));
        let rhs = f(&a) * 2.0 - f(&b) * 0.5;
        assert!((lhs - rhs).amax() <= 1e-11 * rhs.amax().max(1.0));
    }
}

/// ρ g Σ V_i c_i,z: the potential whose gradient is the buoyancy torque.
fn buoyancy_potential(chain: &Robot<f64, 4, 4>, water: &Water<f64>, q: &SVector<f64, 4>) -> f64 {
    let mut kinematics = KinematicsData::new();
    forward_kinematics(chain, &(*q).into(), &mut kinematics);
    chain
        .links()
        .iter()
        .zip(kinematics.poses())
        .map(|(l, m)| water.density() * water.gravity() * l.volume * m.point(&l.cob).z)
        .sum()
}

#[test]
fn buoyancy_is_conservative_and_joint_one_of_the_paper_gets_none() {
    let mut rng = Rng(13);
    let water = Water::default();
    let zero = SVector::<f64, 4>::zeros();
    for _ in 0..100 {
        let chain = random_chain(&mut rng);
        let c = random_coefficients(&mut rng);
        let q = rng.vector::<4>(3.0);
        let tau = hydro(&chain, &water, Some(&c), &q, &zero, &zero).buoyancy;
        let h = 1e-5;
        for j in 0..4 {
            let mut dq = zero;
            dq[j] = h;
            let gradient = (buoyancy_potential(&chain, &water, &(q + dq))
                - buoyancy_potential(&chain, &water, &(q - dq)))
                / (2.0 * h);
            assert!((tau[j] - gradient).abs() <= 1e-6 * (1.0 + tau.amax()), "joint {j}: {} vs {gradient}", tau[j]);
        }
    }
    let paper = paper_torques([1.0, -0.3, 0.8], [0.4, 0.1, 0.2], [0.0; 3]);
    assert_eq!(paper.buoyancy[0], 0.0);
    assert_eq!(paper.gravity[0], 0.0);
}

#[test]
fn gravity_of_the_paper_leg_is_buoyancy_times_minus_link_density_ratio() {
    // COM = COB and V = m/ρ_m: τ_gravity = −(ρ_m/ρ) τ_buoyancy.
    let mut rng = Rng(17);
    for _ in 0..100 {
        let t = paper_torques(rng.vector::<3>(3.0).into(), [0.0; 3], [0.0; 3]);
        let expected = -t.buoyancy * 2.7;
        assert!((t.gravity - expected).amax() <= 1e-12 * (1.0 + expected.amax()));
    }
}

#[test]
fn every_term_is_linear_in_its_coefficient() {
    let mut rng = Rng(19);
    let water = Water::default();
    for _ in 0..100 {
        let chain = random_chain(&mut rng);
        let (q, qd, qdd) = (rng.vector::<4>(3.0), rng.vector::<4>(3.0), rng.vector::<4>(10.0));
        let one = hydro(&chain, &water, Some(&SegmentCoefficients::uniform(1.0, 1.0).unwrap()), &q, &qd, &qdd);
        let other = hydro(&chain, &water, Some(&SegmentCoefficients::uniform(2.2, 0.5).unwrap()), &q, &qd, &qdd);
        assert!((other.drag - one.drag * 2.2).amax() <= 1e-12 * (1.0 + other.drag.amax()));
        assert!((other.added_mass - one.added_mass * 0.5).amax() <= 1e-12 * (1.0 + other.added_mass.amax()));
        assert_eq!(other.buoyancy, one.buoyancy);
    }
}

/// The largest relative error of the f32 core against f64 over random states of the paper leg,
/// per component, scaled by the largest magnitude of that component in the state.
fn f32_error(states: usize) -> [f64; 3] {
    let (leg64, leg32) = (presets::paper_leg::<f64>(), presets::paper_leg::<f32>());
    let mut rng = Rng(23);
    let mut worst = [0.0f64; 3];
    for _ in 0..states {
        let (q, qd, qdd) = (rng.vector::<3>(3.0), rng.vector::<3>(3.0), rng.vector::<3>(10.0));
        let t64 = hydro(&leg64, &Water::default(), None, &q, &qd, &qdd);
        let t32 = hydro(&leg32, &Water::default(), None, &q.cast(), &qd.cast(), &qdd.cast());
        let pairs = [(t64.drag, t32.drag), (t64.added_mass, t32.added_mass), (t64.buoyancy, t32.buoyancy)];
        for (w, (a, b)) in worst.iter_mut().zip(pairs) {
            let err = (a - b.cast::<f64>()).amax() / a.amax().max(1e-12);
            *w = w.max(err);
        }
    }
    worst
}

#[test]
fn f32_core_tracks_f64_within_the_documented_bound() {
    // Bound documented in docs/model.md section 7: 2e-5 of the largest torque of the kind.
    let worst = f32_error(20_000);
    println!("f32 vs f64, worst relative error (drag, added mass, buoyancy): {worst:?}");
    for w in worst {
        assert!(w < 2e-5, "{worst:?}");
    }
}

#[test]
fn non_finite_states_give_non_finite_torques_without_panic() {
    let t = paper_torques([f64::NAN, 0.0, 0.0], [0.0; 3], [0.0; 3]);
    assert!(t.buoyancy[1].is_nan());
    let t = paper_torques([0.0; 3], [f64::INFINITY, 0.0, 0.0], [0.0; 3]);
    assert!(!t.drag[0].is_finite());
}

#[test]
fn rotation_matrices_stay_orthonormal() {
    let mut rng = Rng(29);
    let chain = random_chain(&mut rng);
    let mut kinematics = KinematicsData::new();
    forward_kinematics(&chain, &rng.vector::<4>(10.0).into(), &mut kinematics);
    for m in kinematics.poses() {
        assert!((m.rotation.transpose() * m.rotation - Matrix3::identity()).amax() < 1e-14);
    }
}
