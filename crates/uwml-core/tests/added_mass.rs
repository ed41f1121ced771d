//! The added-mass matrix of whole robots (docs/model.md section 10): the composite added inertias
//! against the matrix's definition, symmetric and positive semi-definite, `−M_A a` the added-mass
//! forces at rest, and the joints' block alone.
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing, clippy::expect_used)]

use uwml_core::nalgebra::Vector3;
use uwml_core::{BaseMotion, Conditions, Current, Robot, RobotData, Water, robot_hydro, robot_joint_added_mass_matrix};

mod common;
use common::Rng;
use common::trees::{added_mass_matrix, assert_close, evaluate};

const J: usize = 12;
const S: usize = 16;
type Model = Robot<f64, J, S>;

fn random_robot(rng: &mut Rng, n: usize) -> Model {
    common::trees::random_robot(rng, n)
}

fn states(rng: &mut Rng, n: usize) -> [[f64; J]; 3] {
    common::trees::states(rng, n)
}

/// `M_A` by its definition: column `k` is minus the added-mass forces (base wrench, then joints)
/// at unit acceleration `k`, every velocity and the current zero.
fn added_mass_by_columns(robot: &Model, q: &[f64; J]) -> Vec<f64> {
    let size = 6 + robot.joint_count();
    let mut out = vec![f64::NAN; size * size];
    let mut data = RobotData::new();
    for k in 0..size {
        let unit = |i: usize| if i == k { 1.0 } else { 0.0 };
        let zero = Vector3::zeros();
        let motion = BaseMotion::new(
            [1.0, 0.0, 0.0, 0.0],
            zero,
            zero,
            Vector3::new(unit(0), unit(1), unit(2)),
            Vector3::new(unit(3), unit(4), unit(5)),
        )
        .unwrap();
        let qdd: [f64; J] = core::array::from_fn(|j| unit(6 + j));
        let conditions = Conditions { motion, ..Conditions::new(Water::default()) };
        robot_hydro(robot, &conditions, [q, &[0.0; J], &qdd], &mut data);
        let base = data.base_wrench().added_mass.to_array();
        let column = base.into_iter().chain(data.joint_forces().iter().map(|f| f.added_mass));
        for (row, value) in column.enumerate() {
            out[row * size + k] = -value;
        }
    }
    out
}

#[test]
fn the_composite_added_inertias_give_the_matrix_of_its_definition() {
    let mut rng = Rng(77);
    for _ in 0..40 {
        let n = 1 + (rng.next().abs() * 9.0) as usize;
        let robot = random_robot(&mut rng, n.min(J));
        let q = states(&mut rng, robot.joint_count())[0];
        let fast = added_mass_matrix(&robot, &q);
        let by_columns = added_mass_by_columns(&robot, &q);
        let scale = by_columns.iter().fold(1e-300_f64, |m, x| m.max(x.abs()));
        for (k, (a, b)) in fast.iter().zip(&by_columns).enumerate() {
            assert_close(*a, *b, scale, 1e-13, &format!("entry {k} of {n} joints"));
        }
    }
}

#[test]
fn the_added_mass_matrix_is_symmetric_positive_semi_definite() {
    let mut rng = Rng(51);
    for _ in 0..100 {
        let n = 1 + (rng.next().abs() * 8.0) as usize;
        let robot = random_robot(&mut rng, n);
        let q = states(&mut rng, n)[0];
        let m = added_mass_matrix(&robot, &q);
        let size = 6 + n;
        let scale = m.iter().fold(0.0_f64, |a, x| a.max(x.abs()));
        for i in 0..size {
            for j in 0..size {
                assert_eq!(m[i * size + j], m[j * size + i]);
            }
        }
        // xᵀ M x ≥ 0 for random x (the kinetic energy of the entrained water).
        for _ in 0..20 {
            let x: Vec<f64> = (0..size).map(|_| rng.next()).collect();
            let energy: f64 = (0..size)
                .flat_map(|i| (0..size).map(move |j| (i, j)))
                .map(|(i, j)| x[i] * m[i * size + j] * x[j])
                .sum();
            assert!(energy >= -1e-12 * scale, "xᵀ M_A x = {energy}");
        }
        // The added-mass forces at any acceleration (velocities zero) are −M_A times it.
        let mut s = states(&mut rng, n);
        s[1] = [0.0; J];
        let (v_dot, w_dot) = (rng.vector::<3>(1.0), rng.vector::<3>(1.0));
        let motion = BaseMotion::new([1.0, 0.0, 0.0, 0.0], Vector3::zeros(), Vector3::zeros(), v_dot, w_dot).unwrap();
        let data = evaluate(&robot, None, &motion, &Current::still(), &[q, s[1], s[2]]);
        let a: Vec<f64> = v_dot.iter().chain(w_dot.iter()).copied().chain(s[2][..n].iter().copied()).collect();
        let forces: Vec<f64> = data
            .base_wrench()
            .added_mass
            .to_array()
            .into_iter()
            .chain(data.joint_forces().iter().map(|f| f.added_mass))
            .collect();
        for i in 0..size {
            let product: f64 = (0..size).map(|j| m[i * size + j] * a[j]).sum();
            assert_close(-product, forces[i], scale * 10.0, 1e-13, "M_A a");
        }
    }
}

#[test]
fn the_joints_block_alone_is_the_full_matrixs_block() {
    let mut rng = Rng(53);
    for _ in 0..50 {
        let n = 1 + (rng.next().abs() * 8.0) as usize;
        let robot = random_robot(&mut rng, n);
        let q = states(&mut rng, n)[0];
        let full = added_mass_matrix(&robot, &q);
        let mut block = vec![f64::NAN; n * n + 3];
        robot_joint_added_mass_matrix(&robot, &Water::default(), None, &q, &mut block);
        for i in 0..n {
            for j in 0..n {
                assert_eq!(block[i * n + j].to_bits(), full[(6 + i) * (6 + n) + 6 + j].to_bits(), "({i}, {j})");
            }
        }
        assert!(block[n * n..].iter().all(|x| x.is_nan()), "wrote past n²");
        // A short output gets what fits (unsymmetrized where the mirror entry does not fit), and
        // nothing panics.
        let mut short = vec![f64::NAN; n * n / 2];
        robot_joint_added_mass_matrix(&robot, &Water::default(), None, &q, &mut short);
        assert!(short.iter().all(|x| x.is_finite()));
    }
}
