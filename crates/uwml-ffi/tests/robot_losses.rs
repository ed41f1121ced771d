//! Joint losses of the robot API (`uwml_robot_set_losses_*`, `_clear_losses_*`,
//! `_set_conditions_*`, `_environment_*`) against the core called directly (bit for bit: the
//! core's `robot_hydro` with the losses in its conditions), the paper's robot against the leg
//! API with the same losses, every error code and field, null pointers, overflow.
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing, clippy::expect_used)]

use core::ptr::{null, null_mut};

use uwml_core::{AddedMassForm, Water, pressure_at_depth};
use uwml_ffi::*;

mod errors;
use errors::{blank_error, expect_error};

mod robots;
use robots::{
    ARM_CURRENT, ARM_STATE, DENSITY, GRAVITY, PAPER_CURRENT, PAPER_STATE, Real, WRENCH_SENTINEL64, arm, arm_conditions,
    arm_losses, arm_motion, built32, built64, core_current, core_environment, core_hydro_with, core_loss_states,
    core_motion, core_robot, count, current32, default_losses, environment32, environment64, losses32, motion32, paper,
    paper_motion, workspace32, workspace64, wrench_bits32, wrench_bits64, wrench32, wrench64, zeroed32, zeroed64,
};

fn expect_ok(code: i32, e: &UwmlError) {
    expect_error(code, e, (UWML_OK, -1, ""));
}

fn set_losses64(
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

fn set_conditions64(robot: *mut UwmlRobotF64, (pressure, temperature): (f64, f64)) -> (i32, UwmlError) {
    let mut error = blank_error();
    // SAFETY: `robot` is null or a live robot; `error` a live local.
    let code = unsafe { uwml_robot_set_conditions_f64(robot, pressure, temperature, &mut error) };
    assert_eq!(error.code, code);
    (code, error)
}

fn clear_losses64(robot: *mut UwmlRobotF64, joint: u32) -> (i32, UwmlError) {
    let mut error = blank_error();
    // SAFETY: `robot` is null or a live robot; `error` a live local.
    let code = unsafe { uwml_robot_clear_losses_f64(robot, joint, &mut error) };
    assert_eq!(error.code, code);
    (code, error)
}

/// The arm's losses at `conditions`, through the C API.
fn with_losses64(robot: &mut UwmlRobotF64, conditions: (f64, f64)) {
    for (joint, p) in arm_losses() {
        let (code, error) = set_losses64(robot, joint, &p, conditions);
        expect_ok(code, &error);
    }
}

fn with_losses32(robot: &mut UwmlRobotF32, (pressure, temperature): (f64, f64)) {
    for (joint, p) in arm_losses() {
        // SAFETY: live locals.
        let code = unsafe {
            uwml_robot_set_losses_f32(robot, joint, &losses32(&p), pressure as f32, temperature as f32, null_mut())
        };
        assert_eq!(code, UWML_OK);
    }
}

/// What an evaluation returned and wrote; the outputs start as a sentinel (-7).
struct Out64 {
    code: i32,
    error: UwmlError,
    joints: Vec<UwmlJointEnvironmentF64>,
    wrench: UwmlBaseWrenchF64,
}

const SENTINEL64: UwmlJointEnvironmentF64 = UwmlJointEnvironmentF64 {
    drag: -7.0,
    added_mass: -7.0,
    buoyancy: -7.0,
    gravity: -7.0,
    visc: -7.0,
    seal: -7.0,
    current: -7.0,
    total: -7.0,
};
fn environment_c64(
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

fn environment_c32(
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

fn hydro_c64(robot: &mut UwmlRobotF64, state: [&[f64]; 3]) -> (Vec<UwmlJointForcesF64>, UwmlBaseWrenchF64) {
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
fn bits64(e: &[UwmlJointEnvironmentF64]) -> Vec<[u64; 8]> {
    e.iter()
        .map(|e| [e.drag, e.added_mass, e.buoyancy, e.gravity, e.visc, e.seal, e.current, e.total].map(f64::to_bits))
        .collect()
}

fn bits32(e: &[UwmlJointEnvironmentF32]) -> Vec<[u32; 8]> {
    e.iter()
        .map(|e| [e.drag, e.added_mass, e.buoyancy, e.gravity, e.visc, e.seal, e.current, e.total].map(f32::to_bits))
        .collect()
}

fn arm_states() -> Vec<[Vec<f64>; 3]> {
    let [q, qd, qdd] = ARM_STATE;
    vec![
        [q.to_vec(), qd.to_vec(), qdd.to_vec()],
        [vec![0.0; 6], vec![0.0; 6], vec![0.0; 6]],
        [
            vec![-1.3, 0.4, -0.2, -0.05, 2.5, -1.0],
            vec![-0.2, 1.1, -0.6, -0.3, 0.0, 2.0],
            vec![0.0, 3.0, -1.0, 0.0, 0.5, -0.4],
        ],
        // Slow: within the smooth sign's width (1e-3 rad/s) and the Stribeck speed.
        [vec![0.1; 6], vec![4e-4, -2e-4, 1e-4, -3e-4, 1e-3, 0.0], vec![0.0; 6]],
    ]
}

fn form_code(form: AddedMassForm) -> i32 {
    match form {
        AddedMassForm::Morison => UWML_ADDED_MASS_MORISON,
        AddedMassForm::Kirchhoff => UWML_ADDED_MASS_KIRCHHOFF,
    }
}

/// The C API's f64 environment of the arm equals the core's forces plus its losses, bit for bit;
/// the f32 one likewise.
fn assert_arm_is_the_core(
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

#[test]
fn the_arm_with_losses_is_the_core_bit_for_bit() {
    let params = arm();
    let (losses, conditions) = (arm_losses(), arm_conditions());
    for form in [AddedMassForm::Morison, AddedMassForm::Kirchhoff] {
        let mut robot = built64(&params);
        let mut robot32 = built32(&params);
        // SAFETY: live robots.
        unsafe {
            assert_eq!(uwml_robot_set_added_mass_form_f64(&mut *robot, form_code(form), null_mut()), UWML_OK);
            assert_eq!(uwml_robot_set_added_mass_form_f32(&mut *robot32, form_code(form), null_mut()), UWML_OK);
        }
        with_losses64(&mut robot, conditions);
        with_losses32(&mut robot32, conditions);
        assert_arm_is_the_core(form, &mut robot, &mut robot32, &losses, conditions);
    }

    // The test can fail: each joint's losses are what it was given (a seal only on the turret, oil
    // only on the telescope, none on the wrist and the camera), they change the totals of the
    // joints that have them and nothing else, and hydrodynamics is uwml_robot_hydro's.
    let mut robot = built64(&params);
    with_losses64(&mut robot, conditions);
    let [q, qd, qdd] = ARM_STATE;
    let state = [&q[..], &qd[..], &qdd[..]];
    let out = environment_c64(&mut robot, state, Some(&arm_motion()), Some(&ARM_CURRENT));
    let (forces, wrench) = hydro_c64(&mut robot, state);
    let has = |x: f64| x != 0.0;
    let kinds: Vec<[bool; 3]> = out.joints.iter().map(|e| [has(e.visc), has(e.seal), has(e.current)]).collect();
    let none = [false; 3];
    assert_eq!(kinds, [[false, true, true], [true; 3], [true; 3], [true, false, true], none, none]);
    for (i, (e, f)) in out.joints.iter().zip(&forces).enumerate() {
        let hydro = [e.drag, e.added_mass, e.buoyancy, e.gravity].map(f64::to_bits);
        assert_eq!(hydro, [f.drag, f.added_mass, f.buoyancy, f.gravity].map(f64::to_bits), "joint {i}");
        assert_eq!(e.total != f.total, i < 4, "joint {i}: {} vs {}", e.total, f.total);
        assert!(e.visc * qd[i] <= 0.0 && e.seal * qd[i] <= 0.0 && e.current * qd[i] >= 0.0, "losses oppose motion");
    }
    assert_eq!(wrench_bits64(&out.wrench), wrench_bits64(&wrench), "losses act inside the robot");
}

#[test]
fn conditions_move_every_joint_and_clearing_removes_one() {
    let params = arm();
    let losses = arm_losses();
    let mut robot = built64(&params);
    let mut robot32 = built32(&params);
    // Each joint at its own conditions first; then all at 6000 m and 2 °C.
    for (k, (joint, p)) in losses.iter().enumerate() {
        let (code, _) = set_losses64(&mut *robot, *joint, p, (1e6 * k as f64, 10.0 + k as f64));
        assert_eq!(code, UWML_OK);
    }
    with_losses32(&mut robot32, (2e6, 30.0));
    let deep = (pressure_at_depth(6000.0, DENSITY, GRAVITY).unwrap(), 2.0);
    let (code, error) = set_conditions64(&mut *robot, deep);
    expect_ok(code, &error);
    // SAFETY: a live robot.
    let code = unsafe { uwml_robot_set_conditions_f32(&mut *robot32, deep.0 as f32, deep.1 as f32, null_mut()) };
    assert_eq!(code, UWML_OK);
    assert_arm_is_the_core(AddedMassForm::Morison, &mut robot, &mut robot32, &losses, deep);

    // Clearing removes one joint's losses (a joint without any is left as it is).
    for joint in [1, 5] {
        assert_eq!(clear_losses64(&mut *robot, joint).0, UWML_OK);
        // SAFETY: a live robot.
        assert_eq!(unsafe { uwml_robot_clear_losses_f32(&mut *robot32, joint, null_mut()) }, UWML_OK);
    }
    let rest: Vec<_> = losses.iter().copied().filter(|(joint, _)| *joint != 1).collect();
    assert_arm_is_the_core(AddedMassForm::Morison, &mut robot, &mut robot32, &rest, deep);

    // A copy (memcpy) carries its losses.
    let mut copy = Box::new(*robot);
    let [q, qd, qdd] = ARM_STATE;
    let state = [&q[..], &qd[..], &qdd[..]];
    let original = environment_c64(&mut robot, state, None, None);
    assert_eq!(bits64(&environment_c64(&mut copy, state, None, None).joints), bits64(&original.joints));

    // Without losses, the environment is uwml_robot_hydro's forces and no loss: a new robot, a
    // robot whose every joint was cleared, and a block rebuilt by uwml_robot_new or
    // uwml_robot_paper over a robot with losses.
    let mut cleared = built64(&params);
    with_losses64(&mut cleared, deep);
    for joint in 0..6 {
        assert_eq!(clear_losses64(&mut *cleared, joint).0, UWML_OK);
    }
    let mut rebuilt = Box::new(*robot);
    let base = params.base.unwrap();
    // SAFETY: live locals; the arrays hold their counts of elements.
    let code = unsafe {
        uwml_robot_new_f64(
            &mut *rebuilt,
            params.joints.as_ptr(),
            6,
            params.links.as_ptr(),
            &base,
            params.segments.as_ptr(),
            count(params.segments.len()),
            DENSITY,
            GRAVITY,
            null_mut(),
        )
    };
    assert_eq!(code, UWML_OK);
    for mut without in [built64(&params), cleared, rebuilt] {
        let out = environment_c64(&mut without, state, Some(&arm_motion()), Some(&ARM_CURRENT));
        assert_eq!(out.code, UWML_OK);
        let (forces, wrench) = hydro_c64(&mut without, state);
        for (e, f) in out.joints.iter().zip(&forces) {
            assert_eq!([e.visc, e.seal, e.current].map(f64::to_bits), [0; 3]);
            let hydro = [e.drag, e.added_mass, e.buoyancy, e.gravity].map(f64::to_bits);
            assert_eq!(hydro, [f.drag, f.added_mass, f.buoyancy, f.gravity].map(f64::to_bits));
            assert!(e.total == f.total, "{} vs {}", e.total, f.total);
        }
        assert_eq!(wrench_bits64(&out.wrench), wrench_bits64(&wrench));
    }
    let mut paper = Box::new(*robot);
    // SAFETY: a live robot.
    assert_eq!(unsafe { uwml_robot_paper_leg_f64(&mut *paper) }, UWML_OK);
    let [q, qd, qdd] = PAPER_STATE;
    let out = environment_c64(&mut paper, [&q, &qd, &qdd], None, None);
    assert!(out.joints.iter().all(|e| e.visc == 0.0 && e.seal == 0.0 && e.current == 0.0));
}

#[test]
fn the_paper_leg_preset_with_losses_is_the_core_bit_for_bit() {
    let mut robot = zeroed64();
    let mut robot32 = zeroed32();
    let mut p = UwmlJointLossParamsF64::default();
    let mut p32 = UwmlJointLossParamsF32::default();
    // SAFETY: live locals.
    unsafe {
        assert_eq!(uwml_robot_paper_leg_f64(&mut *robot), UWML_OK);
        assert_eq!(uwml_robot_paper_leg_f32(&mut *robot32), UWML_OK);
        assert_eq!(uwml_robot_default_losses_f64(&mut p), UWML_OK);
        assert_eq!(uwml_robot_default_losses_f32(&mut p32), UWML_OK);
    }
    assert_eq!(p, default_losses(), "the tests' defaults are the library's");
    assert_eq!(p32, losses32(&p), "in f32 too");
    let mut seal_only = (p, p32);
    (seal_only.0.has_oil, seal_only.1.has_oil) = (0, 0);
    let pressure = pressure_at_depth(1000.0, 1025.0, 9.81).unwrap();
    let pressure32 = pressure_at_depth(1000.0f32, 1025.0, 9.81).unwrap();
    // docs/firmware.md's example (joints 2 and 3 oil-filled) and a seal on joint 1.
    let losses = [(0, seal_only.0), (1, p), (2, p)];
    for (joint, p) in losses {
        let p32 = losses32(&p);
        // SAFETY: live locals.
        unsafe {
            assert_eq!(uwml_robot_set_losses_f64(&mut *robot, joint, &p, pressure, 4.0, null_mut()), UWML_OK);
            assert_eq!(uwml_robot_set_losses_f32(&mut *robot32, joint, &p32, pressure32, 4.0, null_mut()), UWML_OK);
        }
    }
    let params = paper();
    let (water, water32) = (Water::default(), Water::<f32>::default());
    let states =
        [PAPER_STATE, [[0.0; 3], [0.0; 3], [0.0; 3]], [[-0.5, 0.9, -1.2], [-1.5, 0.02, 2.5], [0.3, 0.0, -4.0]]];
    for conditions in [(pressure, 4.0), (5e6, 2.0)] {
        if conditions.0 != pressure {
            // SAFETY: live locals.
            unsafe {
                assert_eq!(uwml_robot_set_conditions_f64(&mut *robot, conditions.0, conditions.1, null_mut()), UWML_OK);
                let (p, t) = (conditions.0 as f32, conditions.1 as f32);
                assert_eq!(uwml_robot_set_conditions_f32(&mut *robot32, p, t, null_mut()), UWML_OK);
            }
        }
        let states64 = core_loss_states::<f64>(&losses, conditions);
        let mut states32 = core_loss_states::<f32>(&losses, conditions);
        if conditions.0 == pressure {
            // Set at the f32 pressure of the depth, as the C caller gave it.
            states32 = core_loss_states::<f32>(&losses, (f64::from(pressure32), conditions.1));
        }
        for [q, qd, qdd] in states {
            let state = [&q[..], &qd[..], &qdd[..]];
            let out = environment_c64(&mut robot, state, None, None);
            expect_ok(out.code, &out.error);
            let data = core_hydro_with(
                &core_robot(&params),
                &water,
                AddedMassForm::Morison,
                &core_motion(None),
                &core_current(None),
                state,
            );
            let want = environment64(&core_environment(&data, &states64, &qd));
            assert_eq!(bits64(&out.joints), bits64(&want), "f64 at {state:?}");

            let (q, qd, qdd) = (q.map(f32::narrow), qd.map(f32::narrow), qdd.map(f32::narrow));
            let state32 = [&q[..], &qd[..], &qdd[..]];
            let (code, e, _) = environment_c32(&mut robot32, state32, None, None);
            assert_eq!(code, UWML_OK);
            let data = core_hydro_with(
                &core_robot::<f32>(&params),
                &water32,
                AddedMassForm::Morison,
                &core_motion(None),
                &core_current(None),
                state32,
            );
            let want = environment32(&core_environment(&data, &states32, &qd));
            assert_eq!(bits32(&e), bits32(&want), "f32 at {state32:?}");
        }
    }
    // The test can fail: at the reference state every joint has losses.
    let [q, qd, qdd] = PAPER_STATE;
    let out = environment_c64(&mut robot, [&q, &qd, &qdd], None, None);
    assert!(out.joints.iter().all(|e| e.seal != 0.0 && e.current != 0.0));
    assert!(out.joints[0].visc == 0.0 && out.joints[1].visc != 0.0 && out.joints[2].visc != 0.0);
    // And a moving base is honoured.
    let moving = environment_c64(&mut robot, [&q, &qd, &qdd], Some(&paper_motion()), Some(&PAPER_CURRENT));
    assert_eq!(moving.code, UWML_OK);
    assert!(moving.joints.iter().zip(&out.joints).all(|(m, f)| m.drag != f.drag && m.seal == f.seal));
}

#[test]
fn invalid_losses_name_the_field_and_the_joint_and_change_nothing() {
    let mut robot = built64(&arm());
    with_losses64(&mut robot, arm_conditions());
    let before = robot.clone();
    let r: *mut UwmlRobotF64 = &mut *robot;
    let ok = (1e6, 20.0);

    type Edit = fn(&mut UwmlJointLossParamsF64);
    let cases: [(Edit, (i32, &str)); 21] = [
        (|p| p.drive.torque_constant = 0.0, (UWML_ERR_NON_POSITIVE, "drive.torque_constant")),
        (|p| p.drive.ratio = -160.0, (UWML_ERR_NON_POSITIVE, "drive.ratio")),
        (|p| p.drive.efficiency = 0.0, (UWML_ERR_NON_POSITIVE, "drive.efficiency")),
        (|p| p.drive.efficiency = 1.5, (UWML_ERR_OUT_OF_RANGE, "drive.efficiency (0 to 1)")),
        (|p| p.drive.rated_current = f64::NAN, (UWML_ERR_NON_FINITE, "drive.rated_current")),
        (|p| p.oil.k_oil = -1.0, (UWML_ERR_NEGATIVE, "oil.k_oil")),
        (|p| p.oil.exponent = 0.5, (UWML_ERR_OUT_OF_RANGE, "oil.exponent (1 to 2)")),
        (|p| p.oil.exponent = 2.5, (UWML_ERR_OUT_OF_RANGE, "oil.exponent (1 to 2)")),
        (|p| p.oil.pressure_sensitivity = -1e-9, (UWML_ERR_NEGATIVE, "oil.pressure_sensitivity")),
        (|p| p.oil.temperature_sensitivity = f64::INFINITY, (UWML_ERR_NON_FINITE, "oil.temperature_sensitivity")),
        (|p| p.oil.reference_pressure = -1.0, (UWML_ERR_NEGATIVE, "oil.reference_pressure")),
        (
            |p| p.oil.reference_temperature = -300.0,
            (UWML_ERR_OUT_OF_RANGE, "oil.reference_temperature (above -273.15 °C)"),
        ),
        (|p| p.seal.c[0] = -1.0, (UWML_ERR_NEGATIVE, "seal.c0")),
        (|p| p.seal.c[1] = f64::NAN, (UWML_ERR_NON_FINITE, "seal.c1")),
        (|p| p.seal.s[0] = p.seal.c[0] / 2.0, (UWML_ERR_OUT_OF_ORDER, "seal.s0")),
        (|p| p.seal.s[1] = p.seal.c[1] / 2.0, (UWML_ERR_OUT_OF_ORDER, "seal.s1")),
        (|p| p.seal.d[0] = -0.1, (UWML_ERR_NEGATIVE, "seal.d0")),
        (|p| p.seal.d[1] = -1e-9, (UWML_ERR_NEGATIVE, "seal.d1")),
        (|p| p.seal.stribeck_speed = 0.0, (UWML_ERR_NON_POSITIVE, "seal.stribeck_speed")),
        (|p| p.epsilon = -1e-3, (UWML_ERR_NEGATIVE, "losses.epsilon")),
        (|p| p.epsilon = f64::NEG_INFINITY, (UWML_ERR_NON_FINITE, "losses.epsilon")),
    ];
    for (edit, (code, field)) in cases {
        for joint in [0, 5] {
            let mut p = default_losses();
            edit(&mut p);
            let (got, error) = set_losses64(r, joint, &p, ok);
            expect_error(got, &error, (code, i64::from(joint), field));
        }
    }
    // Parameters of an absent oil or seal are not read.
    let mut p = default_losses();
    (p.has_oil, p.has_seal, p.oil.exponent, p.seal.stribeck_speed) = (0, 0, f64::NAN, -1.0);
    let mut scratch = robot.clone();
    assert_eq!(set_losses64(&mut *scratch, 4, &p, ok).0, UWML_OK);

    // Joint indices beyond the robot's joints (6), at its capacity and beyond.
    let p = default_losses();
    for index in [6, 15, 16, u32::MAX] {
        let want = (UWML_ERR_INDEX_OUT_OF_RANGE, i64::from(index), "joint_index");
        let (code, error) = set_losses64(r, index, &p, ok);
        expect_error(code, &error, want);
        let (code, error) = clear_losses64(r, index);
        expect_error(code, &error, want);
    }

    // Conditions outside the domain, at set_losses and at set_conditions.
    for (conditions, want) in [
        ((f64::NAN, 20.0), (UWML_ERR_NON_FINITE, -1, "pressure_pa")),
        ((f64::INFINITY, 20.0), (UWML_ERR_NON_FINITE, -1, "pressure_pa")),
        ((-1.0, 20.0), (UWML_ERR_NEGATIVE, -1, "pressure_pa")),
        ((1.3e8, 4.0), (UWML_ERR_BEYOND_DEEPEST_OCEAN, -1, "pressure_pa")),
        ((0.0, f64::NAN), (UWML_ERR_NON_FINITE, -1, "temperature_c")),
        ((0.0, f64::NEG_INFINITY), (UWML_ERR_NON_FINITE, -1, "temperature_c")),
        ((0.0, -280.0), (UWML_ERR_BELOW_ABSOLUTE_ZERO, -1, "temperature_c")),
        ((0.0, -273.15), (UWML_ERR_BELOW_ABSOLUTE_ZERO, -1, "temperature_c")),
    ] {
        let (code, error) = set_losses64(r, 2, &p, conditions);
        expect_error(code, &error, want);
        let (code, error) = set_conditions64(r, conditions);
        expect_error(code, &error, want);
    }
    // The order of the checks is the leg's: the joint index, the parameters, the conditions.
    let mut bad = default_losses();
    bad.drive.ratio = 0.0;
    let (code, error) = set_losses64(r, 6, &bad, (-1.0, 20.0));
    expect_error(code, &error, (UWML_ERR_INDEX_OUT_OF_RANGE, 6, "joint_index"));
    let (code, error) = set_losses64(r, 1, &bad, (-1.0, 20.0));
    expect_error(code, &error, (UWML_ERR_NON_POSITIVE, 1, "drive.ratio"));

    // Depths: what uwml_pressure_at_depth_f64 refuses never reaches the robot; 11000 m does.
    let mut pressure = -7.0;
    for (depth, want) in [
        (-1.0, (UWML_ERR_NEGATIVE, -1, "depth")),
        (11000.5, (UWML_ERR_BEYOND_DEEPEST_OCEAN, -1, "depth")),
        (f64::NAN, (UWML_ERR_NON_FINITE, -1, "depth")),
        (f64::INFINITY, (UWML_ERR_NON_FINITE, -1, "depth")),
    ] {
        let mut error = blank_error();
        // SAFETY: live locals.
        let code = unsafe { uwml_pressure_at_depth_f64(depth, DENSITY, GRAVITY, &mut pressure, &mut error) };
        expect_error(code, &error, want);
        assert_eq!(pressure, -7.0, "nothing written");
    }

    assert_eq!(robot.opaque_tag, before.opaque_tag);
    assert!(robot.opaque == before.opaque, "failed setters change nothing");

    let mut error = blank_error();
    // SAFETY: live locals.
    let code = unsafe { uwml_pressure_at_depth_f64(11000.0, DENSITY, GRAVITY, &mut pressure, &mut error) };
    assert_eq!(code, UWML_OK);
    let (code, error) = set_conditions64(r, (pressure, -2.0));
    expect_ok(code, &error);

    // f32 names the same fields.
    let mut robot32 = built32(&arm());
    let mut p = losses32(&default_losses());
    p.seal.s[0] = 0.0;
    let mut error = blank_error();
    // SAFETY: live locals.
    let code = unsafe { uwml_robot_set_losses_f32(&mut *robot32, 3, &p, 1e6, 20.0, &mut error) };
    expect_error(code, &error, (UWML_ERR_OUT_OF_ORDER, 3, "seal.s0"));
    // SAFETY: live locals.
    let code = unsafe { uwml_robot_set_losses_f32(&mut *robot32, 6, &p, 1e6, 20.0, &mut error) };
    expect_error(code, &error, (UWML_ERR_INDEX_OUT_OF_RANGE, 6, "joint_index"));
    // SAFETY: live locals.
    let code = unsafe { uwml_robot_clear_losses_f32(&mut *robot32, 16, &mut error) };
    expect_error(code, &error, (UWML_ERR_INDEX_OUT_OF_RANGE, 16, "joint_index"));
    // SAFETY: live locals.
    let code = unsafe { uwml_robot_set_conditions_f32(&mut *robot32, 2e8, 4.0, &mut error) };
    expect_error(code, &error, (UWML_ERR_BEYOND_DEEPEST_OCEAN, -1, "pressure_pa"));
    // SAFETY: live locals.
    let code = unsafe { uwml_robot_set_conditions_f32(&mut *robot32, 0.0, -274.0, &mut error) };
    expect_error(code, &error, (UWML_ERR_BELOW_ABSOLUTE_ZERO, -1, "temperature_c"));
}

#[test]
fn null_pointers_and_unwritten_robots_are_refused() {
    let params = arm();
    let mut robot = built64(&params);
    with_losses64(&mut robot, arm_conditions());
    let r: *mut UwmlRobotF64 = &mut *robot;
    let p = default_losses();
    let [q, qd, qdd] = ARM_STATE;
    let (q, qd, qdd) = (q.as_ptr(), qd.as_ptr(), qdd.as_ptr());
    let mut joints = [SENTINEL64; 6];
    let j = joints.as_mut_ptr();
    let (m, c) = (&arm_motion() as *const _, &ARM_CURRENT as *const _);
    let mut e = blank_error();
    // SAFETY: every non-null pointer is a live local of the right size; null ones are checked.
    unsafe {
        expect_error(uwml_robot_set_losses_f64(null_mut(), 0, &p, 0.0, 20.0, &mut e), &e, (1, -1, "robot"));
        expect_error(uwml_robot_set_losses_f64(r, 0, null(), 0.0, 20.0, &mut e), &e, (1, -1, "params"));
        expect_error(uwml_robot_clear_losses_f64(null_mut(), 0, &mut e), &e, (1, -1, "robot"));
        expect_error(uwml_robot_set_conditions_f64(null_mut(), 0.0, 20.0, &mut e), &e, (1, -1, "robot"));
        let code =
            uwml_robot_environment_f64(null_mut(), &mut *workspace64(), q, qd, qdd, 6, m, c, j, null_mut(), &mut e);
        expect_error(code, &e, (1, -1, "robot"));
        expect_error(
            uwml_robot_environment_f64(r, &mut *workspace64(), null(), qd, qdd, 6, m, c, j, null_mut(), &mut e),
            &e,
            (1, -1, "q"),
        );
        expect_error(
            uwml_robot_environment_f64(r, &mut *workspace64(), q, null(), qdd, 6, m, c, j, null_mut(), &mut e),
            &e,
            (1, -1, "qd"),
        );
        expect_error(
            uwml_robot_environment_f64(r, &mut *workspace64(), q, qd, null(), 6, m, c, j, null_mut(), &mut e),
            &e,
            (1, -1, "qdd"),
        );
        let code =
            uwml_robot_environment_f64(r, &mut *workspace64(), q, qd, qdd, 6, m, c, null_mut(), null_mut(), &mut e);
        expect_error(code, &e, (1, -1, "joint_environment"));
        let code = uwml_robot_environment_f64(r, &mut *workspace64(), q, qd, qdd, 5, m, c, j, null_mut(), &mut e);
        expect_error(code, &e, (UWML_ERR_OUT_OF_RANGE, -1, "n (the robot's joint count)"));
        // f32.
        let p32 = losses32(&p);
        let z = [0.0f32; 6];
        expect_error(uwml_robot_set_losses_f32(null_mut(), 0, &p32, 0.0, 20.0, &mut e), &e, (1, -1, "robot"));
        let mut robot32 = built32(&params);
        expect_error(uwml_robot_set_losses_f32(&mut *robot32, 0, null(), 0.0, 20.0, &mut e), &e, (1, -1, "params"));
        expect_error(uwml_robot_clear_losses_f32(null_mut(), 0, &mut e), &e, (1, -1, "robot"));
        expect_error(uwml_robot_set_conditions_f32(null_mut(), 0.0, 20.0, &mut e), &e, (1, -1, "robot"));
        let (z, zp) = (z.as_ptr(), null_mut::<UwmlJointEnvironmentF32>());
        let code = uwml_robot_environment_f32(
            null_mut(),
            &mut *workspace32(),
            z,
            z,
            z,
            6,
            null(),
            null(),
            zp,
            null_mut(),
            &mut e,
        );
        expect_error(code, &e, (1, -1, "robot"));
        let code = uwml_robot_environment_f32(
            &*robot32,
            &mut *workspace32(),
            z,
            z,
            z,
            6,
            null(),
            null(),
            zp,
            null_mut(),
            &mut e,
        );
        expect_error(code, &e, (1, -1, "joint_environment"));
    }
    assert!(joints.iter().all(|x| *x == SENTINEL64), "a failed evaluation writes nothing");

    // Invalid motions write nothing either.
    let [q, qd, qdd] = ARM_STATE;
    let mut motion = arm_motion();
    motion.orientation = [0.0; 4];
    let out = environment_c64(&mut robot, [&q, &qd, &qdd], Some(&motion), None);
    expect_error(out.code, &out.error, (UWML_ERR_NOT_UNIT, -1, "base.orientation"));
    assert!(out.joints.iter().all(|x| *x == SENTINEL64) && out.wrench == WRENCH_SENTINEL64);

    // Blocks the library did not write, or wrote for the other precision or as a workspace.
    for tag in [0, built32(&params).opaque_tag, workspace64().opaque_tag] {
        let mut fake = zeroed64();
        fake.opaque_tag = tag;
        let f: *mut UwmlRobotF64 = &mut *fake;
        let want = (UWML_ERR_UNINITIALIZED, -1, "robot");
        let (code, error) = set_losses64(f, 0, &p, (0.0, 20.0));
        expect_error(code, &error, want);
        let (code, error) = clear_losses64(f, 0);
        expect_error(code, &error, want);
        let (code, error) = set_conditions64(f, (0.0, 20.0));
        expect_error(code, &error, want);
        let out = environment_c64(&mut fake, [&q, &qd, &qdd], None, None);
        expect_error(out.code, &out.error, want);
        assert_eq!(fake.opaque_tag, tag);
        assert!(fake.opaque.iter().all(|&w| w == 0), "nothing written");
    }

    // A robot without joints: no joint to give losses to; its environment is its base wrench.
    let mut params = arm();
    params.joints.clear();
    params.links.clear();
    params.segments.retain(|s| s.owner == UWML_BASE);
    let mut vehicle = built64(&params);
    let (code, error) = set_losses64(&mut *vehicle, 0, &p, (0.0, 20.0));
    expect_error(code, &error, (UWML_ERR_INDEX_OUT_OF_RANGE, 0, "joint_index"));
    assert_eq!(set_conditions64(&mut *vehicle, (1e6, 4.0)).0, UWML_OK);
    let mut wrench = WRENCH_SENTINEL64;
    // SAFETY: live locals; the joint arrays are NULL with n = 0, never read.
    let code = unsafe {
        uwml_robot_environment_f64(
            &*vehicle,
            &mut *workspace64(),
            null(),
            null(),
            null(),
            0,
            &arm_motion(),
            &ARM_CURRENT,
            null_mut(),
            &mut wrench,
            null_mut(),
        )
    };
    assert_eq!(code, UWML_OK);
    let data = core_hydro_with(
        &core_robot(&params),
        &Water::new(DENSITY, GRAVITY).unwrap(),
        AddedMassForm::Morison,
        &core_motion(Some(&arm_motion())),
        &core_current(Some(&ARM_CURRENT)),
        [&[], &[], &[]],
    );
    assert_eq!(wrench_bits64(&wrench), wrench_bits64(&wrench64(&data)));
}

#[test]
fn non_finite_states_and_overflowing_losses_are_reported() {
    let params = arm();
    let mut robot = built64(&params);
    with_losses64(&mut robot, arm_conditions());
    let water = Water::new(DENSITY, GRAVITY).unwrap();
    let states = core_loss_states::<f64>(&arm_losses(), arm_conditions());
    for (which, name) in [(0, "q"), (1, "qd"), (2, "qdd")] {
        let mut state = ARM_STATE;
        state[which][2] = f64::NAN;
        state[which][4] = f64::INFINITY;
        let s = [&state[0][..], &state[1][..], &state[2][..]];
        let out = environment_c64(&mut robot, s, Some(&arm_motion()), Some(&ARM_CURRENT));
        expect_error(out.code, &out.error, (UWML_ERR_NON_FINITE, 2, name));
        assert!(out.joints.iter().all(|e| e.total.is_nan()) && out.wrench.total.iter().all(|x| x.is_nan()));
        let data = core_hydro_with(
            &core_robot(&params),
            &water,
            AddedMassForm::Morison,
            &core_motion(Some(&arm_motion())),
            &core_current(Some(&ARM_CURRENT)),
            s,
        );
        let want = environment64(&core_environment(&data, &states, &state[1]));
        assert_eq!(bits64(&out.joints), bits64(&want), "NaN where the core gives NaN");
    }

    // A finite speed far beyond any robot's: the forces overflow (the first joint named).
    let [q, mut qd, qdd] = ARM_STATE;
    qd[1] = 1e200;
    let out = environment_c64(&mut robot, [&q, &qd, &qdd], None, None);
    expect_error(out.code, &out.error, (UWML_ERR_OVERFLOW, 0, "total"));
    assert!(!out.joints[1].total.is_finite());

    // A loss current that overflows while the torques do not: a torque constant of 1e-300 N·m/A
    // on the camera's joint, turning at 1e9 rad/s.
    let mut p = default_losses();
    p.drive.torque_constant = 1e-300;
    assert_eq!(set_losses64(&mut *robot, 5, &p, (1e6, 4.0)).0, UWML_OK);
    let [q, mut qd, qdd] = ARM_STATE;
    qd[5] = 1e9;
    let out = environment_c64(&mut robot, [&q, &qd, &qdd], None, None);
    expect_error(out.code, &out.error, (UWML_ERR_OVERFLOW, 5, "current"));
    assert!(out.joints[5].current.is_infinite() && out.joints[5].total.is_finite(), "{:?}", out.joints[5]);
    qd[5] = 1e3;
    assert_eq!(environment_c64(&mut robot, [&q, &qd, &qdd], None, None).code, UWML_OK);
}
