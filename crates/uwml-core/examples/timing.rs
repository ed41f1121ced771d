//! Wall-clock ns per call of the paper leg's evaluation (`presets::paper_leg`), and a fixed-work
//! target for callgrind. Usage: `cargo run --release --example timing -- [n_calls] [MODE] [T]`, T
//! `f64` (the default) or `f32`, or `f64x4` (simba's `WideF64x4`, four states per call, for the
//! `robot-*` modes but `robot-arm-hull`). MODE: `robot-leg` (the default: `robot_hydro`, fixed
//! base in still water), `robot-leg-moving` (on a moving base in a current), `robot-arm` and
//! `robot-arm-hull` (a 7-joint arm of 14 segments on a moving ROV in a current, without and with
//! a lumped hull: `benches/common/arm.rs`), `environment` (the leg with the default losses on all
//! three joints), `regressors` (`robot_hydro_regressors`), `kinematics` (`forward_kinematics` and
//! the foot's `point_jacobian`).
#![allow(missing_docs, clippy::unwrap_used)]

use std::hint::black_box;
use std::time::Instant;

use simba::simd::{SimdValue, WideF64x4};

use uwml_core::nalgebra::{RealField, Vector3, convert};
use uwml_core::{
    AddedMassForm, BaseMotion, Conditions, Current, JointLosses, KinematicsData, LossState, Real, Robot, RobotData,
    Water, forward_kinematics, point_jacobian, presets, pressure_at_depth, robot_hydro, robot_hydro_regressors,
};

#[path = "../benches/common/arm.rs"]
mod arm;

// One evaluation each, not inlined into the loop, so that its code can be read on its own; the
// whole result goes through `black_box`, so that no part of it is optimized away.

/// The paper's leg, and the default losses of all three joints at 1000 m (computed once, as a
/// controller does when the pressure changes). The leg with room for a third segment: these modes'
/// `robot_hydro` is an instantiation of its own, so that the `robot-*` modes' stays the only one
/// of `Robot<T, 3, 2>` and is inlined into its caller as before.
type Model<T> = (Robot<T, 3, 3>, [Option<LossState<T>>; 3]);

/// The leg's workspaces.
type Work<T> = (RobotData<T, 3>, KinematicsData<T, 3>);

/// The foot's position and Jacobian (`forward_kinematics` and `point_jacobian`).
#[inline(never)]
fn kinematics<T: RealField + Real>((leg, _): &Model<T>, [q, _, _]: &[[T; 3]; 3], (_, data): &mut Work<T>) -> T {
    forward_kinematics(leg, q, data);
    let mut jacobian = [T::zero(); 18];
    let foot = Vector3::new(T::zero(), T::zero(), convert(-presets::paper::L3));
    let position = point_jacobian(leg, data, 2, &foot, &mut jacobian);
    black_box(jacobian)[0] + black_box(position).map_or(T::zero(), |p| p.x)
}

/// Every drag and added-mass column of the leg (`robot_hydro_regressors`).
#[inline(never)]
fn regressors<T: RealField + Real>((leg, _): &Model<T>, state: &[[T; 3]; 3], (data, _): &mut Work<T>) -> T {
    let (mut drag, mut added_mass) = ([T::zero(); 54], [T::zero(); 54]); // 9 rows, 6 columns
    let [q, qd, qdd] = state;
    robot_hydro_regressors(leg, &Conditions::new(Water::default()), [q, qd, qdd], data, &mut drag, &mut added_mass);
    black_box(drag)[53] + black_box(added_mass)[53]
}

/// The paper leg's hydrodynamics plus the default joint losses on all three joints.
#[inline(never)]
fn environment<T: RealField + Real>((leg, losses): &Model<T>, state: &[[T; 3]; 3], (data, _): &mut Work<T>) -> T {
    let [q, qd, qdd] = state;
    robot_hydro(leg, &Conditions { losses: Some(losses), ..Conditions::new(Water::default()) }, [q, qd, qdd], data);
    black_box(data.joint_losses()).first().map_or(T::zero(), |l| l.seal)
}

/// One of the evaluations above.
type Evaluation<T> = fn(&Model<T>, &[[T; 3]; 3], &mut Work<T>) -> T;

/// Sum of one output per call (so nothing is optimized away); q changes every call.
fn run<T: RealField + Real>(n: usize, evaluate: Evaluation<T>) -> f64 {
    let pressure = pressure_at_depth::<T>(convert(1000.0), convert(1025.0), convert(9.81)).unwrap();
    let losses = [Some(JointLosses::<T>::default().at(pressure, convert(4.0)).unwrap()); 3];
    let model = (presets::paper_leg::<T>().to_capacity().unwrap(), losses);
    let v = |a: f64, b: f64, c: f64| [a, b, c].map(convert::<f64, T>);
    let (qd, qdd) = (v(0.8, 0.5, -0.7), v(1.0, -2.0, 0.5));
    let mut work = (RobotData::new(), KinematicsData::new());
    let mut acc = T::zero();
    for i in 0..n {
        let q = v(0.3 + i as f64 * 1e-7, -0.4, 0.6);
        acc += evaluate(black_box(&model), &[q, qd, qdd], &mut work);
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
    let leg = presets::paper_leg::<T>;
    match mode {
        "robot-leg-moving" => run_robot(n, &leg(), arm::rov_motion()),
        "robot-arm" => run_robot(n, &arm::arm_on_rov::<T, 7, 15>(), arm::rov_motion()),
        "robot-arm-hull" => run_robot(n, &arm::with_hull(&arm::arm_on_rov::<T, 7, 15>()), arm::rov_motion()),
        "kinematics" => run::<T>(n, kinematics),
        "regressors" => run::<T>(n, regressors),
        "environment" => run::<T>(n, environment),
        _ => run_robot(n, &leg(), (BaseMotion::fixed(), Current::still())),
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

fn main() {
    let mut args = std::env::args().skip(1);
    let n: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(5_000_000);
    let mode = args.next().unwrap_or_else(|| "robot-leg".to_string());
    let precision = args.next().unwrap_or_else(|| "f64".to_string());
    let start = Instant::now();
    let acc = match precision.as_str() {
        "f32" => run_mode::<f32>(n, &mode),
        "f64x4" => match mode.as_str() {
            "robot-leg-moving" => run_robot_lanes(n, &presets::paper_leg(), arm::rov_motion()),
            "robot-arm" => run_robot_lanes(n, &arm::arm_on_rov::<f64, 7, 15>(), arm::rov_motion()),
            _ => run_robot_lanes(n, &presets::paper_leg(), (BaseMotion::fixed(), Current::still())),
        },
        _ => run_mode::<f64>(n, &mode),
    };
    let ns = start.elapsed().as_nanos() as f64 / n as f64;
    println!("{mode} {precision}: {ns:.1} ns per call ({acc:.3})");
}
