//! The two added-mass forms against the water's kinetic energy `T_A = ½ xᵀ M_A(q) x`, `x = (ν, q̇)`
//! (docs/simulation.md, "Energy-consistent added mass"), in still water with drag off, on the
//! 7-joint arm of circular and rectangular segments on a turned, moving hull:
//! - Kirchhoff: the power of the added-mass forces is exactly `−dT_A/dt = −(xᵀ M_A ẋ + ½ xᵀ Ṁ_A x)`;
//! - Morison: the same plus `Σ_k ∫ ρ Cm_k A v_k (ṅ_k·v) ds`, which is not zero, and the two forms
//!   share their acceleration part (equal at zero velocities).
//!
//! `Ṁ_A = Σ_i ∂M_A/∂q_i q̇_i` by central differences (step 1e-6: error ~1e-10 of the terms).
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing)]

use uwml_core::nalgebra::Vector3;
use uwml_core::{
    AddedMassForm, BaseMotion, Conditions, Current, Robot, RobotData, SegmentCoefficients, Water,
    robot_added_mass_matrix, robot_hydro,
};

#[path = "../benches/common/arm.rs"]
mod arm;

const N: usize = 7;
const M: usize = 6 + N;

fn added_mass_power(
    robot: &Robot<f64, N, 15>,
    form: AddedMassForm,
    x: &[f64; M],
    x_dot: &[f64; M],
    q: &[f64; N],
) -> f64 {
    let no_drag = SegmentCoefficients::<f64, 15>::uniform(0.0, 1.0).unwrap();
    let motion = BaseMotion::new(
        [0.96, 0.1, -0.2, 0.1735].map(|c: f64| c / (0.96f64 * 0.96 + 0.01 + 0.04 + 0.1735 * 0.1735).sqrt()),
        Vector3::new(x[0], x[1], x[2]),
        Vector3::new(x[3], x[4], x[5]),
        Vector3::new(x_dot[0], x_dot[1], x_dot[2]),
        Vector3::new(x_dot[3], x_dot[4], x_dot[5]),
    )
    .unwrap();
    let still = Current::new(Vector3::zeros(), Vector3::zeros()).unwrap();
    let qd: [f64; N] = core::array::from_fn(|i| x[6 + i]);
    let qdd: [f64; N] = core::array::from_fn(|i| x_dot[6 + i]);
    let mut data = RobotData::new();
    robot_hydro(
        robot,
        &Conditions { motion, current: still, coefficients: Some(&no_drag), form, ..Conditions::new(Water::default()) },
        [q, &qd, &qdd],
        &mut data,
    );
    let base = data.base_wrench().added_mass.to_array();
    let joints = data.joint_forces().iter().map(|f| f.added_mass);
    base.iter().chain(joints.collect::<Vec<_>>().iter()).zip(x).map(|(f, v)| f * v).sum()
}

fn matrix(robot: &Robot<f64, N, 15>, q: &[f64; N]) -> [f64; M * M] {
    let no_drag = SegmentCoefficients::<f64, 15>::uniform(0.0, 1.0).unwrap();
    let mut out = [0.0; M * M];
    robot_added_mass_matrix(robot, &Water::default(), Some(&no_drag), q, &mut out);
    out
}

fn quadratic(a: &[f64; M * M], x: &[f64; M], y: &[f64; M]) -> f64 {
    (0..M).map(|i| (0..M).map(|j| x[i] * a[i * M + j] * y[j]).sum::<f64>()).sum()
}

#[test]
fn kirchhoff_power_is_minus_the_rate_of_the_waters_kinetic_energy_and_morison_is_not() {
    let robot = arm::arm_on_rov::<f64, N, 15>();
    let q = [0.3, -0.4, 0.6, 0.2, -0.5, 0.1, 0.05];
    let x = [0.4, -0.1, 0.2, 0.05, -0.1, 0.08, 0.5, 0.3, -0.4, 0.8, 0.2, -0.6, 0.02];
    let x_dot = [0.1, 0.2, -0.3, 0.02, 0.01, -0.03, 1.0, -0.5, 0.3, 0.2, -1.0, 0.7, 0.1];
    let m_a = matrix(&robot, &q);
    // Ṁ_A along q̇, by central differences.
    let h = 1e-6;
    let (mut plus, mut minus) = (q, q);
    for i in 0..N {
        plus[i] += h * x[6 + i];
        minus[i] -= h * x[6 + i];
    }
    let (m_plus, m_minus) = (matrix(&robot, &plus), matrix(&robot, &minus));
    let m_dot: [f64; M * M] = core::array::from_fn(|k| (m_plus[k] - m_minus[k]) / (2.0 * h));
    let energy_rate = quadratic(&m_a, &x, &x_dot) + 0.5 * quadratic(&m_dot, &x, &x);
    let kirchhoff = added_mass_power(&robot, AddedMassForm::Kirchhoff, &x, &x_dot, &q);
    let morison = added_mass_power(&robot, AddedMassForm::Morison, &x, &x_dot, &q);
    let scale = energy_rate.abs().max(quadratic(&m_a, &x, &x_dot).abs());
    assert!(
        (kirchhoff + energy_rate).abs() <= 1e-8 * scale,
        "Kirchhoff power {kirchhoff} vs −dT_A/dt {}",
        -energy_rate
    );
    assert!(
        (morison + energy_rate).abs() > 1e-3 * scale,
        "Morison power {morison} should differ from {}",
        -energy_rate
    );
    // At zero velocity both are −M_A ẋ: the same acceleration part.
    let rest = |form| {
        let no_drag = SegmentCoefficients::<f64, 15>::uniform(0.0, 1.0).unwrap();
        let motion = BaseMotion::new(
            [1.0, 0.0, 0.0, 0.0],
            Vector3::zeros(),
            Vector3::zeros(),
            Vector3::new(x_dot[0], x_dot[1], x_dot[2]),
            Vector3::new(x_dot[3], x_dot[4], x_dot[5]),
        )
        .unwrap();
        let still = Current::new(Vector3::zeros(), Vector3::zeros()).unwrap();
        let qdd: [f64; N] = core::array::from_fn(|i| x_dot[6 + i]);
        let mut data = RobotData::new();
        robot_hydro(
            &robot,
            &Conditions {
                motion,
                current: still,
                coefficients: Some(&no_drag),
                form,
                ..Conditions::new(Water::default())
            },
            [&q, &[0.0; N], &qdd],
            &mut data,
        );
        let mut all = data.base_wrench().added_mass.to_array().to_vec();
        all.extend(data.joint_forces().iter().map(|f| f.added_mass));
        all
    };
    assert_eq!(rest(AddedMassForm::Kirchhoff), rest(AddedMassForm::Morison));
}

#[test]
fn kirchhoff_regressors_and_jacobians_are_its_forces() {
    use uwml_core::{
        AddedMassForm, Conditions, RobotJacobianData, RobotJacobians, robot_hydro_regressors, robot_jacobians,
    };
    let robot = arm::arm_on_rov::<f64, N, 15>();
    let (motion, current) = arm::rov_motion::<f64>();
    let q = [0.3, -0.4, 0.6, 0.2, -0.5, 0.1, 0.05];
    let qd = [0.5, 0.3, -0.4, 0.8, 0.2, -0.6, 0.02];
    let qdd = [1.0, -0.5, 0.3, 0.2, -1.0, 0.7, 0.1];
    let water = Water::default();
    let mut data = RobotData::new();
    robot_hydro(
        &robot,
        &Conditions { motion, current, form: AddedMassForm::Kirchhoff, ..Conditions::new(water) },
        [&q, &qd, &qdd],
        &mut data,
    );
    let mut forces = data.base_wrench().added_mass.to_array().to_vec();
    forces.extend(data.joint_forces().iter().map(|f| f.added_mass));
    let mut totals = data.base_wrench().total().to_array().to_vec();
    totals.extend(data.joint_forces().iter().map(|f| f.total()));
    // Regressors: Σ columns × each segment's own Cm is the added-mass force.
    let columns = robot.regressor_column_count();
    let (mut drag, mut added) = (vec![0.0; M * columns], vec![0.0; M * columns]);
    let form = AddedMassForm::Kirchhoff;
    robot_hydro_regressors(
        &robot,
        &Conditions { motion, current, form, ..Conditions::new(water) },
        [&q, &qd, &qdd],
        &mut data,
        &mut drag,
        &mut added,
    );
    let scale = forces.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
    for (row, expected) in forces.iter().enumerate() {
        let value: f64 = robot
            .segments()
            .iter()
            .enumerate()
            .map(|(k, s)| added[row * columns + 2 * k] * s.cm[0] + added[row * columns + 2 * k + 1] * s.cm[1])
            .sum();
        assert!((value - expected).abs() <= 1e-12 * scale, "row {row}: {value} vs {expected}");
    }
    // Jacobians: the value is the Kirchhoff total; M_A the same as Morison's; d_velocity differs.
    let run = |kirchhoff: bool| {
        let (mut value, mut d_q, mut d_velocity, mut m_a) =
            (vec![0.0; M], vec![0.0; M * N], vec![0.0; M * M], vec![0.0; M * M]);
        let mut work = RobotJacobianData::new(&robot);
        let out = RobotJacobians {
            value: &mut value,
            d_q: &mut d_q,
            d_velocity: &mut d_velocity,
            added_mass_matrix: &mut m_a,
        };
        let none = [None; N];
        if kirchhoff {
            robot_jacobians(
                &robot,
                &Conditions { motion, current, form, losses: Some(&none), ..Conditions::new(water) },
                [&q, &qd, &qdd],
                &mut work,
                out,
            );
        } else {
            robot_jacobians(
                &robot,
                &Conditions { motion, current, losses: Some(&none), ..Conditions::new(water) },
                [&q, &qd, &qdd],
                &mut work,
                out,
            );
        }
        (value, d_velocity, m_a)
    };
    let (value, d_velocity, m_a) = run(true);
    let (_, morison_velocity, morison_m_a) = run(false);
    let total_scale = totals.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
    for (a, b) in value.iter().zip(&totals) {
        assert!((a - b).abs() <= 1e-12 * total_scale, "{a} vs {b}");
    }
    assert_eq!(m_a, morison_m_a);
    assert!(d_velocity.iter().zip(&morison_velocity).any(|(a, b)| (a - b).abs() > 1e-6));
}
