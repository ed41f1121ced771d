//! The robot API's calls as the tests make them, and what they return and write: a robot built
//! from plain structs, an evaluation of the forces in f64 and f32 into sentinel outputs, the
//! C API's results against the core's, bit for bit. Shared by `robot_api.rs` and
//! `robot_errors.rs`.
#![allow(dead_code, clippy::indexing_slicing, clippy::unwrap_used, clippy::expect_used)]

use core::ptr::{null, null_mut};

use uwml_core::{AddedMassForm, Water};
use uwml_ffi::*;

use crate::errors::blank_error;
use crate::robots::*;

pub fn new64(robot: &mut UwmlRobotF64, p: &Params, density: f64) -> (i32, UwmlError) {
    let mut error = blank_error();
    let base = p.base.as_ref().map_or(null(), |b| b as *const UwmlBodyF64);
    // SAFETY: live locals; the arrays hold their counts of elements.
    let code = unsafe {
        uwml_robot_new_f64(
            robot,
            p.joints.as_ptr(),
            count(p.joints.len()),
            p.links.as_ptr(),
            base,
            p.segments.as_ptr(),
            count(p.segments.len()),
            density,
            GRAVITY,
            &mut error,
        )
    };
    assert_eq!(error.code, code);
    (code, error)
}

/// What an evaluation returned and wrote; the outputs start as a sentinel (-7).
pub struct Out64 {
    pub code: i32,
    pub error: UwmlError,
    pub forces: Vec<UwmlJointForcesF64>,
    pub wrench: UwmlBaseWrenchF64,
}

pub const SENTINEL64: UwmlJointForcesF64 =
    UwmlJointForcesF64 { drag: -7.0, added_mass: -7.0, buoyancy: -7.0, gravity: -7.0, total: -7.0 };
pub fn hydro64(
    robot: &mut UwmlRobotF64,
    state: [&[f64]; 3],
    motion: Option<&UwmlBaseMotionF64>,
    current: Option<&UwmlCurrentF64>,
) -> Out64 {
    let n = state[0].len();
    let mut forces = vec![SENTINEL64; n];
    let mut wrench = WRENCH_SENTINEL64;
    let mut error = blank_error();
    // SAFETY: live locals; every state and `forces` hold n elements.
    let code = unsafe {
        uwml_robot_hydro_f64(
            robot,
            &mut *workspace64(),
            state[0].as_ptr(),
            state[1].as_ptr(),
            state[2].as_ptr(),
            count(n),
            motion.map_or(null(), |m| m as *const _),
            current.map_or(null(), |c| c as *const _),
            forces.as_mut_ptr(),
            &mut wrench,
            &mut error,
        )
    };
    assert_eq!(error.code, code);
    Out64 { code, error, forces, wrench }
}

pub fn hydro32(
    robot: &mut UwmlRobotF32,
    state: [&[f32]; 3],
    motion: Option<&UwmlBaseMotionF32>,
    current: Option<&UwmlCurrentF32>,
) -> (i32, Vec<UwmlJointForcesF32>, UwmlBaseWrenchF32) {
    let n = state[0].len();
    let mut forces = vec![UwmlJointForcesF32::default(); n];
    let mut wrench = UwmlBaseWrenchF32::default();
    // SAFETY: live locals; every state and `forces` hold n elements.
    let code = unsafe {
        uwml_robot_hydro_f32(
            robot,
            &mut *workspace32(),
            state[0].as_ptr(),
            state[1].as_ptr(),
            state[2].as_ptr(),
            count(n),
            motion.map_or(null(), |m| m as *const _),
            current.map_or(null(), |c| c as *const _),
            forces.as_mut_ptr(),
            &mut wrench,
            null_mut(),
        )
    };
    (code, forces, wrench)
}

/// Every number's bits, so that NaN equals NaN and 0.0 differs from -0.0.
pub fn forces_bits64(f: &[UwmlJointForcesF64]) -> Vec<[u64; 5]> {
    f.iter().map(|f| [f.drag, f.added_mass, f.buoyancy, f.gravity, f.total].map(f64::to_bits)).collect()
}

pub fn forces_bits32(f: &[UwmlJointForcesF32]) -> Vec<[u32; 5]> {
    f.iter().map(|f| [f.drag, f.added_mass, f.buoyancy, f.gravity, f.total].map(f32::to_bits)).collect()
}

/// The C API's f64 evaluation of `params` equals the core's, bit for bit.
pub fn assert_core64(
    robot: &mut UwmlRobotF64,
    params: &Params,
    water: &Water<f64>,
    state: [&[f64]; 3],
    motion: Option<&UwmlBaseMotionF64>,
    current: Option<&UwmlCurrentF64>,
) -> Out64 {
    assert_core64_with(AddedMassForm::Morison, robot, params, water, state, motion, current)
}

/// As `assert_core64`, for a robot whose added-mass forces are in `form`.
pub fn assert_core64_with(
    form: AddedMassForm,
    robot: &mut UwmlRobotF64,
    params: &Params,
    water: &Water<f64>,
    state: [&[f64]; 3],
    motion: Option<&UwmlBaseMotionF64>,
    current: Option<&UwmlCurrentF64>,
) -> Out64 {
    let out = hydro64(robot, state, motion, current);
    let data = core_hydro_with(&core_robot(params), water, form, &core_motion(motion), &core_current(current), state);
    assert_eq!(forces_bits64(&out.forces), forces_bits64(&forces64(&data)), "joint forces");
    assert_eq!(wrench_bits64(&out.wrench), wrench_bits64(&wrench64(&data)), "base wrench");
    out
}

pub fn assert_core32(
    robot: &mut UwmlRobotF32,
    params: &Params,
    water: &Water<f32>,
    state: [&[f64]; 3],
    motion: Option<&UwmlBaseMotionF64>,
    current: Option<&UwmlCurrentF64>,
) {
    assert_core32_with(AddedMassForm::Morison, robot, params, water, state, motion, current);
}

pub fn assert_core32_with(
    form: AddedMassForm,
    robot: &mut UwmlRobotF32,
    params: &Params,
    water: &Water<f32>,
    state: [&[f64]; 3],
    motion: Option<&UwmlBaseMotionF64>,
    current: Option<&UwmlCurrentF64>,
) {
    let state: Vec<Vec<f32>> = state.iter().map(|s| s.iter().map(|&x| f32::narrow(x)).collect()).collect();
    let state = [&state[0][..], &state[1][..], &state[2][..]];
    let (m, c) = (motion.map(motion32), current.map(current32));
    let (code, forces, wrench) = hydro32(robot, state, m.as_ref(), c.as_ref());
    assert_eq!(code, UWML_OK);
    let data =
        core_hydro_with(&core_robot::<f32>(params), water, form, &core_motion(motion), &core_current(current), state);
    assert_eq!(forces_bits32(&forces), forces_bits32(&forces32(&data)), "f32 joint forces");
    assert_eq!(wrench_bits32(&wrench), wrench_bits32(&wrench32(&data)), "f32 base wrench");
}
