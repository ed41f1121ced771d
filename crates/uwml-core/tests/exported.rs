//! The Rust constants `uwml export --rust` writes (`tests/exported/arm_on_rov.rs`, for the arm of
//! `uwml.examples.arm_on_rov`, kept equal to the exporter's output by `tests/test_export.py`)
//! compile, build a valid robot, and give the forces of the same arm built here by hand
//! (`benches/common/arm.rs`); the f32 constants (`--f32`, `tests/exported/arm_on_rov_f32.rs`)
//! build the same robot in single precision.
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing)]

use uwml_core::{Conditions, Robot, RobotData, Water, robot_hydro};

mod exported {
    include!("exported/arm_on_rov.rs");
}

mod exported_f32 {
    include!("exported/arm_on_rov_f32.rs");
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
    let water = Water::new(exported::WATER_DENSITY, exported::GRAVITY).unwrap();
    assert_eq!(water, Water::default());
    robot_hydro(&exported, &Conditions { motion, current, ..Conditions::new(water) }, [&q, &qd, &qdd], &mut a);
    robot_hydro(
        &by_hand,
        &Conditions { motion, current, ..Conditions::new(Water::default()) },
        [&q, &qd, &qdd],
        &mut b,
    );
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

#[test]
fn the_f32_export_is_the_arm_in_single_precision() {
    let exported = Robot::<f32, { exported_f32::N_JOINTS }, { exported_f32::N_SEGMENTS }>::new(
        &exported_f32::JOINTS,
        &exported_f32::LINKS,
        exported_f32::BASE,
        &exported_f32::SEGMENTS,
    )
    .unwrap();
    let by_hand = arm::arm_on_rov::<f64, 7, 15>();
    let water = Water::new(exported_f32::WATER_DENSITY, exported_f32::GRAVITY).unwrap();
    let (motion32, current32) = arm::rov_motion::<f32>();
    let (motion, current) = arm::rov_motion::<f64>();
    let q = [0.3, -0.4, 0.6, 0.2, -0.5, 0.1, 0.05];
    let qd = [0.5, 0.3, -0.4, 0.8, 0.2, -0.6, 0.02];
    let qdd = [1.0, -0.5, 0.3, 0.2, -1.0, 0.7, 0.1];
    let single = |x: &[f64; 7]| x.map(|v| v as f32);
    let (mut a, mut b) = (RobotData::<f32, 7>::new(), RobotData::new());
    robot_hydro(
        &exported,
        &Conditions { motion: motion32, current: current32, ..Conditions::new(water) },
        [&single(&q), &single(&qd), &single(&qdd)],
        &mut a,
    );
    robot_hydro(
        &by_hand,
        &Conditions { motion, current, ..Conditions::new(Water::default()) },
        [&q, &qd, &qdd],
        &mut b,
    );
    // Single precision carries ~1e-7 relative per operation; the sums here stay within 1e-4 of
    // the largest force.
    let scale = b.joint_forces().iter().fold(1.0_f64, |m, f| m.max(f.total().abs()));
    for (x, y) in a.joint_forces().iter().zip(b.joint_forces()) {
        assert!((f64::from(x.total()) - y.total()).abs() <= 1e-4 * scale, "{} vs {}", x.total(), y.total());
    }
    let (wa, wb) = (a.base_wrench().total().to_array(), b.base_wrench().total().to_array());
    let base_scale = wb.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
    for (x, y) in wa.iter().zip(wb) {
        assert!((f64::from(*x) - y).abs() <= 1e-4 * base_scale, "{x} vs {y}");
    }
}
