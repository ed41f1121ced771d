//! The robots of the whole-robot benchmarks (shared by `benches/robot.rs` and
//! `examples/timing.rs`): a 7-joint manipulator of 14 segments on an ROV, and its motion.
#![allow(dead_code, clippy::indexing_slicing, clippy::panic)]

use uwml_core::nalgebra::{Matrix3, Matrix6, RealField, Vector3, Vector6, convert};
use uwml_core::{
    BaseMotion, Current, JointKind, LumpedBody, Owner, RigidBody, Robot, RobotSegment, Section, TreeJoint,
};

fn c<T: RealField + Copy>(x: f64) -> T {
    convert(x)
}

fn v<T: RealField + Copy>(x: f64, y: f64, z: f64) -> Vector3<T> {
    Vector3::new(c(x), c(y), c(z))
}

/// A 7-joint arm (yaw, pitch, pitch, roll, pitch, roll, and a prismatic gripper slide) at the
/// front of a 300 kg ROV hull: every link a circular tube and a rectangular housing (14
/// segments), the hull one circular segment, all with their own coefficients.
pub fn arm_on_rov<T: RealField + Copy, const J: usize, const S: usize>() -> Robot<T, J, S> {
    let axes = [
        (0.0, 0.0, 1.0),
        (0.0, 1.0, 0.0),
        (0.0, 1.0, 0.0),
        (1.0, 0.0, 0.0),
        (0.0, 1.0, 0.0),
        (1.0, 0.0, 0.0),
        (1.0, 0.0, 0.0),
    ];
    let origins = [
        (0.9, 0.0, -0.3),
        (0.0, 0.0, -0.15),
        (0.6, 0.0, 0.0),
        (0.5, 0.0, 0.0),
        (0.15, 0.0, 0.0),
        (0.2, 0.0, 0.0),
        (0.1, 0.0, 0.0),
    ];
    let lengths = [0.15, 0.6, 0.5, 0.15, 0.2, 0.1, 0.15];
    let joints: [TreeJoint<T>; 7] = core::array::from_fn(|i| {
        let (x, y, z) = axes[i];
        let (ox, oy, oz) = origins[i];
        TreeJoint {
            parent: i.checked_sub(1),
            kind: if i == 6 { JointKind::Prismatic } else { JointKind::Revolute },
            origin: v(ox, oy, oz),
            axis: v(x, y, z),
        }
    });
    let links: [RigidBody<T>; 7] = core::array::from_fn(|i| {
        let mass = 12.0 - 1.5 * i as f64;
        RigidBody {
            mass: c(mass),
            com: v(lengths[i] / 2.0, 0.0, 0.0),
            volume: c(mass / 3000.0),
            cob: v(lengths[i] / 2.0, 0.0, 0.01),
        }
    });
    let mut segments = [RobotSegment {
        owner: Owner::Base,
        start: v(-0.9, 0.0, 0.0),
        axis: v(1.0, 0.0, 0.0),
        length: c(1.8),
        area: c(0.283),
        section: Section::Circular { diameter: c(0.6) },
        cd: [c(0.9); 2],
        cm: [c(1.0); 2],
        cd_axial: T::zero(),
        axial_area: T::zero(),
    }; 15];
    for (i, &length) in lengths.iter().enumerate() {
        let diameter = 0.12 - 0.01 * i as f64;
        segments[1 + 2 * i] = RobotSegment {
            owner: Owner::Link(i),
            start: v(0.0, 0.0, 0.0),
            axis: v(1.0, 0.0, 0.0),
            length: c(length),
            area: c(core::f64::consts::PI * diameter * diameter / 4.0),
            section: Section::Circular { diameter: c(diameter) },
            cd: [c(1.2); 2],
            cm: [c(1.0); 2],
            cd_axial: T::zero(),
            axial_area: T::zero(),
        };
        segments[2 + 2 * i] = RobotSegment {
            owner: Owner::Link(i),
            start: v(0.0, 0.0, -0.05),
            axis: v(1.0, 0.0, 0.0),
            length: c(length * 0.6),
            area: c(0.004),
            section: Section::Rectangular { normals: [v(0.0, 1.0, 0.0), v(0.0, 0.0, 1.0)], widths: [c(0.05), c(0.08)] },
            cd: [c(2.0), c(2.1)],
            cm: [c(1.2), c(1.5)],
            cd_axial: T::zero(),
            axial_area: T::zero(),
        };
    }
    let hull = RigidBody { mass: c(300.0), com: v(0.0, 0.0, -0.05), volume: c(0.29), cob: v(0.0, 0.0, 0.05) };
    Robot::new(&joints, &links, hull, &segments).unwrap_or_else(|e| panic!("the benchmark arm is valid: {e}"))
}

/// A pitched, rolled ROV surging and heaving while it turns, in a 0.3 m/s current.
pub fn rov_motion<T: RealField + Copy>() -> (BaseMotion<T>, Current<T>) {
    let (half_pitch, half_roll) = (0.05_f64, 0.03_f64);
    let (cp, sp, cr, sr) = (half_pitch.cos(), half_pitch.sin(), half_roll.cos(), half_roll.sin());
    // Roll, then pitch (q = q_pitch ⊗ q_roll).
    let q = [cp * cr, cp * sr, sp * cr, -sp * sr];
    let motion =
        BaseMotion::new(q.map(c), v(0.5, 0.02, -0.05), v(0.01, 0.03, 0.05), v(0.1, 0.0, 0.02), v(0.0, 0.01, 0.0))
            .unwrap_or_else(|e| panic!("a valid motion: {e}"));
    let current = Current::new(v(0.3, 0.1, 0.0), v(0.0, 0.0, 0.0)).unwrap_or_else(|e| panic!("a valid current: {e}"));
    (motion, current)
}

/// `robot` with Fossen's lumped model (docs/model.md section 12.1) on its hull, the base: a
/// 300 kg work-class hull's added mass (with a surge-pitch coupling) and damping, about its
/// centre, in the proportions of the BlueROV2 model of von Benzon et al. (2022), scaled up.
pub fn with_hull<T: RealField + Copy, const J: usize, const S: usize>(robot: &Robot<T, J, S>) -> Robot<T, J, S, 1> {
    let diagonal = |d: [f64; 6]| Matrix6::from_diagonal(&Vector6::from(d.map(c::<T>)));
    let mut added_mass = diagonal([190.0, 360.0, 420.0, 12.0, 30.0, 25.0]);
    added_mass[(0, 4)] = c(8.0);
    added_mass[(4, 0)] = c(8.0);
    let hull = LumpedBody {
        owner: Owner::Base,
        point: v(0.0, 0.0, 0.05),
        axes: Matrix3::identity(),
        added_mass,
        linear_damping: diagonal([120.0, 150.0, 160.0, 20.0, 30.0, 25.0]),
        quadratic_damping: [420.0, 600.0, 700.0, 30.0, 60.0, 50.0].map(c::<T>),
    };
    let robot = Robot::<T, J, S, 1>::new(robot.joints(), robot.links(), *robot.base(), robot.segments())
        .unwrap_or_else(|e| panic!("the arm: {e}"));
    robot.with_lumped(&[hull]).unwrap_or_else(|e| panic!("the hull: {e}"))
}
