//! Joint losses: the smooth sign, the oil and seal laws, the drive, the defaults against the
//! paper's findings, validation, and the whole-leg environment torque.
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing)]

use core::f64::consts::PI;

use uwml_core::{
    Conditions, Drive, JointLosses, OilDrag, Problem, RobotData, Seal, Water, loss_torques, presets, pressure_at_depth,
    robot_hydro, smooth_sign,
};

const MPA: f64 = 1e6;
const RPM: f64 = 2.0 * PI / 60.0;

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs().max(1e-300)
}

#[test]
fn smooth_sign_limits() {
    assert_eq!(smooth_sign(0.0, 0.0), 0.0);
    assert_eq!(smooth_sign(0.0, 1e-3), 0.0);
    assert_eq!((smooth_sign(-2.0, 0.0), smooth_sign(3.0, 0.0)), (-1.0, 1.0));
    for x in [-5.0f64, -1e-3, 1e-6, 0.7] {
        let s = smooth_sign(x, 1e-3);
        assert!(s.abs() < 1.0 && s.signum() == f64::signum(x));
        assert_eq!(smooth_sign(-x, 1e-3), -s);
        // ε → 0: the hard sign.
        assert!((smooth_sign(x, 1e-12) - f64::signum(x)).abs() < 1e-9);
    }
    // At x = ε the smooth sign is 1/√2.
    assert!(close(smooth_sign(0.01, 0.01), 1.0 / 2f64.sqrt(), 1e-15));
    assert!(smooth_sign(f64::NAN, 1e-3).is_nan());
    // Extreme magnitudes: no overflow or underflow of the squares.
    assert_eq!((smooth_sign(1e200, 1e-3), smooth_sign(-1e-200, 0.0)), (1.0, -1.0));
    assert!(close(smooth_sign(3e-200, 4e-200), 0.6, 1e-15));
    assert!(close(smooth_sign(-3e200, 4e200), -0.6, 1e-15));
}

fn seal_only(seal: Seal<f64>, epsilon: f64) -> JointLosses<f64> {
    JointLosses::new(Drive::new(1.0, 1.0, 1.0, 1.0).unwrap(), None, Some(seal), epsilon).unwrap()
}

#[test]
fn stribeck_curve_at_zero_at_the_stribeck_speed_and_far_above() {
    let seal = Seal::new([10.0, 2.0 / MPA], [15.0, 5.0 / MPA], [1.0, 0.5 / MPA], 0.1).unwrap();
    let p = 4.0 * MPA;
    let (c, s, d) = (10.0 + 8.0, 15.0 + 20.0, 1.0 + 2.0);
    let state = seal_only(seal, 0.0).at(p, 20.0).unwrap();
    // Just above zero speed: the breakaway level S(p).
    assert!(close(-state.evaluate(1e-12).seal, s, 1e-9));
    // At ω_s: C + (S − C)/e + D ω_s.
    assert!(close(-state.evaluate(0.1).seal, c + (s - c) / 1f64.exp() + d * 0.1, 1e-14));
    // Far above: C + D ω (the Stribeck term has vanished).
    assert!(close(-state.evaluate(5.0).seal, c + d * 5.0, 1e-14));
    // Odd in speed.
    assert_eq!(state.evaluate(-0.3).seal, -state.evaluate(0.3).seal);
    // With K_t = N = η = 1 the current is the seal torque itself.
    assert!(close(state.evaluate(0.3).current, -state.evaluate(0.3).seal, 1e-15));
}

#[test]
fn oil_drag_law() {
    let oil = OilDrag::new(2e-3, 1.5, 0.03 / MPA, 0.05, 1.0 * MPA, 25.0).unwrap();
    let drive = Drive::new(0.5, 100.0, 0.9, 8.0).unwrap();
    let losses = JointLosses::new(drive, Some(oil), None, 0.0).unwrap();
    let (p, theta, w) = (6.0 * MPA, 5.0, 0.4f64);
    let t_oil = 2e-3 * f64::exp(0.03 * 5.0) * f64::exp(-0.05 * (5.0 - 25.0)) * (100.0 * w).powf(1.5);
    let loss = losses.at(p, theta).unwrap().evaluate(w);
    assert!(close(loss.visc, -100.0 * 0.9 * t_oil, 1e-13));
    assert!(close(loss.current, t_oil / 0.5, 1e-13));
    assert_eq!(loss.seal, 0.0);
    // The exact exponents 1 and 2 skip the power function and agree with it.
    for n in [1.0, 2.0] {
        let oil = OilDrag::new(2e-3, n, 0.0, 0.0, 0.0, 20.0).unwrap();
        let loss = JointLosses::new(drive, Some(oil), None, 0.0).unwrap().at(0.0, 20.0).unwrap().evaluate(-w);
        assert!(close(loss.visc, 100.0 * 0.9 * 2e-3 * (100.0 * w).powf(n), 1e-14));
    }
}

/// A small deterministic generator in [0, 1).
fn uniform(seed: &mut u64) -> f64 {
    *seed ^= *seed << 13;
    *seed ^= *seed >> 7;
    *seed ^= *seed << 17;
    (*seed >> 11) as f64 / (1u64 << 53) as f64
}

#[test]
fn losses_oppose_motion_and_grow_with_pressure() {
    let losses = JointLosses::<f64>::default();
    let mut seed = 99;
    for _ in 0..5000 {
        let speed = 4.0 * (uniform(&mut seed) - 0.5) * 10f64.powf(-4.0 * uniform(&mut seed));
        let (p, theta) = (20.0 * MPA * uniform(&mut seed), 2.0 + 25.0 * uniform(&mut seed));
        let low = losses.at(p, theta).unwrap().evaluate(speed);
        assert!(speed * low.visc <= 0.0 && speed * low.seal <= 0.0, "{speed}: {low:?}");
        assert!(speed * low.current >= 0.0);
        let high = losses.at(p + 1.0 * MPA, theta).unwrap().evaluate(speed);
        assert!(high.visc.abs() >= low.visc.abs() && high.seal.abs() >= low.seal.abs());
    }
}

#[test]
fn defaults_reproduce_the_papers_findings() {
    let losses = JointLosses::<f64>::default();
    let (w, p, theta) = (10.0 * RPM, 10.0 * MPA, 20.0);
    let loss = losses.at(p, theta).unwrap().evaluate(w);
    // 2.85 A total, 27.4 % of the 10.4 A rated current (paper, Section IV).
    assert!((loss.current - 2.85).abs() < 1e-3, "{}", loss.current);
    assert!((loss.current / 10.4 - 0.274).abs() < 5e-4);
    // Elasticities at (10 r/min, 10 MPa): the oil loss is the more speed-sensitive, the seal
    // loss the more pressure-sensitive.
    let elasticity = |f: &dyn Fn(f64) -> f64, x: f64| {
        let h = 1e-4;
        (f(x * (1.0 + h)).abs().ln() - f(x * (1.0 - h)).abs().ln()) / ((1.0 + h).ln() - (1.0 - h).ln())
    };
    let oil_speed = elasticity(&|s| losses.at(p, theta).unwrap().evaluate(s).visc, w);
    let seal_speed = elasticity(&|s| losses.at(p, theta).unwrap().evaluate(s).seal, w);
    let oil_pressure = elasticity(&|x| losses.at(x, theta).unwrap().evaluate(w).visc, p);
    let seal_pressure = elasticity(&|x| losses.at(x, theta).unwrap().evaluate(w).seal, p);
    assert!(
        oil_speed > seal_speed && seal_pressure > oil_pressure,
        "{oil_speed} {seal_speed} {oil_pressure} {seal_pressure}"
    );
    assert!(oil_pressure > 0.0 && seal_pressure > 0.0);
    // Breakaway well above running friction at high pressure: at start-up (0.01 rad/s, ten
    // times the smooth sign's width) against running at 10 r/min.
    let state = losses.at(p, theta).unwrap();
    assert!(state.evaluate(0.01).seal.abs() > 1.3 * state.evaluate(w).seal.abs());
}

#[test]
fn parameters_are_validated() {
    assert_eq!(OilDrag::new(1e-3, 2.5, 0.0, 0.0, 0.0, 20.0).unwrap_err().problem, Problem::OutOfRange);
    assert_eq!(OilDrag::new(-1e-3, 1.0, 0.0, 0.0, 0.0, 20.0).unwrap_err().field, "oil.k_oil");
    assert_eq!(OilDrag::new(1e-3, 1.0, 0.0, 0.0, 0.0, -300.0).unwrap_err().problem, Problem::OutOfRange);
    let e = Seal::new([10.0, 1e-6], [9.0, 2e-6], [0.0, 0.0], 0.1).unwrap_err();
    assert_eq!((e.field, e.problem), ("seal.s0", Problem::OutOfOrder));
    assert_eq!(Seal::new([10.0, 3e-6], [11.0, 2e-6], [0.0, 0.0], 0.1).unwrap_err().field, "seal.s1");
    assert_eq!(Seal::new([1.0, 0.0], [1.0, 0.0], [0.0, 0.0], 0.0).unwrap_err().problem, Problem::NonPositive);
    assert_eq!(Seal::new([1.0, 0.0], [1.0, 0.0], [-1.0, 0.0], 0.1).unwrap_err().field, "seal.d0");
    assert_eq!(Drive::new(0.4, 160.0, 1.2, 10.4).unwrap_err().problem, Problem::OutOfRange);
    assert_eq!(Drive::new(0.0, 160.0, 0.8, 10.4).unwrap_err().field, "drive.torque_constant");
    assert_eq!(Drive::new(0.4, 160.0, 0.8, f64::NAN).unwrap_err().problem, Problem::NonFinite);
    assert!(JointLosses::new(Drive::<f64>::default(), None, None, -1.0).is_err());
    assert_eq!(Drive::<f64>::default(), Drive::new(0.40, 160.0, 0.80, 10.4).unwrap());
}

#[test]
fn the_robot_evaluation_adds_losses_to_hydrodynamics() {
    let leg = presets::paper_leg::<f64>();
    let (q, qd, qdd) = ([0.3, -0.4, 0.6], [0.8, 0.5, -0.7], [1.0, -2.0, 0.5]);
    let p = pressure_at_depth(1000.0, 1025.0, 9.81).unwrap();
    assert!(close(p, 10.055_25 * MPA, 1e-12));
    let joint = JointLosses::default().at(p, 4.0).unwrap();
    let losses = [None, Some(joint), Some(joint)];
    let (mut with, mut without) = (RobotData::new(), RobotData::new());
    let conditions = Conditions::new(Water::default());
    robot_hydro(&leg, &Conditions { losses: Some(&losses), ..conditions }, [&q, &qd, &qdd], &mut with);
    robot_hydro(&leg, &conditions, [&q, &qd, &qdd], &mut without);
    assert_eq!(with.joint_forces(), without.joint_forces());
    assert!(without.joint_losses().iter().all(|l| (l.visc, l.seal, l.current) == (0.0, 0.0, 0.0)));
    let (visc, seal, current) = loss_torques(&losses, &qd.into());
    for (j, loss) in with.joint_losses().iter().enumerate() {
        assert_eq!((loss.visc, loss.seal, loss.current), (visc[j], seal[j], current[j]));
        if j > 0 {
            let alone = joint.evaluate(qd[j]);
            assert_eq!((loss.visc, loss.seal, loss.current), (alone.visc, alone.seal, alone.current));
        }
    }
}

#[test]
fn f32_losses_track_f64() {
    let (l64, l32) = (JointLosses::<f64>::default(), JointLosses::<f32>::default());
    let mut seed = 5;
    for _ in 0..2000 {
        let (w, p) = (3.0 * (uniform(&mut seed) - 0.5), 15.0 * MPA * uniform(&mut seed));
        let (a, b) = (l64.at(p, 4.0).unwrap().evaluate(w), l32.at(p as f32, 4.0).unwrap().evaluate(w as f32));
        for (x, y) in [(a.visc, b.visc), (a.seal, b.seal), (a.current, b.current)] {
            assert!((x - f64::from(y)).abs() <= 2e-5 * (x.abs() + 1e-3), "{x} {y}");
        }
    }
}

#[test]
fn conditions_outside_the_physics_are_refused() {
    use uwml_core::{ABSOLUTE_ZERO_C, MAX_DEPTH, MAX_PRESSURE};
    let joint = JointLosses::<f64>::default();
    for (pressure, temperature, field, problem) in [
        (-1.0, 20.0, "pressure", Problem::Negative),
        (f64::NAN, 20.0, "pressure", Problem::NonFinite),
        (f64::INFINITY, 20.0, "pressure", Problem::NonFinite),
        (MAX_PRESSURE * 1.000_001, 20.0, "pressure", Problem::BeyondDeepestOcean),
        (1e7, ABSOLUTE_ZERO_C, "temperature", Problem::BelowAbsoluteZero),
        (1e7, -300.0, "temperature", Problem::BelowAbsoluteZero),
        (1e7, f64::NAN, "temperature", Problem::NonFinite),
    ] {
        let e = joint.at(pressure, temperature).unwrap_err();
        assert_eq!((e.field, e.problem), (field, problem), "{pressure} Pa, {temperature} degC");
    }
    // The edges are inside: no pressure, the deepest ocean, just above absolute zero.
    for (pressure, temperature) in [(0.0, 20.0), (MAX_PRESSURE, 2.0), (1e7, ABSOLUTE_ZERO_C + 1.0)] {
        assert!(joint.at(pressure, temperature).is_ok());
    }
    for (depth, density, gravity, field, problem) in [
        (-1.0, 1025.0, 9.81, "depth", Problem::Negative),
        (MAX_DEPTH + 1.0, 1025.0, 9.81, "depth", Problem::BeyondDeepestOcean),
        (f64::NAN, 1025.0, 9.81, "depth", Problem::NonFinite),
        (1000.0, -1025.0, 9.81, "sea_density", Problem::NonPositive),
        (1000.0, f64::NAN, 9.81, "sea_density", Problem::NonFinite),
        (1000.0, 1025.0, 0.0, "gravity", Problem::NonPositive),
    ] {
        let e = pressure_at_depth(depth, density, gravity).unwrap_err();
        assert_eq!((e.field, e.problem), (field, problem), "{depth} m, {density} kg/m3, {gravity} m/s2");
    }
    assert_eq!(pressure_at_depth(MAX_DEPTH, 1025.0, 9.81), Ok(1025.0 * 9.81 * MAX_DEPTH));
    // The deepest ocean's pressure is within the pressures taken, even in dense water.
    assert!(pressure_at_depth(MAX_DEPTH, 1060.0, 9.83).unwrap() <= MAX_PRESSURE);
    let message = pressure_at_depth(12_000.0, 1025.0, 9.81).unwrap_err().to_string();
    assert!(message.contains("depth") && message.contains("11000 m"), "{message}");
    let message = joint.at(1e7, -300.0).unwrap_err().to_string();
    assert!(message.contains("temperature") && message.contains("absolute zero"), "{message}");
}

#[test]
fn an_absurd_water_gives_no_absurd_pressure() {
    // Found by fuzzing the C ABI: a density and gravity that are finite and positive but far from
    // the sea's overflowed to an infinite pressure, returned as a success.
    use uwml_core::MAX_PRESSURE;
    let e = pressure_at_depth(2.2e-308, 1e200, f64::MAX).unwrap_err();
    assert_eq!((e.field, e.problem), ("pressure", Problem::BeyondDeepestOcean));
    let e = pressure_at_depth(1000.0, 1e7, 9.81).unwrap_err();
    assert_eq!((e.field, e.problem), ("pressure", Problem::BeyondDeepestOcean));
    assert!(pressure_at_depth(11_000.0, 1025.0, 9.81).unwrap() < MAX_PRESSURE);
}

#[test]
fn dry_friction_split_is_the_hard_sign_loss_as_friction_and_damping() {
    // Hand values: seal C = 18, S = 35, D = 3 at 4 MPa, ω_s = 0.1; laminar oil k = 2e-3,
    // N = 100, η = 0.9: N η k N = 18 N·m·s/rad at the output.
    let seal = Seal::new([10.0, 2.0 / MPA], [15.0, 5.0 / MPA], [1.0, 0.5 / MPA], 0.1).unwrap();
    let oil = OilDrag::new(2e-3, 1.0, 0.0, 0.0, 0.0, 20.0).unwrap();
    let drive = Drive::new(0.5, 100.0, 0.9, 8.0).unwrap();
    let p = 4.0 * MPA;
    let hard = JointLosses::new(drive, Some(oil), Some(seal), 0.0).unwrap().at(p, 20.0).unwrap();
    for speed in [-3.0, -0.1, -1e-9, 1e-9, 0.05, 0.1, 2.0] {
        let split = hard.dry_friction_split(speed);
        assert!(close(split.friction, 18.0 + 17.0 * (-(speed / 0.1f64).powi(2)).exp(), 1e-14), "{speed}");
        assert!(close(split.damping, 18.0 + 3.0, 1e-14), "{speed}: {split:?}");
        // −(friction sgn ω + damping ω) is the evaluated loss.
        let loss = hard.evaluate(speed);
        let rebuilt = -(split.friction * speed.signum() + split.damping * speed);
        assert!(close(rebuilt, loss.visc + loss.seal, 1e-14), "{speed}: {rebuilt} {loss:?}");
    }
    // At rest: the breakaway level, and the laminar oil's slope with the hard sign.
    let rest = hard.dry_friction_split(0.0);
    assert!(close(rest.friction, 35.0, 1e-15) && close(rest.damping, 21.0, 1e-15), "{rest:?}");
    // A smooth sign: the damping at rest is the seal's D alone (the oil's torque is quadratic
    // there), and far above ε the oil's secant slope is N η k N again.
    let smooth = JointLosses::new(drive, Some(oil), Some(seal), 0.01).unwrap().at(p, 20.0).unwrap();
    assert!(close(smooth.dry_friction_split(0.0).damping, 3.0, 1e-15));
    assert!(close(smooth.dry_friction_split(5.0).damping, 3.0 + 18.0 * 5.0 / (25.0f64 + 1e-4).sqrt(), 1e-14));
    // Taylor vortices (n = 1.5): the secant is N η k N^1.5 |ω|^0.5, 0 at rest.
    let vortex = OilDrag::new(2e-3, 1.5, 0.0, 0.0, 0.0, 20.0).unwrap();
    let state = JointLosses::new(drive, Some(vortex), None, 0.0).unwrap().at(0.0, 20.0).unwrap();
    assert!(close(state.dry_friction_split(-0.25).damping, 90.0 * 2e-3 * 1000.0 * 0.5, 1e-14));
    assert_eq!(state.dry_friction_split(0.0), uwml_core::DryFrictionSplit { friction: 0.0, damping: 0.0 });
}
