//! The precision-generic implementation of the `uwml_robot_*` functions: any robot up to `J`
//! joints and `S` segments (docs/model.md section 10), with joint losses, in an opaque block
//! (the model: validated once, then only read by an evaluation), and the evaluation's workspace
//! in another (what an evaluation writes), so that an evaluation needs no other storage.
//!
//! As in `imp`: every caller pointer is checked for null before anything else, inputs are copied
//! by value, outputs are written at the end, and nothing is written on error (except NaN
//! forces for a non-finite joint state).

use uwml_core::nalgebra::{Matrix3, Matrix6, RealField, Vector3};
use uwml_core::{
    AddedMassForm, BaseMotion, Conditions, Current, EnvironmentWrench, JointForces, JointKind, JointLoss, JointLosses,
    LossState, LumpedBody, ModelError, Owner, RigidBody, Robot, RobotData, RobotSegment, Section, SegmentCoefficients,
    TreeJoint, Water, presets, robot_hydro,
};

use crate::imp::{Failure, check_conditions, check_overflow, joint_slot, non_null, read_one};
use crate::{
    UWML_ADDED_MASS_KIRCHHOFF, UWML_ADDED_MASS_MORISON, UWML_BASE, UWML_ERR_NON_FINITE, UWML_ERR_OUT_OF_RANGE,
    UWML_ERR_OVERFLOW, UWML_ERR_UNINITIALIZED, UWML_JOINT_PRISMATIC, UWML_JOINT_REVOLUTE, UWML_SECTION_CIRCULAR,
    UWML_SECTION_RECTANGULAR, UwmlBaseMotionF32, UwmlBaseMotionF64, UwmlBaseWrenchF32, UwmlBaseWrenchF64, UwmlBodyF32,
    UwmlBodyF64, UwmlCurrentF32, UwmlCurrentF64, UwmlJointEnvironmentF32, UwmlJointEnvironmentF64, UwmlJointForcesF32,
    UwmlJointForcesF64, UwmlLumpedF32, UwmlLumpedF64, UwmlRobotF32, UwmlRobotF64, UwmlRobotSegmentF32,
    UwmlRobotSegmentF64, UwmlTreeJointF32, UwmlTreeJointF64, UwmlWorkspaceF32, UwmlWorkspaceF64,
};

/// The joint capacity of the C API's robot.
pub(crate) const J: usize = 16;
/// The segment capacity of the C API's robot.
pub(crate) const S: usize = 32;
/// The lumped-model capacity of the C API's robot (`UWML_ROBOT_MAX_LUMPED`).
pub(crate) const B: usize = 4;

/// What lives in the opaque words of `UwmlRobotF64` / `UwmlRobotF32`: a robot with everything its
/// evaluation takes besides the joint state, the base's motion, the current and a workspace: the
/// water, the added-mass form and the joints' losses. Written by construction and the setters,
/// only read by an evaluation.
#[derive(Clone, Copy)]
pub(crate) struct Model<T: RealField + Copy> {
    pub(crate) robot: Robot<T, J, S, B>,
    pub(crate) water: Water<T>,
    /// How the added-mass forces depend on the velocities (`uwml_robot_set_added_mass_form_*`):
    /// `UWML_ADDED_MASS_KIRCHHOFF` or else Morison's, kept as the C constant so that every bit
    /// pattern of a copied block is a valid value.
    form: i32,
    /// Each joint's loss model (`uwml_robot_set_losses_*`), kept so that a change of conditions
    /// can recompute `states`; `None` for a joint without losses and beyond the robot's joints.
    losses: [Option<JointLosses<T>>; J],
    /// Each joint's losses at its current pressure and temperature.
    states: [Option<LossState<T>>; J],
}

/// What lives in the opaque words of `UwmlWorkspaceF64` / `UwmlWorkspaceF32`: the workspace and
/// results of an evaluation of any robot of the API (`uwml_core::RobotData`).
pub(crate) type Workspace<T> = RobotData<T, J>;

impl<T: RealField + uwml_core::Real> Model<T> {
    /// Joint `slot`'s losses (a joint of the robot), at `pressure` and `temperature` (checked).
    pub(crate) fn set_losses(&mut self, slot: usize, losses: JointLosses<T>, pressure: T, temperature: T) {
        if let (Some(model), Some(state)) = (self.losses.get_mut(slot), self.states.get_mut(slot)) {
            *model = Some(losses);
            *state = losses.at(pressure, temperature).ok();
        }
    }

    /// Joint `slot` without losses.
    pub(crate) fn clear_losses(&mut self, slot: usize) {
        if let (Some(model), Some(state)) = (self.losses.get_mut(slot), self.states.get_mut(slot)) {
            (*model, *state) = (None, None);
        }
    }

    /// Every joint's losses at a new pressure and temperature.
    ///
    /// # Errors
    /// Conditions outside the core's domain; nothing changes.
    pub(crate) fn set_conditions(&mut self, pressure: T, temperature: T) -> Result<(), Failure> {
        check_conditions(pressure, temperature)?;
        for (model, state) in self.losses.iter().zip(self.states.iter_mut()) {
            *state = model.and_then(|m| m.at(pressure, temperature).ok());
        }
        Ok(())
    }

    /// The core's `robot_hydro` at `state` (the robot's joints first), with the joints' losses
    /// if `with_losses` (zero otherwise), into `data`.
    pub(crate) fn evaluate(
        &self,
        state: [&[T; J]; 3],
        motion: BaseMotion<T>,
        current: Current<T>,
        with_losses: bool,
        data: &mut Workspace<T>,
    ) {
        let form =
            if self.form == UWML_ADDED_MASS_KIRCHHOFF { AddedMassForm::Kirchhoff } else { AddedMassForm::Morison };
        let losses = if with_losses { Some(&self.states) } else { None };
        let conditions = Conditions { water: self.water, motion, current, coefficients: None, form, losses };
        robot_hydro(&self.robot, &conditions, state, data);
    }
}

/// The first `n` values of a state.
pub(crate) fn used<T>(state: &[T], n: usize) -> &[T] {
    state.get(..n).unwrap_or(&[])
}

/// After an evaluation into `data` at `state` (the robot's joints only): a non-finite state
/// (its first element), else outputs that overflow: `total` (forces plus losses), `current`, and
/// the base wrench.
fn check_evaluation<T: RealField + Copy>(data: &Workspace<T>, state: [&[T]; 3]) -> Result<(), Failure> {
    let [q, qd, qdd] = state;
    check_states([(q, "q"), (qd, "qd"), (qdd, "qdd")])?;
    let none = JointLoss { visc: T::zero(), seal: T::zero(), current: T::zero() };
    let loss = |i: usize| data.joint_losses().get(i).copied().unwrap_or(none);
    let forces = data.joint_forces().iter().enumerate();
    check_overflow(forces.map(|(i, f)| environment_total(f, &loss(i))), "total")?;
    check_overflow((0..data.joint_forces().len()).map(|i| loss(i).current), "current")?;
    if data.base_wrench().total().to_array().iter().any(|x| !x.is_finite()) {
        return Err(Failure::new(UWML_ERR_OVERFLOW, "base_wrench", None));
    }
    Ok(())
}

/// The arguments of `uwml_robot_new_*`.
pub(crate) struct Params<T: RobotPrecision> {
    pub(crate) joints: *const T::Joint,
    pub(crate) n_joints: u32,
    pub(crate) links: *const T::Body,
    pub(crate) base: *const T::Body,
    pub(crate) segments: *const T::Segment,
    pub(crate) n_segments: u32,
    pub(crate) density: T,
    pub(crate) gravity: T,
}

/// The arguments of `uwml_robot_hydro_*` and `uwml_robot_environment_*` after the robot: `joints`
/// is their array of `n` results per joint (`T::JointForces` or `T::JointEnvironment`), named
/// `joints_name` in errors.
pub(crate) struct Evaluation<T: RobotPrecision, F> {
    pub(crate) q: *const T,
    pub(crate) qd: *const T,
    pub(crate) qdd: *const T,
    pub(crate) n: u32,
    pub(crate) motion: *const T::Motion,
    pub(crate) current: *const T::Current,
    pub(crate) joints: *mut F,
    pub(crate) joints_name: &'static str,
    pub(crate) base_wrench: *mut T::BaseWrench,
}

/// The f32 and f64 halves of the robot API.
pub(crate) trait RobotPrecision: crate::imp::Precision {
    /// The caller-allocated opaque robot: one tag word, then the `Model<Self>`.
    type Robot;
    /// The caller-allocated opaque workspace: one tag word, then the `Workspace<Self>`.
    type Workspace;
    type Joint: Copy;
    type Body: Copy;
    type Segment: Copy;
    type Motion: Copy;
    type Current: Copy;
    type JointForces: Copy;
    type BaseWrench: Copy;
    type JointEnvironment: Copy;
    type Lumped: Copy;
    /// The tag word of a robot written by this library ("UWMLRF64" / "UWMLRF32" in ASCII).
    const TAG: u64;
    /// The tag word of a workspace written by this library ("UWMLWF64" / "UWMLWF32").
    const WORKSPACE_TAG: u64;
    /// # Errors
    /// A parent or kind that is not one of the documented values.
    fn joint(p: &Self::Joint, index: usize) -> Result<TreeJoint<Self>, Failure>;
    fn body(p: &Self::Body) -> RigidBody<Self>;
    /// # Errors
    /// An owner or section that is not one of the documented values.
    fn segment(p: &Self::Segment, index: usize) -> Result<RobotSegment<Self>, Failure>;
    /// # Errors
    /// What `BaseMotion::new` rejects.
    fn motion(p: &Self::Motion) -> Result<BaseMotion<Self>, ModelError>;
    /// # Errors
    /// What `Current::new` rejects.
    fn current(p: &Self::Current) -> Result<Current<Self>, ModelError>;
    fn joint_forces(f: &JointForces<Self>) -> Self::JointForces;
    fn base_wrench(w: &EnvironmentWrench<Self>) -> Self::BaseWrench;
    /// A joint's forces and losses; `total` is the core's `(hydro total + visc) + seal`, as
    /// `EnvironmentTorques::total` sums them.
    fn joint_environment(f: &JointForces<Self>, loss: &JointLoss<Self>) -> Self::JointEnvironment;
    /// # Errors
    /// An owner that is not one of the documented values.
    fn lumped(p: &Self::Lumped, index: usize) -> Result<LumpedBody<Self>, Failure>;
}

/// `UWML_BASE` or an index (checked against the joints by the core).
fn body_index(value: i32, field: &'static str, index: usize) -> Result<Option<usize>, Failure> {
    if value == UWML_BASE {
        return Ok(None);
    }
    usize::try_from(value).map(Some).map_err(|_| Failure::new(UWML_ERR_OUT_OF_RANGE, field, Some(index)))
}

fn joint_kind(value: i32, index: usize) -> Result<JointKind, Failure> {
    match value {
        UWML_JOINT_REVOLUTE => Ok(JointKind::Revolute),
        UWML_JOINT_PRISMATIC => Ok(JointKind::Prismatic),
        _ => Err(Failure::new(UWML_ERR_OUT_OF_RANGE, "joint.kind", Some(index))),
    }
}

/// Which section a segment has: `Ok(true)` for circular.
fn circular(value: i32, index: usize) -> Result<bool, Failure> {
    match value {
        UWML_SECTION_RECTANGULAR => Ok(false),
        UWML_SECTION_CIRCULAR => Ok(true),
        _ => Err(Failure::new(UWML_ERR_OUT_OF_RANGE, "segment.section", Some(index))),
    }
}

macro_rules! robot_precision {
    ($t:ty, $tag:expr, $workspace_tag:expr, $robot:ty, $workspace:ty, $joint:ty, $body:ty, $segment:ty, $motion:ty,
     $current:ty, $forces:ident, $wrench:ident, $environment:ident, $lumped:ty) => {
        impl RobotPrecision for $t {
            type Robot = $robot;
            type Workspace = $workspace;
            type Joint = $joint;
            type Body = $body;
            type Segment = $segment;
            type Motion = $motion;
            type Current = $current;
            type JointForces = $forces;
            type BaseWrench = $wrench;
            type JointEnvironment = $environment;
            type Lumped = $lumped;
            const TAG: u64 = $tag;
            const WORKSPACE_TAG: u64 = $workspace_tag;

            fn joint(p: &$joint, index: usize) -> Result<TreeJoint<$t>, Failure> {
                Ok(TreeJoint {
                    parent: body_index(p.parent, "joint.parent", index)?,
                    kind: joint_kind(p.kind, index)?,
                    origin: p.origin.into(),
                    axis: p.axis.into(),
                })
            }

            fn body(p: &$body) -> RigidBody<$t> {
                RigidBody { mass: p.mass, com: p.com.into(), volume: p.volume, cob: p.cob.into() }
            }

            fn segment(p: &$segment, index: usize) -> Result<RobotSegment<$t>, Failure> {
                let owner = body_index(p.owner, "segment.owner", index)?.map_or(Owner::Base, Owner::Link);
                let [n0, n1] = p.normals;
                let section = if circular(p.section, index)? {
                    Section::Circular { diameter: p.diameter }
                } else {
                    Section::Rectangular { normals: [n0.into(), n1.into()], widths: p.widths }
                };
                Ok(RobotSegment {
                    owner,
                    start: p.start.into(),
                    axis: p.axis.into(),
                    length: p.length,
                    area: p.area,
                    section,
                    cd: p.cd,
                    cm: p.cm,
                    cd_axial: p.cd_axial,
                    axial_area: p.axial_area,
                })
            }

            fn motion(p: &$motion) -> Result<BaseMotion<$t>, ModelError> {
                BaseMotion::new(
                    p.orientation,
                    p.velocity.into(),
                    p.angular_velocity.into(),
                    p.acceleration.into(),
                    p.angular_acceleration.into(),
                )
            }

            fn current(p: &$current) -> Result<Current<$t>, ModelError> {
                Current::new(p.velocity.into(), p.acceleration.into())
            }

            fn joint_forces(f: &JointForces<$t>) -> $forces {
                $forces {
                    drag: f.drag,
                    added_mass: f.added_mass,
                    buoyancy: f.buoyancy,
                    gravity: f.gravity,
                    total: f.total(),
                }
            }

            fn base_wrench(w: &EnvironmentWrench<$t>) -> $wrench {
                $wrench {
                    drag: w.drag.to_array(),
                    added_mass: w.added_mass.to_array(),
                    buoyancy: w.buoyancy.to_array(),
                    gravity: w.gravity.to_array(),
                    total: w.total().to_array(),
                }
            }

            fn lumped(p: &$lumped, index: usize) -> Result<LumpedBody<$t>, Failure> {
                let owner = body_index(p.owner, "lumped.owner", index)?.map_or(Owner::Base, Owner::Link);
                // All-zero axes (as a zeroed struct has them): the body's own.
                let entry = |rows: &[[$t; 6]; 6], r: usize, c: usize| {
                    rows.get(r).and_then(|row| row.get(c)).copied().unwrap_or(0.0)
                };
                let axes = if p.axes == [[0.0; 3]; 3] {
                    Matrix3::identity()
                } else {
                    Matrix3::from_fn(|r, c| p.axes.get(r).and_then(|row| row.get(c)).copied().unwrap_or(0.0))
                };
                let matrix = |rows: &[[$t; 6]; 6]| Matrix6::from_fn(|r, c| entry(rows, r, c));
                Ok(LumpedBody {
                    owner,
                    point: p.point.into(),
                    axes,
                    added_mass: matrix(&p.added_mass),
                    linear_damping: matrix(&p.linear_damping),
                    quadratic_damping: p.quadratic_damping,
                })
            }

            fn joint_environment(f: &JointForces<$t>, loss: &JointLoss<$t>) -> $environment {
                $environment {
                    drag: f.drag,
                    added_mass: f.added_mass,
                    buoyancy: f.buoyancy,
                    gravity: f.gravity,
                    visc: loss.visc,
                    seal: loss.seal,
                    current: loss.current,
                    total: environment_total(f, loss),
                }
            }
        }
    };
}

/// A joint's environment force, hydrodynamics and losses: `(hydro total + visc) + seal`, in the
/// order of the core's `EnvironmentTorques::total`.
pub(crate) fn environment_total<T: RealField + Copy>(f: &JointForces<T>, loss: &JointLoss<T>) -> T {
    f.total() + loss.visc + loss.seal
}

robot_precision!(
    f64,
    u64::from_be_bytes(*b"UWMLRF64"),
    u64::from_be_bytes(*b"UWMLWF64"),
    UwmlRobotF64,
    UwmlWorkspaceF64,
    UwmlTreeJointF64,
    UwmlBodyF64,
    UwmlRobotSegmentF64,
    UwmlBaseMotionF64,
    UwmlCurrentF64,
    UwmlJointForcesF64,
    UwmlBaseWrenchF64,
    UwmlJointEnvironmentF64,
    UwmlLumpedF64
);
robot_precision!(
    f32,
    u64::from_be_bytes(*b"UWMLRF32"),
    u64::from_be_bytes(*b"UWMLWF32"),
    UwmlRobotF32,
    UwmlWorkspaceF32,
    UwmlTreeJointF32,
    UwmlBodyF32,
    UwmlRobotSegmentF32,
    UwmlBaseMotionF32,
    UwmlCurrentF32,
    UwmlJointForcesF32,
    UwmlBaseWrenchF32,
    UwmlJointEnvironmentF32,
    UwmlLumpedF32
);

/// Where the `Model<T>` starts: right after the tag word (offsets asserted in the crate root).
fn storage_mut<T: RobotPrecision>(robot: *mut T::Robot) -> *mut Model<T> {
    robot.cast::<u64>().wrapping_add(1).cast()
}

/// Where the `Workspace<T>` starts: right after the tag word.
fn workspace_storage_mut<T: RobotPrecision>(workspace: *mut T::Workspace) -> *mut Workspace<T> {
    workspace.cast::<u64>().wrapping_add(1).cast()
}

/// Whether the tag word at `p` (not null) is `tag`.
///
/// # Safety
/// `p` is valid for reads of its first `u64`.
unsafe fn tagged<P>(p: *const P, tag: u64) -> bool {
    // SAFETY: valid for reads (contract); the tag is a plain `u64` at offset 0 of an 8-aligned
    // `repr(C)` struct, for which every bit pattern is valid.
    unsafe { p.cast::<u64>().read() == tag }
}

/// The model behind a caller's pointer, if the pointer is not null and the robot was written by
/// this library (its tag word is right).
///
/// # Safety
/// `robot` is null or valid for reads of a `T::Robot` not written during `'a`.
unsafe fn model_ref<'a, T: RobotPrecision>(robot: *const T::Robot) -> Result<&'a Model<T>, Failure> {
    if robot.is_null() {
        return Err(Failure::null("robot"));
    }
    // SAFETY: not null, valid for reads (contract).
    if !unsafe { tagged(robot, T::TAG) } {
        return Err(Failure::new(UWML_ERR_UNINITIALIZED, "robot", None));
    }
    // SAFETY: the tag is only ever written by `finish`, right after a valid `Model<T>` was written
    // at `storage_mut(robot)`, which is in bounds and aligned (compile-time assertions in the
    // crate root); the caller does not write the robot during `'a` (contract).
    Ok(unsafe { &*storage_mut::<T>(robot.cast_mut()) })
}

/// [`model_ref`], mutable.
///
/// # Safety
/// `robot` is null or valid for reads and writes of a `T::Robot` not accessed otherwise during
/// `'a`.
unsafe fn model_mut<'a, T: RobotPrecision>(robot: *mut T::Robot) -> Result<&'a mut Model<T>, Failure> {
    // SAFETY: the contract of `model_ref` is implied by this function's.
    unsafe { model_ref::<T>(robot) }?;
    // SAFETY: as in `model_ref`, and the caller grants exclusive access during `'a`.
    Ok(unsafe { &mut *storage_mut::<T>(robot) })
}

/// The workspace behind a caller's pointer, if not null and written by
/// `uwml_robot_workspace_init_*` (its tag word is right).
///
/// # Safety
/// `workspace` is null or valid for reads and writes of a `T::Workspace` not accessed otherwise
/// during `'a`.
unsafe fn workspace_mut<'a, T: RobotPrecision>(workspace: *mut T::Workspace) -> Result<&'a mut Workspace<T>, Failure> {
    let workspace = non_null(workspace, "workspace")?;
    // SAFETY: not null, valid for reads (contract).
    if !unsafe { tagged(workspace, T::WORKSPACE_TAG) } {
        return Err(Failure::new(UWML_ERR_UNINITIALIZED, "workspace", None));
    }
    // SAFETY: the tag is only ever written by `workspace_init`, right after a valid `Workspace<T>`
    // was written at `workspace_storage_mut(workspace)` (in bounds and aligned: crate root); the
    // caller grants exclusive access during `'a` (contract).
    Ok(unsafe { &mut *workspace_storage_mut::<T>(workspace) })
}

/// # Safety
/// `out` is null or valid for writes of a `T::Workspace`.
pub(crate) unsafe fn workspace_init<T: RobotPrecision>(out: *mut T::Workspace) -> Result<(), Failure> {
    let out = non_null(out, "workspace")?;
    // SAFETY: not null, valid for writes (contract); the workspace is in bounds and aligned (crate
    // root). The tag goes last, so a workspace carries it only once its contents are valid.
    unsafe {
        workspace_storage_mut::<T>(out).write(Workspace::<T>::new());
        out.cast::<u64>().write(T::WORKSPACE_TAG);
    }
    Ok(())
}

/// Validates a robot and writes it into the model's robot field if valid (nothing otherwise).
/// Not inlined, so that the core's robot under construction and its `Result` (each as large as
/// the robot) live in this frame, not in the caller's beside the converted inputs: on a
/// Cortex-M this halves the stack that construction needs.
///
/// # Safety
/// `model` is valid for writes of a `Model<T>` (it may be uninitialized).
#[inline(never)]
unsafe fn write_robot<T: RobotPrecision>(
    model: *mut Model<T>,
    joints: &[TreeJoint<T>],
    links: &[RigidBody<T>],
    base: RigidBody<T>,
    segments: &[RobotSegment<T>],
) -> Result<(), ModelError> {
    let result = Robot::new(joints, links, base, segments);
    let robot = result.as_ref().map_err(|e| *e)?;
    // SAFETY: valid for writes (contract), not overlapping the local `robot`; the place is
    // computed without reading the model.
    unsafe { core::ptr::copy_nonoverlapping(robot, &raw mut (*model).robot, 1) };
    Ok(())
}

/// The paper's leg (`presets::paper_leg`, in the API's capacity) into the model's robot field; as
/// [`write_robot`].
///
/// # Safety
/// `model` is valid for writes of a `Model<T>` (it may be uninitialized).
#[inline(never)]
unsafe fn write_paper<T: RobotPrecision>(model: *mut Model<T>) -> Result<(), ModelError> {
    let result = presets::paper_leg::<T>().to_capacity::<J, S, B>();
    let robot = result.as_ref().map_err(|e| *e)?;
    // SAFETY: valid for writes (contract), not overlapping the local `robot`; the place is
    // computed without reading the model.
    unsafe { core::ptr::copy_nonoverlapping(robot, &raw mut (*model).robot, 1) };
    Ok(())
}

/// Completes a model whose robot field was just written: the water, Morison's added mass, no
/// joint losses, and the tag, last, so that a robot carries the tag only once its contents are
/// valid.
///
/// # Safety
/// `out` is not null and valid for writes of a `T::Robot` whose robot field holds a valid robot.
#[inline(never)]
unsafe fn finish<T: RobotPrecision>(out: *mut T::Robot, water: Water<T>) {
    let model = storage_mut::<T>(out);
    // SAFETY: `model` is in bounds and aligned for `Model<T>` (compile-time assertions in the
    // crate root) and `out` is valid for writes (contract); the field places are computed without
    // reading or referencing the (possibly uninitialized) model.
    unsafe {
        (&raw mut (*model).water).write(water);
        (&raw mut (*model).form).write(UWML_ADDED_MASS_MORISON);
        (&raw mut (*model).losses).write([None; J]);
        (&raw mut (*model).states).write([None; J]);
        out.cast::<u64>().write(T::TAG);
    }
}

/// The first `n` elements of a caller's array (an empty slice, without reading `p`, if `n` is 0).
///
/// # Safety
/// `p` is null or valid for reads of `n` consecutive `P`s, not written during `'a`.
unsafe fn read_slice<'a, P>(p: *const P, n: usize, name: &'static str) -> Result<&'a [P], Failure> {
    if n == 0 {
        return Ok(&[]);
    }
    if p.is_null() {
        return Err(Failure::null(name));
    }
    // SAFETY: not null, aligned (a C array of `P`) and valid for reads of `n` values (contract).
    Ok(unsafe { core::slice::from_raw_parts(p, n) })
}

/// A count, if it is at most `capacity`.
fn count(n: u32, capacity: usize, field: &'static str) -> Result<usize, Failure> {
    usize::try_from(n).ok().filter(|&n| n <= capacity).ok_or(Failure::new(UWML_ERR_OUT_OF_RANGE, field, None))
}

/// # Safety
/// `out` is null or valid for writes of a `T::Robot`.
pub(crate) unsafe fn paper<T: RobotPrecision>(out: *mut T::Robot) -> Result<(), Failure> {
    let out = non_null(out, "robot")?;
    // SAFETY: not null, valid for writes (contract); in bounds and aligned (crate root).
    unsafe { write_paper::<T>(storage_mut::<T>(out)) }?;
    // SAFETY: as above, and the robot field was just written.
    unsafe { finish::<T>(out, Water::default()) };
    Ok(())
}

/// # Safety
/// `out` is null or valid for writes of a `T::Robot`; the pointers of `params` are null or
/// valid for reads of their counts of elements (`base`: one) and do not overlap `out`.
pub(crate) unsafe fn new<T: RobotPrecision>(out: *mut T::Robot, params: &Params<T>) -> Result<(), Failure> {
    let out = non_null(out, "robot")?;
    let n_joints = count(params.n_joints, J, "n_joints (at most 16)")?;
    let n_segments = count(params.n_segments, S, "n_segments (at most 32)")?;
    // SAFETY: forwarded contract; the slices are read here and dropped before `out` is written.
    let (joints, links, segments) = unsafe {
        (
            read_slice(params.joints, n_joints, "joints")?,
            read_slice(params.links, n_joints, "links")?,
            read_slice(params.segments, n_segments, "segments")?,
        )
    };
    let base = if params.base.is_null() {
        RigidBody::empty()
    } else {
        // SAFETY: not null, valid for reads (contract).
        T::body(&unsafe { read_one(params.base, "base") }?)
    };
    let zero = Vector3::zeros();
    let mut tree = [TreeJoint { parent: None, kind: JointKind::Revolute, origin: zero, axis: zero }; J];
    for (index, (slot, joint)) in tree.iter_mut().zip(joints).enumerate() {
        *slot = T::joint(joint, index)?;
    }
    let mut bodies = [RigidBody::empty(); J];
    for (slot, link) in bodies.iter_mut().zip(links) {
        *slot = T::body(link);
    }
    let mut pieces = [RobotSegment {
        owner: Owner::Base,
        start: zero,
        axis: zero,
        length: T::zero(),
        area: T::zero(),
        section: Section::Circular { diameter: T::zero() },
        cd: [T::zero(); 2],
        cm: [T::zero(); 2],
        cd_axial: T::zero(),
        axial_area: T::zero(),
    }; S];
    for (index, (slot, segment)) in pieces.iter_mut().zip(segments).enumerate() {
        *slot = T::segment(segment, index)?;
    }
    // The water first: once the robot is written, nothing may fail.
    let water = Water::new(params.density, params.gravity)?;
    let used = |n: usize| ..n;
    // SAFETY: not null, valid for writes (contract); in bounds and aligned (crate root). On
    // error nothing is written.
    unsafe {
        write_robot::<T>(
            storage_mut::<T>(out),
            tree.get(used(n_joints)).unwrap_or(&[]),
            bodies.get(used(n_joints)).unwrap_or(&[]),
            base,
            pieces.get(used(n_segments)).unwrap_or(&[]),
        )
    }
    .map_err(Failure::from)?;
    // SAFETY: as above, and the robot field was just written.
    unsafe { finish::<T>(out, water) };
    Ok(())
}

/// A joint state of `n` values, zero beyond.
///
/// # Safety
/// `p` is null or valid for reads of `n` values; `n` is at most `J`.
unsafe fn read_state<T: RobotPrecision>(p: *const T, n: usize, name: &'static str) -> Result<[T; J], Failure> {
    // SAFETY: forwarded contract.
    let values = unsafe { read_slice(p, n, name) }?;
    let mut state = [T::zero(); J];
    for (slot, &value) in state.iter_mut().zip(values) {
        *slot = value;
    }
    Ok(state)
}

/// `UWML_ERR_NON_FINITE` naming the first non-finite element of a state.
pub(crate) fn check_states<T: RealField + Copy>(states: [(&[T], &'static str); 3]) -> Result<(), Failure> {
    for (state, name) in states {
        if let Some(i) = state.iter().position(|x| !x.is_finite()) {
            return Err(Failure::new(UWML_ERR_NON_FINITE, name, Some(i)));
        }
    }
    Ok(())
}

/// Writes joint `i`'s forces and losses to an evaluation's output.
type WriteJoint<'a, T> = dyn FnMut(usize, &JointForces<T>, &JointLoss<T>) + 'a;

/// The evaluation behind `uwml_robot_hydro_*` (`with_losses` false: every joint's loss is
/// zero, and the joint losses are not evaluated) and `uwml_robot_environment_*`: checks, and
/// the core's `robot_hydro` with the joints' losses in its conditions, into the workspace; hands
/// every joint's forces and losses to `write` (joint index, in order) and writes the base wrench;
/// then reports a non-finite state or outputs that overflow (`total`: forces plus losses;
/// `current`; `base_wrench`). One instance per precision, whatever the caller's output type
/// (`write` is dynamic), so that the two evaluations share its code.
///
/// # Safety
/// `robot` is null or valid for reads of a `T::Robot` not written during the call; `workspace`
/// is null or valid for reads and writes of a `T::Workspace` not accessed otherwise during the
/// call; the pointers of `io` are null or valid for their `n` elements (`motion`, `current`,
/// `base_wrench`: one), reads or writes as their constness says, and overlap neither the robot
/// nor the workspace; `joints` says whether `io.joints` is null.
#[inline(never)]
unsafe fn evaluate<T: RobotPrecision>(
    robot: *const T::Robot,
    workspace: *mut T::Workspace,
    io: &Evaluation<T, ()>,
    joints: Result<(), Failure>,
    with_losses: bool,
    write: &mut WriteJoint<'_, T>,
) -> Result<(), Failure> {
    // SAFETY: forwarded contract; the model is only read.
    let model = unsafe { model_ref::<T>(robot) }?;
    // SAFETY: forwarded contract; the reference is this call's only access to the workspace.
    let data = unsafe { workspace_mut::<T>(workspace) }?;
    let n = model.robot.joint_count();
    if usize::try_from(io.n).ok() != Some(n) {
        return Err(Failure::new(UWML_ERR_OUT_OF_RANGE, "n (the robot's joint count)", None));
    }
    // SAFETY: forwarded contract; n <= J (the robot's capacity).
    let (q, qd, qdd) =
        unsafe { (read_state(io.q, n, "q")?, read_state(io.qd, n, "qd")?, read_state(io.qdd, n, "qdd")?) };
    let motion = if io.motion.is_null() {
        BaseMotion::fixed()
    } else {
        // SAFETY: not null, valid for reads (contract).
        T::motion(&unsafe { read_one(io.motion, "motion") }?)?
    };
    let current = if io.current.is_null() {
        Current::still()
    } else {
        // SAFETY: not null, valid for reads (contract).
        T::current(&unsafe { read_one(io.current, "current") }?)?
    };
    if n > 0 {
        joints?;
    }
    model.evaluate([&q, &qd, &qdd], motion, current, with_losses, data);
    let none = JointLoss { visc: T::zero(), seal: T::zero(), current: T::zero() };
    for (i, forces) in data.joint_forces().iter().enumerate() {
        write(i, forces, &data.joint_losses().get(i).copied().unwrap_or(none));
    }
    if !io.base_wrench.is_null() {
        // SAFETY: not null, valid for writes (contract).
        unsafe { io.base_wrench.write(T::base_wrench(data.base_wrench())) };
    }
    check_evaluation(data, [used(&q, n), used(&qd, n), used(&qdd, n)])
}

/// [`evaluate`] writing `row` of every joint's forces and losses to `io.joints`.
///
/// # Safety
/// As [`evaluate`]; `io.joints` is null or valid for writes of `io.n` elements.
unsafe fn evaluate_into<T: RobotPrecision, F>(
    robot: *const T::Robot,
    workspace: *mut T::Workspace,
    io: &Evaluation<T, F>,
    with_losses: bool,
    row: impl Fn(&JointForces<T>, &JointLoss<T>) -> F,
) -> Result<(), Failure> {
    let (joints, joints_name) = (io.joints, io.joints_name);
    let common = Evaluation {
        q: io.q,
        qd: io.qd,
        qdd: io.qdd,
        n: io.n,
        motion: io.motion,
        current: io.current,
        joints: core::ptr::null_mut::<()>(),
        joints_name,
        base_wrench: io.base_wrench,
    };
    let mut write = |i: usize, forces: &JointForces<T>, loss: &JointLoss<T>| {
        // SAFETY: `evaluate` calls this for `i` < n only, and only once `joints` was found not
        // null (when n > 0); it is then valid for writes of n elements (contract).
        unsafe { joints.add(i).write(row(forces, loss)) };
    };
    let joints_ok = non_null(joints, joints_name).map(|_| ());
    // SAFETY: forwarded contract.
    unsafe { evaluate(robot, workspace, &common, joints_ok, with_losses, &mut write) }
}

/// # Safety
/// As [`evaluate_into`].
pub(crate) unsafe fn hydro<T: RobotPrecision>(
    robot: *const T::Robot,
    workspace: *mut T::Workspace,
    io: &Evaluation<T, T::JointForces>,
) -> Result<(), Failure> {
    // SAFETY: forwarded contract.
    unsafe { evaluate_into(robot, workspace, io, false, |forces, _| T::joint_forces(forces)) }
}

/// # Safety
/// As [`evaluate_into`].
pub(crate) unsafe fn environment<T: RobotPrecision>(
    robot: *const T::Robot,
    workspace: *mut T::Workspace,
    io: &Evaluation<T, T::JointEnvironment>,
) -> Result<(), Failure> {
    // SAFETY: forwarded contract.
    unsafe { evaluate_into(robot, workspace, io, true, T::joint_environment) }
}

/// # Safety
/// `robot` is null or valid for reads and writes of a `T::Robot` not accessed otherwise during
/// the call; `params` is null or valid for reads of a `T::LossParams` that does not overlap it.
pub(crate) unsafe fn set_losses<T: RobotPrecision>(
    robot: *mut T::Robot,
    joint_index: u32,
    params: *const T::LossParams,
    pressure: T,
    temperature: T,
) -> Result<(), Failure> {
    // SAFETY: forwarded contract; the reference is this call's only access to the robot.
    let model = unsafe { model_mut::<T>(robot) }?;
    let slot = joint_slot(joint_index, model.robot.joint_count())?;
    // SAFETY: forwarded contract.
    let params = unsafe { read_one(params, "params") }?;
    let losses = T::losses(&params).map_err(|e| Failure::from_model(e, Some(slot)))?;
    check_conditions(pressure, temperature)?;
    model.set_losses(slot, losses, pressure, temperature);
    Ok(())
}

/// # Safety
/// `robot` is null or valid for reads and writes of a `T::Robot` not accessed otherwise during
/// the call; `models` is null or valid for reads of `count` `T::Lumped`s that do not overlap it.
pub(crate) unsafe fn set_lumped<T: RobotPrecision>(
    robot: *mut T::Robot,
    models: *const T::Lumped,
    count: u32,
) -> Result<(), Failure> {
    // SAFETY: forwarded contract; the reference is this call's only access to the robot.
    let model = unsafe { model_mut::<T>(robot) }?;
    let n = self::count(count, B, "lumped (at most UWML_ROBOT_MAX_LUMPED)")?;
    // SAFETY: forwarded contract.
    let given = unsafe { read_slice(models, n, "models") }?;
    let mut bodies = [LumpedBody::none(Owner::Base); B];
    for (index, (slot, lumped)) in bodies.iter_mut().zip(given).enumerate() {
        *slot = T::lumped(lumped, index)?;
    }
    let robot = model.robot.with_lumped(bodies.get(..n).unwrap_or_default())?;
    model.robot = robot;
    Ok(())
}

/// The coefficients of `n` segments, `cd[k]` and `cm[k]` segment `k`'s per normal direction.
///
/// # Safety
/// `robot` is null or valid for reads and writes of a `T::Robot` not accessed otherwise during
/// the call; `cd` and `cm` are null or valid for reads of `n` pairs that do not overlap it.
pub(crate) unsafe fn set_coefficients<T: RobotPrecision>(
    robot: *mut T::Robot,
    cd: *const [T; 2],
    cm: *const [T; 2],
    n: u32,
) -> Result<(), Failure> {
    // SAFETY: forwarded contract; the reference is this call's only access to the robot.
    let model = unsafe { model_mut::<T>(robot) }?;
    let segments = model.robot.segments();
    if usize::try_from(n).ok() != Some(segments.len()) {
        return Err(Failure::new(UWML_ERR_OUT_OF_RANGE, "n_segments (the robot's segment count)", None));
    }
    // SAFETY: forwarded contract.
    let (cd, cm) = unsafe { (read_slice(cd, segments.len(), "cd")?, read_slice(cm, segments.len(), "cm")?) };
    let (mut cd_table, mut cm_table) = ([[T::zero(); 2]; S], [[T::zero(); 2]; S]);
    for (k, (((cd_slot, cm_slot), &cd), (&cm, segment))) in
        cd_table.iter_mut().zip(cm_table.iter_mut()).zip(cd).zip(cm.iter().zip(segments)).enumerate()
    {
        // A circular segment has one coefficient of each kind (given twice), as at construction.
        if let Section::Circular { .. } = segment.section {
            if cd[0] != cd[1] {
                return Err(Failure::new(UWML_ERR_OUT_OF_RANGE, "segment.cd", Some(k)));
            }
            if cm[0] != cm[1] {
                return Err(Failure::new(UWML_ERR_OUT_OF_RANGE, "segment.cm", Some(k)));
            }
        }
        (*cd_slot, *cm_slot) = (cd, cm);
    }
    let table = SegmentCoefficients::per_segment(cd_table, cm_table)?;
    model.robot = model.robot.with_coefficients(&table);
    Ok(())
}

/// # Safety
/// `robot` is null or valid for reads and writes of a `T::Robot` not accessed otherwise during
/// the call.
pub(crate) unsafe fn set_water<T: RobotPrecision>(robot: *mut T::Robot, density: T, gravity: T) -> Result<(), Failure> {
    // SAFETY: forwarded contract; the reference is this call's only access to the robot.
    let model = unsafe { model_mut::<T>(robot) }?;
    model.water = Water::new(density, gravity)?;
    Ok(())
}

/// # Safety
/// `robot` is null or valid for reads and writes of a `T::Robot` not accessed otherwise during
/// the call.
pub(crate) unsafe fn clear_losses<T: RobotPrecision>(robot: *mut T::Robot, joint_index: u32) -> Result<(), Failure> {
    // SAFETY: forwarded contract; the reference is this call's only access to the robot.
    let model = unsafe { model_mut::<T>(robot) }?;
    let slot = joint_slot(joint_index, model.robot.joint_count())?;
    model.clear_losses(slot);
    Ok(())
}

/// # Safety
/// `robot` is null or valid for reads and writes of a `T::Robot` not accessed otherwise during
/// the call.
pub(crate) unsafe fn set_conditions<T: RobotPrecision>(
    robot: *mut T::Robot,
    pressure: T,
    temperature: T,
) -> Result<(), Failure> {
    // SAFETY: forwarded contract; the reference is this call's only access to the robot.
    unsafe { model_mut::<T>(robot) }?.set_conditions(pressure, temperature)
}

/// # Safety
/// `robot` is null or valid for reads and writes of a `T::Robot` not accessed otherwise during
/// the call.
pub(crate) unsafe fn set_added_mass_form<T: RobotPrecision>(robot: *mut T::Robot, form: i32) -> Result<(), Failure> {
    if form != UWML_ADDED_MASS_MORISON && form != UWML_ADDED_MASS_KIRCHHOFF {
        return Err(Failure::new(UWML_ERR_OUT_OF_RANGE, "form (UWML_ADDED_MASS_MORISON or _KIRCHHOFF)", None));
    }
    // SAFETY: forwarded contract; the reference is this call's only access to the robot.
    unsafe { model_mut::<T>(robot) }?.form = form;
    Ok(())
}
