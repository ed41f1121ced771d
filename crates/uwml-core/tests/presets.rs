//! The paper's leg as a preset robot (`presets::paper_leg`): the same forces in any capacity
//! (`Robot::to_capacity`, as the C ABI and the Python package hold it), bit for bit, and a
//! capacity too small refused. Its forces against docs/model.md section 5 are in `hydro.rs`, its
//! parts against Table II in `model.rs`, its kinematics in `jacobian.rs`.
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing, clippy::expect_used)]

use uwml_core::{Conditions, JointLosses, Problem, Robot, RobotData, Water, presets, robot_hydro};

mod common;
use common::Rng;

#[test]
fn the_preset_in_a_larger_capacity_gives_the_same_forces_bit_for_bit() {
    let leg = presets::paper_leg::<f64>();
    let large: Robot<f64, 16, 32, 4> = leg.to_capacity().unwrap();
    assert_eq!((large.joint_count(), large.segments().len()), (3, 2));
    assert_eq!((large.joints(), large.links(), large.segments()), (leg.joints(), leg.links(), leg.segments()));
    let losses = [Some(JointLosses::default().at(1e7, 4.0).unwrap()); 3];
    let many = [Some(JointLosses::default().at(1e7, 4.0).unwrap()); 16];
    let water = Water::new(1025.0, 9.80665).unwrap();
    let mut rng = Rng(21);
    let (mut small_data, mut large_data) = (RobotData::new(), RobotData::new());
    for _ in 0..200 {
        let (q, qd, qdd) = (rng.vector::<3>(3.0), rng.vector::<3>(2.0), rng.vector::<3>(5.0));
        let pad = |v: uwml_core::nalgebra::Vector3<f64>| -> [f64; 16] {
            core::array::from_fn(|i| if i < 3 { v[i] } else { 0.0 })
        };
        let small = Conditions { losses: Some(&losses), ..Conditions::new(water) };
        robot_hydro(&leg, &small, [&q.into(), &qd.into(), &qdd.into()], &mut small_data);
        let wide = Conditions { losses: Some(&many), ..Conditions::new(water) };
        robot_hydro(&large, &wide, [&pad(q), &pad(qd), &pad(qdd)], &mut large_data);
        assert_eq!(small_data.joint_forces(), large_data.joint_forces());
        assert_eq!(small_data.joint_losses(), large_data.joint_losses());
        assert_eq!(small_data.base_wrench(), large_data.base_wrench());
    }
}

#[test]
fn a_capacity_too_small_is_refused() {
    let leg = presets::paper_leg::<f64>();
    let joints = leg.to_capacity::<2, 4, 0>().unwrap_err();
    assert_eq!((joints.field, joints.problem), ("joints", Problem::OutOfRange));
    assert_eq!(leg.to_capacity::<3, 1, 0>().unwrap_err().field, "segments");
    assert!(leg.to_capacity::<3, 2, 0>().unwrap() == leg);
}
