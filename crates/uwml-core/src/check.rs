//! The checks a model's numbers pass once, when it is built (docs/domains.md): finite, positive,
//! within the bounds of their kind, unit and perpendicular directions; each failure a
//! [`ModelError`] naming the field and the index.

use nalgebra::{RealField, SimdRealField, Vector3};

use crate::bounds::{AXIS_TOLERANCE, MAX_COEFFICIENT, MAX_LENGTH};
use crate::error::{ModelError, Problem};

pub(crate) fn constant<T: SimdRealField + Copy>(x: f64) -> T {
    nalgebra::convert(x)
}

pub(crate) fn check_finite<T: RealField + Copy>(
    x: T,
    field: &'static str,
    index: Option<usize>,
) -> Result<T, ModelError> {
    if x.is_finite() { Ok(x) } else { Err(ModelError::new(field, index, Problem::NonFinite)) }
}

pub(crate) fn check_positive<T: RealField + Copy>(
    x: T,
    field: &'static str,
    index: Option<usize>,
) -> Result<T, ModelError> {
    let x = check_finite(x, field, index)?;
    if x > T::zero() { Ok(x) } else { Err(ModelError::new(field, index, Problem::NonPositive)) }
}

pub(crate) fn check_non_negative<T: RealField + Copy>(
    x: T,
    field: &'static str,
    index: Option<usize>,
) -> Result<T, ModelError> {
    let x = check_finite(x, field, index)?;
    if x >= T::zero() { Ok(x) } else { Err(ModelError::new(field, index, Problem::Negative)) }
}

/// `x` finite and at least `low`, else `problem`.
pub(crate) fn check_at_least<T: RealField + Copy>(
    x: T,
    low: T,
    field: &'static str,
    problem: Problem,
) -> Result<T, ModelError> {
    let x = check_finite(x, field, None)?;
    if x >= low { Ok(x) } else { Err(ModelError::new(field, None, problem)) }
}

/// Every drag and added-mass coefficient of a table (`[owner][k]`) finite and non-negative, or
/// an error naming `fields` and the owner's index.
pub(crate) fn check_coefficient_table<T: RealField + Copy>(
    cd: &[[T; 2]],
    cm: &[[T; 2]],
    [cd_field, cm_field]: [&'static str; 2],
) -> Result<(), ModelError> {
    for (index, (cd, cm)) in cd.iter().zip(cm.iter()).enumerate() {
        for (&d, &m) in cd.iter().zip(cm.iter()) {
            check_coefficient(d, cd_field, Some(index))?;
            check_coefficient(m, cm_field, Some(index))?;
        }
    }
    Ok(())
}

/// `x` (already checked finite) at most `limit` in magnitude, else [`Problem::TooLarge`].
pub(crate) fn check_at_most<T: RealField + Copy>(
    x: T,
    limit: f64,
    field: &'static str,
    index: Option<usize>,
) -> Result<T, ModelError> {
    if x.abs() <= constant(limit) { Ok(x) } else { Err(ModelError::new(field, index, Problem::TooLarge)) }
}

/// A drag or added-mass coefficient: finite, not negative, at most [`MAX_COEFFICIENT`].
pub(crate) fn check_coefficient<T: RealField + Copy>(
    x: T,
    field: &'static str,
    index: Option<usize>,
) -> Result<T, ModelError> {
    check_at_most(check_non_negative(x, field, index)?, MAX_COEFFICIENT, field, index)
}

/// A point of the model: finite, each coordinate at most [`MAX_LENGTH`] in magnitude.
pub(crate) fn check_point<T: RealField + Copy>(
    v: Vector3<T>,
    field: &'static str,
    index: Option<usize>,
) -> Result<Vector3<T>, ModelError> {
    let v = check_vector(v, field, index)?;
    for &x in v.iter() {
        check_at_most(x, MAX_LENGTH, field, index)?;
    }
    Ok(v)
}

/// A length, width, diameter: finite, positive, at most [`MAX_LENGTH`].
pub(crate) fn check_length<T: RealField + Copy>(
    x: T,
    field: &'static str,
    index: Option<usize>,
) -> Result<T, ModelError> {
    check_at_most(check_positive(x, field, index)?, MAX_LENGTH, field, index)
}

pub(crate) fn check_vector<T: RealField + Copy>(
    v: Vector3<T>,
    field: &'static str,
    index: Option<usize>,
) -> Result<Vector3<T>, ModelError> {
    if v.iter().all(|x| x.is_finite()) { Ok(v) } else { Err(ModelError::new(field, index, Problem::NonFinite)) }
}

/// Checks that `v` is a unit vector within [`AXIS_TOLERANCE`] and returns it normalized exactly.
pub(crate) fn check_unit<T: RealField + Copy>(
    v: Vector3<T>,
    field: &'static str,
    index: Option<usize>,
) -> Result<Vector3<T>, ModelError> {
    let v = check_vector(v, field, index)?;
    let norm = v.norm();
    if (norm - T::one()).abs() <= constant(AXIS_TOLERANCE) {
        Ok(v / norm)
    } else {
        Err(ModelError::new(field, index, Problem::NotUnit))
    }
}

/// `v` made exactly perpendicular to the unit `axis` and normalized, if it was within
/// [`AXIS_TOLERANCE`] of perpendicular and of unit length.
pub(crate) fn check_normal<T: RealField + Copy>(
    v: Vector3<T>,
    axis: &Vector3<T>,
    field: &'static str,
    index: Option<usize>,
) -> Result<Vector3<T>, ModelError> {
    let v = check_unit(v, field, index)?;
    if v.dot(axis).abs() > constant(AXIS_TOLERANCE) {
        return Err(ModelError::new(field, index, Problem::NotPerpendicular));
    }
    Ok((v - axis * v.dot(axis)).normalize())
}
