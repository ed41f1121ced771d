//! Fuzzing the C ABI (proptest): constructors, setters (joint losses and their conditions
//! included) and evaluations of the robot API (the paper's leg preset among them), f64 and f32, from valid parameters with arbitrary words written over them (NaN, ±inf, huge,
//! tiny, subnormal, negative zero, random bit patterns; any i32 in the enum and flag fields) and
//! from arbitrary joint states, base motions and currents. Every parameter struct is plain old
//! data (floats and i32), so any bytes are a valid value. What must hold: nothing panics (a
//! panic across `extern "C"` aborts the test process), every return is one of the documented
//! codes and the same as the `UwmlError` written, a failed constructor writes no robot,
//! and an evaluation that returns `UWML_OK` gives finite outputs.
//!
//! CI runs the default number of cases (`FUZZ_CASES` below); the long run:
//! `PROPTEST_CASES=200000 cargo test --release -p uwml-ffi --test fuzz` (docs/domains.md).
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

use std::mem::size_of;
use std::ptr::{null, null_mut};

use proptest::prelude::*;
use uwml_ffi::*;

mod robots;
use robots::{workspace32, workspace64};

/// Cases per property in the default (CI) run; `PROPTEST_CASES` overrides it.
const FUZZ_CASES: u32 = 600;

/// Float bit patterns an adversary would try, and some arbitrary ones.
fn float() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        Just(0.0),
        Just(-0.0),
        Just(f64::MAX),
        Just(-f64::MAX),
        Just(f64::MIN_POSITIVE),
        Just(5e-324),
        Just(1e200),
        Just(-1e200),
        Just(1.0),
        -20.0..20.0f64,
        any::<u64>().prop_map(f64::from_bits),
    ]
}

/// One edit of a struct's bytes: at a word offset (8-byte words for floats, 4-byte for i32),
/// a float, an f32, or an i32.
#[derive(Clone, Copy, Debug)]
enum Edit {
    F64(usize, f64),
    F32(usize, f32),
    I32(usize, i32),
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (any::<usize>(), float()).prop_map(|(at, x)| Edit::F64(at, x)),
        #[allow(clippy::cast_possible_truncation)]
        (any::<usize>(), float()).prop_map(|(at, x)| Edit::F32(at, x as f32)),
        (any::<usize>(), prop_oneof![-3..20i32, Just(i32::MIN), Just(i32::MAX), any::<i32>()])
            .prop_map(|(at, x)| Edit::I32(at, x)),
    ]
}

/// `value` with `edits` written over its bytes (each at its offset modulo the size).
fn edited<T: Copy>(value: T, edits: &[Edit]) -> T {
    let mut value = value;
    let size = size_of::<T>();
    // SAFETY: `value` is a live local of `size` bytes; every `T` here is plain old data (floats
    // and i32 in a repr(C) struct or array), so any bytes written leave a valid `T`.
    let bytes = unsafe { std::slice::from_raw_parts_mut((&raw mut value).cast::<u8>(), size) };
    for edit in edits {
        let (at, word): (usize, Vec<u8>) = match *edit {
            Edit::F64(at, x) => (at % (size / 8).max(1) * 8, x.to_ne_bytes().to_vec()),
            Edit::F32(at, x) => (at % (size / 4).max(1) * 4, x.to_ne_bytes().to_vec()),
            Edit::I32(at, x) => (at % (size / 4).max(1) * 4, x.to_ne_bytes().to_vec()),
        };
        for (k, byte) in word.into_iter().enumerate() {
            if let Some(slot) = bytes.get_mut(at + k) {
                *slot = byte;
            }
        }
    }
    value
}

const CODES: std::ops::RangeInclusive<i32> = UWML_OK..=UWML_ERR_TOO_LARGE;

fn blank() -> UwmlError {
    UwmlError { code: -99, reserved: -99, index: -99, field: [b'x' as _; UWML_ERROR_FIELD_LEN] }
}

/// The return is a documented code, the error record says the same, with a NUL-terminated field.
fn check(code: i32, error: &UwmlError) {
    assert!(CODES.contains(&code), "undocumented code {code}");
    assert_eq!(error.code, code);
    assert_eq!(error.reserved, 0);
    assert!(error.field.contains(&0), "the field is NUL-terminated");
}

/// A joint index: the small ones (valid for some robots), the capacity's edge, and any.
fn index() -> impl Strategy<Value = u32> {
    prop_oneof![0..7u32, Just(15), Just(16), Just(u32::MAX), any::<u32>()]
}

/// A pressure [Pa] and a temperature [°C]: the sea's, at the domain's edges, or any float.
fn conditions() -> impl Strategy<Value = (f64, f64)> {
    (
        prop_oneof![0.0..1.2e8f64, Just(1.2e8), Just(1.2e8 + 1.0), float()],
        prop_oneof![-2.0..40.0f64, Just(-273.15), Just(-273.14), float()],
    )
}

fn robot_params() -> (Vec<UwmlTreeJointF64>, Vec<UwmlBodyF64>, UwmlBodyF64, Vec<UwmlRobotSegmentF64>) {
    let joint =
        |parent: i32, kind: i32, axis: [f64; 3]| UwmlTreeJointF64 { parent, kind, origin: [0.3, 0.0, 0.0], axis };
    let joints = vec![
        joint(UWML_BASE, UWML_JOINT_REVOLUTE, [0.0, 0.0, 1.0]),
        joint(0, UWML_JOINT_REVOLUTE, [0.0, 1.0, 0.0]),
        joint(1, UWML_JOINT_PRISMATIC, [1.0, 0.0, 0.0]),
        joint(UWML_BASE, UWML_JOINT_REVOLUTE, [0.0, 1.0, 0.0]),
    ];
    let body = UwmlBodyF64 { mass: 1.5, com: [0.1, 0.0, 0.0], volume: 8e-4, cob: [0.1, 0.0, 0.0] };
    let segment = |owner: i32, section: i32| UwmlRobotSegmentF64 {
        owner,
        section,
        start: [0.0; 3],
        axis: [1.0, 0.0, 0.0],
        length: 0.3,
        area: 0.003,
        normals: [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        widths: [0.08, 0.04],
        diameter: 0.06,
        cd: [1.2, 1.2],
        cm: [1.0, 1.0],
        cd_axial: 0.0,
        axial_area: 0.0,
    };
    let segments = vec![
        segment(UWML_BASE, UWML_SECTION_RECTANGULAR),
        segment(0, UWML_SECTION_CIRCULAR),
        segment(1, UWML_SECTION_RECTANGULAR),
        segment(2, UWML_SECTION_CIRCULAR),
        segment(3, UWML_SECTION_RECTANGULAR),
    ];
    let base = UwmlBodyF64 { mass: 40.0, com: [0.0; 3], volume: 0.04, cob: [0.0, 0.0, 0.05] };
    (joints, vec![body; 4], base, segments)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: FUZZ_CASES, failure_persistence: None, ..ProptestConfig::default() })]

    /// The paper's leg (the preset) in f64: set water, coefficients, losses and conditions, evaluate.
    #[test]
    fn paper_leg_takes_any_input(
        loss_edits in prop::collection::vec(edit(), 0..3),
        water in (float(), float()),
        coefficients in prop::array::uniform4(float()),
        conditions in (float(), float()),
        joint_index in prop_oneof![0..4u32, Just(u32::MAX), any::<u32>()],
        state in prop::array::uniform9(float()),
        depth in (float(), float(), float()),
    ) {
        let mut robot = Box::new(UwmlRobotF64 { opaque_tag: 0, opaque: [0; UWML_ROBOT_F64_WORDS] });
        let mut workspace = Box::new(UwmlWorkspaceF64 { opaque_tag: 0, opaque: [0; UWML_WORKSPACE_F64_WORDS] });
        let mut error = blank();
        let mut losses = UwmlJointLossParamsF64::default();
        // SAFETY: live locals.
        unsafe {
            prop_assert_eq!(uwml_robot_paper_leg_f64(&mut *robot), UWML_OK);
            prop_assert_eq!(uwml_robot_workspace_init_f64(&mut *workspace), UWML_OK);
            prop_assert_eq!(uwml_robot_default_losses_f64(&mut losses), UWML_OK);
            let losses = edited(losses, &loss_edits);
            let [cd0, cd1, cm0, cm1] = coefficients;
            let (cd, cm) = ([[cd0, cd1], [cd1, cd0]], [[cm0, cm1], [cm1, cm0]]);
            let before = robot.opaque;
            let code = uwml_robot_set_coefficients_f64(&mut *robot, cd.as_ptr(), cm.as_ptr(), 2, &mut error);
            check(code, &error);
            prop_assert!(code == UWML_OK || robot.opaque == before, "a failed setter changes nothing");
            for code in [
                uwml_robot_set_water_f64(&mut *robot, water.0, water.1, &mut error),
                uwml_robot_set_losses_f64(&mut *robot, joint_index, &losses, conditions.0, conditions.1, &mut error),
                uwml_robot_set_conditions_f64(&mut *robot, conditions.0, conditions.1, &mut error),
            ] {
                prop_assert!(CODES.contains(&code));
            }
            let mut pressure = 0.0;
            let code = uwml_pressure_at_depth_f64(depth.0, depth.1, depth.2, &mut pressure, &mut error);
            check(code, &error);
            prop_assert!(code != UWML_OK || (pressure.is_finite() && pressure >= 0.0));
            let (q, qd, qdd) = (&state[0..3], &state[3..6], &state[6..9]);
            let mut out = [UwmlJointEnvironmentF64::default(); 3];
            let code = uwml_robot_environment_f64(&*robot, &mut *workspace, q.as_ptr(), qd.as_ptr(), qdd.as_ptr(), 3,
                null(), null(), out.as_mut_ptr(), null_mut(), &mut error);
            check(code, &error);
            if code == UWML_OK {
                prop_assert!(out.iter().all(|e| e.total.is_finite() && e.current.is_finite()));
            }
            let mut forces = [UwmlJointForcesF64::default(); 3];
            let code = uwml_robot_hydro_f64(&*robot, &mut *workspace, q.as_ptr(), qd.as_ptr(), qdd.as_ptr(), 3,
                null(), null(), forces.as_mut_ptr(), null_mut(), &mut error);
            check(code, &error);
            if code == UWML_OK {
                prop_assert!(forces.iter().all(|f| f.total.is_finite()));
            }
        }
    }

    /// The robot API in f64: build from edited joints, links, base and segments (and counts),
    /// set edited joint losses on any joint index at any conditions, move them to other
    /// conditions, clear any joint, evaluate with arbitrary states, base motion and current.
    #[test]
    fn robot_api_takes_any_input(
        joint_edits in prop::collection::vec(edit(), 0..3),
        link_edits in prop::collection::vec(edit(), 0..2),
        segment_edits in prop::collection::vec(edit(), 0..3),
        counts in (0..6u32, 0..7u32),
        water in (float(), float()),
        state in prop::array::uniform12(float()),
        motion_edits in prop::collection::vec(edit(), 0..4),
        current in prop::array::uniform6(float()),
        with_motion in any::<bool>(),
        form in prop_oneof![Just(UWML_ADDED_MASS_MORISON), Just(UWML_ADDED_MASS_KIRCHHOFF), any::<i32>()],
        losses in prop::collection::vec((index(), prop::collection::vec(edit(), 0..3), conditions()), 0..4),
        moved in conditions(),
        cleared in index(),
    ) {
        let (joints, links, base, segments) = robot_params();
        let joints: Vec<_> = joints.into_iter().map(|j| edited(j, &joint_edits)).collect();
        let links: Vec<_> = links.into_iter().enumerate().map(|(i, l)| if i == 1 { edited(l, &link_edits) } else { l }).collect();
        let segments: Vec<_> = segments.into_iter().map(|s| edited(s, &segment_edits)).collect();
        // Counts up to one beyond the arrays' lengths would read past them: the arrays here are
        // the ones given, so the counts stay within them (the API cannot know a C array's size).
        let (n_joints, n_segments) = (counts.0.min(4), counts.1.min(5));
        let mut robot = Box::new(UwmlRobotF64 { opaque_tag: 0, opaque: [0; UWML_ROBOT_F64_WORDS] });
        let mut error = blank();
        let density = if water.0.is_finite() && water.0 > 0.0 { 1025.0 } else { water.0 };
        // SAFETY: live locals; the counts are within the arrays.
        let code = unsafe {
            uwml_robot_new_f64(&mut *robot, joints.as_ptr(), n_joints, links.as_ptr(), &base, segments.as_ptr(),
                n_segments, density, water.1, &mut error)
        };
        check(code, &error);
        if code != UWML_OK {
            prop_assert_eq!(robot.opaque_tag, 0, "a failed construction writes no robot");
            return Ok(());
        }
        // SAFETY: a live robot and error.
        let code = unsafe { uwml_robot_set_added_mass_form_f64(&mut *robot, form, &mut error) };
        check(code, &error);
        let known = form == UWML_ADDED_MASS_MORISON || form == UWML_ADDED_MASS_KIRCHHOFF;
        prop_assert_eq!(code, if known { UWML_OK } else { UWML_ERR_OUT_OF_RANGE });
        let mut defaults = UwmlJointLossParamsF64::default();
        // SAFETY: a live local.
        prop_assert_eq!(unsafe { uwml_robot_default_losses_f64(&mut defaults) }, UWML_OK);
        for (joint_index, loss_edits, (pressure, temperature)) in &losses {
            let params = edited(defaults, loss_edits);
            let before = robot.opaque;
            // SAFETY: live locals.
            let code = unsafe {
                uwml_robot_set_losses_f64(&mut *robot, *joint_index, &params, *pressure, *temperature, &mut error)
            };
            check(code, &error);
            prop_assert!(code != UWML_OK || *joint_index < n_joints, "only the robot's joints take losses");
            prop_assert!(code == UWML_OK || robot.opaque == before, "a failed setter changes nothing");
        }
        let before = robot.opaque;
        // SAFETY: a live robot and error.
        let code = unsafe { uwml_robot_set_conditions_f64(&mut *robot, moved.0, moved.1, &mut error) };
        check(code, &error);
        prop_assert!(code == UWML_OK || robot.opaque == before, "a failed setter changes nothing");
        // SAFETY: a live robot and error.
        let code = unsafe { uwml_robot_clear_losses_f64(&mut *robot, cleared, &mut error) };
        check(code, &error);
        prop_assert_eq!(code, if cleared < n_joints { UWML_OK } else { UWML_ERR_INDEX_OUT_OF_RANGE });
        let n = n_joints as usize;
        let motion = edited(UwmlBaseMotionF64 { orientation: [1.0, 0.0, 0.0, 0.0], ..Default::default() }, &motion_edits);
        let current = UwmlCurrentF64 { velocity: [current[0], current[1], current[2]], acceleration: [current[3], current[4], current[5]] };
        let mut forces = vec![UwmlJointForcesF64::default(); n.max(1)];
        let mut wrench = UwmlBaseWrenchF64::default();
        let (q, qd, qdd) = (&state[0..4], &state[4..8], &state[8..12]);
        // SAFETY: live locals; q, qd, qdd and forces hold at least n elements.
        let code = unsafe {
            uwml_robot_hydro_f64(&*robot, &mut *workspace64(), q.as_ptr(), qd.as_ptr(), qdd.as_ptr(), n_joints,
                if with_motion { &motion } else { null() }, &current, forces.as_mut_ptr(), &mut wrench, &mut error)
        };
        check(code, &error);
        if code == UWML_OK {
            prop_assert!(forces.iter().take(n).all(|f| f.total.is_finite()));
            prop_assert!(wrench.total.iter().all(|x| x.is_finite()));
        }
        let hydro_code = code;
        let mut environment = vec![UwmlJointEnvironmentF64::default(); n.max(1)];
        // SAFETY: live locals; q, qd, qdd and environment hold at least n elements.
        let code = unsafe {
            uwml_robot_environment_f64(&*robot, &mut *workspace64(), q.as_ptr(), qd.as_ptr(), qdd.as_ptr(), n_joints,
                if with_motion { &motion } else { null() }, &current, environment.as_mut_ptr(), &mut wrench, &mut error)
        };
        check(code, &error);
        if code == UWML_OK {
            prop_assert!(environment.iter().take(n).all(|e| e.total.is_finite() && e.current.is_finite()));
            prop_assert!(wrench.total.iter().all(|x| x.is_finite()));
            prop_assert_eq!(hydro_code, UWML_OK, "losses add errors, never remove one");
        }
        // A joint count not the robot's is refused, not read past.
        // SAFETY: as above, with n + 1 <= 5 elements in every array.
        let code = unsafe {
            uwml_robot_hydro_f64(&*robot, &mut *workspace64(), q.as_ptr(), qd.as_ptr(), qdd.as_ptr(), n_joints + 1, null(), null(),
                forces.as_mut_ptr(), null_mut(), &mut error)
        };
        prop_assert_eq!(code, UWML_ERR_OUT_OF_RANGE);
    }

    /// The f32 robot (the paper's leg): losses and conditions, then the environment.
    #[test]
    fn f32_robot_losses_take_any_input(
        loss_edits in prop::collection::vec(edit(), 0..3),
        joint_index in index(),
        conditions in conditions(),
        moved in conditions(),
        state in prop::array::uniform9(float()),
    ) {
        #[allow(clippy::cast_possible_truncation)]
        let narrow = |x: f64| x as f32;
        let mut robot = Box::new(UwmlRobotF32 { opaque_tag: 0, opaque: [0; UWML_ROBOT_F32_WORDS] });
        let mut error = blank();
        let mut losses = UwmlJointLossParamsF32::default();
        // SAFETY: live locals.
        unsafe {
            prop_assert_eq!(uwml_robot_paper_leg_f32(&mut *robot), UWML_OK);
            prop_assert_eq!(uwml_robot_default_losses_f32(&mut losses), UWML_OK);
            let losses = edited(losses, &loss_edits);
            let (p, t) = (narrow(conditions.0), narrow(conditions.1));
            let code = uwml_robot_set_losses_f32(&mut *robot, joint_index, &losses, p, t, &mut error);
            check(code, &error);
            prop_assert!(code != UWML_OK || joint_index < 3);
            let code = uwml_robot_set_conditions_f32(&mut *robot, narrow(moved.0), narrow(moved.1), &mut error);
            check(code, &error);
            let s = state.map(narrow);
            let mut out = [UwmlJointEnvironmentF32::default(); 3];
            let mut wrench = UwmlBaseWrenchF32::default();
            let code = uwml_robot_environment_f32(&*robot, &mut *workspace32(), s[0..3].as_ptr(), s[3..6].as_ptr(), s[6..9].as_ptr(), 3,
                null(), null(), out.as_mut_ptr(), &mut wrench, &mut error);
            check(code, &error);
            if code == UWML_OK {
                prop_assert!(out.iter().all(|e| e.total.is_finite() && e.current.is_finite()));
                prop_assert!(wrench.total.iter().all(|x| x.is_finite()));
            }
        }
    }
}
