//! The robot API (`uwml_robot_*`) against the core called directly, bit for bit: an arm on a
//! moving vehicle, the paper's leg preset, a robot without joints, the capacity, Kirchhoff's
//! added mass, lumped models. Its refusals are in `robot_errors.rs`.
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing, clippy::expect_used)]

use core::ptr::{null, null_mut};

use uwml_core::{AddedMassForm, Water};
use uwml_ffi::*;

mod errors;
use errors::{blank_error, parts};

mod calls;
use calls::*;

mod robots;
use robots::*;

#[test]
fn the_arm_on_a_moving_vehicle_is_the_core_bit_for_bit() {
    let params = arm();
    let mut robot = zeroed64();
    let (code, error) = new64(&mut robot, &params, DENSITY);
    assert_eq!((code, parts(&error)), (UWML_OK, (UWML_OK, -1, String::new())), "success is written too");
    let mut robot32 = built32(&params);
    let water = Water::new(DENSITY, GRAVITY).unwrap();
    let water32 = Water::new(DENSITY as f32, GRAVITY as f32).unwrap();
    let motion = arm_motion();
    for [q, qd, qdd] in arm_states() {
        let state = [&q[..], &qd[..], &qdd[..]];
        // Moving, still, with and without current: NULL is a fixed upright base, still water.
        for (m, c) in
            [(Some(&motion), Some(&ARM_CURRENT)), (None, None), (Some(&motion), None), (None, Some(&ARM_CURRENT))]
        {
            let out = assert_core64(&mut robot, &params, &water, state, m, c);
            assert_eq!(out.code, UWML_OK);
            assert_eq!(parts(&out.error), (UWML_OK, -1, String::new()));
            assert_core32(&mut robot32, &params, &water32, state, m, c);
        }
    }
    // The test can fail: the vehicle's motion and the current change every output.
    let [q, qd, qdd] = ARM_STATE;
    let moving = hydro64(&mut robot, [&q, &qd, &qdd], Some(&motion), Some(&ARM_CURRENT));
    let fixed = hydro64(&mut robot, [&q, &qd, &qdd], None, None);
    for (joint, (a, b)) in moving.forces.iter().zip(&fixed.forces).enumerate() {
        if joint != 4 {
            // (The wrist rolls about the line of its links' centres of buoyancy: rounding only.)
            assert!(a.buoyancy != b.buoyancy, "joint {joint}: {a:?} {b:?}");
        }
        if joint == 3 || joint == 4 {
            // The telescope slides, and the wrist rolls, along circular links on the forearm's
            // axis: the cross-flow model has no axial force there, nor a moment about that axis,
            // exactly, however the vehicle moves.
            assert!([a.drag, a.added_mass, b.drag, b.added_mass] == [0.0; 4], "{a:?} {b:?}");
        } else {
            assert!(a.drag != b.drag && a.added_mass != b.added_mass, "joint {joint}: {a:?} {b:?}");
        }
    }
    assert!(moving.wrench.drag.iter().zip(fixed.wrench.drag).all(|(a, b)| *a != b));
}

#[test]
fn a_base_wrench_pointer_may_be_null_and_a_copy_is_a_robot() {
    let params = arm();
    let mut robot = built64(&params);
    let [q, qd, qdd] = ARM_STATE;
    let with = hydro64(&mut robot, [&q, &qd, &qdd], Some(&arm_motion()), Some(&ARM_CURRENT));
    let mut forces = [UwmlJointForcesF64::default(); 6];
    // SAFETY: live locals of 6 elements.
    let code = unsafe {
        uwml_robot_hydro_f64(
            &*robot,
            &mut *workspace64(),
            q.as_ptr(),
            qd.as_ptr(),
            qdd.as_ptr(),
            6,
            &arm_motion(),
            &ARM_CURRENT,
            forces.as_mut_ptr(),
            null_mut(),
            null_mut(),
        )
    };
    assert_eq!(code, UWML_OK);
    assert_eq!(forces_bits64(&forces), forces_bits64(&with.forces));
    // memcpy.
    let mut copy = Box::new(*robot);
    let again = hydro64(&mut copy, [&q, &qd, &qdd], Some(&arm_motion()), Some(&ARM_CURRENT));
    assert_eq!(forces_bits64(&again.forces), forces_bits64(&with.forces));
}

#[test]
fn the_paper_leg_preset_is_the_core_and_the_published_torques() {
    let mut preset = zeroed64();
    // SAFETY: a live local.
    assert_eq!(unsafe { uwml_robot_paper_leg_f64(&mut *preset) }, UWML_OK);
    let mut preset32 = zeroed32();
    // SAFETY: a live local.
    assert_eq!(unsafe { uwml_robot_paper_leg_f32(&mut *preset32) }, UWML_OK);
    let params = paper();
    let mut robot = zeroed64();
    let (code, _) = new64(&mut robot, &params, 1000.0);
    assert_eq!(code, UWML_OK);
    let water = Water::default();
    let [q, qd, qdd] = PAPER_STATE;
    let motion = paper_motion();
    for (m, c) in [(None, None), (Some(&motion), Some(&PAPER_CURRENT))] {
        let from_preset = assert_core64(&mut preset, &params, &water, [&q, &qd, &qdd], m, c);
        assert_core32(&mut preset32, &params, &Water::default(), [&q, &qd, &qdd], m, c);
        // The preset and the same leg from plain structs: the same robot, bit for bit.
        let from_params = hydro64(&mut robot, [&q, &qd, &qdd], m, c);
        assert_eq!(forces_bits64(&from_params.forces), forces_bits64(&from_preset.forces));
        assert_eq!(wrench_bits64(&from_params.wrench), wrench_bits64(&from_preset.wrench));
        if m.is_none() {
            // On a fixed base in still water, docs/model.md section 5's torques (an independent
            // brute-force computation, about 1e-7 relative).
            let published =
                [[-24.24084, -5.060505, -0.7383118], [-8.525438, 21.77596, 9.484545], [0.0, 59.72457, 4.193843]];
            for (i, f) in from_preset.forces.iter().enumerate() {
                for (a, b) in
                    [(f.drag, published[0][i]), (f.added_mass, published[1][i]), (f.buoyancy, published[2][i])]
                {
                    assert!((a - b).abs() <= 2e-7 * b.abs(), "joint {i}: {a} vs {b}");
                }
            }
        }
    }
}

#[test]
fn a_robot_without_joints_is_its_base() {
    let mut params = arm();
    params.joints.clear();
    params.links.clear();
    params.segments.retain(|s| s.owner == UWML_BASE);
    let mut robot = zeroed64();
    let base = params.base.unwrap();
    let mut error = blank_error();
    // SAFETY: live locals; joints and links are NULL with a count of 0, never read.
    let code = unsafe {
        uwml_robot_new_f64(
            &mut *robot,
            null(),
            0,
            null(),
            &base,
            params.segments.as_ptr(),
            count(params.segments.len()),
            DENSITY,
            GRAVITY,
            &mut error,
        )
    };
    assert_eq!(code, UWML_OK);
    let mut wrench = UwmlBaseWrenchF64::default();
    // SAFETY: live locals; the joint arrays are NULL with n = 0, never read.
    let code = unsafe {
        uwml_robot_hydro_f64(
            &*robot,
            &mut *workspace64(),
            null(),
            null(),
            null(),
            0,
            &arm_motion(),
            &ARM_CURRENT,
            null_mut(),
            &mut wrench,
            &mut error,
        )
    };
    assert_eq!(code, UWML_OK);
    let water = Water::new(DENSITY, GRAVITY).unwrap();
    let data = core_hydro(
        &core_robot(&params),
        &water,
        &core_motion(Some(&arm_motion())),
        &core_current(Some(&ARM_CURRENT)),
        [&[], &[], &[]],
    );
    assert_eq!(wrench_bits64(&wrench), wrench_bits64(&wrench64(&data)));
    // The hull and skid lie along x: no drag along x (strip theory), some across.
    assert!(wrench.drag[0] == 0.0 && wrench.drag[1] != 0.0 && wrench.buoyancy[2] > 0.0);
}

/// A chain of 16 joints with two segments on every link: the capacity, exactly.
#[test]
fn a_robot_at_full_capacity() {
    let axes = [[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]];
    let joints: Vec<_> = (0..UWML_ROBOT_MAX_JOINTS)
        .map(|i| UwmlTreeJointF64 {
            parent: i32::try_from(i).unwrap() - 1,
            kind: if i % 5 == 3 { UWML_JOINT_PRISMATIC } else { UWML_JOINT_REVOLUTE },
            origin: if i == 0 { [0.0; 3] } else { [0.1, 0.0, 0.0] },
            axis: axes[i % 3],
        })
        .collect();
    let links = vec![UwmlBodyF64 { mass: 1.0, com: [0.05, 0.0, 0.0], volume: 5e-4, cob: [0.05, 0.01, 0.0] }; 16];
    let segment = |owner: usize, section: i32| UwmlRobotSegmentF64 {
        owner: i32::try_from(owner).unwrap(),
        section,
        start: [0.0; 3],
        axis: [1.0, 0.0, 0.0],
        length: 0.1,
        area: 1e-3,
        normals: [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        widths: [0.03, 0.04],
        diameter: 0.035,
        cd: [1.2; 2],
        cm: [1.0; 2],
        cd_axial: 0.0,
        axial_area: 0.0,
    };
    let segments: Vec<_> =
        (0..16).flat_map(|i| [segment(i, UWML_SECTION_RECTANGULAR), segment(i, UWML_SECTION_CIRCULAR)]).collect();
    assert_eq!(segments.len(), UWML_ROBOT_MAX_SEGMENTS);
    let params = Params { joints, links, base: None, segments };
    let mut robot = built64(&params);
    let q: Vec<f64> = (0..16).map(|i| 0.1 * f64::from(i) - 0.7).collect();
    let qd: Vec<f64> = (0..16).map(|i| 0.3 * f64::from(i % 4) - 0.4).collect();
    let qdd: Vec<f64> = (0..16).map(|i| f64::from(i % 3) - 1.0).collect();
    let water = Water::new(DENSITY, GRAVITY).unwrap();
    let out = assert_core64(&mut robot, &params, &water, [&q, &qd, &qdd], Some(&arm_motion()), Some(&ARM_CURRENT));
    assert_eq!(out.code, UWML_OK);
    assert!(out.forces.iter().all(|f| f.total.is_finite() && f.drag != 0.0));
}

fn set_form64(robot: *mut UwmlRobotF64, form: i32) -> (i32, UwmlError) {
    let mut error = blank_error();
    // SAFETY: `robot` is null or a live robot; `error` a live local.
    let code = unsafe { uwml_robot_set_added_mass_form_f64(robot, form, &mut error) };
    assert_eq!(error.code, code);
    (code, error)
}

#[test]
fn kirchhoffs_added_mass_is_the_cores_and_can_be_chosen_back() {
    let params = arm();
    let mut robot = built64(&params);
    let mut robot32 = built32(&params);
    let water = Water::new(DENSITY, GRAVITY).unwrap();
    let water32 = Water::new(DENSITY as f32, GRAVITY as f32).unwrap();
    let motion = arm_motion();
    let [q, qd, qdd] = ARM_STATE;
    let state = [&q[..], &qd[..], &qdd[..]];
    let morison = hydro64(&mut robot, state, Some(&motion), Some(&ARM_CURRENT));
    assert_eq!(morison.code, UWML_OK);

    let (code, error) = set_form64(&mut *robot, UWML_ADDED_MASS_KIRCHHOFF);
    assert_eq!((code, parts(&error)), (UWML_OK, (UWML_OK, -1, String::new())));
    // SAFETY: a live robot; a null error is allowed.
    let code32 = unsafe { uwml_robot_set_added_mass_form_f32(&mut *robot32, UWML_ADDED_MASS_KIRCHHOFF, null_mut()) };
    assert_eq!(code32, UWML_OK);
    for (m, c) in [(Some(&motion), Some(&ARM_CURRENT)), (None, None)] {
        let kirchhoff = assert_core64_with(AddedMassForm::Kirchhoff, &mut robot, &params, &water, state, m, c);
        assert_eq!(kirchhoff.code, UWML_OK);
        assert_core32_with(AddedMassForm::Kirchhoff, &mut robot32, &params, &water32, state, m, c);
    }
    // The test can fail: the two forms differ in the added mass of a moving robot, not in drag
    // or buoyancy.
    let kirchhoff = hydro64(&mut robot, state, Some(&motion), Some(&ARM_CURRENT));
    assert!(kirchhoff.forces.iter().zip(&morison.forces).all(|(k, m)| k.drag == m.drag && k.buoyancy == m.buoyancy));
    assert!(kirchhoff.forces.iter().zip(&morison.forces).any(|(k, m)| k.added_mass != m.added_mass));

    // Another value is refused and changes nothing; Morison again gives the first forces.
    for bad in [-1, 2, i32::MAX] {
        let (code, error) = set_form64(&mut *robot, bad);
        assert_eq!(code, UWML_ERR_OUT_OF_RANGE);
        assert!(parts(&error).2.starts_with("form"), "{:?}", parts(&error));
        let again = hydro64(&mut robot, state, Some(&motion), Some(&ARM_CURRENT));
        assert_eq!(forces_bits64(&again.forces), forces_bits64(&kirchhoff.forces));
    }
    assert_eq!(set_form64(&mut *robot, UWML_ADDED_MASS_MORISON).0, UWML_OK);
    let back = hydro64(&mut robot, state, Some(&motion), Some(&ARM_CURRENT));
    assert_eq!(forces_bits64(&back.forces), forces_bits64(&morison.forces));
    assert_eq!(wrench_bits64(&back.wrench), wrench_bits64(&morison.wrench));

    // A new robot is Morison's; null and unwritten robots are refused.
    let mut fresh = built64(&params);
    let first = hydro64(&mut fresh, state, Some(&motion), Some(&ARM_CURRENT));
    assert_eq!(forces_bits64(&first.forces), forces_bits64(&morison.forces));
    assert_eq!(set_form64(null_mut(), UWML_ADDED_MASS_KIRCHHOFF).0, UWML_ERR_NULL_POINTER);
    assert_eq!(set_form64(&mut *zeroed64(), UWML_ADDED_MASS_KIRCHHOFF).0, UWML_ERR_UNINITIALIZED);
}

/// A lumped hull and a lumped can on link 2 (its model's axes turned about z), in C.
fn lumped_models() -> [UwmlLumpedF64; 2] {
    let diagonal = |d: [f64; 6]| core::array::from_fn(|r| core::array::from_fn(|c| if r == c { d[r] } else { 0.0 }));
    let mut added_mass: [[f64; 6]; 6] = diagonal([120.0, 200.0, 260.0, 8.0, 20.0, 16.0]);
    added_mass[0][4] = 5.0;
    added_mass[4][0] = 5.0;
    let hull = UwmlLumpedF64 {
        owner: UWML_BASE,
        point: [0.0, 0.0, 0.05],
        axes: [[0.0; 3]; 3],
        added_mass,
        linear_damping: diagonal([80.0, 90.0, 100.0, 10.0, 12.0, 9.0]),
        quadratic_damping: [300.0, 420.0, 500.0, 20.0, 30.0, 25.0],
    };
    let can = UwmlLumpedF64 {
        owner: 2,
        point: [0.1, 0.0, 0.0],
        axes: [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]],
        added_mass: diagonal([1.0, 2.0, 3.0, 0.01, 0.02, 0.03]),
        linear_damping: diagonal([2.0, 3.0, 4.0, 0.1, 0.1, 0.1]),
        quadratic_damping: [5.0, 6.0, 7.0, 0.2, 0.2, 0.2],
    };
    [hull, can]
}

fn set_lumped64(robot: &mut UwmlRobotF64, models: &[UwmlLumpedF64]) -> UwmlError {
    let mut error = blank_error();
    // SAFETY: live locals; `models` holds its length.
    let code = unsafe { uwml_robot_set_lumped_f64(robot, models.as_ptr(), count(models.len()), &mut error) };
    assert_eq!(error.code, code);
    error
}

#[test]
fn lumped_models_are_the_cores_bit_for_bit_and_bad_ones_change_nothing() {
    use uwml_core::nalgebra::{Matrix3, Matrix6};
    use uwml_core::{LumpedBody, Owner, Robot};
    let params = arm();
    let mut robot = built64(&params);
    let models = lumped_models();
    assert_eq!(parts(&set_lumped64(&mut robot, &models)), (UWML_OK, -1, String::new()));
    let plain = core_robot::<f64>(&params);
    let core = Robot::<f64, 16, 32, 4>::new(plain.joints(), plain.links(), *plain.base(), plain.segments()).unwrap();
    let body = |m: &UwmlLumpedF64, owner| LumpedBody {
        owner,
        point: m.point.into(),
        axes: if m.axes == [[0.0; 3]; 3] { Matrix3::identity() } else { Matrix3::from_fn(|r, c| m.axes[r][c]) },
        added_mass: Matrix6::from_fn(|r, c| m.added_mass[r][c]),
        linear_damping: Matrix6::from_fn(|r, c| m.linear_damping[r][c]),
        quadratic_damping: m.quadratic_damping,
    };
    let core = core.with_lumped(&[body(&models[0], Owner::Base), body(&models[1], Owner::Link(2))]).unwrap();
    let water = Water::new(DENSITY, GRAVITY).unwrap();
    let motion = arm_motion();
    for [q, qd, qdd] in arm_states() {
        let state = [&q[..], &qd[..], &qdd[..]];
        let out = hydro64(&mut robot, state, Some(&motion), Some(&ARM_CURRENT));
        let data = core_hydro(&core, &water, &core_motion(Some(&motion)), &core_current(Some(&ARM_CURRENT)), state);
        assert_eq!(forces_bits64(&out.forces), forces_bits64(&forces64(&data)));
        assert_eq!(wrench_bits64(&out.wrench), wrench_bits64(&wrench64(&data)));
    }
    // The hull's damping is in the base drag: without it (count 0), another drag.
    let [q, qd, qdd] = ARM_STATE;
    let with = hydro64(&mut robot, [&q, &qd, &qdd], Some(&motion), None);
    let bad = |change: &dyn Fn(&mut [UwmlLumpedF64; 2]), n: usize| {
        let mut changed = models;
        change(&mut changed);
        changed[..n].to_vec()
    };
    for (given, expected) in [
        (
            bad(&|m| m[1].added_mass[2][2] = -1.0, 2),
            (UWML_ERR_NOT_POSITIVE_SEMIDEFINITE, 1, "lumped.added_mass".to_string()),
        ),
        (bad(&|m| m[0].added_mass[0][1] = 3.0, 2), (UWML_ERR_NOT_SYMMETRIC, 0, "lumped.added_mass".to_string())),
        (bad(&|m| m[1].quadratic_damping[0] = -1.0, 2), (UWML_ERR_NEGATIVE, 1, "lumped.quadratic_damping".to_string())),
        (bad(&|m| m[1].owner = 99, 2), (UWML_ERR_OUT_OF_RANGE, 1, "lumped.owner".to_string())),
        (bad(&|m| m[1].owner = UWML_BASE, 2), (UWML_ERR_OUT_OF_RANGE, 1, "lumped.owner".to_string())),
        (
            bad(&|m| m[0].axes = [[2.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], 1),
            (UWML_ERR_NOT_UNIT, 0, "lumped.axes".to_string()),
        ),
    ] {
        assert_eq!(parts(&set_lumped64(&mut robot, &given)), expected);
        let again = hydro64(&mut robot, [&q, &qd, &qdd], Some(&motion), None);
        assert_eq!(wrench_bits64(&again.wrench), wrench_bits64(&with.wrench), "unchanged after an error");
    }
    let five = [models[0]; 5];
    assert_eq!(set_lumped64(&mut robot, &five).code, UWML_ERR_OUT_OF_RANGE);
    assert_eq!(parts(&set_lumped64(&mut robot, &[])), (UWML_OK, -1, String::new()));
    let without = hydro64(&mut robot, [&q, &qd, &qdd], Some(&motion), None);
    assert!(without.wrench.drag[0] != with.wrench.drag[0]);
    let plain_data = core_hydro(&plain, &water, &core_motion(Some(&motion)), &core_current(None), [&q, &qd, &qdd]);
    assert_eq!(wrench_bits64(&without.wrench), wrench_bits64(&wrench64(&plain_data)));
}

/// A lumped model's f64 numbers rounded to f32.
fn narrow(m: &UwmlLumpedF64) -> UwmlLumpedF32 {
    UwmlLumpedF32 {
        owner: m.owner,
        point: m.point.map(|x| x as f32),
        axes: m.axes.map(|r| r.map(|x| x as f32)),
        added_mass: m.added_mass.map(|r| r.map(|x| x as f32)),
        linear_damping: m.linear_damping.map(|r| r.map(|x| x as f32)),
        quadratic_damping: m.quadratic_damping.map(|x| x as f32),
    }
}

#[test]
fn a_huge_entry_hides_no_negative_eigenvalue_or_asymmetry_in_either_precision() {
    // Issue 31: at the 1e12 cap, diag(1e12, −99, …) and an asymmetry of 900 passed the relative
    // tolerances alone; the absolute floor refuses them, in f64 and f32, and a negative quadratic
    // damping too; nothing changes on an error.
    let params = arm();
    let models = lumped_models();
    let (mut robot, mut robot32) = (built64(&params), built32(&params));
    let set32 = |robot: &mut UwmlRobotF32, given: &[UwmlLumpedF64]| {
        let narrowed: Vec<UwmlLumpedF32> = given.iter().map(narrow).collect();
        let mut error = blank_error();
        // SAFETY: live locals; `narrowed` holds its length.
        let code = unsafe { uwml_robot_set_lumped_f32(robot, narrowed.as_ptr(), count(narrowed.len()), &mut error) };
        assert_eq!(error.code, code);
        parts(&error)
    };
    let changed = |change: &dyn Fn(&mut UwmlLumpedF64)| {
        let mut changed = models;
        change(&mut changed[1]);
        changed
    };
    let cases = [
        (
            changed(&|m| (m.added_mass[0][0], m.added_mass[1][1]) = (1e12, -99.0)),
            (UWML_ERR_NOT_POSITIVE_SEMIDEFINITE, 1, "lumped.added_mass".to_string()),
        ),
        (
            changed(&|m| (m.added_mass[0][0], m.added_mass[0][1]) = (1e12, 900.0)),
            (UWML_ERR_NOT_SYMMETRIC, 1, "lumped.added_mass".to_string()),
        ),
        (
            changed(&|m| (m.linear_damping[0][0], m.linear_damping[1][1]) = (1e12, -99.0)),
            (UWML_ERR_NOT_POSITIVE_SEMIDEFINITE, 1, "lumped.linear_damping".to_string()),
        ),
        (changed(&|m| m.quadratic_damping[3] = -1e-3), (UWML_ERR_NEGATIVE, 1, "lumped.quadratic_damping".to_string())),
    ];
    let [q, qd, qdd] = ARM_STATE;
    let before = hydro64(&mut robot, [&q, &qd, &qdd], Some(&arm_motion()), None);
    for (given, expected) in cases {
        assert_eq!(parts(&set_lumped64(&mut robot, &given)), expected);
        assert_eq!(set32(&mut robot32, &given), expected, "f32");
        let after = hydro64(&mut robot, [&q, &qd, &qdd], Some(&arm_motion()), None);
        assert_eq!(wrench_bits64(&after.wrench), wrench_bits64(&before.wrench), "unchanged after an error");
    }
    // Within the floor (1e-2): taken in both.
    let within = changed(&|m| (m.added_mass[0][0], m.added_mass[1][1], m.added_mass[0][1]) = (1e12, -0.9e-2, 0.0));
    assert_eq!(parts(&set_lumped64(&mut robot, &within)), (UWML_OK, -1, String::new()));
    assert_eq!(set32(&mut robot32, &within), (UWML_OK, -1, String::new()), "f32");
}

#[test]
fn lumped_models_null_pointers_and_the_f32_half() {
    let params = arm();
    let models = lumped_models();
    let mut error = blank_error();
    // SAFETY: null robot and models, a live error.
    let code = unsafe { uwml_robot_set_lumped_f64(null_mut(), models.as_ptr(), 2, &mut error) };
    assert_eq!((code, parts(&error).2), (UWML_ERR_NULL_POINTER, "robot".to_string()));
    let mut robot = built64(&params);
    // SAFETY: a live robot, null models with a count.
    let code = unsafe { uwml_robot_set_lumped_f64(&mut *robot, null(), 1, &mut error) };
    assert_eq!((code, parts(&error).2), (UWML_ERR_NULL_POINTER, "models".to_string()));
    let mut robot32 = built32(&params);
    let models32 = models.map(|m| narrow(&m));
    // SAFETY: live locals.
    let code = unsafe { uwml_robot_set_lumped_f32(&mut *robot32, models32.as_ptr(), 2, &mut error) };
    assert_eq!(code, UWML_OK);
    let [q, qd, qdd] = ARM_STATE;
    let (q, qd, qdd) = (q.map(|x| x as f32), qd.map(|x| x as f32), qdd.map(|x| x as f32));
    let (code, forces, wrench) = hydro32(&mut robot32, [&q, &qd, &qdd], Some(&motion32(&arm_motion())), None);
    assert_eq!(code, UWML_OK);
    assert!(forces.iter().all(|f| f.total.is_finite()) && wrench.total.iter().all(|x| x.is_finite()));
}
