#![doc = include_str!("../README.md")]
#![no_std]

// One model, its evaluation, its derivatives; files by layer, imports one way (a test holds
// the `use crate::` graph acyclic: tests/layers.rs).
pub mod added_mass;
mod algebra;
pub mod bounds;
mod check;
pub mod conditions;
pub mod derivatives;
pub mod dual;
pub mod error;
mod frames;
pub mod hydro;
pub mod kinematics;
pub mod losses;
pub mod lumped;
pub mod model;
pub mod motion;
pub mod parts;
pub mod presets;
pub mod real;
pub mod regressors;
mod segment_coefficients;
mod segment_forces;
mod segment_frame;
pub mod strip;
pub mod water;
pub mod wrench;

pub use added_mass::{robot_added_mass_matrix, robot_joint_added_mass_matrix};
pub use bounds::{
    AXIS_TOLERANCE, LUMPED_ABSOLUTE_TOLERANCE, LUMPED_EIGENVALUE_TOLERANCE, LUMPED_SYMMETRY_TOLERANCE, MAX_AREA,
    MAX_COEFFICIENT, MAX_DENSITY, MAX_GRAVITY, MAX_LENGTH, MAX_LUMPED, MAX_MASS, MAX_VOLUME,
};
pub use conditions::{AddedMassForm, Conditions};
pub use derivatives::{DUAL_WIDTH, RobotJacobianData, RobotJacobians, robot_jacobians};
pub use dual::Dual;
pub use error::{ModelError, Problem};
pub use hydro::{RobotData, robot_hydro};
pub use kinematics::{KinematicsData, LinkPose, forward_kinematics, point_jacobian};
pub use losses::{
    ABSOLUTE_ZERO_C, Drive, DryFrictionSplit, JointLoss, JointLosses, LossState, MAX_DEPTH, MAX_PRESSURE,
    OIL_TEMPERATURE_RANGE_C, OilDrag, Seal, check_conditions, loss_torques, pressure_at_depth, smooth_sign,
};
pub use lumped::{LUMPED_COLUMNS, LumpedBody};
pub use model::Robot;
pub use motion::{BaseMotion, Current};
pub use nalgebra;
pub use parts::{JointKind, Owner, RigidBody, RobotSegment, Section, TreeJoint};
pub use real::Real;
pub use regressors::robot_hydro_regressors;
pub use segment_coefficients::SegmentCoefficients;
pub use water::Water;
pub use wrench::{EnvironmentWrench, JointForces, Wrench};

/// The README's Rust snippets, compiled and run as doctests (`cargo test --doc`): the README's
/// examples run as written.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
struct ReadmeDoctests;

/// The Rust snippets of the documentation site's pages, compiled and run the same way (their
/// lines that start with `# ` are rustdoc's hidden lines: the site leaves them out).
#[cfg(doctest)]
#[doc = include_str!("../../../docs/firmware.md")]
struct FirmwareDoctests;

#[cfg(doctest)]
#[doc = include_str!("../../../docs/model.md")]
struct ModelDoctests;
