//! The Rust constants `uwml export --rust` writes (`tests/exported/arm_on_rov.rs`, for the arm of
//! `uwml.examples.arm_on_rov`, kept equal to the exporter's output by `tests/test_export.py`)
//! compile, build a valid robot, and give the forces of the same arm built here by hand
//! (`benches/common/arm.rs`).
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing)]

use uwml_core::{Robot, RobotData, Water, robot_hydro};

mod exported {
    include!("exported/arm_on_rov.rs");
}

#[path = "../benches/common/arm.rs"]
mod arm;

#[test]
fn the_exported_arm_is_the_arm() {
    let exported = Robot::<f64, { exported::N_JOINTS }, { exported::N_SEGMENTS }>::new(
        &exported::JOINTS,
        &exported::LINKS,
        exported::BASE,
        &exported::SEGMENTS,
    )
    .unwrap();
    let by_hand = arm::arm_on_rov::<f64, 7, 15>();
    let (motion, current) = arm::rov_motion::<f64>();
    let q = [0.3, -0.4, 0.6, 0.2, -0.5, 0.1, 0.05];
    let qd = [0.5, 0.3, -0.4, 0.8, 0.2, -0.6, 0.02];
    let qdd = [1.0, -0.5, 0.3, 0.2, -1.0, 0.7, 0.1];
    let (mut a, mut b) = (RobotData::new(), RobotData::new());
    robot_hydro(&exported, &Water::default(), None, &motion, &current, &q, &qd, &qdd, &mut a);
    robot_hydro(&by_hand, &Water::default(), None, &motion, &current, &q, &qd, &qdd, &mut b);
    let scale = b.joint_forces().iter().fold(1.0_f64, |m, f| m.max(f.total().abs()));
    for (x, y) in a.joint_forces().iter().zip(b.joint_forces()) {
        assert!((x.total() - y.total()).abs() <= 1e-12 * scale, "{} vs {}", x.total(), y.total());
        assert!((x.gravity - y.gravity).abs() <= 1e-12 * scale);
    }
    let (wa, wb) = (a.base_wrench().total().to_array(), b.base_wrench().total().to_array());
    let base_scale = wb.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
    for (x, y) in wa.iter().zip(wb) {
        assert!((x - y).abs() <= 1e-12 * base_scale, "{x} vs {y}");
    }
}
