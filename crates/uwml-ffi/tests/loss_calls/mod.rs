//! The joint losses' calls as the tests make them, and what they return and write: the setters,
//! an evaluation of the environment in f64 and f32 into sentinel outputs, the C API's
//! environment of the arm against the core's, bit for bit. Shared by `robot_losses.rs` and
//! `robot_loss_errors.rs`.
#![allow(dead_code, clippy::indexing_slicing, clippy::unwrap_used, clippy::expect_used)]

use core::ptr::{null, null_mut};

use uwml_core::{AddedMassForm, Water};
use uwml_ffi::*;

use crate::errors::{blank_error, expect_error};
use crate::robots::*;

pub fn expect_ok(code: i32, e: &UwmlError) {
    expect_error(code, e, (UWML_OK, -1, ""));
}

pub fn set_losses64(
    robot: *mut UwmlRobotF64,
    joint: u32,
    p: &UwmlJointLossParamsF64,
    (pressure, temperature): (f64, f64),
) -> (i32, UwmlError) {
    let mut error = blank_error();
    // SAFETY: `robot` is null or a live robot; `p` and `error` live locals.
    let code = unsafe { uwml_robot_set_losses_f64(robot, joint, p, pressure, temperature, &mut error) };
    assert_eq!(error.code, code);
    (code, error)
}

pub fn set_conditions64(robot: *mut UwmlRobotF64, (pressure, temperature): (f64, f64)) -> (i32, UwmlError) {
    let mut error = blank_error();
    // SAFETY: `robot` is null or a live robot; `error` a live local.
    let code = unsafe { uwml_robot_set_conditions_f64(robot, pressure, temperature, &mut error) };
    assert_eq!(error.code, code);
    (code, error)
}

pub fn clear_losses64(robot: *mut UwmlRobotF64, joint: u32) -> (i32, UwmlError) {
    let mut error = blank_error();
    // SAFETY: `robot` is null or a live robot; `error` a live local.
    let code = unsafe { uwml_robot_clear_losses_f64(robot, joint, &mut error) };
    assert_eq!(error.code, code);
    (code, error)
}

/// The arm's losses at `conditions`, through the C API.
pub fn with_losses64(robot: &mut UwmlRobotF64, conditions: (f64, f64)) {
    for (joint, p) in arm_losses() {
        let (code, error) = set_losses64(robot, joint, &p, conditions);
        expect_ok(code, &error);
    }
}

pub fn with_losses32(robot: &mut UwmlRobotF32, (pressure, temperature): (f64, f64)) {
    for (joint, p) in arm_losses() {
        // SAFETY: live locals.
        let code = unsafe {
            uwml_robot_set_losses_f32(robot, joint, &losses32(&p), pressure as f32, temperature as f32, null_mut())
        };
        assert_eq!(code, UWML_OK);
    }
}

/// What an evaluation returned and wrote; the outputs start as a sentinel (-7).
pub struct Out64 {
    pub code: i32,
    pub error: UwmlError,
    pub joints: Vec<UwmlJointEnvironmentF64>,
    pub wrench: UwmlBaseWrenchF64,
}

pub const SENTINEL64: UwmlJointEnvironmentF64 = UwmlJointEnvironmentF64 {
    drag: -7.0,
    added_mass: -7.0,
    buoyancy: -7.0,
    gravity: -7.0,
    visc: -7.0,
    seal: -7.0,
    current: -7.0,
    total: -7.0,
};
pub fn environment_c64(
    robot: &mut UwmlRobotF64,
    state: [&[f64]; 3],
    motion: Option<&UwmlBaseMotionF64>,
    current: Option<&UwmlCurrentF64>,
) -> Out64 {
    let n = state[0].len();
    let mut joints = vec![SENTINEL64; n];
    let mut wrench = WRENCH_SENTINEL64;
    let mut error = blank_error();
    // SAFETY: live locals; every state and `joints` hold n elements.
    let code = unsafe {
        uwml_robot_environment_f64(
            robot,
            &mut *workspace64(),
            state[0].as_ptr(),
            state[1].as_ptr(),
            state[2].as_ptr(),
            count(n),
            motion.map_or(null(), |m| m as *const _),
            current.map_or(null(), |c| c as *const _),
            joints.as_mut_ptr(),
            &mut wrench,
            &mut error,
        )
    };
    assert_eq!(error.code, code);
    Out64 { code, error, joints, wrench }
}

pub fn environment_c32(
    robot: &mut UwmlRobotF32,
    state: [&[f32]; 3],
    motion: Option<&UwmlBaseMotionF32>,
    current: Option<&UwmlCurrentF32>,
) -> (i32, Vec<UwmlJointEnvironmentF32>, UwmlBaseWrenchF32) {
    let n = state[0].len();
    let mut joints = vec![UwmlJointEnvironmentF32::default(); n];
    let mut wrench = UwmlBaseWrenchF32::default();
    // SAFETY: live locals; every state and `joints` hold n elements.
    let code = unsafe {
        uwml_robot_environment_f32(
            robot,
            &mut *workspace32(),
            state[0].as_ptr(),
            state[1].as_ptr(),
            state[2].as_ptr(),
            count(n),
            motion.map_or(null(), |m| m as *const _),
            current.map_or(null(), |c| c as *const _),
            joints.as_mut_ptr(),
            &mut wrench,
            null_mut(),
        )
    };
    (code, joints, wrench)
}

pub fn hydro_c64(robot: &mut UwmlRobotF64, state: [&[f64]; 3]) -> (Vec<UwmlJointForcesF64>, UwmlBaseWrenchF64) {
    let n = state[0].len();
    let mut forces = vec![UwmlJointForcesF64::default(); n];
    let mut wrench = UwmlBaseWrenchF64::default();
    // SAFETY: live locals; every state and `forces` hold n elements.
    let code = unsafe {
        uwml_robot_hydro_f64(
            robot,
            &mut *workspace64(),
            state[0].as_ptr(),
            state[1].as_ptr(),
            state[2].as_ptr(),
            count(n),
            &arm_motion(),
            &ARM_CURRENT,
            forces.as_mut_ptr(),
            &mut wrench,
            null_mut(),
        )
    };
    assert_eq!(code, UWML_OK);
    (forces, wrench)
}

/// Every number's bits, so that NaN equals NaN and 0.0 differs from -0.0.
pub fn bits64(e: &[UwmlJointEnvironmentF64]) -> Vec<[u64; 8]> {
    e.iter()
        .map(|e| [e.drag, e.added_mass, e.buoyancy, e.gravity, e.visc, e.seal, e.current, e.total].map(f64::to_bits))
        .collect()
}

pub fn bits32(e: &[UwmlJointEnvironmentF32]) -> Vec<[u32; 8]> {
    e.iter()
        .map(|e| [e.drag, e.added_mass, e.buoyancy, e.gravity, e.visc, e.seal, e.current, e.total].map(f32::to_bits))
        .collect()
}

pub fn form_code(form: AddedMassForm) -> i32 {
    match form {
        AddedMassForm::Morison => UWML_ADDED_MASS_MORISON,
        AddedMassForm::Kirchhoff => UWML_ADDED_MASS_KIRCHHOFF,
    }
}

/// The C API's f64 environment of the arm equals the core's forces plus its losses, bit for bit;
/// the f32 one likewise.
pub fn assert_arm_is_the_core(
    form: AddedMassForm,
    robot: &mut UwmlRobotF64,
    robot32: &mut UwmlRobotF32,
    losses: &[(u32, UwmlJointLossParamsF64)],
    conditions: (f64, f64),
) {
    let params = arm();
    let water = Water::new(DENSITY, GRAVITY).unwrap();
    let water32 = Water::new(DENSITY as f32, GRAVITY as f32).unwrap();
    let states64 = core_loss_states::<f64>(losses, conditions);
    let states32 = core_loss_states::<f32>(losses, conditions);
    let motion = arm_motion();
    for [q, qd, qdd] in arm_states() {
        let state = [&q[..], &qd[..], &qdd[..]];
        for (m, c) in [(Some(&motion), Some(&ARM_CURRENT)), (None, None)] {
            let out = environment_c64(robot, state, m, c);
            expect_ok(out.code, &out.error);
            let data = core_hydro_with(&core_robot(&params), &water, form, &core_motion(m), &core_current(c), state);
            let want = environment64(&core_environment(&data, &states64, &qd));
            assert_eq!(bits64(&out.joints), bits64(&want), "f64 joints at {state:?}, {form:?}");
            assert_eq!(wrench_bits64(&out.wrench), wrench_bits64(&wrench64(&data)), "f64 base wrench");

            let narrow = |x: &[f64]| x.iter().map(|&x| f32::narrow(x)).collect::<Vec<_>>();
            let (q32, qd32, qdd32) = (narrow(&q), narrow(&qd), narrow(&qdd));
            let state32 = [&q32[..], &qd32[..], &qdd32[..]];
            let (m32, c32) = (m.map(motion32), c.map(current32));
            let (code, joints, wrench) = environment_c32(robot32, state32, m32.as_ref(), c32.as_ref());
            assert_eq!(code, UWML_OK);
            let data = core_hydro_with(
                &core_robot::<f32>(&params),
                &water32,
                form,
                &core_motion(m),
                &core_current(c),
                state32,
            );
            let want = environment32(&core_environment(&data, &states32, &qd32));
            assert_eq!(bits32(&joints), bits32(&want), "f32 joints at {state:?}, {form:?}");
            assert_eq!(wrench_bits32(&wrench), wrench_bits32(&wrench32(&data)), "f32 base wrench");
        }
    }
}
