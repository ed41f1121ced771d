//! Random whole robots and states for the tests of the tree path.

use uwml_core::nalgebra::UnitQuaternion;
use uwml_core::{
    BaseMotion, Conditions, Current, JointKind, Owner, RigidBody, Robot, RobotData, RobotSegment, Section,
    SegmentCoefficients, TreeJoint, Water, robot_added_mass_matrix, robot_hydro,
};

use super::Rng;

/// Random `(q, q̇, q̈)` of the first `n` joints (zero beyond).
pub fn states<const J: usize>(rng: &mut Rng, n: usize) -> [[f64; J]; 3] {
    let mut out = [[0.0; J]; 3];
    for (k, scale) in [3.0, 2.0, 5.0].into_iter().enumerate() {
        for x in out[k].iter_mut().take(n) {
            *x = scale * rng.next();
        }
    }
    out
}

/// A random robot: `n` joints with random parents, kinds, axes; every body (base too) with
/// random mass, volume and one or two segments, rectangular or circular.
pub fn random_robot<const J: usize, const S: usize, const B: usize>(rng: &mut Rng, n: usize) -> Robot<f64, J, S, B> {
    let joints: Vec<_> = (0..n)
        .map(|i| TreeJoint {
            parent: if i == 0 || rng.next() < -0.5 {
                None
            } else {
                Some(((rng.next() + 1.0) / 2.0 * i as f64) as usize)
            },
            kind: if rng.next() < -0.4 { JointKind::Prismatic } else { JointKind::Revolute },
            origin: rng.vector::<3>(0.5),
            axis: rng.unit(),
        })
        .collect();
    let body = |rng: &mut Rng| RigidBody {
        mass: 5.0 + 10.0 * rng.next().abs(),
        com: rng.vector::<3>(0.4),
        volume: 0.001 + 0.004 * rng.next().abs(),
        cob: rng.vector::<3>(0.4),
    };
    let links: Vec<_> = (0..n).map(|_| body(rng)).collect();
    let base = body(rng);
    let mut segments = Vec::new();
    for owner in core::iter::once(Owner::Base).chain((0..n).map(Owner::Link)) {
        for _ in 0..(1 + usize::from(rng.next() > 0.3)) {
            if segments.len() == S {
                break;
            }
            let axis = rng.unit();
            let n0 = axis.cross(&rng.unit()).normalize();
            let circular = rng.next() > 0.0;
            let (cd, cm) = (0.5 + 2.0 * rng.next().abs(), 0.1 + rng.next().abs());
            segments.push(RobotSegment {
                owner,
                start: rng.vector::<3>(0.2),
                axis,
                length: 0.2 + rng.next().abs(),
                area: 0.01 + 0.02 * rng.next().abs(),
                section: if circular {
                    Section::Circular { diameter: 0.05 + 0.1 * rng.next().abs() }
                } else {
                    Section::Rectangular {
                        normals: [n0, axis.cross(&n0)],
                        widths: [0.05 + 0.1 * rng.next().abs(), 0.05 + 0.2 * rng.next().abs()],
                    }
                },
                cd: if circular { [cd; 2] } else { [cd, 0.5 + 2.0 * rng.next().abs()] },
                cm: if circular { [cm; 2] } else { [cm, 0.1 + rng.next().abs()] },
                cd_axial: if rng.next() > 0.0 { 0.2 + rng.next().abs() } else { 0.0 },
                axial_area: 0.002 + 0.01 * rng.next().abs(),
            });
        }
    }
    Robot::new(&joints, &links, base, &segments).expect("a valid random robot")
}

/// A random orientation and motion of the base.
pub fn random_motion(rng: &mut Rng) -> BaseMotion<f64> {
    let q = UnitQuaternion::from_scaled_axis(rng.vector::<3>(2.0));
    BaseMotion::new(
        [q.w, q.i, q.j, q.k],
        rng.vector::<3>(1.0),
        rng.vector::<3>(1.0),
        rng.vector::<3>(2.0),
        rng.vector::<3>(2.0),
    )
    .unwrap()
}

/// `robot_hydro` in default water, with `coefficients` (or the segments' own), on a base moving as
/// `motion` in `current`.
pub fn evaluate<const J: usize, const S: usize>(
    robot: &Robot<f64, J, S>,
    coefficients: Option<&SegmentCoefficients<f64, S>>,
    motion: &BaseMotion<f64>,
    current: &Current<f64>,
    [q, qd, qdd]: &[[f64; J]; 3],
) -> RobotData<f64, J> {
    let mut data = RobotData::new();
    robot_hydro(
        robot,
        &Conditions { motion: *motion, current: *current, coefficients, ..Conditions::new(Water::default()) },
        [q, qd, qdd],
        &mut data,
    );
    data
}

/// `|a − b| ≤ rel · scale`.
pub fn assert_close(a: f64, b: f64, scale: f64, rel: f64, what: &str) {
    assert!((a - b).abs() <= rel * scale, "{what}: {a} vs {b} (scale {scale})");
}

/// `M_A` of a robot, `(6 + n)²` row-major.
pub fn added_mass_matrix<const J: usize, const S: usize>(robot: &Robot<f64, J, S>, q: &[f64; J]) -> Vec<f64> {
    let size = 6 + robot.joint_count();
    let mut out = vec![f64::NAN; size * size];
    robot_added_mass_matrix(robot, &Water::default(), None, q, &mut out);
    out
}
