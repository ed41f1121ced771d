#![doc = include_str!("../README.md")]
#![no_std]

pub mod error;
pub mod hydro;
pub mod kinematics;
pub mod model;
pub mod strip;

pub use error::{ModelError, Problem};
pub use hydro::{HydroRegressors, HydroTorques, hydro_regressors, hydro_torques};
pub use kinematics::{LinkMotion, link_motions};
pub use model::{AXIS_TOLERANCE, Chain, Coefficients, Joint, Link, Segment, Water};
pub use nalgebra;
