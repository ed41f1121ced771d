//! The axial drag of a segment (docs/model.md section 12.2): its closed form on a segment moving
//! along, across and obliquely to its axis, turning about its own axis (no axial speed: none), with
//! the water (none), and zero unless given. The rest (the numpy reference on random trees with
//! axial drag, Galilean and frame invariance) is in `robot.rs` and the Python tests.
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing, clippy::expect_used)]

use uwml_core::nalgebra::Vector3;
use uwml_core::{
    BaseMotion, Conditions, Current, JointKind, Owner, RigidBody, Robot, RobotData, RobotSegment, Section, TreeJoint,
    Water, robot_hydro,
};

type Model = Robot<f64, 2, 2>;

/// A base carrying one circular segment along `axis` from `start`, without cross-flow drag (so
/// that the drag is the axial drag alone), and one idle joint.
fn robot(start: Vector3<f64>, axis: Vector3<f64>, cd_axial: f64, axial_area: f64) -> Model {
    let joint = TreeJoint { parent: None, kind: JointKind::Revolute, origin: Vector3::zeros(), axis: Vector3::z() };
    let segment = RobotSegment {
        owner: Owner::Base,
        start,
        axis,
        length: 0.8,
        area: 0.02,
        section: Section::Circular { diameter: 0.16 },
        cd: [0.0; 2],
        cm: [0.0; 2],
        cd_axial,
        axial_area,
    };
    Model::new(&[joint], &[RigidBody::empty()], RigidBody::empty(), &[segment]).unwrap()
}

fn base_drag(robot: &Model, velocity: Vector3<f64>, angular_velocity: Vector3<f64>, current: Vector3<f64>) -> [f64; 6] {
    let motion =
        BaseMotion::new([1.0, 0.0, 0.0, 0.0], velocity, angular_velocity, Vector3::zeros(), Vector3::zeros()).unwrap();
    let conditions = Conditions {
        motion,
        current: Current::new(current, Vector3::zeros()).unwrap(),
        ..Conditions::new(Water::new(1025.0, 9.81).unwrap())
    };
    let mut data = RobotData::new();
    robot_hydro(robot, &conditions, [&[0.0; 2], &[0.0; 2], &[0.0; 2]], &mut data);
    data.base_wrench().drag.to_array()
}

#[test]
fn the_axial_drag_is_its_closed_form_along_the_axis_through_the_midpoint() {
    let (cd_axial, area, rho) = (0.9, 0.015, 1025.0);
    let axis = Vector3::new(2.0, -1.0, 2.0) / 3.0;
    let start = Vector3::new(0.1, 0.2, -0.3);
    let robot = robot(start, axis, cd_axial, area);
    for velocity in [axis * 1.5, -axis * 0.7, Vector3::new(0.3, -0.8, 0.5)] {
        let speed = axis.dot(&velocity);
        let force = axis * (-0.5 * rho * cd_axial * area * speed.abs() * speed);
        let moment = (start + axis * 0.4).cross(&force);
        let drag = base_drag(&robot, velocity, Vector3::zeros(), Vector3::zeros());
        let expected = [force.x, force.y, force.z, moment.x, moment.y, moment.z];
        for (got, want) in drag.iter().zip(expected) {
            assert!((got - want).abs() <= 1e-12 * (1.0 + want.abs()), "{drag:?} vs {expected:?}");
        }
    }
}

#[test]
fn no_axial_drag_without_axial_motion_relative_to_the_water_or_without_a_coefficient() {
    let axis = Vector3::x();
    let with = robot(Vector3::new(-0.4, 0.0, 0.0), axis, 0.9, 0.015);
    // Across the axis only, turning about it, or moving with the water: nothing (no cross-flow
    // drag either, cd = 0).
    for (velocity, angular_velocity, current) in [
        (Vector3::new(0.0, 1.0, -0.5), Vector3::zeros(), Vector3::zeros()),
        (Vector3::zeros(), Vector3::new(2.0, 0.0, 0.0), Vector3::zeros()),
        (Vector3::new(1.2, 0.0, 0.0), Vector3::zeros(), Vector3::new(1.2, 0.0, 0.0)),
    ] {
        assert_eq!(base_drag(&with, velocity, angular_velocity, current), [0.0; 6]);
    }
    // A current along the axis drags the segment with it: the relative velocity counts.
    let drag = base_drag(&with, Vector3::zeros(), Vector3::zeros(), Vector3::new(-2.0, 0.0, 0.0));
    assert!(drag[0] < 0.0 && (drag[0] + 0.5 * 1025.0 * 0.9 * 0.015 * 4.0).abs() < 1e-12, "{drag:?}");
    // Zero coefficient or zero area: none.
    for robot in [robot(Vector3::zeros(), axis, 0.0, 0.015), robot(Vector3::zeros(), axis, 0.9, 0.0)] {
        assert_eq!(base_drag(&robot, Vector3::new(3.0, 0.0, 0.0), Vector3::zeros(), Vector3::zeros()), [0.0; 6]);
    }
}

#[test]
fn bad_axial_drag_is_refused_naming_the_segment() {
    let joint = TreeJoint { parent: None, kind: JointKind::Revolute, origin: Vector3::zeros(), axis: Vector3::z() };
    let good = RobotSegment {
        owner: Owner::Base,
        start: Vector3::zeros(),
        axis: Vector3::x(),
        length: 1.0,
        area: 0.01,
        section: Section::Circular { diameter: 0.1 },
        cd: [1.0; 2],
        cm: [1.0; 2],
        cd_axial: 0.5,
        axial_area: 0.01,
    };
    for (segment, field) in [
        (RobotSegment { cd_axial: -0.1, ..good }, "segment.cd_axial"),
        (RobotSegment { cd_axial: f64::NAN, ..good }, "segment.cd_axial"),
        (RobotSegment { cd_axial: 2e3, ..good }, "segment.cd_axial"),
        (RobotSegment { axial_area: -1.0, ..good }, "segment.axial_area"),
        (RobotSegment { axial_area: 1e9, ..good }, "segment.axial_area"),
    ] {
        let error = Model::new(&[joint], &[RigidBody::empty()], RigidBody::empty(), &[good, segment]).unwrap_err();
        assert_eq!((error.field, error.index), (field, Some(1)));
    }
}
