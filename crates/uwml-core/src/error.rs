//! Errors found when a model is built. Evaluation never fails: everything is checked here, once.

use core::fmt;

use crate::bounds::{LUMPED_ABSOLUTE_TOLERANCE, LUMPED_EIGENVALUE_TOLERANCE, LUMPED_SYMMETRY_TOLERANCE};

/// What was wrong with a parameter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Problem {
    /// NaN or infinite.
    NonFinite,
    /// Must be strictly positive.
    NonPositive,
    /// Must be zero or positive.
    Negative,
    /// Must be a unit vector (within [`AXIS_TOLERANCE`](crate::AXIS_TOLERANCE)).
    NotUnit,
    /// Must be perpendicular to another direction (within [`AXIS_TOLERANCE`](crate::AXIS_TOLERANCE)).
    NotPerpendicular,
    /// Below its lower counterpart (a seal's breakaway level below its running level).
    OutOfOrder,
    /// Outside a documented range (named in the field).
    OutOfRange,
    /// At or below absolute zero (a temperature, −273.15 °C).
    BelowAbsoluteZero,
    /// Deeper than the deepest ocean: a depth beyond [`MAX_DEPTH`](crate::MAX_DEPTH), or a
    /// pressure beyond [`MAX_PRESSURE`](crate::MAX_PRESSURE).
    BeyondDeepestOcean,
    /// Larger in magnitude than the model's bound for its kind ([`MAX_LENGTH`](crate::MAX_LENGTH),
    /// [`MAX_MASS`](crate::MAX_MASS), [`MAX_VOLUME`](crate::MAX_VOLUME),
    /// [`MAX_AREA`](crate::MAX_AREA), [`MAX_COEFFICIENT`](crate::MAX_COEFFICIENT),
    /// [`MAX_DENSITY`](crate::MAX_DENSITY), [`MAX_GRAVITY`](crate::MAX_GRAVITY)): a unit
    /// mistake, or a value whose forces would overflow.
    TooLarge,
    /// A matrix that must be symmetric is not (beyond rounding: an asymmetry above
    /// [`LUMPED_SYMMETRY_TOLERANCE`](crate::LUMPED_SYMMETRY_TOLERANCE) times its largest entry or
    /// [`LUMPED_ABSOLUTE_TOLERANCE`](crate::LUMPED_ABSOLUTE_TOLERANCE), whichever is smaller).
    NotSymmetric,
    /// A matrix (or a matrix's symmetric part) that must be positive semi-definite is not (its
    /// smallest eigenvalue below `−min(`[`LUMPED_EIGENVALUE_TOLERANCE`](crate::LUMPED_EIGENVALUE_TOLERANCE)
    /// `· s, `[`LUMPED_ABSOLUTE_TOLERANCE`](crate::LUMPED_ABSOLUTE_TOLERANCE)`)`, `s` its largest
    /// diagonal entry in magnitude).
    NotPositiveSemidefinite,
}

/// A non-physical or malformed model parameter, found at construction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ModelError {
    /// The parameter, e.g. `"segment.length"` or `"water.density"`.
    pub field: &'static str,
    /// The joint (fields `joint.*`), the robot segment (`segment.owner`, `.section`, `.cd`,
    /// `.cm`, `.diameter`) or the link (all other fields; a chain's segment is its link's) it
    /// belongs to, 0-based, if any.
    pub index: Option<usize>,
    /// What was wrong with it.
    pub problem: Problem,
}

impl ModelError {
    pub(crate) const fn new(field: &'static str, index: Option<usize>, problem: Problem) -> Self {
        Self { field, index, problem }
    }
}

impl fmt::Display for ModelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(i) = self.index {
            // A robot's segments are numbered on their own, apart from its links.
            let owner = match self.field {
                field if field.starts_with("joint") => "joint",
                field if field.starts_with("lumped") => "lumped model",
                field if field.starts_with("segment") => "segment",
                _ => "link",
            };
            write!(f, "{owner} {i}: ")?;
        }
        let allowed = match self.problem {
            Problem::NonFinite => "must be finite (not NaN or infinite)",
            Problem::NonPositive => "must be positive",
            Problem::Negative => "must be zero or positive",
            Problem::NotUnit => "must be a unit vector (norm 1 within 1e-6)",
            Problem::NotPerpendicular => {
                "must be perpendicular (|cos| <= 1e-6) to the segment axis and to the other normal"
            }
            Problem::OutOfOrder => "must be at least its running counterpart (breakaway s0 >= c0, s1 >= c1)",
            Problem::OutOfRange => "is outside its allowed range",
            Problem::BelowAbsoluteZero => "must be above absolute zero (-273.15 degC)",
            Problem::BeyondDeepestOcean if self.field == "pressure" => {
                "must be at most 1.2e8 Pa (the deepest ocean's 110 MPa, with margin)"
            }
            Problem::BeyondDeepestOcean => "must be at most 11000 m (the deepest ocean)",
            Problem::TooLarge => too_large(self.field),
            Problem::NotSymmetric => "must be symmetric:",
            Problem::NotPositiveSemidefinite if self.field.ends_with("damping") => {
                "must have a positive semi-definite symmetric part (no direction in which it feeds energy in)"
            }
            Problem::NotPositiveSemidefinite => "must be positive semi-definite (no direction of negative energy)",
        };
        write!(f, "{} {allowed}", self.field)?;
        // The lumped model's tolerances (docs/model.md section 12.1), from their constants.
        let floor = LUMPED_ABSOLUTE_TOLERANCE;
        match self.problem {
            Problem::NotSymmetric => write!(
                f,
                " |m[i][j] - m[j][i]| at most min({:e} x its largest entry, {floor:e})",
                LUMPED_SYMMETRY_TOLERANCE
            ),
            Problem::NotPositiveSemidefinite => write!(
                f,
                ": its smallest eigenvalue at least -min({:e} x its largest diagonal entry, {floor:e})",
                LUMPED_EIGENVALUE_TOLERANCE
            ),
            _ => Ok(()),
        }
    }
}

/// The bound a field broke ([`Problem::TooLarge`]), in words.
fn too_large(field: &str) -> &'static str {
    if field.starts_with("lumped.") && field != "lumped.point" {
        "must be at most 1e12 in magnitude (each entry)"
    } else if field.ends_with(".mass") {
        "must be at most 1e9 kg"
    } else if field.ends_with(".volume") {
        "must be at most 1e6 m^3"
    } else if field.ends_with(".area") {
        "must be at most 1e8 m^2"
    } else if field.ends_with("cd") || field.ends_with("cm") {
        "must be at most 1e3 (measured coefficients are of order 1)"
    } else if field.ends_with("density") {
        "must be at most 1e5 kg/m^3"
    } else if field.ends_with("gravity") {
        "must be at most 1e3 m/s^2"
    } else {
        "must be at most 1e4 m in magnitude (each coordinate or length)"
    }
}

impl core::error::Error for ModelError {}
