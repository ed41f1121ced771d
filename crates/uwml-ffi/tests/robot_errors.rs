//! The robot API's refusals: invalid robots, motions and currents naming the field and index,
//! non-finite states, NULL pointers reported and never dereferenced, blocks the library did not
//! write, forces that overflow. Nothing is written on a refusal.
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing, clippy::expect_used)]

use core::ffi::CStr;
use core::ptr::{null, null_mut};

use uwml_core::Water;
use uwml_ffi::*;

mod errors;
use errors::{blank_error, expect_error};

mod robots;
use robots::*;

mod calls;
use calls::*;

#[test]
fn invalid_robots_name_the_field_and_index() {
    type Edit = fn(&mut Params);
    let cases: Vec<(Edit, (i32, i64, &str))> = vec![
        (|p| p.joints[2].parent = 2, (UWML_ERR_OUT_OF_RANGE, 2, "joint.parent")),
        (|p| p.joints[4].parent = 5, (UWML_ERR_OUT_OF_RANGE, 4, "joint.parent")),
        (|p| p.joints[1].parent = -2, (UWML_ERR_OUT_OF_RANGE, 1, "joint.parent")),
        (|p| p.joints[3].kind = 2, (UWML_ERR_OUT_OF_RANGE, 3, "joint.kind")),
        (|p| p.joints[5].axis = [0.0, 0.0, 0.0], (UWML_ERR_NOT_UNIT, 5, "joint.axis")),
        (|p| p.joints[0].origin[1] = f64::NAN, (UWML_ERR_NON_FINITE, 0, "joint.origin")),
        (|p| p.links[4].volume = -1e-4, (UWML_ERR_NEGATIVE, 4, "link.volume")),
        (|p| p.links[1].com[2] = f64::INFINITY, (UWML_ERR_NON_FINITE, 1, "link.com")),
        (|p| p.base.as_mut().unwrap().mass = -1.0, (UWML_ERR_NEGATIVE, -1, "base.mass")),
        (|p| p.base.as_mut().unwrap().cob[0] = f64::NAN, (UWML_ERR_NON_FINITE, -1, "base.cob")),
        (|p| p.base.as_mut().unwrap().volume = f64::NAN, (UWML_ERR_NON_FINITE, -1, "base.volume")),
        (|p| p.segments[7].owner = 6, (UWML_ERR_OUT_OF_RANGE, 7, "segment.owner")),
        (|p| p.segments[2].owner = -5, (UWML_ERR_OUT_OF_RANGE, 2, "segment.owner")),
        (|p| p.segments[3].section = 2, (UWML_ERR_OUT_OF_RANGE, 3, "segment.section")),
        (|p| p.segments[0].diameter = 0.0, (UWML_ERR_NON_POSITIVE, 0, "segment.diameter")),
        (|p| p.segments[4].cd = [1.2, 1.0], (UWML_ERR_OUT_OF_RANGE, 4, "segment.cd")),
        (|p| p.segments[5].cm[1] = 0.5, (UWML_ERR_OUT_OF_RANGE, 5, "segment.cm")),
        (|p| p.segments[1].cd[1] = -0.1, (UWML_ERR_NEGATIVE, 1, "segment.cd")),
        (|p| p.segments[6].normals[1] = [0.0, 1.0, 0.0], (UWML_ERR_NOT_PERPENDICULAR, 6, "segment.normals[1]")),
        (|p| p.segments[3].widths[0] = 0.0, (UWML_ERR_NON_POSITIVE, 3, "segment.widths[0]")),
        (|p| p.segments[2].length = -0.1, (UWML_ERR_NON_POSITIVE, 2, "segment.length")),
        (|p| p.segments[2].area = f64::NAN, (UWML_ERR_NON_FINITE, 2, "segment.area")),
        (|p| p.segments[4].axis = [0.0, 0.0, 2.0], (UWML_ERR_NOT_UNIT, 4, "segment.axis")),
        // Finite but beyond the model's bounds (their forces would overflow).
        (|p| p.links[1].com[0] = 1e308, (UWML_ERR_TOO_LARGE, 1, "link.com")),
        (|p| p.joints[2].origin[2] = -2e4, (UWML_ERR_TOO_LARGE, 2, "joint.origin")),
        (|p| p.base.as_mut().unwrap().mass = 2e9, (UWML_ERR_TOO_LARGE, -1, "base.mass")),
        (|p| p.segments[3].length = 1e5, (UWML_ERR_TOO_LARGE, 3, "segment.length")),
        (|p| p.segments[0].cd = [5e3, 5e3], (UWML_ERR_TOO_LARGE, 0, "segment.cd")),
        (
            |p| {
                let joint = p.joints[5];
                p.joints.resize(UWML_ROBOT_MAX_JOINTS + 1, joint);
                let link = p.links[5];
                p.links.resize(UWML_ROBOT_MAX_JOINTS + 1, link);
            },
            (UWML_ERR_OUT_OF_RANGE, -1, "n_joints (at most 16)"),
        ),
        (
            |p| {
                let segment = p.segments[2];
                p.segments.resize(UWML_ROBOT_MAX_SEGMENTS + 1, segment);
            },
            (UWML_ERR_OUT_OF_RANGE, -1, "n_segments (at most 32)"),
        ),
    ];
    for (edit, want) in cases {
        let mut params = arm();
        edit(&mut params);
        let mut robot = zeroed64();
        let (code, error) = new64(&mut robot, &params, DENSITY);
        expect_error(code, &error, want);
        assert_eq!(robot.opaque_tag, 0, "a failed construction writes nothing");
    }
    // Water.
    let mut robot = zeroed64();
    let (code, error) = new64(&mut robot, &arm(), 0.0);
    expect_error(code, &error, (UWML_ERR_NON_POSITIVE, -1, "water.density"));
    let (code, error) = new64(&mut robot, &arm(), 1e300);
    expect_error(code, &error, (UWML_ERR_TOO_LARGE, -1, "water.density"));
    // Fields a section does not use are not read.
    let mut params = arm();
    params.segments[0].normals = [[f64::NAN; 3]; 2];
    params.segments[0].widths = [-1.0; 2];
    params.segments[1].diameter = f64::NAN;
    let (code, _) = new64(&mut robot, &params, DENSITY);
    assert_eq!(code, UWML_OK);

    // A failed construction leaves a valid robot as it was.
    let before = robot.clone();
    let mut params = arm();
    params.links[0].mass = -1.0;
    let (code, _) = new64(&mut robot, &params, DENSITY);
    assert_eq!(code, UWML_ERR_NEGATIVE);
    assert!(robot.opaque_tag == before.opaque_tag && robot.opaque == before.opaque);

    // f32: the same checks.
    let mut p = params32(&arm());
    p.joints[3].parent = 4;
    let mut robot = zeroed32();
    let mut error = blank_error();
    // SAFETY: live locals; the arrays hold their counts of elements.
    let code = unsafe {
        uwml_robot_new_f32(
            &mut *robot,
            p.joints.as_ptr(),
            6,
            p.links.as_ptr(),
            null(),
            p.segments.as_ptr(),
            count(p.segments.len()),
            1025.0,
            9.81,
            &mut error,
        )
    };
    expect_error(code, &error, (UWML_ERR_OUT_OF_RANGE, 3, "joint.parent"));
}

#[test]
fn invalid_motions_and_currents_name_the_field_and_write_nothing() {
    let mut robot = built64(&arm());
    let [q, qd, qdd] = ARM_STATE;
    type Edit = fn(&mut UwmlBaseMotionF64, &mut UwmlCurrentF64);
    let cases: [(Edit, (i32, i64, &str)); 9] = [
        (|m, _| m.orientation = [0.0; 4], (UWML_ERR_NOT_UNIT, -1, "base.orientation")),
        (|m, _| m.orientation = [1.0, 0.1, 0.0, 0.0], (UWML_ERR_NOT_UNIT, -1, "base.orientation")),
        (|m, _| m.orientation[2] = f64::NAN, (UWML_ERR_NON_FINITE, -1, "base.orientation")),
        (|m, _| m.velocity[0] = f64::INFINITY, (UWML_ERR_NON_FINITE, -1, "base.velocity")),
        (|m, _| m.angular_velocity[1] = f64::NAN, (UWML_ERR_NON_FINITE, -1, "base.angular_velocity")),
        (|m, _| m.acceleration[2] = f64::NAN, (UWML_ERR_NON_FINITE, -1, "base.acceleration")),
        (|m, _| m.angular_acceleration[0] = f64::NEG_INFINITY, (UWML_ERR_NON_FINITE, -1, "base.angular_acceleration")),
        (|_, c| c.velocity[1] = f64::NAN, (UWML_ERR_NON_FINITE, -1, "current.velocity")),
        (|_, c| c.acceleration[2] = f64::INFINITY, (UWML_ERR_NON_FINITE, -1, "current.acceleration")),
    ];
    for (edit, want) in cases {
        let (mut motion, mut current) = (arm_motion(), ARM_CURRENT);
        edit(&mut motion, &mut current);
        let out = hydro64(&mut robot, [&q, &qd, &qdd], Some(&motion), Some(&current));
        expect_error(out.code, &out.error, want);
        assert!(out.forces.iter().all(|f| *f == SENTINEL64) && out.wrench == WRENCH_SENTINEL64, "nothing written");
    }
    // A wrong joint count.
    let out = hydro64(&mut robot, [&q[..5], &qd[..5], &qdd[..5]], None, None);
    expect_error(out.code, &out.error, (UWML_ERR_OUT_OF_RANGE, -1, "n (the robot's joint count)"));
    // f32 names the same fields.
    let robot32 = built32(&arm());
    let mut motion = motion32(&arm_motion());
    motion.orientation[0] *= 1.01;
    let q32 = q.map(f32::narrow);
    let mut forces = [UwmlJointForcesF32::default(); 6];
    let mut error = blank_error();
    // SAFETY: live locals of 6 elements.
    let code = unsafe {
        uwml_robot_hydro_f32(
            &*robot32,
            &mut *workspace32(),
            q32.as_ptr(),
            q32.as_ptr(),
            q32.as_ptr(),
            6,
            &motion,
            null(),
            forces.as_mut_ptr(),
            null_mut(),
            &mut error,
        )
    };
    expect_error(code, &error, (UWML_ERR_NOT_UNIT, -1, "base.orientation"));
}

#[test]
fn non_finite_states_give_nan_and_name_the_element() {
    let params = arm();
    let mut robot = built64(&params);
    let water = Water::new(DENSITY, GRAVITY).unwrap();
    for (which, name) in [(0, "q"), (1, "qd"), (2, "qdd")] {
        let mut state = ARM_STATE;
        state[which][3] = f64::NAN;
        state[which][5] = f64::INFINITY;
        let out = assert_core64(
            &mut robot,
            &params,
            &water,
            [&state[0], &state[1], &state[2]],
            Some(&arm_motion()),
            Some(&ARM_CURRENT),
        );
        expect_error(out.code, &out.error, (UWML_ERR_NON_FINITE, 3, name));
        assert!(out.forces.iter().all(|f| f.total.is_nan()) && out.wrench.total.iter().all(|x| x.is_nan()));
    }
}

#[test]
fn null_pointers_are_reported_never_dereferenced() {
    let p = arm();
    let [q, qd, qdd] = ARM_STATE;
    let (j, l, s) = (p.joints.as_ptr(), p.links.as_ptr(), p.segments.as_ptr());
    let mut robot = built64(&p);
    let r: *mut UwmlRobotF64 = &mut *robot;
    let mut out = zeroed64();
    let o: *mut UwmlRobotF64 = &mut *out;
    let mut forces = [UwmlJointForcesF64::default(); 6];
    let f = forces.as_mut_ptr();
    let (m, c) = (&arm_motion() as *const _, &ARM_CURRENT as *const _);
    let mut e = blank_error();
    // SAFETY: every non-null pointer is a live local of the right size; null ones are checked.
    unsafe {
        assert_eq!(uwml_robot_paper_leg_f64(null_mut()), UWML_ERR_NULL_POINTER);
        assert_eq!(uwml_robot_paper_leg_f32(null_mut()), UWML_ERR_NULL_POINTER);
        let code = uwml_robot_new_f64(null_mut(), j, 6, l, null(), s, 8, 1025.0, 9.81, &mut e);
        expect_error(code, &e, (1, -1, "robot"));
        expect_error(uwml_robot_new_f64(o, null(), 6, l, null(), s, 8, 1025.0, 9.81, &mut e), &e, (1, -1, "joints"));
        expect_error(uwml_robot_new_f64(o, j, 6, null(), null(), s, 8, 1025.0, 9.81, &mut e), &e, (1, -1, "links"));
        expect_error(uwml_robot_new_f64(o, j, 6, l, null(), null(), 8, 1025.0, 9.81, &mut e), &e, (1, -1, "segments"));
        assert_eq!(uwml_robot_new_f64(null_mut(), null(), 1, null(), null(), null(), 1, 0.0, 0.0, null_mut()), 1);
        assert_eq!(uwml_robot_new_f32(null_mut(), null(), 0, null(), null(), null(), 0, 1.0, 1.0, null_mut()), 1);
        assert_eq!(out.opaque_tag, 0);

        let code = uwml_robot_hydro_f64(
            null_mut(),
            &mut *workspace64(),
            q.as_ptr(),
            qd.as_ptr(),
            qdd.as_ptr(),
            6,
            m,
            c,
            f,
            null_mut(),
            &mut e,
        );
        expect_error(code, &e, (1, -1, "robot"));
        let code = uwml_robot_hydro_f64(
            r,
            &mut *workspace64(),
            null(),
            qd.as_ptr(),
            qdd.as_ptr(),
            6,
            m,
            c,
            f,
            null_mut(),
            &mut e,
        );
        expect_error(code, &e, (1, -1, "q"));
        let code = uwml_robot_hydro_f64(
            r,
            &mut *workspace64(),
            q.as_ptr(),
            null(),
            qdd.as_ptr(),
            6,
            m,
            c,
            f,
            null_mut(),
            &mut e,
        );
        expect_error(code, &e, (1, -1, "qd"));
        let code = uwml_robot_hydro_f64(
            r,
            &mut *workspace64(),
            q.as_ptr(),
            qd.as_ptr(),
            null(),
            6,
            m,
            c,
            f,
            null_mut(),
            &mut e,
        );
        expect_error(code, &e, (1, -1, "qdd"));
        let code = uwml_robot_hydro_f64(
            r,
            &mut *workspace64(),
            q.as_ptr(),
            qd.as_ptr(),
            qdd.as_ptr(),
            6,
            m,
            c,
            null_mut(),
            null_mut(),
            &mut e,
        );
        expect_error(code, &e, (1, -1, "joint_forces"));
        let z = [0.0f32; 6];
        let code = uwml_robot_hydro_f32(
            null_mut(),
            &mut *workspace32(),
            z.as_ptr(),
            z.as_ptr(),
            z.as_ptr(),
            6,
            null(),
            null(),
            null_mut(),
            null_mut(),
            &mut e,
        );
        expect_error(code, &e, (1, -1, "robot"));
    }
    // A robot without a base body (base NULL) is one with an empty body.
    let mut params = arm();
    params.base = None;
    let mut robot = built64(&params);
    let water = Water::new(DENSITY, GRAVITY).unwrap();
    assert_core64(&mut robot, &params, &water, [&q, &qd, &qdd], Some(&arm_motion()), Some(&ARM_CURRENT));
}

#[test]
fn robots_not_written_by_the_library_are_refused() {
    let [q, qd, qdd] = ARM_STATE;
    let mut robot = zeroed64();
    let out = hydro64(&mut robot, [&q, &qd, &qdd], None, None);
    expect_error(out.code, &out.error, (UWML_ERR_UNINITIALIZED, -1, "robot"));
    assert!(out.forces.iter().all(|f| *f == SENTINEL64));
    // A robot of the other precision, or a workspace, has another tag.
    let mut as64 = zeroed64();
    as64.opaque_tag = built32(&arm()).opaque_tag;
    assert_eq!(hydro64(&mut as64, [&q, &qd, &qdd], None, None).code, UWML_ERR_UNINITIALIZED);
    as64.opaque_tag = workspace64().opaque_tag;
    assert_eq!(hydro64(&mut as64, [&q, &qd, &qdd], None, None).code, UWML_ERR_UNINITIALIZED);
    // SAFETY: a static NUL-terminated string.
    let message = unsafe { CStr::from_ptr(uwml_error_message(UWML_ERR_UNINITIALIZED)) };
    assert_eq!(message.to_str().unwrap(), "not initialized");
}

#[test]
fn robot_forces_that_overflow_are_an_error() {
    let mut robot = zeroed64();
    // SAFETY: a live local.
    assert_eq!(unsafe { uwml_robot_paper_leg_f64(&mut *robot) }, UWML_OK);
    let out = hydro64(&mut robot, [&[0.1, 0.2, 0.3], &[0.0, 1e200, 0.0], &[0.0; 3]], None, None);
    // Joint 1's speed drags on joint 0 too (it carries the links beyond): the first joint named.
    expect_error(out.code, &out.error, (UWML_ERR_OVERFLOW, 0, "total"));
    assert!(!out.forces[0].total.is_finite() && !out.forces[1].total.is_finite());
    let out = hydro64(&mut robot, [&[0.1, 0.2, 0.3], &[0.0, 1e100, 0.0], &[0.0; 3]], None, None);
    assert_eq!(out.code, UWML_OK);
}
