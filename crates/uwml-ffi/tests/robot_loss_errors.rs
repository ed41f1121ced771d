//! The joint losses' refusals through the C API: invalid parameters naming the field and the joint
//! and changing nothing, NULL pointers and robots the library did not write, non-finite states
//! and losses that overflow.
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing, clippy::expect_used)]

use core::ptr::{null, null_mut};

use uwml_core::{AddedMassForm, Water};
use uwml_ffi::*;

mod errors;
use errors::{blank_error, expect_error};

mod robots;
use robots::*;

mod loss_calls;
use loss_calls::*;

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
