//! The precision-generic implementation behind the `extern "C"` functions of the crate root.
//!
//! Every function here takes the caller's raw pointers, checks them for null before anything
//! else, copies its inputs by value, and writes its outputs with one `write` at the end, so
//! that no Rust reference to caller memory outlives the read it was made for.

use core::ffi::c_char;

use uwml_core::nalgebra::RealField;
use uwml_core::{
    BaseMotion, Chain, Coefficients, Current, Drive, Joint, JointForces, JointLoss, JointLosses, Link, ModelError,
    OilDrag, Problem, RobotData, Seal, Segment, Water,
};

use crate::robot::{Model, check_evaluation, environment_total};
use crate::{
    UWML_ERR_BELOW_ABSOLUTE_ZERO, UWML_ERR_BEYOND_DEEPEST_OCEAN, UWML_ERR_INDEX_OUT_OF_RANGE, UWML_ERR_NEGATIVE,
    UWML_ERR_NON_FINITE, UWML_ERR_NON_POSITIVE, UWML_ERR_NOT_PERPENDICULAR, UWML_ERR_NOT_POSITIVE_SEMIDEFINITE,
    UWML_ERR_NOT_SYMMETRIC, UWML_ERR_NOT_UNIT, UWML_ERR_NULL_POINTER, UWML_ERR_OUT_OF_ORDER, UWML_ERR_OUT_OF_RANGE,
    UWML_ERR_OVERFLOW, UWML_ERR_TOO_LARGE, UWML_ERR_UNINITIALIZED, UWML_ERROR_FIELD_LEN, UWML_OK, UwmlDriveParamsF32,
    UwmlDriveParamsF64, UwmlEnvironment3F32, UwmlEnvironment3F64, UwmlError, UwmlHydro3F32, UwmlHydro3F64,
    UwmlJointLossParamsF32, UwmlJointLossParamsF64, UwmlJointParamsF32, UwmlJointParamsF64, UwmlLeg3F32, UwmlLeg3F64,
    UwmlLinkParamsF32, UwmlLinkParamsF64, UwmlOilParamsF32, UwmlOilParamsF64, UwmlSealParamsF32, UwmlSealParamsF64,
};

/// The joints of the C API's leg.
pub(crate) const N: usize = 3;

/// What lives in the opaque words of `UwmlLeg3F64` / `UwmlLeg3F32`: the leg as a robot of the
/// robot API (`crate::robot`), whose evaluation it is.
#[derive(Clone, Copy)]
pub(crate) struct Leg<T: RealField + Copy> {
    /// The leg's robot (each link's segment in link order), water and joint losses.
    pub(crate) model: Model<T, N, N>,
}

impl<T: RealField + uwml_core::Real> Leg<T> {
    /// A chain in default water, with the default coefficients and no losses.
    fn of_chain(chain: &Chain<T, N>) -> Self {
        Self { model: Model::new(*chain.robot(), Water::default()) }
    }

    /// The same leg with other coefficients (link `i`'s for the segment of link `i`).
    fn with_coefficients(&self, coefficients: &Coefficients<T, N>) -> Self {
        let mut model = self.model;
        model.robot = model.robot.with_coefficients(&model.robot.link_coefficients(coefficients));
        Self { model }
    }
}

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

/// The f32 and f64 halves of the C API.
pub(crate) trait Precision: RealField + Copy + uwml_core::Real {
    /// The caller-allocated opaque leg: one tag word, then the `Leg<Self>`.
    type Leg;
    type JointParams: Copy;
    type LinkParams: Copy;
    type LossParams: Copy;
    type Environment;
    type Hydro;
    /// The tag word of a leg written by this library ("UWML3F64" / "UWML3F32" in ASCII).
    const TAG: u64;
    fn joint(params: &Self::JointParams) -> Joint<Self>;
    fn link(params: &Self::LinkParams) -> Link<Self>;
    /// # Errors
    /// A parameter that the core rejects.
    fn losses(params: &Self::LossParams) -> Result<JointLosses<Self>, ModelError>;
    fn default_loss_params() -> Self::LossParams;
    /// The first three joints' forces and losses (zero where there are fewer).
    fn environment(forces: &[JointForces<Self>], losses: &[JointLoss<Self>]) -> Self::Environment;
    /// The first three joints' forces (zero where there are fewer).
    fn hydro(forces: &[JointForces<Self>]) -> Self::Hydro;
}

macro_rules! precision {
    ($t:ty, $tag:expr, $leg:ty, $joint:ty, $link:ty, $loss:ident, $drive:ident, $oil:ident, $seal:ident,
     $environment:ident, $hydro:ident) => {
        impl Precision for $t {
            type Leg = $leg;
            type JointParams = $joint;
            type LinkParams = $link;
            type LossParams = $loss;
            type Environment = $environment;
            type Hydro = $hydro;
            const TAG: u64 = $tag;

            fn joint(p: &$joint) -> Joint<$t> {
                Joint { origin: p.origin.into(), axis: p.axis.into() }
            }

            fn link(p: &$link) -> Link<$t> {
                let s = &p.segment;
                let [n0, n1] = s.normals;
                Link {
                    mass: p.mass,
                    com: p.com.into(),
                    volume: p.volume,
                    cob: p.cob.into(),
                    segment: (p.has_segment != 0).then(|| Segment {
                        start: s.start.into(),
                        axis: s.axis.into(),
                        length: s.length,
                        normals: [n0.into(), n1.into()],
                        widths: s.widths,
                        area: s.area,
                    }),
                }
            }

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
            /// document them); `tests/api.rs` checks that they build that `JointLosses` again.
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

            fn environment(forces: &[JointForces<$t>], losses: &[JointLoss<$t>]) -> $environment {
                let none = JointLoss { visc: 0.0, seal: 0.0, current: 0.0 };
                let loss = |i: usize| losses.get(i).copied().unwrap_or(none);
                let joint = |i: usize| {
                    forces.get(i).copied().unwrap_or(JointForces {
                        drag: 0.0,
                        added_mass: 0.0,
                        buoyancy: 0.0,
                        gravity: 0.0,
                    })
                };
                let each = |f: &dyn Fn(&JointForces<$t>, &JointLoss<$t>) -> $t| {
                    core::array::from_fn(|i| f(&joint(i), &loss(i)))
                };
                $environment {
                    drag: each(&|f, _| f.drag),
                    added_mass: each(&|f, _| f.added_mass),
                    buoyancy: each(&|f, _| f.buoyancy),
                    gravity: each(&|f, _| f.gravity),
                    visc: each(&|_, l| l.visc),
                    seal: each(&|_, l| l.seal),
                    current: each(&|_, l| l.current),
                    total: each(&|f, l| environment_total(f, l)),
                }
            }

            fn hydro(forces: &[JointForces<$t>]) -> $hydro {
                let each = |f: &dyn Fn(&JointForces<$t>) -> $t| {
                    core::array::from_fn(|i| {
                        f(&forces.get(i).copied().unwrap_or(JointForces {
                            drag: 0.0,
                            added_mass: 0.0,
                            buoyancy: 0.0,
                            gravity: 0.0,
                        }))
                    })
                };
                $hydro {
                    drag: each(&|f| f.drag),
                    added_mass: each(&|f| f.added_mass),
                    buoyancy: each(&|f| f.buoyancy),
                    gravity: each(&|f| f.gravity),
                    total: each(&|f| f.total()),
                }
            }
        }
    };
}

precision!(
    f64,
    u64::from_be_bytes(*b"UWML3F64"),
    UwmlLeg3F64,
    UwmlJointParamsF64,
    UwmlLinkParamsF64,
    UwmlJointLossParamsF64,
    UwmlDriveParamsF64,
    UwmlOilParamsF64,
    UwmlSealParamsF64,
    UwmlEnvironment3F64,
    UwmlHydro3F64
);
precision!(
    f32,
    u64::from_be_bytes(*b"UWML3F32"),
    UwmlLeg3F32,
    UwmlJointParamsF32,
    UwmlLinkParamsF32,
    UwmlJointLossParamsF32,
    UwmlDriveParamsF32,
    UwmlOilParamsF32,
    UwmlSealParamsF32,
    UwmlEnvironment3F32,
    UwmlHydro3F32
);

/// Where the `Leg<T>` starts: right after the tag word (offsets asserted in the crate root).
fn storage<T: Precision>(leg: *const T::Leg) -> *const Leg<T> {
    leg.cast::<u64>().wrapping_add(1).cast()
}

fn storage_mut<T: Precision>(leg: *mut T::Leg) -> *mut Leg<T> {
    leg.cast::<u64>().wrapping_add(1).cast()
}

/// The leg behind a caller's pointer, if the pointer is not null and the leg was written by
/// this library (its tag word is right).
///
/// # Safety
/// `leg` is null or valid for reads of a `T::Leg` that is not written during `'a`.
unsafe fn leg_ref<'a, T: Precision>(leg: *const T::Leg) -> Result<&'a Leg<T>, Failure> {
    if leg.is_null() {
        return Err(Failure::null("leg"));
    }
    // SAFETY: `leg` is valid for reads (contract) and starts with its tag word, a plain `u64`
    // at offset 0 of an 8-aligned `repr(C)` struct, for which every bit pattern is valid.
    let tag = unsafe { leg.cast::<u64>().read() };
    if tag != T::TAG {
        return Err(Failure::new(UWML_ERR_UNINITIALIZED, "leg", None));
    }
    // SAFETY: the tag is only ever written by `store`, right after a valid `Leg<T>` was written
    // at `storage(leg)`, which is in bounds and aligned (compile-time assertions in the crate
    // root); the caller does not write the leg during `'a` (contract).
    Ok(unsafe { &*storage::<T>(leg) })
}

/// The same as [`leg_ref`], mutable.
///
/// # Safety
/// `leg` is null or valid for reads and writes of a `T::Leg` not accessed otherwise during `'a`.
unsafe fn leg_mut<'a, T: Precision>(leg: *mut T::Leg) -> Result<&'a mut Leg<T>, Failure> {
    // SAFETY: the contract of `leg_ref` is implied by this function's.
    unsafe { leg_ref::<T>(leg) }?;
    // SAFETY: as in `leg_ref`, and the caller grants exclusive access during `'a`.
    Ok(unsafe { &mut *storage_mut::<T>(leg) })
}

/// Writes a leg and its tag.
///
/// # Safety
/// `out` is not null and valid for writes of a `T::Leg`.
unsafe fn store<T: Precision>(out: *mut T::Leg, leg: Leg<T>) {
    // SAFETY: `storage_mut(out)` is in bounds and aligned for `Leg<T>` (compile-time assertions
    // in the crate root) and `out` is valid for writes (contract). The tag goes last, so a leg
    // carries the tag only once its contents are valid.
    unsafe {
        storage_mut::<T>(out).write(leg);
        out.cast::<u64>().write(T::TAG);
    }
}

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

/// `joint_index` as an index, if it is one of `count` joints (the leg's 3, a robot's joint count).
pub(crate) fn joint_slot(joint_index: u32, count: usize) -> Result<usize, Failure> {
    usize::try_from(joint_index).ok().filter(|&i| i < count).ok_or(Failure::new(
        UWML_ERR_INDEX_OUT_OF_RANGE,
        "joint_index",
        usize::try_from(joint_index).ok(),
    ))
}

/// # Safety
/// `out` is null or valid for writes of a `T::Leg`.
pub(crate) unsafe fn paper<T: Precision>(out: *mut T::Leg) -> Result<(), Failure> {
    let out = non_null(out, "out")?;
    // SAFETY: not null, valid for writes (contract).
    unsafe { store::<T>(out, Leg::of_chain(&Chain::paper())) };
    Ok(())
}

/// # Safety
/// `joints` and `links` are null or valid for reads of 3 elements; `out` is null or valid for
/// writes of a `T::Leg`.
pub(crate) unsafe fn new<T: Precision>(
    joints: *const T::JointParams,
    links: *const T::LinkParams,
    out: *mut T::Leg,
) -> Result<(), Failure> {
    // SAFETY: forwarded contract.
    let joints = unsafe { read_array::<_, N>(joints, "joints") }?;
    // SAFETY: forwarded contract.
    let links = unsafe { read_array::<_, N>(links, "links") }?;
    let out = non_null(out, "out")?;
    let leg = Leg::of_chain(&Chain::new(joints.map(|j| T::joint(&j)), links.map(|l| T::link(&l)))?);
    // SAFETY: not null, valid for writes (contract).
    unsafe { store::<T>(out, leg) };
    Ok(())
}

/// # Safety
/// `leg` is null or valid for reads and writes of a `T::Leg`.
pub(crate) unsafe fn set_water<T: Precision>(leg: *mut T::Leg, density: T, gravity: T) -> Result<(), Failure> {
    // SAFETY: forwarded contract; the reference is this call's only access.
    let leg = unsafe { leg_mut::<T>(leg) }?;
    leg.model.water = Water::new(density, gravity)?;
    Ok(())
}

/// # Safety
/// `leg` is null or valid for reads and writes of a `T::Leg`.
pub(crate) unsafe fn set_coefficients<T: Precision>(leg: *mut T::Leg, cd: T, cm: T) -> Result<(), Failure> {
    // SAFETY: forwarded contract; the reference is this call's only access.
    let leg = unsafe { leg_mut::<T>(leg) }?;
    *leg = leg.with_coefficients(&Coefficients::uniform(cd, cm)?);
    Ok(())
}

/// # Safety
/// `leg` is null or valid for reads and writes of a `T::Leg`; `cd` and `cm` are null or valid
/// for reads of 6 values and do not overlap the leg.
pub(crate) unsafe fn set_coefficients_per_direction<T: Precision>(
    leg: *mut T::Leg,
    cd: *const T,
    cm: *const T,
) -> Result<(), Failure> {
    // SAFETY: forwarded contract (the reference is checked first and used last).
    unsafe { leg_ref::<T>(leg) }?;
    // SAFETY: forwarded contract.
    let cd = unsafe { read_array::<[T; 2], N>(cd.cast(), "cd") }?;
    // SAFETY: forwarded contract.
    let cm = unsafe { read_array::<[T; 2], N>(cm.cast(), "cm") }?;
    let coefficients = Coefficients::per_direction(cd, cm)?;
    // SAFETY: forwarded contract; the reference is this call's only access.
    let leg = unsafe { leg_mut::<T>(leg) }?;
    *leg = leg.with_coefficients(&coefficients);
    Ok(())
}

/// # Safety
/// `out` is null or valid for writes of a `T::LossParams`.
pub(crate) unsafe fn default_losses<T: Precision>(out: *mut T::LossParams) -> Result<(), Failure> {
    let out = non_null(out, "out")?;
    // SAFETY: not null, valid for writes (contract).
    unsafe { out.write(T::default_loss_params()) };
    Ok(())
}

/// # Safety
/// `leg` is null or valid for reads and writes of a `T::Leg`; `params` is null or valid for
/// reads of a `T::LossParams`.
pub(crate) unsafe fn set_losses<T: Precision>(
    leg: *mut T::Leg,
    joint_index: u32,
    params: *const T::LossParams,
    pressure: T,
    temperature: T,
) -> Result<(), Failure> {
    // SAFETY: forwarded contract (checked first, the mutable reference is taken last).
    unsafe { leg_ref::<T>(leg) }?;
    let slot = joint_slot(joint_index, N)?;
    // SAFETY: forwarded contract.
    let params = unsafe { read_one(params, "params") }?;
    let losses = T::losses(&params).map_err(|e| Failure::from_model(e, Some(slot)))?;
    check_conditions(pressure, temperature)?;
    // SAFETY: forwarded contract; the reference is this call's only access.
    unsafe { leg_mut::<T>(leg) }?.model.set_losses(slot, losses, pressure, temperature);
    Ok(())
}

/// # Safety
/// `leg` is null or valid for reads and writes of a `T::Leg`.
pub(crate) unsafe fn clear_losses<T: Precision>(leg: *mut T::Leg, joint_index: u32) -> Result<(), Failure> {
    // SAFETY: forwarded contract; the reference is this call's only access.
    let leg = unsafe { leg_mut::<T>(leg) }?;
    leg.model.clear_losses(joint_slot(joint_index, N)?);
    Ok(())
}

/// # Safety
/// `leg` is null or valid for reads and writes of a `T::Leg`.
pub(crate) unsafe fn set_conditions<T: Precision>(
    leg: *mut T::Leg,
    pressure: T,
    temperature: T,
) -> Result<(), Failure> {
    // SAFETY: forwarded contract; the reference is this call's only access.
    unsafe { leg_mut::<T>(leg) }?.model.set_conditions(pressure, temperature)
}

/// `(q, q̇, q̈)`.
type States<T> = [[T; N]; 3];

/// The three joint-state vectors.
///
/// # Safety
/// Each pointer is null or valid for reads of 3 values.
unsafe fn read_states<T: Precision>(q: *const T, qd: *const T, qdd: *const T) -> Result<States<T>, Failure> {
    // SAFETY: forwarded contract.
    let q = unsafe { read_array::<T, N>(q, "q") }?;
    // SAFETY: forwarded contract.
    let qd = unsafe { read_array::<T, N>(qd, "qd") }?;
    // SAFETY: forwarded contract.
    let qdd = unsafe { read_array::<T, N>(qdd, "qdd") }?;
    Ok([q, qd, qdd])
}

/// The robot API's evaluation of the leg, on a fixed base in still water, into a workspace.
fn evaluate<T: Precision>(leg: &Leg<T>, [q, qd, qdd]: &States<T>, with_losses: bool) -> RobotData<T, N> {
    let mut data = RobotData::new();
    leg.model.evaluate([q, qd, qdd], BaseMotion::fixed(), Current::still(), with_losses, &mut data);
    data
}

/// # Safety
/// `leg` is null or valid for reads of a `T::Leg`; `q`, `qd`, `qdd` null or valid for reads of
/// 3 values; `out` null or valid for writes of a `T::Hydro`.
pub(crate) unsafe fn hydro<T: Precision>(
    leg: *const T::Leg,
    q: *const T,
    qd: *const T,
    qdd: *const T,
    out: *mut T::Hydro,
) -> Result<(), Failure> {
    // SAFETY: forwarded contract; the reference is last used before `out` is written.
    let leg = unsafe { leg_ref::<T>(leg) }?;
    // SAFETY: forwarded contract.
    let state = unsafe { read_states(q, qd, qdd) }?;
    let out = non_null(out, "out")?;
    let data = evaluate(leg, &state, false);
    // SAFETY: not null, valid for writes (contract).
    unsafe { out.write(T::hydro(data.joint_forces())) };
    let [q, qd, qdd] = &state;
    check_evaluation(&data, [q, qd, qdd], false)
}

/// # Safety
/// `leg` is null or valid for reads of a `T::Leg`; `q`, `qd`, `qdd` null or valid for reads of
/// 3 values; `out` null or valid for writes of a `T::Environment`.
pub(crate) unsafe fn environment<T: Precision>(
    leg: *const T::Leg,
    q: *const T,
    qd: *const T,
    qdd: *const T,
    out: *mut T::Environment,
) -> Result<(), Failure> {
    // SAFETY: forwarded contract; the reference is last used before `out` is written.
    let leg = unsafe { leg_ref::<T>(leg) }?;
    // SAFETY: forwarded contract.
    let state = unsafe { read_states(q, qd, qdd) }?;
    let out = non_null(out, "out")?;
    let data = evaluate(leg, &state, true);
    // SAFETY: not null, valid for writes (contract).
    unsafe { out.write(T::environment(data.joint_forces(), data.joint_losses())) };
    let [q, qd, qdd] = &state;
    check_evaluation(&data, [q, qd, qdd], false)
}
