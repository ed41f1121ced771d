//! What the C API has besides robots and their evaluation: the error messages, the pressure at a
//! depth, the default joint losses (the core's), and the workspace: what an evaluation writes,
//! apart from the robot, which it only reads (so one robot serves several threads, each with its
//! own workspace).
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing, clippy::expect_used)]

use core::ffi::CStr;
use core::ptr::{null, null_mut};

use uwml_core::{JointLosses, pressure_at_depth};
use uwml_ffi::*;

mod errors;
use errors::{blank_error, expect_error};

mod robots;
use robots::{ARM_CURRENT, ARM_STATE, arm, arm_motion, built64, core_losses, count, losses32, workspace64, zeroed64};

#[test]
fn default_loss_parameters_are_the_cores_defaults() {
    let (mut p, mut p32) = (UwmlJointLossParamsF64::default(), UwmlJointLossParamsF32::default());
    // SAFETY: live locals.
    unsafe {
        assert_eq!(uwml_robot_default_losses_f64(&mut p), UWML_OK);
        assert_eq!(uwml_robot_default_losses_f32(&mut p32), UWML_OK);
        assert_eq!(uwml_robot_default_losses_f64(null_mut()), UWML_ERR_NULL_POINTER);
    }
    // Built again through the core's constructors (f32: each field rounded as C's `(float)x`).
    assert_eq!(core_losses::<f64>(&p), JointLosses::default());
    assert_eq!(core_losses::<f32>(&p), JointLosses::<f32>::default());
    assert_eq!(p32, losses32(&p));
    assert_eq!((p.has_oil, p.has_seal), (1, 1));
}

#[test]
fn error_messages_and_helpers() {
    let codes = [
        UWML_OK,
        UWML_ERR_NULL_POINTER,
        UWML_ERR_NON_FINITE,
        UWML_ERR_NON_POSITIVE,
        UWML_ERR_NEGATIVE,
        UWML_ERR_NOT_UNIT,
        UWML_ERR_NOT_PERPENDICULAR,
        UWML_ERR_OUT_OF_ORDER,
        UWML_ERR_OUT_OF_RANGE,
        UWML_ERR_INDEX_OUT_OF_RANGE,
        UWML_ERR_UNINITIALIZED,
        UWML_ERR_BELOW_ABSOLUTE_ZERO,
        UWML_ERR_BEYOND_DEEPEST_OCEAN,
        UWML_ERR_OVERFLOW,
        UWML_ERR_TOO_LARGE,
        UWML_ERR_NOT_SYMMETRIC,
        UWML_ERR_NOT_POSITIVE_SEMIDEFINITE,
    ];
    assert_eq!(codes, [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16]);
    let mut messages: Vec<String> = codes
        .iter()
        .map(|&code| {
            // SAFETY: the function returns a static NUL-terminated string.
            unsafe { CStr::from_ptr(uwml_error_message(code)) }.to_str().unwrap().to_owned()
        })
        .collect();
    assert_eq!(messages[0], "ok");
    messages.sort();
    messages.dedup();
    assert_eq!(messages.len(), codes.len(), "one message per code");
    // SAFETY: as above.
    assert_eq!(unsafe { CStr::from_ptr(uwml_error_message(-3)) }.to_str().unwrap(), "unknown error");
}

#[test]
fn pressure_at_depth_is_checked() {
    let (mut p64, mut p32, mut error) = (-1.0f64, -1.0f32, blank_error());
    // SAFETY: live locals.
    let code = unsafe { uwml_pressure_at_depth_f64(1000.0, 1025.0, 9.81, &mut p64, &mut error) };
    expect_error(code, &error, (UWML_OK, -1, ""));
    assert_eq!(p64, 1025.0 * 9.81 * 1000.0);
    // SAFETY: live locals.
    let code = unsafe { uwml_pressure_at_depth_f32(11000.0, 1025.0, 9.81, &mut p32, core::ptr::null_mut()) };
    assert_eq!((code, p32), (UWML_OK, pressure_at_depth(11000.0f32, 1025.0, 9.81).unwrap()));
    for (depth, density, gravity, want) in [
        (-1.0, 1025.0, 9.81, (UWML_ERR_NEGATIVE, -1, "depth")),
        (11000.5, 1025.0, 9.81, (UWML_ERR_BEYOND_DEEPEST_OCEAN, -1, "depth")),
        (f64::NAN, 1025.0, 9.81, (UWML_ERR_NON_FINITE, -1, "depth")),
        (1000.0, -1025.0, 9.81, (UWML_ERR_NON_POSITIVE, -1, "sea_density")),
        (1000.0, 1025.0, f64::INFINITY, (UWML_ERR_NON_FINITE, -1, "gravity")),
    ] {
        let (mut out, mut error) = (-7.0, blank_error());
        // SAFETY: live locals.
        let code = unsafe { uwml_pressure_at_depth_f64(depth, density, gravity, &mut out, &mut error) };
        expect_error(code, &error, want);
        assert_eq!(out, -7.0, "nothing written on an error");
    }
    let mut error = blank_error();
    // SAFETY: a null `out` is refused, not written.
    let code = unsafe { uwml_pressure_at_depth_f64(1000.0, 1025.0, 9.81, core::ptr::null_mut(), &mut error) };
    expect_error(code, &error, (UWML_ERR_NULL_POINTER, -1, "out"));
}

/// One evaluation of `robot` in `workspace`: the code, the error, the joint forces.
fn hydro(robot: *const UwmlRobotF64, workspace: *mut UwmlWorkspaceF64) -> (i32, UwmlError, Vec<UwmlJointForcesF64>) {
    let [q, qd, qdd] = ARM_STATE;
    let (mut forces, mut error) = (vec![UwmlJointForcesF64::default(); 6], blank_error());
    let (motion, current) = (arm_motion(), ARM_CURRENT);
    // SAFETY: live locals (the robot and workspace as the caller gives them, NULL or not).
    let code = unsafe {
        uwml_robot_hydro_f64(
            robot,
            workspace,
            q.as_ptr(),
            qd.as_ptr(),
            qdd.as_ptr(),
            count(q.len()),
            &motion,
            &current,
            forces.as_mut_ptr(),
            null_mut(),
            &mut error,
        )
    };
    (code, error, forces)
}

#[test]
fn a_workspace_is_written_by_the_library_and_named_in_errors() {
    let robot = built64(&arm());
    let (code, error, _) = hydro(&*robot, null_mut());
    expect_error(code, &error, (UWML_ERR_NULL_POINTER, -1, "workspace"));
    let mut zeroed = UwmlWorkspaceF64 { opaque_tag: 0, opaque: [0; UWML_WORKSPACE_F64_WORDS] };
    let (code, error, forces) = hydro(&*robot, &mut zeroed);
    expect_error(code, &error, (UWML_ERR_UNINITIALIZED, -1, "workspace"));
    assert!(forces.iter().all(|f| *f == UwmlJointForcesF64::default()), "nothing written");
    // A robot's tag is not a workspace's, nor an f32 workspace's.
    zeroed.opaque_tag = robot.opaque_tag;
    assert_eq!(hydro(&*robot, &mut zeroed).0, UWML_ERR_UNINITIALIZED);
    let mut f32_workspace = UwmlWorkspaceF32 { opaque_tag: 0, opaque: [0; UWML_WORKSPACE_F32_WORDS] };
    // SAFETY: a live local.
    assert_eq!(unsafe { uwml_robot_workspace_init_f32(&mut f32_workspace) }, UWML_OK);
    zeroed.opaque_tag = f32_workspace.opaque_tag;
    assert_eq!(hydro(&*robot, &mut zeroed).0, UWML_ERR_UNINITIALIZED);
    // The robot is checked first: an unwritten robot with a NULL workspace names the robot.
    let (code, error, _) = hydro(&*zeroed64(), null_mut());
    expect_error(code, &error, (UWML_ERR_UNINITIALIZED, -1, "robot"));
    let (code, error, _) = hydro(null(), &mut *workspace64());
    expect_error(code, &error, (UWML_ERR_NULL_POINTER, -1, "robot"));
    // SAFETY: NULL is refused, not written.
    assert_eq!(unsafe { uwml_robot_workspace_init_f64(null_mut()) }, UWML_ERR_NULL_POINTER);
}

#[test]
fn evaluations_only_read_the_robot_and_any_workspace_gives_the_same_forces() {
    let robot = built64(&arm());
    let before = robot.opaque;
    let (first, second) = (hydro(&*robot, &mut *workspace64()), hydro(&*robot, &mut *workspace64()));
    assert_eq!((first.0, second.0), (UWML_OK, UWML_OK));
    let bits = |f: &[UwmlJointForcesF64]| f.iter().map(|f| f.total.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&first.2), bits(&second.2));
    assert!(first.2.iter().any(|f| f.total != 0.0), "the test can fail");
    assert!(robot.opaque == before, "an evaluation writes nothing into the robot");
    // Several threads, one robot (shared, read only), a workspace each: the same bits.
    let shared: &UwmlRobotF64 = &robot;
    std::thread::scope(|scope| {
        let runs: Vec<_> = (0..4)
            .map(|_| {
                scope.spawn(|| {
                    let mut workspace = workspace64();
                    (0..50).map(|_| hydro(shared, &mut *workspace)).last().expect("50 runs")
                })
            })
            .collect();
        for run in runs {
            let (code, _, forces) = run.join().expect("no panic");
            assert_eq!(code, UWML_OK);
            assert_eq!(bits(&forces), bits(&first.2));
        }
    });
}
