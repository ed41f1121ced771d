//! Whole robots (docs/model.md section 10) at construction: malformed models and motions are
//! errors naming the field and index, model values beyond their bounds (docs/domains.md, "Model
//! values") are refused, and at the bounds every force of an ordinary state is finite.
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing, clippy::expect_used)]

use uwml_core::nalgebra::{Matrix3, Vector3};
use uwml_core::{
    BaseMotion, Current, JointKind, Owner, Problem, RigidBody, Robot, RobotData, RobotSegment, Section,
    SegmentCoefficients, TreeJoint, Water, robot_hydro,
};

const J: usize = 12;
const S: usize = 16;
type Model = Robot<f64, J, S>;

#[test]
fn bad_models_and_motions_are_errors_naming_the_field() {
    let joint = TreeJoint { parent: None, kind: JointKind::Revolute, origin: Vector3::zeros(), axis: Vector3::z() };
    let body = RigidBody::empty();
    // A parent that is not an earlier link.
    let bad = [joint, TreeJoint { parent: Some(1), ..joint }];
    let error = Model::new(&bad, &[body; 2], body, &[]).unwrap_err();
    assert_eq!((error.field, error.index, error.problem), ("joint.parent", Some(1), Problem::OutOfRange));
    // Too many joints for the capacity.
    let error = Robot::<f64, 1, 1>::new(&[joint; 2], &[body; 2], body, &[]).unwrap_err();
    assert_eq!(error.field, "joints");
    // A segment on a link that does not exist.
    let segment = RobotSegment {
        owner: Owner::Link(3),
        start: Vector3::zeros(),
        axis: Vector3::x(),
        length: 1.0,
        area: 0.01,
        section: Section::Circular { diameter: 0.1 },
        cd: [1.2; 2],
        cm: [1.0; 2],
        cd_axial: 0.0,
        axial_area: 0.0,
    };
    let error = Model::new(&[joint], &[body], body, &[segment]).unwrap_err();
    assert_eq!((error.field, error.index), ("segment.owner", Some(0)));
    // A circular segment with two drag coefficients.
    let error = Model::new(&[joint], &[body], body, &[RobotSegment { owner: Owner::Base, cd: [1.0, 2.0], ..segment }])
        .unwrap_err();
    assert_eq!(error.field, "segment.cd");
    // NaN coefficients are non-finite, whatever the section; the base's fields are named `base.*`.
    let error =
        Model::new(&[joint], &[body], body, &[RobotSegment { owner: Owner::Base, cd: [f64::NAN; 2], ..segment }])
            .unwrap_err();
    assert_eq!((error.field, error.problem), ("segment.cd", Problem::NonFinite));
    let error = Model::new(&[joint], &[body], RigidBody { mass: -1.0, ..body }, &[]).unwrap_err();
    assert_eq!((error.field, error.index, error.problem), ("base.mass", None, Problem::Negative));
    let error = Model::new(&[joint], &[RigidBody { volume: -1.0, ..body }], body, &[]).unwrap_err();
    assert_eq!((error.field, error.index), ("link.volume", Some(0)));
    assert_eq!(
        Model::new(&[joint], &[body], body, &[RobotSegment { owner: Owner::Link(4), ..segment }])
            .unwrap_err()
            .to_string(),
        "segment 0: segment.owner is outside its allowed range"
    );
    // Zero, non-unit and non-finite orientations; non-finite motion and current.
    let zero = Vector3::zeros();
    for (orientation, problem) in [
        ([0.0; 4], Problem::NotUnit),
        ([1.0, 0.1, 0.0, 0.0], Problem::NotUnit),
        ([f64::NAN, 0.0, 0.0, 0.0], Problem::NonFinite),
    ] {
        let error = BaseMotion::new(orientation, zero, zero, zero, zero).unwrap_err();
        assert_eq!((error.field, error.problem), ("base.orientation", problem));
    }
    let inf = Vector3::new(0.0, f64::INFINITY, 0.0);
    assert_eq!(
        BaseMotion::new([1.0, 0.0, 0.0, 0.0], zero, zero, zero, inf).unwrap_err().field,
        "base.angular_acceleration"
    );
    assert_eq!(Current::new(zero, inf).unwrap_err().field, "current.acceleration");
    // A quaternion within tolerance of unit is normalized exactly.
    let motion = BaseMotion::new([1.0 + 1e-9, 0.0, 0.0, 0.0], zero, zero, zero, zero).unwrap();
    assert_eq!(*motion.rotation(), Matrix3::identity());
}

#[test]
fn model_values_beyond_their_bounds_are_refused_and_at_the_bounds_forces_stay_finite() {
    use uwml_core::{
        Conditions, MAX_AREA, MAX_COEFFICIENT, MAX_DENSITY, MAX_GRAVITY, MAX_LENGTH, MAX_MASS, MAX_VOLUME,
    };
    let joint = TreeJoint { parent: None, kind: JointKind::Revolute, origin: Vector3::zeros(), axis: Vector3::z() };
    let body = RigidBody { mass: 2.0, com: Vector3::new(0.1, 0.0, 0.0), volume: 0.001, cob: Vector3::zeros() };
    let segment = RobotSegment {
        owner: Owner::Link(0),
        start: Vector3::zeros(),
        axis: Vector3::x(),
        length: 1.0,
        area: 0.01,
        section: Section::Circular { diameter: 0.1 },
        cd: [1.2; 2],
        cm: [1.0; 2],
        cd_axial: 0.0,
        axial_area: 0.0,
    };
    let refused = |joints: &[TreeJoint<f64>], links: &[RigidBody<f64>], base, segments: &[RobotSegment<f64>]| {
        let error = Model::new(joints, links, base, segments).unwrap_err();
        assert_eq!(error.problem, Problem::TooLarge, "{error}");
        (error.field, error.index, error.to_string())
    };
    // A finite but huge centre of mass gave NaN and infinite forces: now an error at construction.
    let (field, index, message) =
        refused(&[joint], &[RigidBody { com: Vector3::new(1e308, 0.0, 0.0), ..body }], body, &[]);
    assert_eq!((field, index), ("link.com", Some(0)));
    assert_eq!(message, "link 0: link.com must be at most 1e4 m in magnitude (each coordinate or length)");
    let far = Vector3::new(0.0, -1.0001 * MAX_LENGTH, 0.0);
    assert_eq!(refused(&[TreeJoint { origin: far, ..joint }], &[body], body, &[]).0, "joint.origin");
    assert_eq!(refused(&[joint], &[body], RigidBody { cob: far, ..body }, &[]).0, "base.cob");
    assert_eq!(
        refused(&[joint], &[RigidBody { mass: 1.01 * MAX_MASS, ..body }], body, &[]).2,
        "link 0: link.mass must be at most 1e9 kg"
    );
    assert_eq!(refused(&[joint], &[body], RigidBody { volume: 1.01 * MAX_VOLUME, ..body }, &[]).0, "base.volume");
    for bad in [
        RobotSegment { start: far, ..segment },
        RobotSegment { length: 2.0 * MAX_LENGTH, ..segment },
        RobotSegment { area: 2.0 * MAX_AREA, ..segment },
        RobotSegment { section: Section::Circular { diameter: 2.0 * MAX_LENGTH }, ..segment },
        RobotSegment { cd: [2.0 * MAX_COEFFICIENT; 2], ..segment },
        RobotSegment { cm: [2.0 * MAX_COEFFICIENT; 2], ..segment },
    ] {
        refused(&[joint], &[body], body, &[bad]);
    }
    assert_eq!(Water::new(2.0 * MAX_DENSITY, 9.81).unwrap_err().problem, Problem::TooLarge);
    assert_eq!(Water::new(1025.0, 2.0 * MAX_GRAVITY).unwrap_err().problem, Problem::TooLarge);
    let table = SegmentCoefficients::<f64, S>::per_segment([[2.0 * MAX_COEFFICIENT; 2]; S], [[1.0; 2]; S]);
    assert_eq!(table.unwrap_err().problem, Problem::TooLarge);

    // Everything at its bound, in the densest, heaviest water, at a brisk state: finite forces.
    let corner = Vector3::new(MAX_LENGTH, -MAX_LENGTH, MAX_LENGTH);
    let heavy = RigidBody { mass: MAX_MASS, com: corner, volume: MAX_VOLUME, cob: -corner };
    let joints = [
        TreeJoint { origin: corner, ..joint },
        TreeJoint { parent: Some(0), origin: corner, axis: Vector3::y(), ..joint },
    ];
    let big = RobotSegment {
        start: corner,
        length: MAX_LENGTH,
        area: MAX_AREA,
        section: Section::Circular { diameter: MAX_LENGTH },
        cd: [MAX_COEFFICIENT; 2],
        cm: [MAX_COEFFICIENT; 2],
        ..segment
    };
    let robot = Model::new(
        &joints,
        &[heavy; 2],
        heavy,
        &[big, RobotSegment { owner: Owner::Link(1), ..big }, RobotSegment { owner: Owner::Base, ..big }],
    )
    .unwrap();
    let water = Water::new(MAX_DENSITY, MAX_GRAVITY).unwrap();
    let motion = BaseMotion::new(
        [1.0, 0.0, 0.0, 0.0],
        Vector3::new(3.0, 0.0, 1.0),
        Vector3::new(0.0, 0.5, 0.0),
        Vector3::zeros(),
        Vector3::zeros(),
    )
    .unwrap();
    let current = Current::new(Vector3::new(2.0, 1.0, 0.0), Vector3::new(0.1, 0.0, 0.0)).unwrap();
    let mut q = [0.0; J];
    let (mut qd, mut qdd) = ([0.0; J], [0.0; J]);
    (q[0], q[1], qd[0], qd[1], qdd[0], qdd[1]) = (0.3, -0.7, 2.0, -1.5, 3.0, 1.0);
    let mut data = RobotData::new();
    robot_hydro(&robot, &Conditions { motion, current, ..Conditions::new(water) }, [&q, &qd, &qdd], &mut data);
    let joint_forces = data.joint_forces().iter().flat_map(|f| [f.total(), f.gravity]);
    let base = data.base_wrench();
    assert!(joint_forces.chain(base.total().to_array()).chain(base.gravity.to_array()).all(f64::is_finite));
}

#[test]
fn a_coefficient_table_starts_from_the_segments_own_and_refuses_bad_entries_naming_the_segment() {
    let joint = TreeJoint { parent: None, kind: JointKind::Revolute, origin: Vector3::zeros(), axis: Vector3::z() };
    let body = RigidBody::empty();
    let segment = RobotSegment {
        owner: Owner::Link(0),
        start: Vector3::zeros(),
        axis: Vector3::x(),
        length: 1.0,
        area: 0.01,
        section: Section::Rectangular { widths: [0.1, 0.2], normals: [Vector3::y(), Vector3::z()] },
        cd: [1.2, 1.4],
        cm: [0.8, 0.9],
        cd_axial: 0.0,
        axial_area: 0.0,
    };
    let other = RobotSegment { cd: [2.0; 2], cm: [0.5; 2], ..segment };
    let robot = Model::new(&[joint], &[body], body, &[segment, other]).unwrap();
    let mut table = robot.coefficients();
    assert_eq!(
        (table.cd()[0], table.cm()[0], table.cd()[1], table.cm()[1]),
        ([1.2, 1.4], [0.8, 0.9], [2.0; 2], [0.5; 2])
    );
    assert_eq!(table.cd()[2..], [[0.0; 2]; S - 2]);
    table.set(1, [3.0, 3.5], [0.25; 2]).unwrap();
    assert_eq!((table.cd()[1], table.cm()[1], table.cd()[0]), ([3.0, 3.5], [0.25; 2], [1.2, 1.4]));
    let before = table;
    for (cd, cm, field, problem) in [
        ([-1.0, 1.0], [1.0; 2], "segment.cd", Problem::Negative),
        ([1.0; 2], [1.0, f64::NAN], "segment.cm", Problem::NonFinite),
        ([2.0 * uwml_core::MAX_COEFFICIENT, 1.0], [1.0; 2], "segment.cd", Problem::TooLarge),
    ] {
        let error = table.set(1, cd, cm).unwrap_err();
        assert_eq!((error.field, error.index, error.problem), (field, Some(1), problem));
    }
    let error = table.set(S, [1.0; 2], [1.0; 2]).unwrap_err();
    assert_eq!((error.field, error.index, error.problem), ("segment.cd", Some(S), Problem::OutOfRange));
    assert_eq!(table, before);
}
