//! The checks of a lumped model (docs/model.md section 12.1) when a robot takes it: the model and
//! the field named, singular semi-definite matrices taken and slightly indefinite ones refused,
//! no huge entry hiding a negative eigenvalue or an asymmetry, rounding at the cap, f32 judged as
//! f64.
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing, clippy::expect_used)]

use uwml_core::nalgebra::{Matrix3, Matrix6, Vector3};
use uwml_core::{JointKind, LumpedBody, Owner, Problem, RigidBody, Robot, TreeJoint};

mod common;
use common::{Rng, random_psd};

const J: usize = 12;
const S: usize = 16;
type Model = Robot<f64, J, S, 4>;

/// A robot of one revolute joint, no segments, empty bodies.
fn one_joint() -> Model {
    let joint = TreeJoint { parent: None, kind: JointKind::Revolute, origin: Vector3::zeros(), axis: Vector3::z() };
    Model::new(&[joint], &[RigidBody::empty()], RigidBody::empty(), &[]).unwrap()
}

#[test]
fn bad_lumped_models_are_refused_naming_the_model_and_the_field() {
    let robot = one_joint();
    let good = LumpedBody::none(Owner::Link(0));
    let refused = |bodies: &[LumpedBody<f64>]| {
        let e = robot.with_lumped(bodies).unwrap_err();
        (e.field, e.index, e.problem)
    };
    let mut asymmetric = Matrix6::identity();
    asymmetric[(0, 1)] = 0.5;
    let mut indefinite = Matrix6::identity();
    indefinite[(2, 2)] = -1e-3;
    // Symmetric with a positive diagonal, yet indefinite: a coupling larger than the diagonal.
    let mut coupled = Matrix6::identity();
    coupled[(0, 4)] = 2.0;
    coupled[(4, 0)] = 2.0;
    let mut feeding = Matrix6::zeros();
    feeding[(1, 1)] = -2.0;
    let cases = [
        (LumpedBody { owner: Owner::Link(1), ..good }, ("lumped.owner", Some(0), Problem::OutOfRange)),
        (LumpedBody { added_mass: asymmetric, ..good }, ("lumped.added_mass", Some(0), Problem::NotSymmetric)),
        (
            LumpedBody { added_mass: indefinite, ..good },
            ("lumped.added_mass", Some(0), Problem::NotPositiveSemidefinite),
        ),
        (LumpedBody { added_mass: coupled, ..good }, ("lumped.added_mass", Some(0), Problem::NotPositiveSemidefinite)),
        (
            LumpedBody { linear_damping: feeding, ..good },
            ("lumped.linear_damping", Some(0), Problem::NotPositiveSemidefinite),
        ),
        (
            LumpedBody { quadratic_damping: [0.0, 0.0, -1.0, 0.0, 0.0, 0.0], ..good },
            ("lumped.quadratic_damping", Some(0), Problem::Negative),
        ),
        (LumpedBody { point: Vector3::new(f64::NAN, 0.0, 0.0), ..good }, ("lumped.point", Some(0), Problem::NonFinite)),
        (
            LumpedBody { added_mass: Matrix6::identity() * 1e13, ..good },
            ("lumped.added_mass", Some(0), Problem::TooLarge),
        ),
        (LumpedBody { axes: Matrix3::identity() * 2.0, ..good }, ("lumped.axes", Some(0), Problem::NotUnit)),
        (
            LumpedBody { axes: Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, -1.0)), ..good },
            ("lumped.axes", Some(0), Problem::OutOfRange),
        ),
    ];
    for (body, expected) in cases {
        assert_eq!(refused(&[body]), expected);
    }
    // Two on one body; the second named.
    assert_eq!(refused(&[good, good]), ("lumped.owner", Some(1), Problem::OutOfRange));
    let message = robot.with_lumped(&[LumpedBody { added_mass: indefinite, ..good }]).unwrap_err().to_string();
    assert_eq!(
        message,
        "lumped model 0: lumped.added_mass must be positive semi-definite (no direction of negative energy): \
         its smallest eigenvalue at least -min(1e-10 x its largest diagonal entry, 1e-2)"
    );
    // A positive semi-definite matrix of lower rank, and one symmetric to rounding, are taken.
    let mut rng = Rng(21);
    let singular = random_psd(&mut rng, 2, 30.0);
    let mut rounded = singular;
    rounded[(0, 3)] += 1e-14;
    robot.with_lumped(&[LumpedBody { added_mass: rounded, ..good }]).unwrap();
}

#[test]
fn singular_semidefinite_matrices_are_taken_and_slightly_indefinite_ones_refused() {
    // A Aᵀ of every rank, at scales from 1e-3 to 1e6, as added mass and as the symmetric part of a
    // damping with a skew part: taken; a singular one less 1e-6 of its scale on the diagonal:
    // refused.
    let robot = one_joint();
    let mut rng = Rng(29);
    for rank in 0..=6 {
        for scale in [1e-3, 1.0, 1e6] {
            let psd = random_psd(&mut rng, rank, scale);
            let skew = {
                let a: Matrix6<f64> = Matrix6::from_fn(|_, _| scale * rng.next());
                a - a.transpose()
            };
            let good = LumpedBody { added_mass: psd, linear_damping: psd + skew, ..LumpedBody::none(Owner::Base) };
            robot.with_lumped(&[good]).unwrap();
            if rank < 6 {
                // Singular: a zero eigenvalue, made slightly negative.
                let size = psd.diagonal().amax().max(scale);
                let bad = psd - Matrix6::identity() * (1e-6 * size);
                let error = robot.with_lumped(&[LumpedBody { added_mass: bad, ..good }]).unwrap_err();
                assert_eq!((error.field, error.problem), ("lumped.added_mass", Problem::NotPositiveSemidefinite));
            }
        }
    }
}

/// `diag(head, 1, …)`.
fn diag_from(head: &[f64]) -> Matrix6<f64> {
    Matrix6::from_fn(|r, c| if r == c { head.get(r).copied().unwrap_or(1.0) } else { 0.0 })
}

#[test]
fn a_huge_entry_hides_no_negative_eigenvalue_or_asymmetry() {
    // Issue 31: with tolerances relative to the largest entry alone, diag(1e12, −99, …) was taken
    // (−99 ≥ −1e-10·1e12) and an asymmetry of 900 at 1e12 averaged away (900 ≤ 1e-9·1e12). The
    // absolute floor LUMPED_ABSOLUTE_TOLERANCE bounds both, in f64 and f32 alike.
    use uwml_core::{LUMPED_ABSOLUTE_TOLERANCE, LUMPED_EIGENVALUE_TOLERANCE, LUMPED_SYMMETRY_TOLERANCE};
    let negative = diag_from(&[1e12, -99.0]);
    let mut asymmetric = diag_from(&[1e12]);
    asymmetric[(0, 1)] = 900.0;
    let good = LumpedBody::none(Owner::Link(0));
    let cases = [
        (LumpedBody { added_mass: negative, ..good }, ("lumped.added_mass", Problem::NotPositiveSemidefinite)),
        (LumpedBody { added_mass: asymmetric, ..good }, ("lumped.added_mass", Problem::NotSymmetric)),
        (LumpedBody { linear_damping: negative, ..good }, ("lumped.linear_damping", Problem::NotPositiveSemidefinite)),
        (
            LumpedBody { added_mass: diag_from(&[1e9, -0.1]), ..good },
            ("lumped.added_mass", Problem::NotPositiveSemidefinite),
        ),
    ];
    let robot = one_joint();
    let robot32 = robot_f32();
    for (body, expected) in cases {
        assert_eq!(robot.with_lumped(&[body]).err().map(|e| (e.field, e.problem)), Some(expected));
        assert_eq!(robot32.with_lumped(&[to_f32(&body)]).err().map(|e| (e.field, e.problem)), Some(expected), "f32");
    }
    // The messages say what is allowed.
    let message = |body: LumpedBody<f64>| robot.with_lumped(&[body]).err().map(|e| e.to_string());
    assert_eq!(
        message(LumpedBody { added_mass: negative, ..good }).as_deref(),
        Some(
            "lumped model 0: lumped.added_mass must be positive semi-definite (no direction of negative energy): \
             its smallest eigenvalue at least -min(1e-10 x its largest diagonal entry, 1e-2)"
        )
    );
    assert_eq!(
        message(LumpedBody { added_mass: asymmetric, ..good }).as_deref(),
        Some(
            "lumped model 0: lumped.added_mass must be symmetric: |m[i][j] - m[j][i]| at most min(1e-9 x its largest entry, 1e-2)"
        )
    );
    assert_eq!(
        (LUMPED_SYMMETRY_TOLERANCE, LUMPED_EIGENVALUE_TOLERANCE, LUMPED_ABSOLUTE_TOLERANCE),
        (1e-9, 1e-10, 1e-2)
    );
    // Just within the floor: taken.
    let mut within = diag_from(&[1e12]);
    within[(0, 1)] = 0.9e-2;
    robot.with_lumped(&[LumpedBody { added_mass: within, ..good }]).unwrap();
    robot.with_lumped(&[LumpedBody { added_mass: diag_from(&[1e12, -0.9e-2]), ..good }]).unwrap();
}

/// A robot of one revolute joint in f32.
fn robot_f32() -> Robot<f32, 1, 1, 1> {
    let joint = TreeJoint { parent: None, kind: JointKind::Revolute, origin: Vector3::zeros(), axis: Vector3::z() };
    Robot::new(&[joint], &[RigidBody::empty()], RigidBody::empty(), &[]).unwrap()
}

fn to_f32(body: &LumpedBody<f64>) -> LumpedBody<f32> {
    let cast = |x: f64| x as f32;
    LumpedBody {
        owner: body.owner,
        point: body.point.map(cast),
        axes: body.axes.map(cast),
        added_mass: body.added_mass.map(cast),
        linear_damping: body.linear_damping.map(cast),
        quadratic_damping: body.quadratic_damping.map(cast),
    }
}

#[test]
fn rounding_at_the_cap_is_taken_and_f32_judges_as_f64_does() {
    // Singular semi-definite matrices of every rank up to the 1e12 cap, rounded to f64 (their zero
    // eigenvalues come out as ± rounding, up to ~1e-3 at 1e12), with an asymmetry of one ulp: taken.
    // The same matrices rounded to f32 are judged as f64 judges those rounded values (the checks
    // run in f64 on the exact values), so that an export's f32 model is refused or taken alike.
    let robot = one_joint();
    let robot32 = robot_f32();
    let reference: Robot<f64, 1, 1, 1> = Robot::new(
        &[TreeJoint { parent: None, kind: JointKind::Revolute, origin: Vector3::zeros(), axis: Vector3::z() }],
        &[RigidBody::empty()],
        RigidBody::empty(),
        &[],
    )
    .unwrap();
    let mut rng = Rng(31);
    let mut worst: f64 = 0.0;
    let (mut taken32, mut refused32) = (0, 0);
    for rank in 0..6 {
        for scale in [1e-3, 1.0, 1e6, 1e9, 1e11, 1e12] {
            for _ in 0..20 {
                let mut psd = random_psd(&mut rng, rank, 1.0);
                let largest = psd.diagonal().amax();
                if largest > 0.0 {
                    psd *= scale / largest * 0.999_999; // not above the cap by rounding
                }
                psd = (psd + psd.transpose()) * 0.5;
                let mut rounded = psd;
                if rank > 0 {
                    rounded[(0, 3)] = f64::from_bits(rounded[(0, 3)].to_bits() + 1);
                }
                worst = worst.min(psd.symmetric_eigenvalues().min());
                let body = LumpedBody { added_mass: rounded, linear_damping: psd, ..LumpedBody::none(Owner::Base) };
                assert_eq!(robot.with_lumped(&[body]).err().map(|e| e.to_string()), None, "rank {rank} at {scale}");
                let single = to_f32(&body);
                let as_f64 = LumpedBody {
                    added_mass: single.added_mass.map(f64::from),
                    linear_damping: single.linear_damping.map(f64::from),
                    ..body
                };
                let verdict32 = robot32.with_lumped(&[single]).map(|_| ()).map_err(|e| (e.field, e.problem));
                let verdict64 = reference.with_lumped(&[as_f64]).map(|_| ()).map_err(|e| (e.field, e.problem));
                assert_eq!(verdict32, verdict64, "rank {rank} at {scale}");
                if verdict32.is_ok() { taken32 += 1 } else { refused32 += 1 }
            }
        }
    }
    println!(
        "smallest eigenvalue of the rounded singular matrices: {worst:e}; f32: {taken32} taken, {refused32} refused"
    );
    // Diagonal models, the usual hull's, survive f32 at any scale.
    let hull =
        LumpedBody { added_mass: diag_from(&[1e12, 3e11, 7.5, 1e-3, 0.0, 2.0]), ..LumpedBody::none(Owner::Base) };
    robot32.with_lumped(&[to_f32(&hull)]).unwrap();
}
