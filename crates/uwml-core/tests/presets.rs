//! The paper's leg as a preset robot against the chain path it replaces (hydrodynamics and the
//! point Jacobian), before the chain path goes.
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing, clippy::expect_used)]

use uwml_core::kinematics::point_jacobian as robot_point_jacobian;
use uwml_core::nalgebra::Vector3;
use uwml_core::{
    Chain, Coefficients, Conditions, KinematicsData, RobotData, Water, forward_kinematics, hydro_torques,
    point_jacobian, presets, robot_hydro,
};

mod common;
use common::Rng;

#[test]
fn the_preset_is_the_chain_path_to_1e_12() {
    let (leg, chain) = (presets::paper_leg::<f64>(), Chain::<f64, 3>::paper());
    let water = Water::new(1025.0, 9.80665).unwrap();
    let mut rng = Rng(21);
    let mut data = RobotData::new();
    for _ in 0..300 {
        let (q, qd, qdd) = (rng.vector::<3>(3.0), rng.vector::<3>(2.0), rng.vector::<3>(5.0));
        let want = hydro_torques(&chain, &water, &Coefficients::default(), &q, &qd, &qdd);
        robot_hydro(&leg, &Conditions::new(water), [&q.into(), &qd.into(), &qdd.into()], &mut data);
        for (i, f) in data.joint_forces().iter().enumerate() {
            let scale = 1.0 + want.total().amax();
            for (a, b) in [(f.drag, want.drag[i]), (f.added_mass, want.added_mass[i]), (f.buoyancy, want.buoyancy[i])] {
                assert!((a - b).abs() <= 1e-12 * scale, "{a} vs {b}");
            }
            assert!((f.gravity - want.gravity[i]).abs() <= 1e-12 * scale);
        }
        let mut kinematics = KinematicsData::new();
        forward_kinematics(&leg, &q.into(), &mut kinematics);
        let point = rng.vector::<3>(0.7);
        for link in 0..3 {
            let (p, j) = point_jacobian(&chain, &q, link, &point).unwrap();
            let mut jacobian = [0.0; 18];
            let position = robot_point_jacobian(&leg, &kinematics, link, &point, &mut jacobian).unwrap();
            assert!((p - position).norm() <= 1e-14);
            for (row, column) in (0..6).flat_map(|r| (0..3).map(move |c| (r, c))) {
                assert!((j[(row, column)] - jacobian[row * 3 + column]).abs() <= 1e-14);
            }
        }
        assert!((kinematics.poses()[0].origin - Vector3::zeros()).norm() == 0.0);
    }
}
