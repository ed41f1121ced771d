//! Wall-clock ns per call of the paper leg's evaluation, and a fixed-work target for callgrind.
//! Usage: `cargo run --release --example timing -- [n_calls] [kinematics|torques|regressors|environment] [f64|f32]`,
//! or `... [n_calls] torques f64x4`: `hydro_torques` over simba's `WideF64x4`, four states per call
//! (and `robot-leg|robot-leg-moving|robot-arm f64x4`: `robot_hydro` so);
//! `... [n_calls] robot-leg|robot-leg-moving|robot-arm [f64|f32]`: `robot_hydro` on the paper leg
//! (fixed base in still water, or on a moving base in a current) and on a 7-joint arm of 14
//! segments on a moving ROV in a current (`benches/common/arm.rs`).
#![allow(missing_docs, clippy::unwrap_used)]

use std::hint::black_box;
use std::time::Instant;

use simba::simd::{SimdValue, WideF64x4};

use uwml_core::nalgebra::{RealField, Vector3, convert};
use uwml_core::{
    AddedMassForm, BaseMotion, Chain, Coefficients, Conditions, Current, JointLosses, LossState, Real, Robot,
    RobotData, Water, environment_torques, hydro_regressors, hydro_torques, link_motions, pressure_at_depth,
    robot_hydro,
};

#[path = "../benches/common/arm.rs"]
mod arm;

// One evaluation each, not inlined into the loop, so that its code can be read on its own; the
// whole result goes through `black_box`, so that no part of it is optimized away.

/// The leg, the water, the coefficients, and the default losses of all three joints at 1000 m
/// (computed once, as a controller does when the pressure changes).
type Model<T> = (Chain<T, 3>, Water<T>, Coefficients<T, 3>, [Option<LossState<T>>; 3]);

#[inline(never)]
fn kinematics<T: RealField + Copy>((leg, _, _, _): &Model<T>, [q, qd, qdd]: &[Vector3<T>; 3]) -> T {
    black_box(link_motions(leg, q, qd, qdd))[2].origin.x
}

#[inline(never)]
fn torques<T: RealField + Real>((leg, water, coefficients, _): &Model<T>, [q, qd, qdd]: &[Vector3<T>; 3]) -> T {
    black_box(hydro_torques(leg, water, coefficients, q, qd, qdd)).drag.x
}

#[inline(never)]
fn regressors<T: RealField + Real>((leg, water, _, _): &Model<T>, [q, qd, qdd]: &[Vector3<T>; 3]) -> T {
    black_box(hydro_regressors(leg, water, q, qd, qdd)).drag[2][1].x
}

/// The paper leg's hydrodynamics plus the default joint losses on all three joints.
#[inline(never)]
fn environment<T: RealField + Real>(
    (leg, water, coefficients, losses): &Model<T>,
    [q, qd, qdd]: &[Vector3<T>; 3],
) -> T {
    black_box(environment_torques(leg, water, coefficients, losses, q, qd, qdd)).seal.x
}

/// Sum of one output per call (so nothing is optimized away); q changes every call.
fn run<T: RealField + Real>(n: usize, evaluate: fn(&Model<T>, &[Vector3<T>; 3]) -> T) -> f64 {
    let pressure = pressure_at_depth::<T>(convert(1000.0), convert(1025.0), convert(9.81)).unwrap();
    let losses = [Some(JointLosses::<T>::default().at(pressure, convert(4.0)).unwrap()); 3];
    let model = (Chain::<T, 3>::paper(), Water::default(), Coefficients::default(), losses);
    let v = |a: f64, b: f64, c: f64| Vector3::<T>::new(convert(a), convert(b), convert(c));
    let (qd, qdd) = (v(0.8, 0.5, -0.7), v(1.0, -2.0, 0.5));
    let mut acc = T::zero();
    for i in 0..n {
        let q = v(0.3 + i as f64 * 1e-7, -0.4, 0.6);
        acc += evaluate(black_box(&model), &[q, qd, qdd]);
    }
    // Every RealField here is f32 or f64; their Display round-trips.
    format!("{acc}").parse().unwrap_or(f64::NAN)
}

/// One `robot_hydro` evaluation.
#[inline(never)]
fn robot_torques<T: RealField + Real, const J: usize, const S: usize, const B: usize>(
    robot: &Robot<T, J, S, B>,
    (motion, current): &(BaseMotion<T>, Current<T>),
    [q, qd, qdd]: &[[T; J]; 3],
    data: &mut RobotData<T, J>,
) -> T {
    robot_hydro(
        robot,
        &Conditions { motion: *motion, current: *current, ..Conditions::new(Water::default()) },
        [q, qd, qdd],
        data,
    );
    black_box(data.base_wrench()).drag.force.x + black_box(data.joint_forces()).first().map_or(T::zero(), |f| f.drag)
}

/// [`run`] for [`robot_torques`] on `robot`.
fn run_robot<T: RealField + Real, const J: usize, const S: usize, const B: usize>(
    n: usize,
    robot: &Robot<T, J, S, B>,
    surroundings: (BaseMotion<T>, Current<T>),
) -> f64 {
    let state = |base: f64, step: f64| core::array::from_fn(|i| convert::<f64, T>(base + step * i as f64));
    let (qd, qdd) = (state(0.8, -0.45), state(1.0, -0.7));
    let mut data = RobotData::new();
    let mut acc = T::zero();
    for i in 0..n {
        let q = state(0.3 + i as f64 * 1e-7, -0.2);
        acc += robot_torques(black_box(robot), &surroundings, &[q, qd, qdd], &mut data);
    }
    format!("{acc}").parse().unwrap_or(f64::NAN)
}

fn run_mode<T: RealField + Real>(n: usize, mode: &str) -> f64 {
    let leg = || Robot::<T, 3, 2>::from_chain(&Chain::paper(), &Coefficients::default());
    match mode {
        "robot-leg" => leg().map_or(f64::NAN, |leg| run_robot(n, &leg, (BaseMotion::fixed(), Current::still()))),
        "robot-leg-moving" => leg().map_or(f64::NAN, |leg| run_robot(n, &leg, arm::rov_motion())),
        "robot-arm" => run_robot(n, &arm::arm_on_rov::<T, 7, 15>(), arm::rov_motion()),
        "robot-arm-hull" => run_robot(n, &arm::with_hull(&arm::arm_on_rov::<T, 7, 15>()), arm::rov_motion()),
        "kinematics" => run::<T>(n, kinematics),
        "regressors" => run::<T>(n, regressors),
        "environment" => run::<T>(n, environment),
        _ => run::<T>(n, torques),
    }
}

/// One `robot_hydro` evaluation over four lanes: four states per call.
#[inline(never)]
fn robot_torques_lanes<const J: usize, const S: usize>(
    robot: &Robot<WideF64x4, J, S>,
    (motion, current): &(BaseMotion<WideF64x4>, Current<WideF64x4>),
    [q, qd, qdd]: &[[WideF64x4; J]; 3],
    data: &mut RobotData<WideF64x4, J>,
) -> WideF64x4 {
    robot_hydro(
        robot,
        &Conditions {
            water: Water::<f64>::default().splat(),
            motion: *motion,
            current: *current,
            coefficients: None,
            form: AddedMassForm::Morison,
            losses: None,
        },
        [q, qd, qdd],
        data,
    );
    black_box(data.base_wrench()).drag.force.x
        + black_box(data.joint_forces()).first().map_or(WideF64x4::splat(0.0), |f| f.drag)
}

/// [`run_robot`] over four lanes: the sum over the lanes of every call's output.
fn run_robot_lanes<const J: usize, const S: usize>(
    n: usize,
    robot: &Robot<f64, J, S>,
    (motion, current): (BaseMotion<f64>, Current<f64>),
) -> f64 {
    let robot = robot.splat::<WideF64x4>();
    let surroundings = (BaseMotion::from_lanes(&[motion]), Current::from_lanes(&[current]));
    let state = |base: f64, step: f64| core::array::from_fn(|i| WideF64x4::splat(base + step * i as f64));
    let (qd, qdd) = (state(0.8, -0.45), state(1.0, -0.7));
    let mut data = RobotData::new();
    let mut acc = WideF64x4::splat(0.0);
    for i in 0..n {
        let q = core::array::from_fn(|j| {
            WideF64x4::from([0.0, 1e-3, 2e-3, 3e-3].map(|d| 0.3 + d + i as f64 * 1e-7 - 0.2 * j as f64))
        });
        acc += robot_torques_lanes(black_box(&robot), &surroundings, &[q, qd, qdd], &mut data);
    }
    <[f64; 4]>::from(acc).iter().sum()
}

/// `hydro_torques` over four lanes: four states per call.
#[inline(never)]
fn torques_lanes(
    (leg, water, coefficients): &(Chain<WideF64x4, 3>, Water<WideF64x4>, Coefficients<WideF64x4, 3>),
    [q, qd, qdd]: &[Vector3<WideF64x4>; 3],
) -> WideF64x4 {
    black_box(hydro_torques(leg, water, coefficients, q, qd, qdd)).drag.x
}

/// [`run`] for [`torques_lanes`]: the sum over the lanes of every call's output.
fn run_lanes(n: usize) -> f64 {
    let model =
        (Chain::<f64, 3>::paper().splat(), Water::<f64>::default().splat(), Coefficients::<f64, 3>::default().splat());
    let v = |a: f64, b: f64, c: f64| Vector3::new(WideF64x4::splat(a), WideF64x4::splat(b), WideF64x4::splat(c));
    let (qd, qdd) = (v(0.8, 0.5, -0.7), v(1.0, -2.0, 0.5));
    let mut acc = WideF64x4::splat(0.0);
    for i in 0..n {
        let first = WideF64x4::from([0.0, 1e-3, 2e-3, 3e-3].map(|d| 0.3 + d + i as f64 * 1e-7));
        let q = Vector3::new(first, WideF64x4::splat(-0.4), WideF64x4::splat(0.6));
        acc += torques_lanes(black_box(&model), &[q, qd, qdd]);
    }
    <[f64; 4]>::from(acc).iter().sum()
}

fn main() {
    let mut args = std::env::args().skip(1);
    let n: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(5_000_000);
    let mode = args.next().unwrap_or_else(|| "torques".to_string());
    let precision = args.next().unwrap_or_else(|| "f64".to_string());
    let start = Instant::now();
    let acc = match precision.as_str() {
        "f32" => run_mode::<f32>(n, &mode),
        "f64x4" => match mode.as_str() {
            "robot-leg" => Robot::<f64, 3, 2>::from_chain(&Chain::paper(), &Coefficients::default())
                .map_or(f64::NAN, |leg| run_robot_lanes(n, &leg, (BaseMotion::fixed(), Current::still()))),
            "robot-leg-moving" => Robot::<f64, 3, 2>::from_chain(&Chain::paper(), &Coefficients::default())
                .map_or(f64::NAN, |leg| run_robot_lanes(n, &leg, arm::rov_motion())),
            "robot-arm" => run_robot_lanes(n, &arm::arm_on_rov::<f64, 7, 15>(), arm::rov_motion()),
            _ => run_lanes(n),
        },
        _ => run_mode::<f64>(n, &mode),
    };
    let ns = start.elapsed().as_nanos() as f64 / n as f64;
    println!("{mode} {precision}: {ns:.1} ns per call ({acc:.3})");
}
