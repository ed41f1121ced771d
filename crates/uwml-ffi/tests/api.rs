//! The C API against the core called directly (bit for bit), every error code, null pointers.
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing, clippy::expect_used)]

use core::ffi::CStr;
use core::ptr::{null, null_mut};

use uwml_core::nalgebra::Vector3;
use uwml_core::{
    Chain, Coefficients, Conditions, Drive, EnvironmentTorques, HydroTorques, JointLosses, LossState, OilDrag, Real,
    Robot, RobotData, Seal, Water, environment_torques, pressure_at_depth, robot_hydro,
};
use uwml_ffi::*;

mod errors;
use errors::{blank_error, expect_error, parts};

const Q: [f64; 3] = [0.3, -0.4, 0.6];
const QD: [f64; 3] = [0.8, 0.5, -0.7];
const QDD: [f64; 3] = [1.0, -2.0, 0.5];

fn zeroed64() -> UwmlLeg3F64 {
    UwmlLeg3F64 { opaque_tag: 0, opaque: [0; UWML_LEG3_F64_WORDS] }
}

fn zeroed32() -> UwmlLeg3F32 {
    UwmlLeg3F32 { opaque_tag: 0, opaque: [0; UWML_LEG3_F32_WORDS] }
}

fn paper64() -> UwmlLeg3F64 {
    let mut leg = zeroed64();
    // SAFETY: a live local.
    assert_eq!(unsafe { uwml_leg3_paper_f64(&mut leg) }, UWML_OK);
    leg
}

fn paper32() -> UwmlLeg3F32 {
    let mut leg = zeroed32();
    // SAFETY: a live local.
    assert_eq!(unsafe { uwml_leg3_paper_f32(&mut leg) }, UWML_OK);
    leg
}

fn environment64(leg: &UwmlLeg3F64, q: [f64; 3], qd: [f64; 3], qdd: [f64; 3]) -> (i32, UwmlEnvironment3F64) {
    let mut out = UwmlEnvironment3F64::default();
    let mut error = blank_error();
    // SAFETY: live locals; q, qd, qdd hold 3 values each.
    let code = unsafe { uwml_leg3_environment_f64(leg, q.as_ptr(), qd.as_ptr(), qdd.as_ptr(), &mut out, &mut error) };
    assert_eq!(error.code, code);
    (code, out)
}

fn environment32(leg: &UwmlLeg3F32, q: [f32; 3], qd: [f32; 3], qdd: [f32; 3]) -> (i32, UwmlEnvironment3F32) {
    let mut out = UwmlEnvironment3F32::default();
    // SAFETY: live locals; q, qd, qdd hold 3 values each.
    let code = unsafe { uwml_leg3_environment_f32(leg, q.as_ptr(), qd.as_ptr(), qdd.as_ptr(), &mut out, null_mut()) };
    (code, out)
}

/// The core's evaluation of the leg as a robot (the leg API is the robot API's evaluation),
/// with `losses`, as the chain API's result type.
fn core_environment<T: uwml_core::nalgebra::RealField + Real>(
    chain: &Chain<T, 3>,
    water: &Water<T>,
    coefficients: &Coefficients<T, 3>,
    losses: &[Option<LossState<T>>; 3],
    (q, qd, qdd): ([T; 3], [T; 3], [T; 3]),
) -> EnvironmentTorques<T, 3> {
    let robot = Robot::<T, 3, 3>::from_chain(chain, coefficients).unwrap();
    let mut data = RobotData::new();
    robot_hydro(&robot, &Conditions { losses: Some(losses), ..Conditions::new(*water) }, [&q, &qd, &qdd], &mut data);
    let (forces, loss) = (data.joint_forces(), data.joint_losses());
    let each = |f: &dyn Fn(usize) -> T| Vector3::from_fn(|i, _| f(i));
    EnvironmentTorques {
        hydro: HydroTorques {
            drag: each(&|i| forces[i].drag),
            added_mass: each(&|i| forces[i].added_mass),
            buoyancy: each(&|i| forces[i].buoyancy),
            gravity: each(&|i| forces[i].gravity),
        },
        visc: each(&|i| loss[i].visc),
        seal: each(&|i| loss[i].seal),
        current: each(&|i| loss[i].current),
    }
}

/// [`core_environment`] without losses.
fn core_hydro<T: uwml_core::nalgebra::RealField + Real>(
    chain: &Chain<T, 3>,
    state: ([T; 3], [T; 3], [T; 3]),
) -> HydroTorques<T, 3> {
    core_environment(chain, &Water::default(), &Coefficients::default(), &[None; 3], state).hydro
}

/// Bitwise equality of the C output and the core's, so NaN compares equal to NaN.
fn assert_same64(c: &UwmlEnvironment3F64, core: &EnvironmentTorques<f64, 3>) {
    let h = &core.hydro;
    let pairs: [(&str, [f64; 3], Vector3<f64>); 8] = [
        ("drag", c.drag, h.drag),
        ("added_mass", c.added_mass, h.added_mass),
        ("buoyancy", c.buoyancy, h.buoyancy),
        ("gravity", c.gravity, h.gravity),
        ("visc", c.visc, core.visc),
        ("seal", c.seal, core.seal),
        ("current", c.current, core.current),
        ("total", c.total, core.total()),
    ];
    for (name, c, core) in pairs {
        let core: [f64; 3] = core.into();
        assert_eq!(c.map(f64::to_bits), core.map(f64::to_bits), "{name}: {c:?} vs {core:?}");
    }
}

fn assert_same32(c: &UwmlEnvironment3F32, core: &EnvironmentTorques<f32, 3>) {
    let h = &core.hydro;
    let pairs: [(&str, [f32; 3], Vector3<f32>); 8] = [
        ("drag", c.drag, h.drag),
        ("added_mass", c.added_mass, h.added_mass),
        ("buoyancy", c.buoyancy, h.buoyancy),
        ("gravity", c.gravity, h.gravity),
        ("visc", c.visc, core.visc),
        ("seal", c.seal, core.seal),
        ("current", c.current, core.current),
        ("total", c.total, core.total()),
    ];
    for (name, c, core) in pairs {
        let core: [f32; 3] = core.into();
        assert_eq!(c.map(f32::to_bits), core.map(f32::to_bits), "{name}: {c:?} vs {core:?}");
    }
}

fn states() -> Vec<([f64; 3], [f64; 3], [f64; 3])> {
    vec![
        (Q, QD, QDD),
        ([0.0; 3], [0.0; 3], [0.0; 3]),
        ([-1.2, 0.7, -2.1], [-0.3, 1.5, 0.9], [0.4, 0.0, -3.0]),
        ([2.0, -1.0, 1.0], [1e-4, -2e-4, 0.0], [0.0, 5.0, 0.1]),
    ]
}

/// The paper leg's parameters, as C would give them.
fn paper_params64() -> ([UwmlJointParamsF64; 3], [UwmlLinkParamsF64; 3]) {
    let chain = Chain::<f64, 3>::paper();
    let joints = chain.joints().map(|j| UwmlJointParamsF64 { origin: j.origin.into(), axis: j.axis.into() });
    let links = chain.links().map(|l| {
        let mut p = UwmlLinkParamsF64 {
            mass: l.mass,
            com: l.com.into(),
            volume: l.volume,
            cob: l.cob.into(),
            ..Default::default()
        };
        if let Some(s) = l.segment {
            p.has_segment = 1;
            p.segment = UwmlSegmentParamsF64 {
                start: s.start.into(),
                axis: s.axis.into(),
                normals: s.normals.map(Into::into),
                length: s.length,
                widths: s.widths,
                area: s.area,
            };
        }
        p
    });
    (joints, links)
}

fn paper_params32() -> ([UwmlJointParamsF32; 3], [UwmlLinkParamsF32; 3]) {
    let chain = Chain::<f32, 3>::paper();
    let joints = chain.joints().map(|j| UwmlJointParamsF32 { origin: j.origin.into(), axis: j.axis.into() });
    let links = chain.links().map(|l| {
        let mut p = UwmlLinkParamsF32 {
            mass: l.mass,
            com: l.com.into(),
            volume: l.volume,
            cob: l.cob.into(),
            ..Default::default()
        };
        if let Some(s) = l.segment {
            p.has_segment = 1;
            p.segment = UwmlSegmentParamsF32 {
                start: s.start.into(),
                axis: s.axis.into(),
                normals: s.normals.map(Into::into),
                length: s.length,
                widths: s.widths,
                area: s.area,
            };
        }
        p
    });
    (joints, links)
}

fn new64(joints: &[UwmlJointParamsF64; 3], links: &[UwmlLinkParamsF64; 3]) -> (i32, UwmlError, UwmlLeg3F64) {
    let mut leg = zeroed64();
    let mut error = blank_error();
    // SAFETY: live locals; joints and links hold 3 elements.
    let code = unsafe { uwml_leg3_new_f64(joints.as_ptr(), links.as_ptr(), &mut leg, &mut error) };
    (code, error, leg)
}

fn default_params64() -> UwmlJointLossParamsF64 {
    let mut p = UwmlJointLossParamsF64::default();
    // SAFETY: a live local.
    assert_eq!(unsafe { uwml_leg3_default_losses_f64(&mut p) }, UWML_OK);
    p
}

fn default_params32() -> UwmlJointLossParamsF32 {
    let mut p = UwmlJointLossParamsF32::default();
    // SAFETY: a live local.
    assert_eq!(unsafe { uwml_leg3_default_losses_f32(&mut p) }, UWML_OK);
    p
}

fn set_losses64(
    leg: &mut UwmlLeg3F64,
    joint: u32,
    p: &UwmlJointLossParamsF64,
    pressure: f64,
    temperature: f64,
) -> (i32, UwmlError) {
    let mut error = blank_error();
    // SAFETY: live locals.
    let code = unsafe { uwml_leg3_set_losses_f64(leg, joint, p, pressure, temperature, &mut error) };
    (code, error)
}

#[test]
fn paper_preset_is_the_core_bit_for_bit() {
    let (leg64, leg32) = (paper64(), paper32());
    let (chain64, chain32) = (Chain::<f64, 3>::paper(), Chain::<f32, 3>::paper());
    for (q, qd, qdd) in states() {
        let (code, out) = environment64(&leg64, q, qd, qdd);
        assert_eq!(code, UWML_OK);
        assert_same64(
            &out,
            &core_environment(&chain64, &Water::default(), &Coefficients::default(), &[None; 3], (q, qd, qdd)),
        );

        let (q, qd, qdd) = (q.map(|x| x as f32), qd.map(|x| x as f32), qdd.map(|x| x as f32));
        let (code, out) = environment32(&leg32, q, qd, qdd);
        assert_eq!(code, UWML_OK);
        assert_same32(
            &out,
            &core_environment(&chain32, &Water::default(), &Coefficients::default(), &[None; 3], (q, qd, qdd)),
        );
    }
}

/// The leg API against the core's chain convenience (`environment_torques`), with losses set on
/// every joint: one evaluation, so bit for bit.
#[test]
fn the_leg_is_the_cores_chain_convenience_bit_for_bit() {
    let mut leg = paper64();
    let p = default_params64();
    let (pressure, temperature) = (pressure_at_depth(3000.0, 1025.0, 9.81).unwrap(), 4.0);
    for joint in 0..3 {
        assert_eq!(set_losses64(&mut leg, joint, &p, pressure, temperature).0, UWML_OK);
    }
    let state = JointLosses::<f64>::default().at(pressure, temperature).unwrap();
    let chain = Chain::<f64, 3>::paper();
    for (q, qd, qdd) in states() {
        let (code, out) = environment64(&leg, q, qd, qdd);
        assert_eq!(code, UWML_OK);
        let chain_convenience = environment_torques(
            &chain,
            &Water::default(),
            &Coefficients::default(),
            &[Some(state); 3],
            &q.into(),
            &qd.into(),
            &qdd.into(),
        );
        assert_same64(&out, &chain_convenience);
    }
}

#[test]
fn hydro_is_the_core_bit_for_bit() {
    let leg = paper64();
    let chain = Chain::<f64, 3>::paper();
    for (q, qd, qdd) in states() {
        let mut out = UwmlHydro3F64::default();
        // SAFETY: live locals of 3 values.
        let code = unsafe { uwml_leg3_hydro_f64(&leg, q.as_ptr(), qd.as_ptr(), qdd.as_ptr(), &mut out, null_mut()) };
        assert_eq!(code, UWML_OK);
        let core = core_hydro(&chain, (q, qd, qdd));
        let total: [f64; 3] = core.total().into();
        assert_eq!(out.drag, <[f64; 3]>::from(core.drag));
        assert_eq!(out.added_mass, <[f64; 3]>::from(core.added_mass));
        assert_eq!(out.buoyancy, <[f64; 3]>::from(core.buoyancy));
        assert_eq!(out.gravity, <[f64; 3]>::from(core.gravity));
        assert_eq!(out.total, total);
    }
    let leg = paper32();
    let chain = Chain::<f32, 3>::paper();
    let (q, qd, qdd) = (Q.map(|x| x as f32), QD.map(|x| x as f32), QDD.map(|x| x as f32));
    let mut out = UwmlHydro3F32::default();
    // SAFETY: live locals of 3 values.
    let code = unsafe { uwml_leg3_hydro_f32(&leg, q.as_ptr(), qd.as_ptr(), qdd.as_ptr(), &mut out, null_mut()) };
    assert_eq!(code, UWML_OK);
    let core = core_hydro(&chain, (q, qd, qdd));
    assert_eq!(out.total, <[f32; 3]>::from(core.total()));
}

#[test]
fn legs_from_parameters_are_the_core_chain() {
    let (joints, links) = paper_params64();
    let (code, error, built) = new64(&joints, &links);
    assert_eq!(code, UWML_OK);
    assert_eq!(parts(&error), (UWML_OK, -1, String::new()), "success is written too");
    let chain = Chain::<f64, 3>::paper();
    let (_, out) = environment64(&built, Q, QD, QDD);
    assert_same64(
        &out,
        &core_environment(&chain, &Water::default(), &Coefficients::default(), &[None; 3], (Q, QD, QDD)),
    );

    let (joints, links) = paper_params32();
    let mut built = zeroed32();
    // SAFETY: live locals; joints and links hold 3 elements.
    let code = unsafe { uwml_leg3_new_f32(joints.as_ptr(), links.as_ptr(), &mut built, null_mut()) };
    assert_eq!(code, UWML_OK);
    let chain = Chain::<f32, 3>::paper();
    let (q, qd, qdd) = (Q.map(|x| x as f32), QD.map(|x| x as f32), QDD.map(|x| x as f32));
    let (_, out) = environment32(&built, q, qd, qdd);
    assert_same32(
        &out,
        &core_environment(&chain, &Water::default(), &Coefficients::default(), &[None; 3], (q, qd, qdd)),
    );
}

#[test]
fn default_loss_parameters_are_the_cores_defaults() {
    let p = default_params64();
    let (d, o, s) = (p.drive, p.oil, p.seal);
    let losses = JointLosses::new(
        Drive::new(d.torque_constant, d.ratio, d.efficiency, d.rated_current).unwrap(),
        Some(
            OilDrag::new(
                o.k_oil,
                o.exponent,
                o.pressure_sensitivity,
                o.temperature_sensitivity,
                o.reference_pressure,
                o.reference_temperature,
            )
            .unwrap(),
        ),
        Some(Seal::new(s.c, s.s, s.d, s.stribeck_speed).unwrap()),
        p.epsilon,
    )
    .unwrap();
    assert_eq!(losses, JointLosses::default());
    assert_eq!((p.has_oil, p.has_seal), (1, 1));

    let p = default_params32();
    let (d, o, s) = (p.drive, p.oil, p.seal);
    let losses = JointLosses::new(
        Drive::new(d.torque_constant, d.ratio, d.efficiency, d.rated_current).unwrap(),
        Some(
            OilDrag::new(
                o.k_oil,
                o.exponent,
                o.pressure_sensitivity,
                o.temperature_sensitivity,
                o.reference_pressure,
                o.reference_temperature,
            )
            .unwrap(),
        ),
        Some(Seal::new(s.c, s.s, s.d, s.stribeck_speed).unwrap()),
        p.epsilon,
    )
    .unwrap();
    assert_eq!(losses, JointLosses::<f32>::default());
}

#[test]
fn settings_are_the_core_bit_for_bit() {
    let mut leg = paper64();
    let mut error = blank_error();
    let cd = [[1.9, 2.4], [2.0, 2.1], [0.0, 3.0]];
    let cm = [[0.4, 0.6], [0.5, 0.45], [1.0, 0.0]];
    // SAFETY: live locals; cd and cm hold 6 values.
    unsafe {
        assert_eq!(uwml_leg3_set_water_f64(&mut leg, 1025.0, 9.80665, &mut error), UWML_OK);
        assert_eq!(
            uwml_leg3_set_coefficients_per_direction_f64(&mut leg, cd.as_ptr().cast(), cm.as_ptr().cast(), &mut error),
            UWML_OK
        );
    }
    let mut p = default_params64();
    let (pressure, temperature) = (pressure_at_depth(1000.0, 1025.0, 9.81).unwrap(), 4.0);
    assert_eq!(set_losses64(&mut leg, 1, &p, pressure, temperature).0, UWML_OK);
    p.has_oil = 0;
    assert_eq!(set_losses64(&mut leg, 2, &p, 2e6, 10.0).0, UWML_OK);

    let chain = Chain::<f64, 3>::paper();
    let water = Water::new(1025.0, 9.80665).unwrap();
    let coefficients = Coefficients::per_direction(cd, cm).unwrap();
    let joint = JointLosses::<f64>::default();
    let mut seal_only = joint;
    seal_only.oil = None;
    let losses = [None, Some(joint.at(pressure, temperature).unwrap()), Some(seal_only.at(2e6, 10.0).unwrap())];
    for state in states() {
        let (code, out) = environment64(&leg, state.0, state.1, state.2);
        assert_eq!(code, UWML_OK);
        assert_same64(&out, &core_environment(&chain, &water, &coefficients, &losses, state));
    }

    // A change of conditions moves every joint with losses; clearing removes one.
    // SAFETY: a live local.
    unsafe {
        assert_eq!(uwml_leg3_set_conditions_f64(&mut leg, 5e6, 2.0, &mut error), UWML_OK);
        assert_eq!(uwml_leg3_clear_losses_f64(&mut leg, 2, &mut error), UWML_OK);
        assert_eq!(uwml_leg3_set_coefficients_f64(&mut leg, 2.0, 0.7, &mut error), UWML_OK);
    }
    let losses = [None, Some(joint.at(5e6, 2.0).unwrap()), None];
    let coefficients = Coefficients::uniform(2.0, 0.7).unwrap();
    let (_, out) = environment64(&leg, Q, QD, QDD);
    assert_same64(&out, &core_environment(&chain, &water, &coefficients, &losses, (Q, QD, QDD)));

    // f32.
    let mut leg = paper32();
    let p = default_params32();
    // SAFETY: live locals.
    unsafe {
        assert_eq!(uwml_leg3_set_water_f32(&mut leg, 1025.0, 9.81, null_mut()), UWML_OK);
        assert_eq!(uwml_leg3_set_coefficients_f32(&mut leg, 2.0, 0.7, null_mut()), UWML_OK);
        assert_eq!(uwml_leg3_set_losses_f32(&mut leg, 0, &p, 1e7, 20.0, null_mut()), UWML_OK);
        assert_eq!(uwml_leg3_set_losses_f32(&mut leg, 2, &p, 1e7, 20.0, null_mut()), UWML_OK);
        assert_eq!(uwml_leg3_set_conditions_f32(&mut leg, 3e6, 8.0, null_mut()), UWML_OK);
        assert_eq!(uwml_leg3_clear_losses_f32(&mut leg, 0, null_mut()), UWML_OK);
    }
    let joint = JointLosses::<f32>::default();
    let (q, qd, qdd) = (Q.map(|x| x as f32), QD.map(|x| x as f32), QDD.map(|x| x as f32));
    let (_, out) = environment32(&leg, q, qd, qdd);
    let core = core_environment(
        &Chain::paper(),
        &Water::new(1025.0, 9.81).unwrap(),
        &Coefficients::uniform(2.0, 0.7).unwrap(),
        &[None, None, Some(joint.at(3e6, 8.0).unwrap())],
        (q, qd, qdd),
    );
    assert_same32(&out, &core);
}

#[test]
fn non_finite_states_give_nan_and_name_the_element() {
    let leg = paper64();
    let chain = Chain::<f64, 3>::paper();
    for (which, name) in [(0, "q"), (1, "qd"), (2, "qdd")] {
        let mut state = [Q, QD, QDD];
        state[which][2] = f64::INFINITY;
        let mut out = UwmlEnvironment3F64::default();
        let mut error = blank_error();
        // SAFETY: live locals of 3 values.
        let code = unsafe {
            uwml_leg3_environment_f64(
                &leg,
                state[0].as_ptr(),
                state[1].as_ptr(),
                state[2].as_ptr(),
                &mut out,
                &mut error,
            )
        };
        expect_error(code, &error, (UWML_ERR_NON_FINITE, 2, name));
        assert!(out.total.iter().all(|x| x.is_nan()));
        let core = core_environment(
            &chain,
            &Water::default(),
            &Coefficients::default(),
            &[None; 3],
            (state[0], state[1], state[2]),
        );
        assert_same64(&out, &core);
    }
}

#[test]
fn invalid_parameters_name_the_field_and_index() {
    type Edit = fn(&mut [UwmlJointParamsF64; 3], &mut [UwmlLinkParamsF64; 3]);
    let cases: [(Edit, (i32, i64, &str)); 9] = [
        (|j, _| j[2].origin[0] = f64::NAN, (UWML_ERR_NON_FINITE, 2, "joint.origin")),
        (|j, _| j[0].axis = [0.0, 0.0, 1.1], (UWML_ERR_NOT_UNIT, 0, "joint.axis")),
        (|_, l| l[1].volume = -1e-3, (UWML_ERR_NEGATIVE, 1, "link.volume")),
        (|_, l| l[0].mass = -1.0, (UWML_ERR_NEGATIVE, 0, "link.mass")),
        (|_, l| l[2].cob[1] = f64::INFINITY, (UWML_ERR_NON_FINITE, 2, "link.cob")),
        (|_, l| l[2].segment.length = 0.0, (UWML_ERR_NON_POSITIVE, 2, "segment.length")),
        (|_, l| l[1].segment.widths[1] = -0.1, (UWML_ERR_NON_POSITIVE, 1, "segment.widths[1]")),
        (|_, l| l[1].segment.normals[1] = [1.0, 0.0, 0.0], (UWML_ERR_NOT_PERPENDICULAR, 1, "segment.normals[1]")),
        (|_, l| l[1].segment.area = f64::NAN, (UWML_ERR_NON_FINITE, 1, "segment.area")),
    ];
    for (edit, want) in cases {
        let (mut joints, mut links) = paper_params64();
        edit(&mut joints, &mut links);
        let (code, error, leg) = new64(&joints, &links);
        expect_error(code, &error, want);
        assert_eq!(leg.opaque_tag, 0, "a failed construction writes nothing");
    }
    // A link without a segment ignores the segment's fields.
    let (joints, mut links) = paper_params64();
    links[0].segment.length = f64::NAN;
    assert_eq!(new64(&joints, &links).0, UWML_OK);

    // f32: the same mapping.
    let (joints, mut links) = paper_params32();
    links[2].segment.normals[0] = [0.0, 0.5, 0.0];
    let mut leg = zeroed32();
    let mut error = blank_error();
    // SAFETY: live locals; joints and links hold 3 elements.
    let code = unsafe { uwml_leg3_new_f32(joints.as_ptr(), links.as_ptr(), &mut leg, &mut error) };
    expect_error(code, &error, (UWML_ERR_NOT_UNIT, 2, "segment.normals[0]"));
}

#[test]
fn invalid_settings_name_the_field_and_leave_the_leg_unchanged() {
    let mut leg = paper64();
    let before = leg;
    let mut error = blank_error();
    let bad_cd = [[2.2, 2.2], [2.2, 2.2], [2.2, -0.1]];
    let cm = [[0.5; 2]; 3];
    // SAFETY: live locals; bad_cd and cm hold 6 values.
    unsafe {
        let code = uwml_leg3_set_water_f64(&mut leg, f64::NAN, 9.81, &mut error);
        expect_error(code, &error, (UWML_ERR_NON_FINITE, -1, "water.density"));
        let code = uwml_leg3_set_water_f64(&mut leg, 1000.0, -9.81, &mut error);
        expect_error(code, &error, (UWML_ERR_NEGATIVE, -1, "water.gravity"));
        let code = uwml_leg3_set_coefficients_f64(&mut leg, 2.2, -0.5, &mut error);
        expect_error(code, &error, (UWML_ERR_NEGATIVE, 0, "cm"));
        let code = uwml_leg3_set_coefficients_per_direction_f64(
            &mut leg,
            bad_cd.as_ptr().cast(),
            cm.as_ptr().cast(),
            &mut error,
        );
        expect_error(code, &error, (UWML_ERR_NEGATIVE, 2, "cd"));
        let code = uwml_leg3_set_conditions_f64(&mut leg, -1.0, 20.0, &mut error);
        expect_error(code, &error, (UWML_ERR_NEGATIVE, -1, "pressure_pa"));
    }

    type Edit = fn(&mut UwmlJointLossParamsF64);
    let cases: [(Edit, (i32, i64, &str)); 8] = [
        (|p| p.drive.ratio = 0.0, (UWML_ERR_NON_POSITIVE, 1, "drive.ratio")),
        (|p| p.drive.efficiency = 1.5, (UWML_ERR_OUT_OF_RANGE, 1, "drive.efficiency (0 to 1)")),
        (|p| p.oil.exponent = 2.5, (UWML_ERR_OUT_OF_RANGE, 1, "oil.exponent (1 to 2)")),
        (|p| p.oil.k_oil = -1.0, (UWML_ERR_NEGATIVE, 1, "oil.k_oil")),
        (
            |p| p.oil.reference_temperature = -300.0,
            (UWML_ERR_OUT_OF_RANGE, 1, "oil.reference_temperature (above -273.15 °C)"),
        ),
        (|p| p.seal.s[1] = p.seal.c[1] / 2.0, (UWML_ERR_OUT_OF_ORDER, 1, "seal.s1")),
        (|p| p.seal.stribeck_speed = 0.0, (UWML_ERR_NON_POSITIVE, 1, "seal.stribeck_speed")),
        (|p| p.epsilon = f64::NEG_INFINITY, (UWML_ERR_NON_FINITE, 1, "losses.epsilon")),
    ];
    for (edit, want) in cases {
        let mut p = default_params64();
        edit(&mut p);
        let (code, error) = set_losses64(&mut leg, 1, &p, 1e6, 20.0);
        expect_error(code, &error, want);
    }
    // Parameters of an absent oil or seal are not read.
    let mut p = default_params64();
    (p.has_oil, p.has_seal, p.oil.exponent, p.seal.stribeck_speed) = (0, 0, f64::NAN, -1.0);
    let mut scratch = leg;
    assert_eq!(set_losses64(&mut scratch, 1, &p, 1e6, 20.0).0, UWML_OK);

    let p = default_params64();
    for (pressure, temperature, want) in [
        (f64::NAN, 20.0, (UWML_ERR_NON_FINITE, -1, "pressure_pa")),
        (-1.0, 20.0, (UWML_ERR_NEGATIVE, -1, "pressure_pa")),
        (0.0, f64::INFINITY, (UWML_ERR_NON_FINITE, -1, "temperature_c")),
        (0.0, -280.0, (UWML_ERR_BELOW_ABSOLUTE_ZERO, -1, "temperature_c")),
        (0.0, -273.15, (UWML_ERR_BELOW_ABSOLUTE_ZERO, -1, "temperature_c")),
        (1.3e8, 4.0, (UWML_ERR_BEYOND_DEEPEST_OCEAN, -1, "pressure_pa")),
    ] {
        let (code, error) = set_losses64(&mut leg, 0, &p, pressure, temperature);
        expect_error(code, &error, want);
    }
    for index in [3, u32::MAX] {
        let (code, error) = set_losses64(&mut leg, index, &p, 0.0, 20.0);
        expect_error(code, &error, (UWML_ERR_INDEX_OUT_OF_RANGE, i64::from(index), "joint_index"));
    }
    let mut error = blank_error();
    // SAFETY: a live local.
    let code = unsafe { uwml_leg3_clear_losses_f64(&mut leg, 7, &mut error) };
    expect_error(code, &error, (UWML_ERR_INDEX_OUT_OF_RANGE, 7, "joint_index"));

    assert_eq!(leg.opaque_tag, before.opaque_tag);
    assert_eq!(leg.opaque, before.opaque, "failed setters change nothing");
}

#[test]
fn null_pointers_are_reported_never_dereferenced() {
    let mut leg = paper64();
    let (joints, links) = paper_params64();
    let p = default_params64();
    let six = [0.5; 6];
    let mut env = UwmlEnvironment3F64::default();
    let mut hydro = UwmlHydro3F64::default();
    let mut e = blank_error();
    let leg_ptr: *mut UwmlLeg3F64 = &mut leg;
    let (q, qd, qdd) = (Q.as_ptr(), QD.as_ptr(), QDD.as_ptr());
    // SAFETY: every non-null pointer is a live local of the right size; null ones are checked.
    unsafe {
        assert_eq!(uwml_leg3_paper_f64(null_mut()), UWML_ERR_NULL_POINTER);
        assert_eq!(uwml_leg3_paper_f32(null_mut()), UWML_ERR_NULL_POINTER);
        assert_eq!(uwml_leg3_default_losses_f64(null_mut()), UWML_ERR_NULL_POINTER);
        assert_eq!(uwml_leg3_default_losses_f32(null_mut()), UWML_ERR_NULL_POINTER);

        let mut out = zeroed64();
        expect_error(uwml_leg3_new_f64(null(), links.as_ptr(), &mut out, &mut e), &e, (1, -1, "joints"));
        expect_error(uwml_leg3_new_f64(joints.as_ptr(), null(), &mut out, &mut e), &e, (1, -1, "links"));
        expect_error(uwml_leg3_new_f64(joints.as_ptr(), links.as_ptr(), null_mut(), &mut e), &e, (1, -1, "out"));
        assert_eq!(uwml_leg3_new_f64(null(), null(), null_mut(), null_mut()), UWML_ERR_NULL_POINTER);
        let mut out32 = zeroed32();
        assert_eq!(uwml_leg3_new_f32(null(), null(), &mut out32, null_mut()), UWML_ERR_NULL_POINTER);

        expect_error(uwml_leg3_set_water_f64(null_mut(), 1000.0, 9.81, &mut e), &e, (1, -1, "leg"));
        expect_error(uwml_leg3_set_coefficients_f64(null_mut(), 2.2, 0.5, &mut e), &e, (1, -1, "leg"));
        let code = uwml_leg3_set_coefficients_per_direction_f64(null_mut(), six.as_ptr(), six.as_ptr(), &mut e);
        expect_error(code, &e, (1, -1, "leg"));
        let code = uwml_leg3_set_coefficients_per_direction_f64(leg_ptr, null(), six.as_ptr(), &mut e);
        expect_error(code, &e, (1, -1, "cd"));
        let code = uwml_leg3_set_coefficients_per_direction_f64(leg_ptr, six.as_ptr(), null(), &mut e);
        expect_error(code, &e, (1, -1, "cm"));
        expect_error(uwml_leg3_set_losses_f64(null_mut(), 0, &p, 0.0, 20.0, &mut e), &e, (1, -1, "leg"));
        expect_error(uwml_leg3_set_losses_f64(leg_ptr, 0, null(), 0.0, 20.0, &mut e), &e, (1, -1, "params"));
        expect_error(uwml_leg3_clear_losses_f64(null_mut(), 0, &mut e), &e, (1, -1, "leg"));
        expect_error(uwml_leg3_set_conditions_f64(null_mut(), 0.0, 20.0, &mut e), &e, (1, -1, "leg"));

        expect_error(uwml_leg3_environment_f64(null(), q, qd, qdd, &mut env, &mut e), &e, (1, -1, "leg"));
        expect_error(uwml_leg3_environment_f64(leg_ptr, null(), qd, qdd, &mut env, &mut e), &e, (1, -1, "q"));
        expect_error(uwml_leg3_environment_f64(leg_ptr, q, null(), qdd, &mut env, &mut e), &e, (1, -1, "qd"));
        expect_error(uwml_leg3_environment_f64(leg_ptr, q, qd, null(), &mut env, &mut e), &e, (1, -1, "qdd"));
        expect_error(uwml_leg3_environment_f64(leg_ptr, q, qd, qdd, null_mut(), &mut e), &e, (1, -1, "out"));
        expect_error(uwml_leg3_hydro_f64(null(), q, qd, qdd, &mut hydro, &mut e), &e, (1, -1, "leg"));
        expect_error(uwml_leg3_hydro_f64(leg_ptr, q, qd, null(), &mut hydro, &mut e), &e, (1, -1, "qdd"));
        expect_error(uwml_leg3_hydro_f64(leg_ptr, q, qd, qdd, null_mut(), &mut e), &e, (1, -1, "out"));
        let q32 = [0.0f32; 3];
        let code = uwml_leg3_environment_f32(null(), q32.as_ptr(), q32.as_ptr(), q32.as_ptr(), null_mut(), &mut e);
        expect_error(code, &e, (1, -1, "leg"));
        let code = uwml_leg3_hydro_f32(null(), q32.as_ptr(), q32.as_ptr(), q32.as_ptr(), null_mut(), &mut e);
        expect_error(code, &e, (1, -1, "leg"));
        expect_error(uwml_leg3_set_water_f32(null_mut(), 1.0, 1.0, &mut e), &e, (1, -1, "leg"));
        expect_error(uwml_leg3_set_coefficients_f32(null_mut(), 1.0, 1.0, &mut e), &e, (1, -1, "leg"));
        let code = uwml_leg3_set_coefficients_per_direction_f32(null_mut(), null(), null(), &mut e);
        expect_error(code, &e, (1, -1, "leg"));
        expect_error(uwml_leg3_set_losses_f32(null_mut(), 0, null(), 0.0, 20.0, &mut e), &e, (1, -1, "leg"));
        expect_error(uwml_leg3_clear_losses_f32(null_mut(), 0, &mut e), &e, (1, -1, "leg"));
        expect_error(uwml_leg3_set_conditions_f32(null_mut(), 0.0, 20.0, &mut e), &e, (1, -1, "leg"));
    }
}

#[test]
fn legs_not_written_by_the_library_are_refused() {
    let mut leg = zeroed64();
    let (code, _) = environment64(&leg, Q, QD, QDD);
    assert_eq!(code, UWML_ERR_UNINITIALIZED);
    let mut error = blank_error();
    // SAFETY: a live local.
    let code = unsafe { uwml_leg3_set_water_f64(&mut leg, 1000.0, 9.81, &mut error) };
    expect_error(code, &error, (UWML_ERR_UNINITIALIZED, -1, "leg"));
    assert_eq!(leg.opaque_tag, 0);
    // A leg of the other precision has the other tag.
    let leg32 = paper32();
    let mut as64 = zeroed64();
    as64.opaque_tag = leg32.opaque_tag;
    assert_eq!(environment64(&as64, Q, QD, QDD).0, UWML_ERR_UNINITIALIZED);
    // A copy (memcpy) of a leg is a leg.
    let copy = paper64();
    assert_eq!(environment64(&copy, Q, QD, QDD).0, UWML_OK);
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
    ];
    assert_eq!(codes, [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14]);
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

/// The Rust example of docs/firmware.md (the same code, between the markers).
#[test]
fn firmware_doc_rust_example() -> Result<(), uwml_core::ModelError> {
    // --- docs/firmware.md
    use uwml_core::nalgebra::Vector3;
    use uwml_core::{Chain, Coefficients, JointLosses, Water, environment_torques, pressure_at_depth};

    let leg = Chain::<f32, 3>::paper(); // or Chain::new(joints, links)?
    let water = Water::new(1025.0, 9.81)?;
    let coefficients = Coefficients::<f32, 3>::default(); // Cd 2.2, Cm 0.5
    let joint = JointLosses::<f32>::default().at(pressure_at_depth(1000.0, 1025.0, 9.81)?, 4.0)?;
    let losses = [None, Some(joint), Some(joint)]; // recompute when depth or θ change

    // every control period:
    let (q, qd, qdd) = (Vector3::new(0.3, -0.4, 0.6), Vector3::new(0.8, 0.5, -0.7), Vector3::zeros());
    let env = environment_torques(&leg, &water, &coefficients, &losses, &q, &qd, &qdd);
    let feedforward = -env.total(); // env.current: loss current [A]
    // --- end
    assert!(feedforward.iter().all(|x| x.is_finite()));
    assert!(env.seal[1] * qd[1] < 0.0);
    Ok(())
}

#[test]
fn forces_that_overflow_are_an_error_not_a_silent_infinity() {
    let leg = paper64();
    // A finite speed no robot reaches: the drag (∝ q̇²) exceeds f64's range.
    let (code, out) = environment64(&leg, Q, [0.0, 1e200, 0.0], QDD);
    assert_eq!(code, UWML_ERR_OVERFLOW);
    assert!(out.total.iter().any(|x| !x.is_finite()), "the outputs are written, and show it");
    let mut error = blank_error();
    let mut hydro = UwmlHydro3F64::default();
    let (q, qd, qdd) = (Q, [0.0, 0.0, 1e200], QDD);
    // SAFETY: live locals.
    let code = unsafe { uwml_leg3_hydro_f64(&leg, q.as_ptr(), qd.as_ptr(), qdd.as_ptr(), &mut hydro, &mut error) };
    expect_error(code, &error, (UWML_ERR_OVERFLOW, 0, "total"));
    // Large but representable: no error.
    let (code, out) = environment64(&leg, Q, [0.0, 1e100, 0.0], QDD);
    assert_eq!(code, UWML_OK);
    assert!(out.total.iter().all(|x| x.is_finite()));
}
