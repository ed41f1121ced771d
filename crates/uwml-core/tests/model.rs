//! Construction-time validation of a robot's parts (on the paper's leg), the water and the
//! coefficients.
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing, clippy::panic)]

use uwml_core::nalgebra::Vector3;
use uwml_core::{
    ModelError, Problem, RigidBody, Robot, RobotSegment, Section, SegmentCoefficients, TreeJoint, Water, presets,
};

type Parts = ([TreeJoint<f64>; 3], [RigidBody<f64>; 3], [RobotSegment<f64>; 2]);
type Leg = Robot<f64, 3, 2>;

fn paper_parts() -> Parts {
    let leg = presets::paper_leg::<f64>();
    (leg.joints().try_into().unwrap(), leg.links().try_into().unwrap(), leg.segments().try_into().unwrap())
}

fn build((joints, links, segments): Parts) -> Result<Leg, ModelError> {
    Leg::new(&joints, &links, RigidBody::empty(), &segments)
}

fn error_of(parts: Parts) -> ModelError {
    build(parts).unwrap_err()
}

/// The two normals of a rectangular segment.
fn normals(segment: &RobotSegment<f64>) -> [uwml_core::nalgebra::Vector3<f64>; 2] {
    match segment.section {
        Section::Rectangular { normals, .. } => normals,
        Section::Circular { .. } => panic!("the paper's segments are rectangular"),
    }
}

fn set_normals(segment: &mut RobotSegment<f64>, new: [uwml_core::nalgebra::Vector3<f64>; 2]) {
    if let Section::Rectangular { normals, .. } = &mut segment.section {
        *normals = new;
    }
}

#[test]
fn the_paper_preset_is_valid_and_matches_table_2() {
    let parts = paper_parts();
    assert_eq!(build(parts).unwrap(), presets::paper_leg());
    let (joints, links, [thigh, calf]) = parts;
    let widths = |s: &RobotSegment<f64>| match s.section {
        Section::Rectangular { widths, .. } => widths,
        Section::Circular { .. } => [0.0; 2],
    };
    assert_eq!(
        (thigh.length, widths(&thigh), calf.length, widths(&calf)),
        (0.660, [0.131, 0.238], 0.714, [0.131, 0.279])
    );
    assert_eq!((thigh.owner, calf.owner), (uwml_core::Owner::Link(1), uwml_core::Owner::Link(2)));
    assert_eq!((thigh.cd, thigh.cm, calf.cd, calf.cm), ([2.2; 2], [0.5; 2], [2.2; 2], [0.5; 2]));
    assert_eq!(joints[2].origin, Vector3::new(0.660, 0.0, 0.0));
    assert_eq!(joints.map(|j| j.parent), [None, Some(0), Some(1)]);
    assert_eq!(links.map(|l| l.mass), [10.758, 19.261, 10.375]);
    assert!((links[1].volume - 19.261 / 2700.0).abs() < 1e-18);
}

#[test]
fn axes_must_be_unit_and_are_renormalized() {
    let mut parts = paper_parts();
    parts.0[1].axis = Vector3::new(0.0, -1.5, 0.0);
    let e = error_of(parts);
    assert_eq!((e.field, e.index, e.problem), ("joint.axis", Some(1), Problem::NotUnit));
    assert_eq!(e.to_string(), "joint 1: joint.axis must be a unit vector (norm 1 within 1e-6)");
    parts.0[1].axis = Vector3::zeros();
    assert_eq!(error_of(parts).problem, Problem::NotUnit);
    parts.0[1].axis = Vector3::new(0.0, -(1.0 + 5e-7), 0.0);
    assert_eq!(build(parts).unwrap().joints()[1].axis, Vector3::new(0.0, -1.0, 0.0));
}

#[test]
fn non_finite_values_are_rejected() {
    let mut parts = paper_parts();
    parts.0[2].origin.x = f64::NAN;
    let e = error_of(parts);
    assert_eq!((e.field, e.index, e.problem), ("joint.origin", Some(2), Problem::NonFinite));
    let mut parts = paper_parts();
    parts.1[0].com.z = f64::INFINITY;
    assert_eq!(error_of(parts).field, "link.com");
}

#[test]
fn segment_geometry_must_be_physical() {
    type Edit = fn(&mut RobotSegment<f64>);
    let cases: [(Edit, &str, Problem); 6] = [
        (|s| s.length = 0.0, "segment.length", Problem::NonPositive),
        (
            |s| s.section = Section::Rectangular { normals: normals(s), widths: [0.1, -0.1] },
            "segment.widths[1]",
            Problem::NonPositive,
        ),
        (|s| s.area = 0.0, "segment.area", Problem::NonPositive),
        (
            |s| set_normals(s, [Vector3::new(0.0, 0.0, 1.0), normals(s)[1]]),
            "segment.normals[0]",
            Problem::NotPerpendicular,
        ),
        (
            |s| set_normals(s, [normals(s)[0], Vector3::new(0.0, 1.0, 0.0)]),
            "segment.normals[1]",
            Problem::NotPerpendicular,
        ),
        (|s| s.axis = Vector3::new(0.0, 0.0, -2.0), "segment.axis", Problem::NotUnit),
    ];
    for (edit, field, problem) in cases {
        let mut parts = paper_parts();
        edit(&mut parts.2[1]);
        let e = error_of(parts);
        assert_eq!((e.field, e.index, e.problem), (field, Some(1), problem));
        assert!(e.to_string().starts_with("segment 1: "), "{e}");
    }
}

#[test]
fn mass_and_volume_must_not_be_negative() {
    let mut parts = paper_parts();
    parts.1[2].mass = -1.0;
    assert_eq!(error_of(parts).problem, Problem::Negative);
    let mut parts = paper_parts();
    parts.1[2].volume = -1e-3;
    let e = error_of(parts);
    assert_eq!((e.field, e.index), ("link.volume", Some(2)));
    let mut parts = paper_parts();
    parts.1[2].volume = 0.0;
    parts.1[2].mass = 0.0;
    assert!(build(parts).is_ok());
}

#[test]
fn water_and_coefficients_are_validated() {
    assert_eq!(Water::new(0.0, 9.81).unwrap_err().problem, Problem::NonPositive);
    assert_eq!(Water::new(1000.0, -1.0).unwrap_err().problem, Problem::Negative);
    assert_eq!(Water::new(f64::NAN, 9.81).unwrap_err().problem, Problem::NonFinite);
    assert_eq!(Water::<f64>::default(), Water::new(1000.0, 9.81).unwrap());
    assert_eq!(SegmentCoefficients::<f64, 3>::uniform(-0.1, 0.5).unwrap_err().field, "segment.cd");
    let e = SegmentCoefficients::<f64, 2>::per_segment([[1.0; 2]; 2], [[0.5, 0.5], [0.5, f64::NAN]]).unwrap_err();
    assert_eq!((e.field, e.index, e.problem), ("segment.cm", Some(1), Problem::NonFinite));
    assert_eq!(presets::paper_leg::<f64>().coefficients(), SegmentCoefficients::uniform(2.2, 0.5).unwrap());
}

#[test]
fn normals_within_the_tolerance_become_an_exact_frame() {
    // The strip integrals' identities assume an exact frame: normals accepted within
    // AXIS_TOLERANCE are made exactly orthonormal and perpendicular to the axis (Gram-Schmidt,
    // the second on the side it was given), not only renormalized.
    let mut parts = paper_parts();
    let segment = &mut parts.2[0];
    let [n0, n1] = normals(segment);
    let exact = (n0, n1, segment.axis);
    let axis = segment.axis;
    set_normals(segment, [(n0 + axis * 5e-7).normalize(), (n1 + n0 * 5e-7 + axis * 3e-7).normalize()]);
    let [m0, m1] = normals(&build(parts).unwrap().segments()[0]);
    assert!(m0.dot(&exact.2).abs() < 1e-16 && m1.dot(&exact.2).abs() < 1e-16 && m0.dot(&m1).abs() < 1e-16);
    assert!((m0 - exact.0).norm() < 1e-15 && (m1 - exact.1).norm() < 1e-15);
    // The second normal keeps the side it was given.
    let mut parts = paper_parts();
    let [n0, n1] = normals(&parts.2[0]);
    set_normals(&mut parts.2[0], [n0, -n1]);
    assert!((normals(&build(parts).unwrap().segments()[0])[1] + exact.1).norm() < 1e-15);
}
