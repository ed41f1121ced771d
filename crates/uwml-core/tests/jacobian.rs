//! Forward kinematics of a point and the geometric Jacobian: the paper leg's closed form
//! (docs/model.md section 2), central finite differences, and the velocities of `link_motions`.
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing, clippy::expect_used)]

use uwml_core::nalgebra::{SVector, Vector3};
use uwml_core::{Chain, Joint, Link, link_motions, point_jacobian};

mod common;
use common::Rng;

/// A random chain of `N` joints with arbitrary axes and offsets (no hydrodynamic geometry).
fn random_chain<const N: usize>(rng: &mut Rng) -> Chain<f64, N> {
    let joints = core::array::from_fn(|_| Joint { origin: rng.vector(0.8), axis: rng.unit() });
    let link = Link { mass: 0.0, com: Vector3::zeros(), volume: 0.0, cob: Vector3::zeros(), segment: None };
    Chain::new(joints, [link; N]).unwrap()
}

fn position<const N: usize>(
    chain: &Chain<f64, N>,
    q: &SVector<f64, N>,
    link: usize,
    point: &Vector3<f64>,
) -> Vector3<f64> {
    point_jacobian(chain, q, link, point).unwrap().0
}

/// Every column of the linear part against central differences of the position.
fn check_against_finite_differences<const N: usize>(chain: &Chain<f64, N>, rng: &mut Rng) {
    let step = 1e-6;
    for _ in 0..20 {
        let q = rng.vector::<N>(3.0);
        let point = rng.vector::<3>(0.7);
        for link in 0..N {
            let (_, jacobian) = point_jacobian(chain, &q, link, &point).unwrap();
            for j in 0..N {
                let mut dq = SVector::<f64, N>::zeros();
                dq[j] = step;
                let numeric = (position(chain, &(q + dq), link, &point) - position(chain, &(q - dq), link, &point))
                    / (2.0 * step);
                let analytic = jacobian.fixed_view::<3, 1>(0, j).into_owned();
                assert!((numeric - analytic).norm() < 1e-7, "link {link}, joint {j}: {numeric} vs {analytic}");
            }
        }
    }
}

#[test]
fn linear_rows_match_finite_differences_of_the_position() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    for _ in 0..10 {
        check_against_finite_differences(&random_chain::<5>(&mut rng), &mut rng);
        check_against_finite_differences(&random_chain::<1>(&mut rng), &mut rng);
    }
    check_against_finite_differences(&Chain::<f64, 3>::paper(), &mut rng);
}

#[test]
fn jacobian_times_rates_is_the_velocity_of_link_motions() {
    let mut rng = Rng(0x1234_5678_9ABC_DEF1);
    for _ in 0..50 {
        let chain = random_chain::<4>(&mut rng);
        let (q, qd) = (rng.vector::<4>(3.0), rng.vector::<4>(2.0));
        let motions = link_motions(&chain, &q, &qd, &SVector::zeros());
        for (link, motion) in motions.iter().enumerate() {
            let point = rng.vector::<3>(0.7);
            let (p, jacobian) = point_jacobian(&chain, &q, link, &point).unwrap();
            let twist = jacobian * qd;
            let angular = twist.fixed_rows::<3>(3).into_owned();
            let linear = twist.fixed_rows::<3>(0).into_owned();
            assert!((angular - motion.angular_velocity).norm() < 1e-12, "link {link}");
            let (velocity, _) = motion.point_motion(&(p - motion.origin));
            assert!((linear - velocity).norm() < 1e-12, "link {link}");
            assert!((p - motion.point(&point)).norm() < 1e-12);
        }
    }
}

#[test]
fn joints_after_the_link_have_zero_columns() {
    let mut rng = Rng(0xDEAD_BEEF_CAFE_F00D);
    let chain = random_chain::<6>(&mut rng);
    for link in 0..6 {
        let (_, jacobian) = point_jacobian(&chain, &rng.vector::<6>(3.0), link, &rng.vector::<3>(1.0)).unwrap();
        for j in 0..6 {
            let column = jacobian.column(j);
            if j > link {
                assert!(column.iter().all(|&x| x == 0.0), "link {link}, joint {j}: {column}");
            } else {
                // The angular part is the joint's (unit) axis.
                assert!((column.fixed_rows::<3>(3).norm() - 1.0).abs() < 1e-12);
            }
        }
    }
}

#[test]
fn a_link_out_of_range_gives_none() {
    let chain = Chain::<f64, 3>::paper();
    let q = SVector::<f64, 3>::new(0.1, 0.2, 0.3);
    assert!(point_jacobian(&chain, &q, 3, &Vector3::zeros()).is_none());
    assert!(point_jacobian(&chain, &q, usize::MAX, &Vector3::zeros()).is_none());
    assert!(point_jacobian(&chain, &q, 2, &Vector3::zeros()).is_some());
}

#[test]
fn the_paper_foot_is_the_closed_form_of_model_md() {
    // docs/model.md section 2: foot = L2 u2 + L3 u3, the calf's tip at s = L3 along local -z.
    let (l2, l3) = (0.660, 0.714);
    let chain = Chain::<f64, 3>::paper();
    let mut rng = Rng(0x0F0F_0F0F_1234_4321);
    for _ in 0..200 {
        let q = rng.vector::<3>(3.0);
        let (q1, q2, q3) = (q[0], q[1], q[2]);
        let e_r = Vector3::new(q1.cos(), q1.sin(), 0.0);
        let z = Vector3::z();
        let u2 = e_r * q2.cos() + z * q2.sin();
        let u3 = e_r * (q2 + q3).sin() - z * (q2 + q3).cos();
        let (foot, _) = point_jacobian(&chain, &q, 2, &Vector3::new(0.0, 0.0, -l3)).unwrap();
        assert!((foot - (u2 * l2 + u3 * l3)).norm() < 1e-14, "{foot}");
        let (knee, _) = point_jacobian(&chain, &q, 1, &Vector3::new(l2, 0.0, 0.0)).unwrap();
        assert!((knee - u2 * l2).norm() < 1e-14);
    }
}

#[test]
fn single_precision_agrees_with_double() {
    let q = SVector::<f64, 3>::new(0.3, -0.4, 0.6);
    let point = Vector3::new(0.0, 0.0, -0.714);
    let (p64, j64) = point_jacobian(&Chain::<f64, 3>::paper(), &q, 2, &point).unwrap();
    let (p32, j32) = point_jacobian(&Chain::<f32, 3>::paper(), &q.cast::<f32>(), 2, &point.cast::<f32>()).unwrap();
    assert!((p32.cast::<f64>() - p64).norm() < 1e-6);
    assert!((j32.cast::<f64>() - j64).norm() < 1e-6);
}
