//! The precision-generic implementation behind the `extern "C"` functions of the crate root.
//!
//! Every function here takes the caller's raw pointers, checks them for null before anything
//! else, copies its inputs by value, and writes its outputs with one `write` at the end, so
//! that no Rust reference to caller memory outlives the read it was made for.

use core::ffi::c_char;

use uwml_core::nalgebra::RealField;
use uwml_core::{Drive, JointLosses, ModelError, OilDrag, Problem, Seal};

use crate::{
    UWML_ERR_BELOW_ABSOLUTE_ZERO, UWML_ERR_BEYOND_DEEPEST_OCEAN, UWML_ERR_INDEX_OUT_OF_RANGE, UWML_ERR_NEGATIVE,
    UWML_ERR_NON_FINITE, UWML_ERR_NON_POSITIVE, UWML_ERR_NOT_PERPENDICULAR, UWML_ERR_NOT_POSITIVE_SEMIDEFINITE,
    UWML_ERR_NOT_SYMMETRIC, UWML_ERR_NOT_UNIT, UWML_ERR_NULL_POINTER, UWML_ERR_OUT_OF_ORDER, UWML_ERR_OUT_OF_RANGE,
    UWML_ERR_OVERFLOW, UWML_ERR_TOO_LARGE, UWML_ERROR_FIELD_LEN, UWML_OK, UwmlDriveParamsF32, UwmlDriveParamsF64,
    UwmlError, UwmlJointLossParamsF32, UwmlJointLossParamsF64, UwmlOilParamsF32, UwmlOilParamsF64, UwmlSealParamsF32,
    UwmlSealParamsF64,
};

/// An error on its way to the caller's `UwmlError`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Failure {
    code: i32,
    index: Option<usize>,
    field: &'static str,
}

impl Failure {
    pub(crate) const fn new(code: i32, field: &'static str, index: Option<usize>) -> Self {
        Self { code, index, field }
    }

    pub(crate) const fn null(field: &'static str) -> Self {
        Self::new(UWML_ERR_NULL_POINTER, field, None)
    }

    /// A core error, attributed to joint `joint` when the core names no index.
    pub(crate) fn from_model(error: ModelError, joint: Option<usize>) -> Self {
        let code = match error.problem {
            Problem::NonFinite => UWML_ERR_NON_FINITE,
            Problem::NonPositive => UWML_ERR_NON_POSITIVE,
            Problem::Negative => UWML_ERR_NEGATIVE,
            Problem::NotUnit => UWML_ERR_NOT_UNIT,
            Problem::NotPerpendicular => UWML_ERR_NOT_PERPENDICULAR,
            Problem::OutOfOrder => UWML_ERR_OUT_OF_ORDER,
            Problem::OutOfRange => UWML_ERR_OUT_OF_RANGE,
            Problem::BelowAbsoluteZero => UWML_ERR_BELOW_ABSOLUTE_ZERO,
            Problem::BeyondDeepestOcean => UWML_ERR_BEYOND_DEEPEST_OCEAN,
            Problem::TooLarge => UWML_ERR_TOO_LARGE,
            Problem::NotSymmetric => UWML_ERR_NOT_SYMMETRIC,
            Problem::NotPositiveSemidefinite => UWML_ERR_NOT_POSITIVE_SEMIDEFINITE,
        };
        Self::new(code, error.field, error.index.or(joint))
    }
}

impl From<ModelError> for Failure {
    fn from(error: ModelError) -> Self {
        Self::from_model(error, None)
    }
}

/// The C view of a result: `UWML_OK` or the failure's code; fills `*error` when it is not null.
///
/// # Safety
/// `error` is null or valid for one write of a `UwmlError`.
pub(crate) unsafe fn report(error: *mut UwmlError, result: Result<(), Failure>) -> i32 {
    let failure = match result {
        Ok(()) => Failure::new(UWML_OK, "", None),
        Err(failure) => failure,
    };
    if !error.is_null() {
        let mut field = [0 as c_char; UWML_ERROR_FIELD_LEN];
        // The longest prefix that ends on a character boundary and leaves room for the NUL.
        let mut end = failure.field.len().min(UWML_ERROR_FIELD_LEN - 1);
        while !failure.field.is_char_boundary(end) {
            end -= 1;
        }
        let bytes = failure.field.as_bytes().iter().take(end);
        for (slot, &byte) in field.iter_mut().zip(bytes) {
            *slot = byte as c_char;
        }
        let index = failure.index.map_or(-1, |i| i64::try_from(i).unwrap_or(i64::MAX));
        // SAFETY: `error` is not null and, by this function's contract, valid for one write.
        unsafe { error.write(UwmlError { code: failure.code, reserved: 0, index, field }) };
    }
    failure.code
}

/// The f32 and f64 halves of the joint losses' parameters.
pub(crate) trait Precision: RealField + Copy + uwml_core::Real {
    type LossParams: Copy;
    /// # Errors
    /// A parameter that the core rejects.
    fn losses(params: &Self::LossParams) -> Result<JointLosses<Self>, ModelError>;
    fn default_loss_params() -> Self::LossParams;
}

macro_rules! precision {
    ($t:ty, $loss:ident, $drive:ident, $oil:ident, $seal:ident) => {
        impl Precision for $t {
            type LossParams = $loss;

            fn losses(p: &$loss) -> Result<JointLosses<$t>, ModelError> {
                let d = &p.drive;
                let drive = Drive::new(d.torque_constant, d.ratio, d.efficiency, d.rated_current)?;
                let o = &p.oil;
                let oil = match p.has_oil {
                    0 => None,
                    _ => Some(OilDrag::new(
                        o.k_oil,
                        o.exponent,
                        o.pressure_sensitivity,
                        o.temperature_sensitivity,
                        o.reference_pressure,
                        o.reference_temperature,
                    )?),
                };
                let s = &p.seal;
                let seal = match p.has_seal {
                    0 => None,
                    _ => Some(Seal::new(s.c, s.s, s.d, s.stribeck_speed)?),
                };
                JointLosses::new(drive, oil, seal, p.epsilon)
            }

            /// The parameters of `JointLosses::default()`, read from the core (its `Default` impls
            /// document them); `tests/robot_losses.rs` checks that they build that `JointLosses`
            /// again.
            fn default_loss_params() -> $loss {
                let defaults = JointLosses::<$t>::default();
                let (drive, oil, seal) =
                    (defaults.drive, defaults.oil.unwrap_or_default(), defaults.seal.unwrap_or_default());
                $loss {
                    drive: $drive {
                        torque_constant: drive.torque_constant(),
                        ratio: drive.ratio(),
                        efficiency: drive.efficiency(),
                        rated_current: drive.rated_current(),
                    },
                    oil: $oil {
                        k_oil: oil.k_oil(),
                        exponent: oil.exponent(),
                        pressure_sensitivity: oil.pressure_sensitivity(),
                        temperature_sensitivity: oil.temperature_sensitivity(),
                        reference_pressure: oil.reference_pressure(),
                        reference_temperature: oil.reference_temperature(),
                    },
                    seal: $seal {
                        c: seal.running(),
                        s: seal.breakaway(),
                        d: seal.viscous(),
                        stribeck_speed: seal.stribeck_speed(),
                    },
                    epsilon: defaults.epsilon(),
                    has_oil: i32::from(defaults.oil.is_some()),
                    has_seal: i32::from(defaults.seal.is_some()),
                }
            }
        }
    };
}

precision!(f64, UwmlJointLossParamsF64, UwmlDriveParamsF64, UwmlOilParamsF64, UwmlSealParamsF64);
precision!(f32, UwmlJointLossParamsF32, UwmlDriveParamsF32, UwmlOilParamsF32, UwmlSealParamsF32);

/// Copies `K` values from a caller's array.
///
/// # Safety
/// `p` is null or valid for reads of `K` consecutive `P`s.
unsafe fn read_array<P: Copy, const K: usize>(p: *const P, name: &'static str) -> Result<[P; K], Failure> {
    if p.is_null() {
        return Err(Failure::null(name));
    }
    // SAFETY: not null, valid for reads of `K` values (contract); `[P; K]` has `P`'s alignment.
    Ok(unsafe { p.cast::<[P; K]>().read() })
}

/// Copies one value.
///
/// # Safety
/// `p` is null or valid for reads of a `P`.
pub(crate) unsafe fn read_one<P: Copy>(p: *const P, name: &'static str) -> Result<P, Failure> {
    // SAFETY: forwarded contract, with K = 1.
    let [value] = unsafe { read_array::<P, 1>(p, name) }?;
    Ok(value)
}

pub(crate) fn non_null<P>(p: *mut P, name: &'static str) -> Result<*mut P, Failure> {
    if p.is_null() { Err(Failure::null(name)) } else { Ok(p) }
}

/// `UWML_ERR_NON_FINITE` naming the first non-finite element of a state.
/// `UWML_ERR_OVERFLOW` naming `field` and the first of `values` (per joint) that is not finite;
/// for outputs of a finite state (the inputs are checked first).
pub(crate) fn check_overflow<T: RealField + Copy>(
    values: impl Iterator<Item = T>,
    field: &'static str,
) -> Result<(), Failure> {
    let mut values = values;
    match values.position(|x| !x.is_finite()) {
        Some(i) => Err(Failure::new(UWML_ERR_OVERFLOW, field, Some(i))),
        None => Ok(()),
    }
}

/// The core's domain of the loss conditions (`JointLosses::at`), with the C names of the
/// arguments: pressure from 0 to 1.2e8 Pa, temperature above absolute zero.
pub(crate) fn check_conditions<T: RealField + Copy>(pressure: T, temperature: T) -> Result<(), Failure> {
    uwml_core::check_conditions(pressure, temperature).map_err(|e| {
        let field = if e.field == "pressure" { "pressure_pa" } else { "temperature_c" };
        Failure { field, ..Failure::from(e) }
    })
}

/// # Safety
/// `out` is null or valid for one write of a `T`.
pub(crate) unsafe fn pressure_at_depth<T: RealField + Copy>(
    depth: T,
    sea_density: T,
    gravity: T,
    out: *mut T,
) -> Result<(), Failure> {
    if out.is_null() {
        return Err(Failure::null("out"));
    }
    let pressure = uwml_core::pressure_at_depth(depth, sea_density, gravity)?;
    // SAFETY: not null, and by this function's contract valid for one write.
    unsafe { out.write(pressure) };
    Ok(())
}

/// `joint_index` as an index, if it is one of the robot's `count` joints.
pub(crate) fn joint_slot(joint_index: u32, count: usize) -> Result<usize, Failure> {
    usize::try_from(joint_index).ok().filter(|&i| i < count).ok_or(Failure::new(
        UWML_ERR_INDEX_OUT_OF_RANGE,
        "joint_index",
        usize::try_from(joint_index).ok(),
    ))
}

/// # Safety
/// `out` is null or valid for writes of a `T::LossParams`.
pub(crate) unsafe fn default_losses<T: Precision>(out: *mut T::LossParams) -> Result<(), Failure> {
    let out = non_null(out, "out")?;
    // SAFETY: not null, valid for writes (contract).
    unsafe { out.write(T::default_loss_params()) };
    Ok(())
}
