//! Forward kinematics of any robot and the geometric Jacobian of a point on a link: the paper
//! leg's closed form (docs/model.md section 2), central finite differences on random trees with
//! revolute and prismatic joints, the tree's structure, f32 against f64.
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing, clippy::expect_used)]

use uwml_core::kinematics::point_jacobian;
use uwml_core::nalgebra::{Matrix3, Vector3};
use uwml_core::{JointKind, KinematicsData, Robot, forward_kinematics, presets};

mod common;
use common::Rng;
use common::trees::random_robot;

/// The position of `point` on `link` and the Jacobian (`6 × n`, row-major) at `q`.
fn evaluate<const J: usize, const S: usize>(
    robot: &Robot<f64, J, S>,
    q: &[f64; J],
    link: usize,
    point: &Vector3<f64>,
) -> (Vector3<f64>, Vec<f64>) {
    let mut data = KinematicsData::new();
    forward_kinematics(robot, q, &mut data);
    let mut jacobian = vec![f64::NAN; 6 * robot.joint_count()];
    let position = point_jacobian(robot, &data, link, point, &mut jacobian).unwrap();
    (position, jacobian)
}

/// The link's rotation at `q`.
fn rotation<const J: usize, const S: usize>(robot: &Robot<f64, J, S>, q: &[f64; J], link: usize) -> Matrix3<f64> {
    let mut data = KinematicsData::new();
    forward_kinematics(robot, q, &mut data);
    data.poses()[link].rotation
}

/// Every column against central differences: the linear rows of the position, the angular rows
/// of the rotation (`Ṙ Rᵀ = [ω]×`).
fn check_against_finite_differences<const J: usize, const S: usize>(robot: &Robot<f64, J, S>, rng: &mut Rng) {
    let (step, n) = (1e-6, robot.joint_count());
    for _ in 0..10 {
        let mut q = [0.0; J];
        q.iter_mut().take(n).for_each(|x| *x = 3.0 * rng.next());
        let point = rng.vector::<3>(0.7);
        for link in 0..n {
            let (_, jacobian) = evaluate(robot, &q, link, &point);
            for j in 0..n {
                let (mut plus, mut minus) = (q, q);
                plus[j] += step;
                minus[j] -= step;
                let linear =
                    (evaluate(robot, &plus, link, &point).0 - evaluate(robot, &minus, link, &point).0) / (2.0 * step);
                let turn = (rotation(robot, &plus, link) - rotation(robot, &minus, link)) / (2.0 * step)
                    * rotation(robot, &q, link).transpose();
                let angular = Vector3::new(turn[(2, 1)], turn[(0, 2)], turn[(1, 0)]);
                let column = |row: usize| jacobian[row * n + j];
                let analytic =
                    [Vector3::new(column(0), column(1), column(2)), Vector3::new(column(3), column(4), column(5))];
                assert!((linear - analytic[0]).norm() < 1e-7, "link {link}, joint {j}: {linear} vs {}", analytic[0]);
                assert!((angular - analytic[1]).norm() < 1e-7, "link {link}, joint {j}: {angular} vs {}", analytic[1]);
            }
        }
    }
}

#[test]
fn columns_match_finite_differences_of_the_pose() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    for n in [1, 2, 5, 7] {
        for _ in 0..4 {
            check_against_finite_differences(&random_robot::<8, 16, 0>(&mut rng, n), &mut rng);
        }
    }
    check_against_finite_differences(&presets::paper_leg::<f64>(), &mut rng);
}

#[test]
fn only_the_joints_that_carry_the_link_have_columns() {
    let mut rng = Rng(0xDEAD_BEEF_CAFE_F00D);
    for _ in 0..20 {
        let robot = random_robot::<8, 16, 0>(&mut rng, 8);
        let q: [f64; 8] = core::array::from_fn(|_| 3.0 * rng.next());
        for link in 0..8 {
            let (_, jacobian) = evaluate(&robot, &q, link, &rng.vector::<3>(1.0));
            let mut carriers = Vec::new();
            let mut at = Some(link);
            while let Some(j) = at {
                carriers.push(j);
                at = robot.joints()[j].parent;
            }
            for (j, joint) in robot.joints().iter().enumerate() {
                let column: Vec<f64> = (0..6).map(|row| jacobian[row * 8 + j]).collect();
                let angular = Vector3::new(column[3], column[4], column[5]).norm();
                match (carriers.contains(&j), joint.kind) {
                    (false, _) => assert!(column.iter().all(|&x| x == 0.0), "link {link}, joint {j}: {column:?}"),
                    // A revolute joint's angular part is its (unit) axis, a prismatic one's zero.
                    (true, JointKind::Revolute) => assert!((angular - 1.0).abs() < 1e-12),
                    (true, JointKind::Prismatic) => assert_eq!(angular, 0.0),
                }
            }
        }
    }
}

#[test]
fn a_link_out_of_range_gives_none_and_writes_nothing() {
    let leg = presets::paper_leg::<f64>();
    let mut data = KinematicsData::new();
    forward_kinematics(&leg, &[0.1, 0.2, 0.3], &mut data);
    let mut jacobian = [7.0; 18];
    for link in [3, usize::MAX] {
        assert!(point_jacobian(&leg, &data, link, &Vector3::zeros(), &mut jacobian).is_none());
        assert_eq!(jacobian, [7.0; 18]);
    }
    assert!(point_jacobian(&leg, &data, 2, &Vector3::zeros(), &mut jacobian).is_some());
    // A shorter output gets what fits.
    assert!(point_jacobian(&leg, &data, 2, &Vector3::zeros(), &mut [0.0; 4]).is_some());
}

#[test]
fn the_paper_foot_is_the_closed_form_of_model_md() {
    // docs/model.md section 2: foot = L2 u2 + L3 u3, the calf's tip at s = L3 along local -z.
    let (l2, l3) = (presets::paper::L2, presets::paper::L3);
    let leg = presets::paper_leg::<f64>();
    let mut rng = Rng(0x0F0F_0F0F_1234_4321);
    for _ in 0..200 {
        let q = rng.vector::<3>(3.0);
        let (q1, q2, q3) = (q[0], q[1], q[2]);
        let e_r = Vector3::new(q1.cos(), q1.sin(), 0.0);
        let z = Vector3::z();
        let u2 = e_r * q2.cos() + z * q2.sin();
        let u3 = e_r * (q2 + q3).sin() - z * (q2 + q3).cos();
        let (foot, _) = evaluate(&leg, &q.into(), 2, &Vector3::new(0.0, 0.0, -l3));
        assert!((foot - (u2 * l2 + u3 * l3)).norm() < 1e-14, "{foot}");
        let (knee, _) = evaluate(&leg, &q.into(), 1, &Vector3::new(l2, 0.0, 0.0));
        assert!((knee - u2 * l2).norm() < 1e-14);
    }
}

#[test]
fn single_precision_agrees_with_double() {
    let point = Vector3::new(0.0, 0.0, -0.714);
    let (p64, j64) = evaluate(&presets::paper_leg::<f64>(), &[0.3, -0.4, 0.6], 2, &point);
    let leg = presets::paper_leg::<f32>();
    let mut data = KinematicsData::new();
    forward_kinematics(&leg, &[0.3, -0.4, 0.6], &mut data);
    let mut j32 = [0.0f32; 18];
    let p32 = point_jacobian(&leg, &data, 2, &point.cast::<f32>(), &mut j32).unwrap();
    assert!((p32.cast::<f64>() - p64).norm() < 1e-6);
    assert!(j32.iter().zip(&j64).all(|(a, b)| (f64::from(*a) - b).abs() < 1e-6));
}
