//! The robot API of the C ABI (`uwml_robot_*`): its plain structs and functions, any tree of up
//! to `UWML_ROBOT_MAX_JOINTS` joints and `UWML_ROBOT_MAX_SEGMENTS` segments on a base that may
//! move, in a current, with joint losses (the implementation is `crate::robot`). The joint losses'
//! parameters, the error codes and the constants are in the crate root.

use crate::{
    UWML_ROBOT_F32_WORDS, UWML_ROBOT_F64_WORDS, UWML_WORKSPACE_F32_WORDS, UWML_WORKSPACE_F64_WORDS, UwmlError,
    UwmlJointLossParamsF32, UwmlJointLossParamsF64, imp, robot,
};

/// A robot (tree, bodies, segments, water, added-mass form, joint losses) in f64: the model, for C
/// to allocate (statically: `static UwmlRobotF64 robot;`). Opaque: written only by
/// `uwml_robot_paper_leg_f64` or `uwml_robot_new_f64` and changed only by the setters; the
/// evaluations only read it (`const UwmlRobotF64 *`), so several threads may evaluate one robot at
/// once, each with its own `UwmlWorkspaceF64`. It holds no pointer, so it may be copied with
/// `memcpy`. Other functions refuse a block these did not write (`UWML_ERR_UNINITIALIZED`).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct UwmlRobotF64 {
    /// A tag saying that the library wrote this robot. Do not touch.
    pub opaque_tag: u64,
    /// The robot. Do not touch.
    pub opaque: [u64; UWML_ROBOT_F64_WORDS],
}

/// A robot in f32; as `UwmlRobotF64`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct UwmlRobotF32 {
    /// A tag saying that the library wrote this robot. Do not touch.
    pub opaque_tag: u64,
    /// The robot. Do not touch.
    pub opaque: [u64; UWML_ROBOT_F32_WORDS],
}

/// The workspace of an evaluation in f64 (each link's frame and wrenches, the results), for any
/// robot of the API: `uwml_robot_hydro_f64` and `uwml_robot_environment_f64` write it, and nothing
/// else may use it during the call (one per thread that evaluates). Opaque: written first by
/// `uwml_robot_workspace_init_f64` (others refuse a block it did not write,
/// `UWML_ERR_UNINITIALIZED`); it holds no pointer.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct UwmlWorkspaceF64 {
    /// A tag saying that the library wrote this workspace. Do not touch.
    pub opaque_tag: u64,
    /// The workspace. Do not touch.
    pub opaque: [u64; UWML_WORKSPACE_F64_WORDS],
}

/// A workspace in f32; as `UwmlWorkspaceF64`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct UwmlWorkspaceF32 {
    /// A tag saying that the library wrote this workspace. Do not touch.
    pub opaque_tag: u64,
    /// The workspace. Do not touch.
    pub opaque: [u64; UWML_WORKSPACE_F32_WORDS],
}

/// A joint of a robot: joint `i` moves link `i`. Every frame is parallel to the base frame when
/// all joint positions are zero (URDF without fixed rotations).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct UwmlTreeJointF64 {
    /// The parent: an earlier link (0 to i - 1), or `UWML_BASE` (-1).
    pub parent: i32,
    /// `UWML_JOINT_REVOLUTE` (0) or `UWML_JOINT_PRISMATIC` (1).
    pub kind: i32,
    /// Position of the joint in the parent's frame (the parent link's joint, or the base
    /// origin) [m].
    pub origin: [f64; 3],
    /// Unit axis in the parent's frame (norm 1 within 1e-6; re-normalized).
    pub axis: [f64; 3],
}

/// The bulk of a body (a link or the base), in its own frame (whose origin is its joint, or the
/// base origin).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct UwmlBodyF64 {
    /// Mass [kg], zero or positive.
    pub mass: f64,
    /// Centre of mass [m].
    pub com: [f64; 3],
    /// Displaced volume [m³], zero or positive.
    pub volume: f64,
    /// Centre of buoyancy [m].
    pub cob: [f64; 3],
}

/// A straight piece of a body that meets the water (strip theory), in its body's frame: the
/// slice at arc length s in [0, length] lies at `start + s axis`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct UwmlRobotSegmentF64 {
    /// The body: a link (0 to n_joints - 1), or `UWML_BASE` (-1).
    pub owner: i32,
    /// `UWML_SECTION_RECTANGULAR` (0) or `UWML_SECTION_CIRCULAR` (1).
    pub section: i32,
    /// Start point [m].
    pub start: [f64; 3],
    /// Unit direction.
    pub axis: [f64; 3],
    /// Length [m], positive.
    pub length: f64,
    /// Cross-section area for added mass [m²], positive.
    pub area: f64,
    /// Rectangular only: the two principal normal directions, unit, perpendicular to `axis`
    /// and to each other (within 1e-6; made exact).
    pub normals: [[f64; 3]; 2],
    /// Rectangular only: frontal width for flow along each normal [m], positive.
    pub widths: [f64; 2],
    /// Circular only: diameter [m], positive.
    pub diameter: f64,
    /// Drag coefficients per normal, zero or positive; circular: one, `cd[0] == cd[1]`.
    pub cd: [f64; 2],
    /// Added-mass coefficients per normal, zero or positive; circular: `cm[0] == cm[1]`.
    pub cm: [f64; 2],
    /// Axial drag coefficient, zero or positive (docs/model.md section 12.2): the force
    /// `−½ ρ cd_axial axial_area |u·v| (u·v) u` along the axis; zero (as a zeroed struct has
    /// it): none.
    pub cd_axial: f64,
    /// The axial drag's reference area [m²], zero or positive (typically the section area).
    pub axial_area: f64,
}

/// Fossen's lumped model of one body (docs/model.md section 12.1): a hull's, a bulky link's. Every
/// matrix is row-major, ordered `(x, y, z, roll, pitch, yaw)`, linear first, in the model's axes,
/// about its point. Magnitudes as they act: SNAME's `X_u̇` is `-added_mass[0][0]`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct UwmlLumpedF64 {
    /// The body: a link (0 to n_joints - 1), or `UWML_BASE` (-1).
    pub owner: i32,
    /// The reference point P in the body's frame [m].
    pub point: [f64; 3],
    /// The model's axes in the body's frame: a rotation whose columns are its x, y, z (row-major);
    /// all zero (as a zeroed struct has it): the body's own axes.
    pub axes: [[f64; 3]; 3],
    /// M_A about P: symmetric, positive semi-definite [kg, kg·m, kg·m²].
    pub added_mass: [[f64; 6]; 6],
    /// D_L about P, its symmetric part positive semi-definite [N·s/m, N·s, N·m·s].
    pub linear_damping: [[f64; 6]; 6],
    /// The quadratic damping d_i >= 0 of -d_i |nu_i| nu_i.
    pub quadratic_damping: [f64; 6],
}

/// `UwmlLumpedF64` in f32.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct UwmlLumpedF32 {
    /// The body: a link, or `UWML_BASE`.
    pub owner: i32,
    /// The reference point [m].
    pub point: [f32; 3],
    /// The model's axes (all zero: the body's).
    pub axes: [[f32; 3]; 3],
    /// M_A about the point.
    pub added_mass: [[f32; 6]; 6],
    /// D_L about the point.
    pub linear_damping: [[f32; 6]; 6],
    /// The quadratic damping.
    pub quadratic_damping: [f32; 6],
}

/// The base's orientation and motion at one instant (docs/model.md section 10, "Base motion and
/// current").
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct UwmlBaseMotionF64 {
    /// World from base, a unit quaternion `(w, x, y, z)`, scalar first (norm 1 within 1e-6;
    /// re-normalized). The world's z axis points up.
    pub orientation: [f64; 4],
    /// Velocity of the base origin v [m/s], base components.
    pub velocity: [f64; 3],
    /// Angular velocity ω [rad/s], base components.
    pub angular_velocity: [f64; 3],
    /// dv/dt of the base components [m/s²] (Fossen's ν̇: the classical acceleration of the base
    /// origin is `acceleration + angular_velocity × velocity`).
    pub acceleration: [f64; 3],
    /// dω/dt [rad/s²], base components.
    pub angular_acceleration: [f64; 3],
}

/// The water's uniform velocity and acceleration, world components.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct UwmlCurrentF64 {
    /// Velocity [m/s].
    pub velocity: [f64; 3],
    /// Acceleration [m/s²].
    pub acceleration: [f64; 3],
}

/// The environment's generalized force on one joint, in the joint's positive direction
/// [N·m for a revolute joint, N for a prismatic one].
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct UwmlJointForcesF64 {
    /// Drag (relative to the current).
    pub drag: f64,
    /// Added mass (relative to the current's acceleration).
    pub added_mass: f64,
    /// Buoyancy, with the Froude-Krylov force of an accelerating current.
    pub buoyancy: f64,
    /// Gravity of the links (not part of `total`).
    pub gravity: f64,
    /// `drag + added_mass + buoyancy`.
    pub total: f64,
}

/// The wrench of everything the environment exerts on the whole robot (base body included):
/// each component `{Fx, Fy, Fz, Mx, My, Mz}`, force [N] and moment about the base origin [N·m],
/// in base components.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct UwmlBaseWrenchF64 {
    /// Drag.
    pub drag: [f64; 6],
    /// Added mass.
    pub added_mass: [f64; 6],
    /// Buoyancy and Froude-Krylov.
    pub buoyancy: [f64; 6],
    /// Gravity (not part of `total`).
    pub gravity: [f64; 6],
    /// `drag + added_mass + buoyancy`.
    pub total: [f64; 6],
}

/// The environment's generalized force on one joint with its joint losses, in the joint's
/// positive direction [N·m for a revolute joint, N for a prismatic one], and the loss current [A]:
/// `UwmlJointForcesF64` with the joint's losses.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct UwmlJointEnvironmentF64 {
    /// Drag (relative to the current).
    pub drag: f64,
    /// Added mass (relative to the current's acceleration).
    pub added_mass: f64,
    /// Buoyancy, with the Froude-Krylov force of an accelerating current.
    pub buoyancy: f64,
    /// Gravity of the links (not part of `total`).
    pub gravity: f64,
    /// Oil drag reflected to the output (0 without oil or losses).
    pub visc: f64,
    /// Seal friction (0 without a seal or losses).
    pub seal: f64,
    /// Loss current [A], signed like the motion (0 without losses).
    pub current: f64,
    /// `drag + added_mass + buoyancy + visc + seal`.
    pub total: f64,
}

/// `UwmlTreeJointF64` in f32.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct UwmlTreeJointF32 {
    /// The parent: an earlier link, or `UWML_BASE` (-1).
    pub parent: i32,
    /// `UWML_JOINT_REVOLUTE` (0) or `UWML_JOINT_PRISMATIC` (1).
    pub kind: i32,
    /// Position of the joint in the parent's frame [m].
    pub origin: [f32; 3],
    /// Unit axis in the parent's frame.
    pub axis: [f32; 3],
}

/// `UwmlBodyF64` in f32.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct UwmlBodyF32 {
    /// Mass [kg], zero or positive.
    pub mass: f32,
    /// Centre of mass [m].
    pub com: [f32; 3],
    /// Displaced volume [m³], zero or positive.
    pub volume: f32,
    /// Centre of buoyancy [m].
    pub cob: [f32; 3],
}

/// `UwmlRobotSegmentF64` in f32.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct UwmlRobotSegmentF32 {
    /// The body: a link, or `UWML_BASE` (-1).
    pub owner: i32,
    /// `UWML_SECTION_RECTANGULAR` (0) or `UWML_SECTION_CIRCULAR` (1).
    pub section: i32,
    /// Start point [m].
    pub start: [f32; 3],
    /// Unit direction.
    pub axis: [f32; 3],
    /// Length [m], positive.
    pub length: f32,
    /// Cross-section area for added mass [m²], positive.
    pub area: f32,
    /// Rectangular only: the two principal normal directions.
    pub normals: [[f32; 3]; 2],
    /// Rectangular only: frontal width for flow along each normal [m], positive.
    pub widths: [f32; 2],
    /// Circular only: diameter [m], positive.
    pub diameter: f32,
    /// Drag coefficients per normal; circular: `cd[0] == cd[1]`.
    pub cd: [f32; 2],
    /// Added-mass coefficients per normal; circular: `cm[0] == cm[1]`.
    pub cm: [f32; 2],
    /// Axial drag coefficient (zero: none).
    pub cd_axial: f32,
    /// The axial drag's reference area [m²].
    pub axial_area: f32,
}

/// `UwmlBaseMotionF64` in f32.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct UwmlBaseMotionF32 {
    /// World from base, a unit quaternion `(w, x, y, z)`.
    pub orientation: [f32; 4],
    /// Velocity of the base origin [m/s], base components.
    pub velocity: [f32; 3],
    /// Angular velocity [rad/s], base components.
    pub angular_velocity: [f32; 3],
    /// dv/dt of the base components [m/s²].
    pub acceleration: [f32; 3],
    /// dω/dt [rad/s²], base components.
    pub angular_acceleration: [f32; 3],
}

/// `UwmlCurrentF64` in f32.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct UwmlCurrentF32 {
    /// Velocity [m/s], world components.
    pub velocity: [f32; 3],
    /// Acceleration [m/s²], world components.
    pub acceleration: [f32; 3],
}

/// `UwmlJointForcesF64` in f32.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct UwmlJointForcesF32 {
    /// Drag.
    pub drag: f32,
    /// Added mass.
    pub added_mass: f32,
    /// Buoyancy and Froude-Krylov.
    pub buoyancy: f32,
    /// Gravity (not part of `total`).
    pub gravity: f32,
    /// `drag + added_mass + buoyancy`.
    pub total: f32,
}

/// `UwmlBaseWrenchF64` in f32.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct UwmlBaseWrenchF32 {
    /// Drag.
    pub drag: [f32; 6],
    /// Added mass.
    pub added_mass: [f32; 6],
    /// Buoyancy and Froude-Krylov.
    pub buoyancy: [f32; 6],
    /// Gravity (not part of `total`).
    pub gravity: [f32; 6],
    /// `drag + added_mass + buoyancy`.
    pub total: [f32; 6],
}

/// `UwmlJointEnvironmentF64` in f32.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct UwmlJointEnvironmentF32 {
    /// Drag.
    pub drag: f32,
    /// Added mass.
    pub added_mass: f32,
    /// Buoyancy and Froude-Krylov.
    pub buoyancy: f32,
    /// Gravity (not part of `total`).
    pub gravity: f32,
    /// Oil drag reflected to the output.
    pub visc: f32,
    /// Seal friction.
    pub seal: f32,
    /// Loss current [A].
    pub current: f32,
    /// `drag + added_mass + buoyancy + visc + seal`.
    pub total: f32,
}

/// Writes the paper's leg (Table II, the preset `uwml_core::presets::paper_leg`) to `*robot`: 3
/// revolute joints in a chain on a fixed base without a body of its own, rectangular segments
/// with Cd = 2.2, Cm = 0.5, fresh water (1000 kg/m³, g = 9.81), Morison's added mass, no joint
/// losses.
///
/// # Safety
/// `robot` is NULL (`UWML_ERR_NULL_POINTER`) or valid for writes of a `UwmlRobotF64`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn uwml_robot_paper_leg_f64(robot: *mut UwmlRobotF64) -> i32 {
    // SAFETY: this function's contract is `robot::paper`'s.
    unsafe { imp::report(core::ptr::null_mut(), robot::paper::<f64>(robot)) }
}

/// Writes a fresh workspace to `*workspace`, for the evaluations of any robot of this API (in
/// f64): once, before its first evaluation.
///
/// # Safety
/// `workspace` is NULL (`UWML_ERR_NULL_POINTER`) or valid for writes of a `UwmlWorkspaceF64`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn uwml_robot_workspace_init_f64(workspace: *mut UwmlWorkspaceF64) -> i32 {
    // SAFETY: this function's contract is `robot::workspace_init`'s.
    unsafe { imp::report(core::ptr::null_mut(), robot::workspace_init::<f64>(workspace)) }
}

/// Fills `*out` with the core's illustrative default joint losses (`JointLosses::default()`:
/// drive K_t 0.40, ratio 160, η 0.80, 10.4 A; oil and seal as in docs/losses.md; ε = 1e-3), a
/// start for `uwml_robot_set_losses_f64`.
///
/// # Safety
/// `out` is NULL or valid for writes of a `UwmlJointLossParamsF64`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn uwml_robot_default_losses_f64(out: *mut UwmlJointLossParamsF64) -> i32 {
    // SAFETY: this function's contract is `imp::default_losses`'s.
    unsafe { imp::report(core::ptr::null_mut(), imp::default_losses::<f64>(out)) }
}

/// Validates a robot and writes it to `*robot`: `n_joints` joints (at most
/// `UWML_ROBOT_MAX_JOINTS`) and as many links (joint `i` moves link `i`), the base's own body
/// (`base`, NULL for none), `n_segments` segments of all bodies (at most
/// `UWML_ROBOT_MAX_SEGMENTS`), in water of `density` [kg/m³] (positive) under `gravity` [m/s²]
/// (zero or positive), with Morison's added mass and no joint losses. Errors name the field and
/// the joint, link or segment index: e.g.
/// "joint.parent", "link.volume", "base.mass" (index -1), "segment.diameter",
/// "n_joints (at most 16)". On error `*robot` is left as it was.
///
/// # Safety
/// `robot` is NULL or valid for writes of a `UwmlRobotF64`; `joints` and `links` are NULL or
/// point to `n_joints` elements each (NULL allowed, and not read, when `n_joints` is 0);
/// `segments` likewise with `n_segments`; `base` is NULL or valid for reads of a `UwmlBodyF64`;
/// `error` is NULL or valid for writes of a `UwmlError`. None of them overlaps `*robot`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn uwml_robot_new_f64(
    robot: *mut UwmlRobotF64,
    joints: *const UwmlTreeJointF64,
    n_joints: u32,
    links: *const UwmlBodyF64,
    base: *const UwmlBodyF64,
    segments: *const UwmlRobotSegmentF64,
    n_segments: u32,
    density: f64,
    gravity: f64,
    error: *mut UwmlError,
) -> i32 {
    let params = robot::Params { joints, n_joints, links, base, segments, n_segments, density, gravity };
    // SAFETY: this function's contract is `robot::new`'s and `imp::report`'s.
    unsafe { imp::report(error, robot::new::<f64>(robot, &params)) }
}

/// Generalized forces on every joint and the wrench on the base of `robot` at joint state `q`,
/// `qd`, `qdd` (`n` values each, `n` the robot's joint count; [rad] or [m] and their
/// derivatives), base motion `*motion` (NULL: a fixed, upright base) and current `*current`
/// (NULL: still water), evaluated in `workspace` (written; the robot is only read). Writes `n`
/// `UwmlJointForcesF64` to `joint_forces` and, if `base_wrench` is not NULL, the base wrench.
///
/// The motion and the current are validated on every call: an error ("base.orientation" not a
/// unit quaternion, "current.velocity" not finite, ...) writes nothing. A non-finite joint state
/// writes NaN forces and returns `UWML_ERR_NON_FINITE` (field "q", "qd" or "qdd", index the
/// element).
///
/// # Safety
/// `robot` is NULL or valid for reads of a `UwmlRobotF64` that nothing writes during the call;
/// `workspace` is NULL or valid for reads and writes of a `UwmlWorkspaceF64` that nothing else
/// accesses during the call; `q`, `qd`, `qdd` are NULL or point to `n` values; `joint_forces` is
/// NULL or valid for writes of `n` `UwmlJointForcesF64` (NULL and these allowed when `n` is 0);
/// `motion`, `current` and `base_wrench` are NULL or valid for one element; `error` is NULL or
/// valid for writes of a `UwmlError`. None of them overlaps `*robot` or `*workspace`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn uwml_robot_hydro_f64(
    robot: *const UwmlRobotF64,
    workspace: *mut UwmlWorkspaceF64,
    q: *const f64,
    qd: *const f64,
    qdd: *const f64,
    n: u32,
    motion: *const UwmlBaseMotionF64,
    current: *const UwmlCurrentF64,
    joint_forces: *mut UwmlJointForcesF64,
    base_wrench: *mut UwmlBaseWrenchF64,
    error: *mut UwmlError,
) -> i32 {
    let joints_name = "joint_forces";
    let io = robot::Evaluation { q, qd, qdd, n, motion, current, joints: joint_forces, joints_name, base_wrench };
    // SAFETY: this function's contract is `robot::hydro`'s and `imp::report`'s.
    unsafe { imp::report(error, robot::hydro::<f64>(robot, workspace, &io)) }
}

/// Chooses how the added-mass forces of `robot` depend on the velocities, for every later
/// `uwml_robot_hydro_f64`: `UWML_ADDED_MASS_MORISON` (the paper's, what a new robot uses) or
/// `UWML_ADDED_MASS_KIRCHHOFF` (from the water's kinetic energy: the form that conserves energy
/// in a simulation, docs/simulation.md, "Energy-consistent added mass"; a controller designed in `uwml.mujoco.Simulation(...,
/// added_mass="kirchhoff")` gets the same forces). Both share the added-mass matrix; they differ
/// where the links move. Another value is `UWML_ERR_OUT_OF_RANGE` (field "form ...") and changes
/// nothing.
///
/// # Safety
/// `robot` is NULL or valid for reads and writes of a `UwmlRobotF64` that nothing else accesses
/// during the call; `error` is NULL or valid for writes of a `UwmlError`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn uwml_robot_set_added_mass_form_f64(
    robot: *mut UwmlRobotF64,
    form: i32,
    error: *mut UwmlError,
) -> i32 {
    // SAFETY: this function's contract is `robot::set_added_mass_form`'s and `imp::report`'s.
    unsafe { imp::report(error, robot::set_added_mass_form::<f64>(robot, form)) }
}

/// Gives joint `joint_index` (0 to the robot's joint count - 1) of `robot` the losses `*params`
/// (start from `uwml_robot_default_losses_f64`) at gauge pressure
/// `pressure_pa` [Pa] (finite, 0 to 1.2e8: `uwml_pressure_at_depth_f64` gives it from a depth) and
/// oil temperature `temperature_c` [°C] (finite, above -273.15), for every later
/// `uwml_robot_environment_f64`. Checked in this order:
/// the robot, `UWML_ERR_INDEX_OUT_OF_RANGE` (field "joint_index", index the value given),
/// `params` NULL, the parameters (field e.g. "drive.ratio", "oil.exponent (1 to 2)", "seal.s0",
/// "losses.epsilon", index the joint), the conditions (field "pressure_pa" or "temperature_c").
/// On a prismatic joint the same laws hold in its units (speed in m/s, forces in N, the drive's
/// ratio in rad/m). On error the robot is left as it was.
///
/// # Safety
/// `robot` is NULL or valid for reads and writes of a `UwmlRobotF64` that nothing else accesses
/// during the call; `params` is NULL or valid for reads of a `UwmlJointLossParamsF64`; `error` is
/// NULL or valid for writes of a `UwmlError`. None of them overlaps `*robot`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn uwml_robot_set_losses_f64(
    robot: *mut UwmlRobotF64,
    joint_index: u32,
    params: *const UwmlJointLossParamsF64,
    pressure_pa: f64,
    temperature_c: f64,
    error: *mut UwmlError,
) -> i32 {
    // SAFETY: this function's contract is `robot::set_losses`'s and `imp::report`'s.
    unsafe { imp::report(error, robot::set_losses::<f64>(robot, joint_index, params, pressure_pa, temperature_c)) }
}

/// Removes the losses of joint `joint_index` (0 to the robot's joint count - 1; else
/// `UWML_ERR_INDEX_OUT_OF_RANGE`, nothing changed).
///
/// # Safety
/// `robot` is NULL or valid for reads and writes of a `UwmlRobotF64` that nothing else accesses
/// during the call; `error` is NULL or valid for writes of a `UwmlError`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn uwml_robot_clear_losses_f64(
    robot: *mut UwmlRobotF64,
    joint_index: u32,
    error: *mut UwmlError,
) -> i32 {
    // SAFETY: this function's contract is `robot::clear_losses`'s and `imp::report`'s.
    unsafe { imp::report(error, robot::clear_losses::<f64>(robot, joint_index)) }
}

/// Moves every joint of `robot` that has losses to a new gauge pressure [Pa] and oil temperature
/// [°C] (checked as in `uwml_robot_set_losses_f64`; on error nothing changes): call it when the
/// depth or temperature changes.
///
/// # Safety
/// As `uwml_robot_clear_losses_f64`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn uwml_robot_set_conditions_f64(
    robot: *mut UwmlRobotF64,
    pressure_pa: f64,
    temperature_c: f64,
    error: *mut UwmlError,
) -> i32 {
    // SAFETY: this function's contract is `robot::set_conditions`'s and `imp::report`'s.
    unsafe { imp::report(error, robot::set_conditions::<f64>(robot, pressure_pa, temperature_c)) }
}

/// `uwml_robot_hydro_f64` with the joint losses: writes `n` `UwmlJointEnvironmentF64` to
/// `joint_environment` (each joint's forces as `uwml_robot_hydro_f64` gives them, its oil drag,
/// seal friction and loss current at its speed `qd[i]`, zero for a joint without losses, and
/// `total` = drag + added mass + buoyancy + visc + seal) and, if `base_wrench` is not NULL, the
/// base wrench, which losses do not change (they act between a link and its parent). The same
/// arguments, checks and errors as `uwml_robot_hydro_f64` (the array's field is
/// "joint_environment"); a finite state whose loss current overflows is `UWML_ERR_OVERFLOW`
/// with field "current".
///
/// # Safety
/// As `uwml_robot_hydro_f64`, with `joint_environment` NULL or valid for writes of `n`
/// `UwmlJointEnvironmentF64`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn uwml_robot_environment_f64(
    robot: *const UwmlRobotF64,
    workspace: *mut UwmlWorkspaceF64,
    q: *const f64,
    qd: *const f64,
    qdd: *const f64,
    n: u32,
    motion: *const UwmlBaseMotionF64,
    current: *const UwmlCurrentF64,
    joint_environment: *mut UwmlJointEnvironmentF64,
    base_wrench: *mut UwmlBaseWrenchF64,
    error: *mut UwmlError,
) -> i32 {
    let joints_name = "joint_environment";
    let io = robot::Evaluation { q, qd, qdd, n, motion, current, joints: joint_environment, joints_name, base_wrench };
    // SAFETY: this function's contract is `robot::environment`'s and `imp::report`'s.
    unsafe { imp::report(error, robot::environment::<f64>(robot, workspace, &io)) }
}

/// `uwml_robot_set_added_mass_form_f64` in f32.
///
/// # Safety
/// As `uwml_robot_set_added_mass_form_f64`, with `UwmlRobotF32`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn uwml_robot_set_added_mass_form_f32(
    robot: *mut UwmlRobotF32,
    form: i32,
    error: *mut UwmlError,
) -> i32 {
    // SAFETY: this function's contract is `robot::set_added_mass_form`'s and `imp::report`'s.
    unsafe { imp::report(error, robot::set_added_mass_form::<f32>(robot, form)) }
}

/// `uwml_robot_paper_leg_f64` in f32.
///
/// # Safety
/// `robot` is NULL or valid for writes of a `UwmlRobotF32`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn uwml_robot_paper_leg_f32(robot: *mut UwmlRobotF32) -> i32 {
    // SAFETY: this function's contract is `robot::paper`'s.
    unsafe { imp::report(core::ptr::null_mut(), robot::paper::<f32>(robot)) }
}

/// `uwml_robot_workspace_init_f64` in f32.
///
/// # Safety
/// `workspace` is NULL or valid for writes of a `UwmlWorkspaceF32`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn uwml_robot_workspace_init_f32(workspace: *mut UwmlWorkspaceF32) -> i32 {
    // SAFETY: this function's contract is `robot::workspace_init`'s.
    unsafe { imp::report(core::ptr::null_mut(), robot::workspace_init::<f32>(workspace)) }
}

/// `uwml_robot_default_losses_f64` in f32.
///
/// # Safety
/// `out` is NULL or valid for writes of a `UwmlJointLossParamsF32`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn uwml_robot_default_losses_f32(out: *mut UwmlJointLossParamsF32) -> i32 {
    // SAFETY: this function's contract is `imp::default_losses`'s.
    unsafe { imp::report(core::ptr::null_mut(), imp::default_losses::<f32>(out)) }
}

/// `uwml_robot_new_f64` in f32.
///
/// # Safety
/// As `uwml_robot_new_f64`, with the f32 types.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn uwml_robot_new_f32(
    robot: *mut UwmlRobotF32,
    joints: *const UwmlTreeJointF32,
    n_joints: u32,
    links: *const UwmlBodyF32,
    base: *const UwmlBodyF32,
    segments: *const UwmlRobotSegmentF32,
    n_segments: u32,
    density: f32,
    gravity: f32,
    error: *mut UwmlError,
) -> i32 {
    let params = robot::Params { joints, n_joints, links, base, segments, n_segments, density, gravity };
    // SAFETY: this function's contract is `robot::new`'s and `imp::report`'s.
    unsafe { imp::report(error, robot::new::<f32>(robot, &params)) }
}

/// `uwml_robot_hydro_f64` in f32.
///
/// # Safety
/// As `uwml_robot_hydro_f64`, with the f32 types.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn uwml_robot_hydro_f32(
    robot: *const UwmlRobotF32,
    workspace: *mut UwmlWorkspaceF32,
    q: *const f32,
    qd: *const f32,
    qdd: *const f32,
    n: u32,
    motion: *const UwmlBaseMotionF32,
    current: *const UwmlCurrentF32,
    joint_forces: *mut UwmlJointForcesF32,
    base_wrench: *mut UwmlBaseWrenchF32,
    error: *mut UwmlError,
) -> i32 {
    let joints_name = "joint_forces";
    let io = robot::Evaluation { q, qd, qdd, n, motion, current, joints: joint_forces, joints_name, base_wrench };
    // SAFETY: this function's contract is `robot::hydro`'s and `imp::report`'s.
    unsafe { imp::report(error, robot::hydro::<f32>(robot, workspace, &io)) }
}

/// `uwml_robot_set_losses_f64` in f32.
///
/// # Safety
/// As `uwml_robot_set_losses_f64`, with the f32 types.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn uwml_robot_set_losses_f32(
    robot: *mut UwmlRobotF32,
    joint_index: u32,
    params: *const UwmlJointLossParamsF32,
    pressure_pa: f32,
    temperature_c: f32,
    error: *mut UwmlError,
) -> i32 {
    // SAFETY: this function's contract is `robot::set_losses`'s and `imp::report`'s.
    unsafe { imp::report(error, robot::set_losses::<f32>(robot, joint_index, params, pressure_pa, temperature_c)) }
}

/// `uwml_robot_clear_losses_f64` in f32.
///
/// # Safety
/// As `uwml_robot_clear_losses_f64`, with `UwmlRobotF32`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn uwml_robot_clear_losses_f32(
    robot: *mut UwmlRobotF32,
    joint_index: u32,
    error: *mut UwmlError,
) -> i32 {
    // SAFETY: this function's contract is `robot::clear_losses`'s and `imp::report`'s.
    unsafe { imp::report(error, robot::clear_losses::<f32>(robot, joint_index)) }
}

/// `uwml_robot_set_conditions_f64` in f32.
///
/// # Safety
/// As `uwml_robot_clear_losses_f64`, with `UwmlRobotF32`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn uwml_robot_set_conditions_f32(
    robot: *mut UwmlRobotF32,
    pressure_pa: f32,
    temperature_c: f32,
    error: *mut UwmlError,
) -> i32 {
    // SAFETY: this function's contract is `robot::set_conditions`'s and `imp::report`'s.
    unsafe { imp::report(error, robot::set_conditions::<f32>(robot, pressure_pa, temperature_c)) }
}

/// `uwml_robot_environment_f64` in f32.
///
/// # Safety
/// As `uwml_robot_environment_f64`, with the f32 types.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn uwml_robot_environment_f32(
    robot: *const UwmlRobotF32,
    workspace: *mut UwmlWorkspaceF32,
    q: *const f32,
    qd: *const f32,
    qdd: *const f32,
    n: u32,
    motion: *const UwmlBaseMotionF32,
    current: *const UwmlCurrentF32,
    joint_environment: *mut UwmlJointEnvironmentF32,
    base_wrench: *mut UwmlBaseWrenchF32,
    error: *mut UwmlError,
) -> i32 {
    let joints_name = "joint_environment";
    let io = robot::Evaluation { q, qd, qdd, n, motion, current, joints: joint_environment, joints_name, base_wrench };
    // SAFETY: this function's contract is `robot::environment`'s and `imp::report`'s.
    unsafe { imp::report(error, robot::environment::<f32>(robot, workspace, &io)) }
}

/// Gives `robot`'s bodies the `count` lumped models `models` (docs/model.md section 12.1; at most
/// `UWML_ROBOT_MAX_LUMPED`, one per body), replacing any it had (`count` 0: none; `models` may then
/// be NULL). Checked as the core checks them (`UWML_ERR_NOT_SYMMETRIC`,
/// `UWML_ERR_NOT_POSITIVE_SEMIDEFINITE`, `UWML_ERR_NEGATIVE`, `UWML_ERR_TOO_LARGE`, ...; field
/// e.g. "lumped.added_mass", index the model's); on error the robot is left as it was. Its forces
/// join every later evaluation: the damping the drag, the rest the added mass.
///
/// # Safety
/// `robot` is NULL or valid for reads and writes of a `UwmlRobotF64` that nothing else accesses
/// during the call; `models` is NULL or valid for reads of `count` `UwmlLumpedF64`s; `error` is
/// NULL or valid for writes of a `UwmlError`. None of them overlaps `*robot`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn uwml_robot_set_lumped_f64(
    robot: *mut UwmlRobotF64,
    models: *const UwmlLumpedF64,
    count: u32,
    error: *mut UwmlError,
) -> i32 {
    // SAFETY: this function's contract is `robot::set_lumped`'s and `imp::report`'s.
    unsafe { imp::report(error, robot::set_lumped::<f64>(robot, models, count)) }
}

/// `uwml_robot_set_lumped_f64` in f32.
///
/// # Safety
/// As `uwml_robot_set_lumped_f64`, with the f32 types.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn uwml_robot_set_lumped_f32(
    robot: *mut UwmlRobotF32,
    models: *const UwmlLumpedF32,
    count: u32,
    error: *mut UwmlError,
) -> i32 {
    // SAFETY: this function's contract is `robot::set_lumped`'s and `imp::report`'s.
    unsafe { imp::report(error, robot::set_lumped::<f32>(robot, models, count)) }
}

/// Gives the `n_segments` segments of `robot` (exactly its segment count, in the order given to
/// `uwml_robot_new_f64`; the paper's leg: thigh, calf) other drag and added-mass coefficients:
/// `cd[k]` and `cm[k]` segment `k`'s per normal direction (a fit's; zero or positive, at most
/// 1e3; a circular segment's two equal), for every later evaluation. Errors name the field and
/// the segment ("segment.cd", "segment.cm"; "n_segments (the robot's segment count)"); on error
/// the robot is left as it was. `cd` and `cm` may be NULL when `n_segments` is 0.
///
/// # Safety
/// `robot` is NULL or valid for reads and writes of a `UwmlRobotF64` that nothing else accesses
/// during the call; `cd` and `cm` are NULL or valid for reads of `n_segments` pairs; `error` is
/// NULL or valid for writes of a `UwmlError`. None of them overlaps `*robot`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn uwml_robot_set_coefficients_f64(
    robot: *mut UwmlRobotF64,
    cd: *const [f64; 2],
    cm: *const [f64; 2],
    n_segments: u32,
    error: *mut UwmlError,
) -> i32 {
    // SAFETY: this function's contract is `robot::set_coefficients`'s and `imp::report`'s.
    unsafe { imp::report(error, robot::set_coefficients::<f64>(robot, cd, cm, n_segments)) }
}

/// `uwml_robot_set_coefficients_f64` in f32.
///
/// # Safety
/// As `uwml_robot_set_coefficients_f64`, with the f32 types.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn uwml_robot_set_coefficients_f32(
    robot: *mut UwmlRobotF32,
    cd: *const [f32; 2],
    cm: *const [f32; 2],
    n_segments: u32,
    error: *mut UwmlError,
) -> i32 {
    // SAFETY: this function's contract is `robot::set_coefficients`'s and `imp::report`'s.
    unsafe { imp::report(error, robot::set_coefficients::<f32>(robot, cd, cm, n_segments)) }
}

/// Sets the water of `robot`: density [kg/m³] (positive, at most 1e5) and gravity [m/s²] (zero or
/// positive, at most 1e3), for every later evaluation (a new robot's: the density and gravity
/// given to `uwml_robot_new_f64`, or fresh water for the paper's leg). On error ("water.density",
/// "water.gravity") the robot is left as it was.
///
/// # Safety
/// `robot` is NULL or valid for reads and writes of a `UwmlRobotF64` that nothing else accesses
/// during the call; `error` is NULL or valid for writes of a `UwmlError`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn uwml_robot_set_water_f64(
    robot: *mut UwmlRobotF64,
    density: f64,
    gravity: f64,
    error: *mut UwmlError,
) -> i32 {
    // SAFETY: this function's contract is `robot::set_water`'s and `imp::report`'s.
    unsafe { imp::report(error, robot::set_water::<f64>(robot, density, gravity)) }
}

/// `uwml_robot_set_water_f64` in f32.
///
/// # Safety
/// As `uwml_robot_set_water_f64`, with `UwmlRobotF32`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn uwml_robot_set_water_f32(
    robot: *mut UwmlRobotF32,
    density: f32,
    gravity: f32,
    error: *mut UwmlError,
) -> i32 {
    // SAFETY: this function's contract is `robot::set_water`'s and `imp::report`'s.
    unsafe { imp::report(error, robot::set_water::<f32>(robot, density, gravity)) }
}
