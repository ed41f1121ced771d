#![doc = include_str!("../README.md")]
#![no_std]

mod added_mass;
pub mod conditions;
pub mod derivatives;
pub mod dual;
pub mod error;
mod frames;
pub mod hydro;
pub mod jacobian;
pub mod kinematics;
pub mod losses;
pub mod lumped;
pub mod model;
pub mod motion;
pub mod presets;
pub mod real;
pub mod robot;
pub mod robot_derivatives;
mod segment_coefficients;
mod segment_forces;
mod segment_frame;
pub mod strip;
pub mod tree;
mod tree_regressors;
mod wrench;

pub use conditions::Conditions;
pub use derivatives::{EnvironmentJacobians, environment_jacobians, hydro_jacobians};
pub use dual::Dual;
pub use error::{ModelError, Problem};
pub use hydro::{HydroRegressors, HydroTorques, hydro_regressors, hydro_torques};
pub use jacobian::point_jacobian;
pub use kinematics::{KinematicsData, LinkMotion, LinkPose, forward_kinematics, link_motions};
pub use losses::{
    ABSOLUTE_ZERO_C, Drive, DryFrictionSplit, EnvironmentTorques, JointLoss, JointLosses, LossState, MAX_DEPTH,
    MAX_PRESSURE, OIL_TEMPERATURE_RANGE_C, OilDrag, Seal, check_conditions, environment_torques, loss_torques,
    pressure_at_depth, smooth_sign,
};
pub use lumped::{
    LUMPED_ABSOLUTE_TOLERANCE, LUMPED_COLUMNS, LUMPED_EIGENVALUE_TOLERANCE, LUMPED_SYMMETRY_TOLERANCE, LumpedBody,
    MAX_LUMPED,
};
pub use model::{
    AXIS_TOLERANCE, Chain, Coefficients, Joint, Link, MAX_AREA, MAX_COEFFICIENT, MAX_DENSITY, MAX_GRAVITY, MAX_LENGTH,
    MAX_MASS, MAX_VOLUME, Segment, Water,
};
pub use motion::{BaseMotion, Current};
pub use nalgebra;
pub use real::Real;
pub use robot::{JointKind, Owner, RigidBody, Robot, RobotSegment, Section, SegmentCoefficients, TreeJoint};
pub use robot_derivatives::{DUAL_WIDTH, RobotJacobianData, RobotJacobians, robot_jacobians};
pub use tree::{
    AddedMassForm, EnvironmentWrench, JointForces, RobotData, Wrench, robot_added_mass_matrix, robot_hydro,
    robot_hydro_regressors, robot_joint_added_mass_matrix,
};

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
