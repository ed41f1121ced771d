//! Helpers shared by the integration tests.
#![allow(dead_code, missing_docs)]

use uwml_core::nalgebra::{Matrix6, SVector, SimdRealField, Vector3, Vector6};
use uwml_core::{
    Conditions, JointForces, JointKind, Owner, Real, RigidBody, Robot, RobotData, RobotSegment, Section,
    SegmentCoefficients, TreeJoint, Water, robot_hydro,
};

pub mod trees;

/// xorshift64: deterministic random numbers in [-1, 1) without a dependency.
pub struct Rng(pub u64);
impl Rng {
    pub fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
    pub fn vector<const N: usize>(&mut self, scale: f64) -> SVector<f64, N> {
        SVector::from_fn(|_, _| scale * self.next())
    }
    pub fn unit(&mut self) -> Vector3<f64> {
        loop {
            let v = Vector3::new(self.next(), self.next(), self.next());
            if v.norm() > 0.2 {
                return v.normalize();
            }
        }
    }
}

/// A random serial chain of 4 revolute joints on a fixed base, with arbitrary axes, offsets,
/// segment directions and normals (the general body frames and the full recursion, which the
/// paper leg does not reach); link 1 has no segment, the others one rectangular segment each
/// with random coefficients (drag 0.5 to 2.5, added mass 0.1 to 1.1, per direction).
pub fn random_chain(rng: &mut Rng) -> Robot<f64, 4, 4> {
    let joints: [TreeJoint<f64>; 4] = core::array::from_fn(|i| TreeJoint {
        parent: i.checked_sub(1),
        kind: JointKind::Revolute,
        origin: rng.vector::<3>(0.5),
        axis: rng.unit(),
    });
    let mut links = [RigidBody::empty(); 4];
    let mut segments = Vec::new();
    for (i, link) in links.iter_mut().enumerate() {
        let axis = rng.unit();
        let n1 = axis.cross(&rng.unit()).normalize();
        let segment = RobotSegment {
            owner: Owner::Link(i),
            start: rng.vector::<3>(0.2),
            axis,
            length: 0.2 + rng.next().abs(),
            area: 0.01 + 0.02 * rng.next().abs(),
            section: Section::Rectangular {
                normals: [n1, axis.cross(&n1)],
                widths: [0.05 + 0.1 * rng.next().abs(), 0.05 + 0.2 * rng.next().abs()],
            },
            cd: [2.2; 2],
            cm: [0.5; 2],
            cd_axial: 0.0,
            axial_area: 0.0,
        };
        *link = RigidBody {
            mass: 5.0 + 10.0 * rng.next().abs(),
            com: rng.vector::<3>(0.4),
            volume: 0.001 + 0.004 * rng.next().abs(),
            cob: rng.vector::<3>(0.4),
        };
        if i != 1 {
            segments.push(segment);
        }
    }
    let robot = Robot::new(&joints, &links, RigidBody::empty(), &segments).expect("a valid random chain");
    robot.with_coefficients(&random_coefficients(rng))
}

/// Random drag (0.5 to 2.5) and added-mass (0.1 to 1.1) coefficients per segment and direction.
pub fn random_coefficients<const S: usize>(rng: &mut Rng) -> SegmentCoefficients<f64, S> {
    let mut draw = || core::array::from_fn(|_| [0.5 + 2.0 * rng.next().abs(), 0.1 + rng.next().abs()]);
    SegmentCoefficients::per_segment(draw(), draw()).expect("valid coefficients")
}

/// The environment's forces on every joint, one vector per kind.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Forces<T: SimdRealField + Copy, const N: usize> {
    pub drag: SVector<T, N>,
    pub added_mass: SVector<T, N>,
    pub buoyancy: SVector<T, N>,
    pub gravity: SVector<T, N>,
}

impl<T: SimdRealField + Copy, const N: usize> Forces<T, N> {
    /// `drag + added_mass + buoyancy`.
    pub fn total(&self) -> SVector<T, N> {
        self.drag + self.added_mass + self.buoyancy
    }

    /// Every vector mapped by `f` (one lane of SIMD forces, say).
    pub fn map<U: SimdRealField + Copy>(&self, f: impl Fn(&SVector<T, N>) -> SVector<U, N>) -> Forces<U, N> {
        Forces {
            drag: f(&self.drag),
            added_mass: f(&self.added_mass),
            buoyancy: f(&self.buoyancy),
            gravity: f(&self.gravity),
        }
    }
}

/// `robot_hydro` of a robot of `N` joints (all used) at `(q, q̇, q̈)`, as vectors.
pub fn forces<T: Real, const N: usize, const S: usize, const B: usize>(
    robot: &Robot<T, N, S, B>,
    conditions: &Conditions<'_, T, N, S>,
    q: &SVector<T, N>,
    qd: &SVector<T, N>,
    qdd: &SVector<T, N>,
) -> Forces<T, N> {
    let mut data = RobotData::new();
    let state = |v: &SVector<T, N>| -> [T; N] { (*v).into() };
    robot_hydro(robot, conditions, [&state(q), &state(qd), &state(qdd)], &mut data);
    let each =
        |f: fn(&JointForces<T>) -> T| SVector::<T, N>::from_fn(|i, _| data.joint_forces().get(i).map_or(T::zero(), f));
    Forces {
        drag: each(|f| f.drag),
        added_mass: each(|f| f.added_mass),
        buoyancy: each(|f| f.buoyancy),
        gravity: each(|f| f.gravity),
    }
}

/// [`forces`] in `water` with the segments' own coefficients, or `coefficients`.
pub fn hydro<T: Real, const N: usize, const S: usize, const B: usize>(
    robot: &Robot<T, N, S, B>,
    water: &Water<T>,
    coefficients: Option<&SegmentCoefficients<T, S>>,
    q: &SVector<T, N>,
    qd: &SVector<T, N>,
    qdd: &SVector<T, N>,
) -> Forces<T, N> {
    forces(robot, &Conditions { coefficients, ..Conditions::new(*water) }, q, qd, qdd)
}

/// A random symmetric positive semi-definite matrix, `A Aᵀ` (rank `rank`) at scale `scale`.
pub fn random_psd(rng: &mut Rng, rank: usize, scale: f64) -> Matrix6<f64> {
    let mut m = Matrix6::zeros();
    for _ in 0..rank {
        let a: Vector6<f64> = rng.vector(scale.sqrt());
        m += a * a.transpose();
    }
    m
}
