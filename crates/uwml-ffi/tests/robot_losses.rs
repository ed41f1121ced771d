//! Joint losses of the robot API (`uwml_robot_set_losses_*`, `_clear_losses_*`,
//! `_set_conditions_*`, `_environment_*`) against the core called directly (bit for bit: the
//! core's `robot_hydro` with the losses in its conditions), on the arm and the paper's leg preset.
//! Their refusals are in `robot_loss_errors.rs`.
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing, clippy::expect_used)]

use core::ptr::null_mut;

use uwml_core::{AddedMassForm, Water, pressure_at_depth};
use uwml_ffi::*;

mod errors;

mod robots;
use robots::*;

mod loss_calls;
use loss_calls::*;

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
