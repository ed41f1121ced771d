//! Robots that come with uwml: the paper's underwater mechanical leg (docs/model.md, "The paper's
//! leg"), as a [`Robot`] like any other, with its parameters (Table II) and coefficients.

use nalgebra::{RealField, Vector3};

use crate::check::constant;
use crate::model::Robot;
use crate::parts::{JointKind, Owner, RigidBody, RobotSegment, Section, TreeJoint};

/// Table II of the paper, the UWML's parameters (SI units).
pub mod paper {
    /// Thigh length `L2` [m].
    pub const L2: f64 = 0.660;
    /// Calf length `L3` [m].
    pub const L3: f64 = 0.714;
    /// Thigh COM/COB distance from joint 2, `Lc2` [m].
    pub const LC2: f64 = 0.506;
    /// Calf COM/COB distance from joint 3, `Lc3` [m].
    pub const LC3: f64 = 0.560;
    /// Thigh frontal width for out-of-plane flow, `D21` [m].
    pub const D21: f64 = 0.131;
    /// Thigh frontal width for in-plane flow, `D22` [m].
    pub const D22: f64 = 0.238;
    /// Calf frontal width for out-of-plane flow, `D31` [m].
    pub const D31: f64 = 0.131;
    /// Calf frontal width for in-plane flow, `D32` [m].
    pub const D32: f64 = 0.279;
    /// Link masses `m1, m2, m3` [kg].
    pub const MASSES: [f64; 3] = [10.758, 19.261, 10.375];
    /// Equivalent link density `ρ_m` [kg/m³]; a link's displaced volume is `m / ρ_m`.
    pub const LINK_DENSITY: f64 = 2700.0;
    /// The drag coefficient of every segment and direction: the paper's fitted values rounded.
    pub const CD: f64 = 2.2;
    /// The added-mass coefficient of every segment and direction.
    pub const CM: f64 = 0.5;
}

/// The paper's underwater mechanical leg (UWML, Table II) on a fixed base without a body of its
/// own: hip yaw about the base's z, hip roll and knee roll about `-e_y`; the thigh (link 1) along
/// its local +x and the calf (link 2) along its local −z at `q = 0`, each a rectangular segment
/// with `Cd = 2.2` and `Cm = 0.5` in both directions (normal 0 out of the leg's plane); link 0
/// has no segment.
///
/// ```
/// use uwml_core::{Conditions, RobotData, Water, presets, robot_hydro};
/// let leg = presets::paper_leg::<f64>();
/// let mut data = RobotData::new();
/// robot_hydro(&leg, &Conditions::new(Water::default()), [&[0.3, -0.4, 0.6], &[0.8, 0.5, -0.7], &[0.0; 3]], &mut data);
/// assert!(data.joint_forces()[0].drag < 0.0);
/// ```
#[must_use]
pub fn paper_leg<T: RealField + Copy>() -> Robot<T, 3, 2> {
    let c = constant::<T>;
    let v = |x: f64, y: f64, z: f64| Vector3::new(c(x), c(y), c(z));
    let revolute = |parent, origin, axis| TreeJoint { parent, kind: JointKind::Revolute, origin, axis };
    let roll_axis = v(0.0, -1.0, 0.0);
    let joints = [
        revolute(None, Vector3::zeros(), v(0.0, 0.0, 1.0)),
        revolute(Some(0), Vector3::zeros(), roll_axis),
        revolute(Some(1), v(paper::L2, 0.0, 0.0), roll_axis),
    ];
    let body = |mass: f64, centre: Vector3<T>| RigidBody {
        mass: c(mass),
        com: centre,
        volume: c(mass / paper::LINK_DENSITY),
        cob: centre,
    };
    let [m1, m2, m3] = paper::MASSES;
    let links = [body(m1, Vector3::zeros()), body(m2, v(paper::LC2, 0.0, 0.0)), body(m3, v(0.0, 0.0, -paper::LC3))];
    let out_of_plane = v(0.0, 1.0, 0.0);
    let segment = |link, axis, length: f64, in_plane, widths: [f64; 2]| RobotSegment {
        owner: Owner::Link(link),
        start: Vector3::zeros(),
        axis,
        length: c(length),
        area: c(widths[0] * widths[1]),
        section: Section::Rectangular { normals: [out_of_plane, in_plane], widths: widths.map(c) },
        cd: [c(paper::CD); 2],
        cm: [c(paper::CM); 2],
        cd_axial: T::zero(),
        axial_area: T::zero(),
    };
    let segments = [
        segment(1, v(1.0, 0.0, 0.0), paper::L2, v(0.0, 0.0, 1.0), [paper::D21, paper::D22]),
        segment(2, v(0.0, 0.0, -1.0), paper::L3, v(1.0, 0.0, 0.0), [paper::D31, paper::D32]),
    ];
    // Valid as written (unit axes, exact orthonormal frames, positive sizes): Robot::new would
    // give the same robot.
    Robot::from_valid_parts(&joints, &links, RigidBody::empty(), &segments)
}
