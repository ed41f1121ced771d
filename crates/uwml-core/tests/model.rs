//! Construction-time validation of the chain, the water and the coefficients.
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing)]

use uwml_core::nalgebra::Vector3;
use uwml_core::{Chain, Coefficients, Joint, Link, ModelError, Problem, Water};

fn paper_parts() -> ([Joint<f64>; 3], [Link<f64>; 3]) {
    let leg = Chain::<f64, 3>::paper();
    (*leg.joints(), *leg.links())
}

fn error_of(joints: [Joint<f64>; 3], links: [Link<f64>; 3]) -> ModelError {
    Chain::new(joints, links).unwrap_err()
}

#[test]
fn the_paper_preset_is_valid_and_matches_table_2() {
    let (joints, links) = paper_parts();
    assert_eq!(Chain::new(joints, links).unwrap(), Chain::paper());
    let thigh = links[1].segment.unwrap();
    let calf = links[2].segment.unwrap();
    assert_eq!((thigh.length, thigh.widths, calf.length, calf.widths), (0.660, [0.131, 0.238], 0.714, [0.131, 0.279]));
    assert_eq!(joints[2].origin, Vector3::new(0.660, 0.0, 0.0));
    assert_eq!(links.map(|l| l.mass), [10.758, 19.261, 10.375]);
    assert!((links[1].volume - 19.261 / 2700.0).abs() < 1e-18);
    assert!(links[0].segment.is_none());
}

#[test]
fn axes_must_be_unit_and_are_renormalized() {
    let (mut joints, links) = paper_parts();
    joints[1].axis = Vector3::new(0.0, -1.5, 0.0);
    let e = error_of(joints, links);
    assert_eq!((e.field, e.index, e.problem), ("joint.axis", Some(1), Problem::NotUnit));
    assert_eq!(e.to_string(), "joint 1: joint.axis must be a unit vector (norm 1 within 1e-6)");
    joints[1].axis = Vector3::zeros();
    assert_eq!(error_of(joints, links).problem, Problem::NotUnit);
    joints[1].axis = Vector3::new(0.0, -(1.0 + 5e-7), 0.0);
    let chain = Chain::new(joints, links).unwrap();
    assert_eq!(chain.joints()[1].axis, Vector3::new(0.0, -1.0, 0.0));
}

#[test]
fn non_finite_values_are_rejected() {
    let (mut joints, links) = paper_parts();
    joints[2].origin.x = f64::NAN;
    let e = error_of(joints, links);
    assert_eq!((e.field, e.index, e.problem), ("joint.origin", Some(2), Problem::NonFinite));
    let (joints, mut links) = paper_parts();
    links[0].com.z = f64::INFINITY;
    assert_eq!(error_of(joints, links).field, "link.com");
}

#[test]
fn segment_geometry_must_be_physical() {
    type Edit = fn(&mut uwml_core::Segment<f64>);
    let cases: [(Edit, &str, Problem); 6] = [
        (|s| s.length = 0.0, "segment.length", Problem::NonPositive),
        (|s| s.widths[1] = -0.1, "segment.widths[1]", Problem::NonPositive),
        (|s| s.area = 0.0, "segment.area", Problem::NonPositive),
        (|s| s.normals[0] = Vector3::new(1.0, 0.0, 0.0), "segment.normals[0]", Problem::NotPerpendicular),
        (|s| s.normals[1] = Vector3::new(0.0, 1.0, 0.0), "segment.normals[1]", Problem::NotPerpendicular),
        (|s| s.axis = Vector3::new(2.0, 0.0, 0.0), "segment.axis", Problem::NotUnit),
    ];
    for (edit, field, problem) in cases {
        let (joints, mut links) = paper_parts();
        let mut segment = links[1].segment.unwrap();
        edit(&mut segment);
        links[1].segment = Some(segment);
        let e = error_of(joints, links);
        assert_eq!((e.field, e.index, e.problem), (field, Some(1), problem));
        assert!(e.to_string().starts_with("link 1: "));
    }
}

#[test]
fn mass_and_volume_must_not_be_negative() {
    let (joints, mut links) = paper_parts();
    links[2].mass = -1.0;
    assert_eq!(error_of(joints, links).problem, Problem::Negative);
    let (joints, mut links) = paper_parts();
    links[2].volume = -1e-3;
    let e = error_of(joints, links);
    assert_eq!((e.field, e.index), ("link.volume", Some(2)));
    let (joints, mut links) = paper_parts();
    links[2].volume = 0.0;
    links[2].mass = 0.0;
    assert!(Chain::new(joints, links).is_ok());
}

#[test]
fn water_and_coefficients_are_validated() {
    assert_eq!(Water::new(0.0, 9.81).unwrap_err().problem, Problem::NonPositive);
    assert_eq!(Water::new(1000.0, -1.0).unwrap_err().problem, Problem::Negative);
    assert_eq!(Water::new(f64::NAN, 9.81).unwrap_err().problem, Problem::NonFinite);
    assert_eq!(Water::<f64>::default(), Water::new(1000.0, 9.81).unwrap());
    assert_eq!(Coefficients::<f64, 3>::uniform(-0.1, 0.5).unwrap_err().field, "cd");
    let e = Coefficients::<f64, 2>::per_direction([[1.0; 2]; 2], [[0.5, 0.5], [0.5, f64::NAN]]).unwrap_err();
    assert_eq!((e.field, e.index, e.problem), ("cm", Some(1), Problem::NonFinite));
    assert_eq!(Coefficients::<f64, 3>::default(), Coefficients::uniform(2.2, 0.5).unwrap());
}

#[test]
fn normals_within_the_tolerance_become_an_exact_frame() {
    // The strip integrals' identities assume an exact frame: normals accepted within
    // AXIS_TOLERANCE are made exactly orthonormal and perpendicular to the axis (Gram-Schmidt,
    // the second on the side it was given), not only renormalized.
    let (joints, mut links) = paper_parts();
    let mut segment = links[1].segment.unwrap();
    let [n0, n1] = segment.normals;
    let exact = (n0, n1, segment.axis);
    segment.normals = [(n0 + segment.axis * 5e-7).normalize(), (n1 + n0 * 5e-7 + segment.axis * 3e-7).normalize()];
    links[1].segment = Some(segment);
    let chain = Chain::new(joints, links).unwrap();
    let stored = chain.links()[1].segment.unwrap();
    let [m0, m1] = stored.normals;
    assert!(m0.dot(&exact.2).abs() < 1e-16 && m1.dot(&exact.2).abs() < 1e-16 && m0.dot(&m1).abs() < 1e-16);
    assert!((m0 - exact.0).norm() < 1e-15 && (m1 - exact.1).norm() < 1e-15);
    // The second normal keeps the side it was given.
    let (joints, mut links) = paper_parts();
    let mut flipped = links[1].segment.unwrap();
    flipped.normals[1] = -flipped.normals[1];
    links[1].segment = Some(flipped);
    let chain = Chain::new(joints, links).unwrap();
    assert!((chain.links()[1].segment.unwrap().normals[1] + exact.1).norm() < 1e-15);
}
