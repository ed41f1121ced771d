//! The evaluation over SIMD lanes (`Robot::splat` and simba's `WideF64x4`/`WideF32x4`, four
//! joint states per call, as the Python batch evaluates them) against the scalar paths, lane by
//! lane. They differ only by the sine and cosine (wide's polynomial, not the platform's), so by
//! a few units in the last place.
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing, clippy::expect_used)]

mod common;

use common::{Forces, Rng, hydro, random_chain};
use simba::simd::{SimdValue, WideF32x4, WideF64x4};
use uwml_core::nalgebra::{SVector, Scalar};
use uwml_core::{BaseMotion, Conditions, Real, Robot, RobotData, Water, presets, robot_hydro_regressors};

/// Four states side by side (one per lane) of `N` joints.
fn lanes<L, const N: usize>(states: &[SVector<L::Element, N>; 4]) -> SVector<L, N>
where
    L: SimdValue + Scalar + From<[L::Element; 4]>,
    L::Element: Copy,
{
    SVector::from_fn(|j, _| L::from(states.each_ref().map(|s| s[j])))
}

/// Lane `l` of a vector of lanes.
fn lane<L: SimdValue + Scalar, const N: usize>(v: &SVector<L, N>, l: usize) -> SVector<L::Element, N>
where
    L::Element: Copy + PartialEq + core::fmt::Debug + 'static,
{
    v.map(|x| x.extract(l))
}

/// The drag and added-mass regressors of `robot` at one state, row-major `(6 + N) × columns`.
fn regressors<T: Real, const N: usize, const S: usize>(
    robot: &Robot<T, N, S>,
    water: &Water<T>,
    [q, qd, qdd]: [&SVector<T, N>; 3],
) -> Vec<T> {
    let width = (6 + N) * robot.regressor_column_count();
    let (mut drag, mut added_mass) = (vec![T::zero(); width], vec![T::zero(); width]);
    let state = |v: &SVector<T, N>| -> [T; N] { (*v).into() };
    let mut data = RobotData::new();
    let conditions = Conditions::new(*water);
    robot_hydro_regressors(
        robot,
        &conditions,
        [&state(q), &state(qd), &state(qdd)],
        &mut data,
        &mut drag,
        &mut added_mass,
    );
    drag.extend(added_mass);
    drag
}

/// The largest difference between a lane and its scalar evaluation, relative to `1 +` the
/// largest magnitude of the scalar torques of that kind.
fn worst_difference<const N: usize, const S: usize>(robot: &Robot<f64, N, S>, rng: &mut Rng, groups: usize) -> f64 {
    let water = Water::new(1025.0, 9.81).unwrap();
    let (lane_robot, lane_water) = (robot.splat::<WideF64x4>(), water.splat::<WideF64x4>());
    let mut worst = 0.0f64;
    for _ in 0..groups {
        let q: [SVector<f64, N>; 4] = core::array::from_fn(|_| rng.vector(3.5));
        let qd: [SVector<f64, N>; 4] = core::array::from_fn(|_| rng.vector(3.0));
        let qdd: [SVector<f64, N>; 4] = core::array::from_fn(|_| rng.vector(10.0));
        let (lq, lqd, lqdd) = (lanes::<WideF64x4, N>(&q), lanes(&qd), lanes(&qdd));
        let tau = hydro(&lane_robot, &lane_water, None, &lq, &lqd, &lqdd);
        let lane_regressors = regressors(&lane_robot, &lane_water, [&lq, &lqd, &lqdd]);
        for l in 0..4 {
            let scalar = hydro(robot, &water, None, &q[l], &qd[l], &qdd[l]);
            let mut compare = |lanes: &SVector<WideF64x4, N>, scalar: &SVector<f64, N>| {
                worst = worst.max((lane(lanes, l) - scalar).amax() / (1.0 + scalar.amax()));
            };
            compare(&tau.drag, &scalar.drag);
            compare(&tau.added_mass, &scalar.added_mass);
            compare(&tau.buoyancy, &scalar.buoyancy);
            compare(&tau.gravity, &scalar.gravity);
            let scalar_regressors = regressors(robot, &water, [&q[l], &qd[l], &qdd[l]]);
            let scale = 1.0 + scalar_regressors.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            for (a, b) in lane_regressors.iter().zip(&scalar_regressors) {
                worst = worst.max((a.extract(l) - b).abs() / scale);
            }
        }
    }
    worst
}

#[test]
fn f64_lanes_match_the_scalar_path_on_the_paper_leg_and_random_chains() {
    let mut rng = Rng(41);
    let paper = worst_difference(&presets::paper_leg(), &mut rng, 5_000);
    let mut random = 0.0f64;
    for _ in 0..20 {
        let chain = random_chain(&mut rng);
        random = random.max(worst_difference(&chain, &mut rng, 250));
    }
    println!("f64 lanes vs scalar, worst relative difference: paper {paper:.2e}, random chains {random:.2e}");
    assert!(paper < 1e-13 && random < 1e-13, "paper {paper:e}, random {random:e}");
}

#[test]
fn f32_lanes_match_the_scalar_f32_path() {
    let (leg, water) = (presets::paper_leg::<f32>(), Water::default());
    let (lane_leg, lane_water) = (leg.splat::<WideF32x4>(), water.splat::<WideF32x4>());
    let mut rng = Rng(43);
    let mut worst = 0.0f32;
    for _ in 0..5_000 {
        let mut state =
            |scale: f64| -> [SVector<f32, 3>; 4] { core::array::from_fn(|_| rng.vector::<3>(scale).cast()) };
        let (q, qd, qdd) = (state(3.5), state(3.0), state(10.0));
        let tau = hydro(&lane_leg, &lane_water, None, &lanes(&q), &lanes(&qd), &lanes(&qdd));
        for l in 0..4 {
            let total = hydro(&leg, &water, None, &q[l], &qd[l], &qdd[l]).total();
            worst = worst.max((lane(&tau.total(), l) - total).amax() / (1.0 + total.amax()));
        }
    }
    println!("f32 lanes vs scalar f32, worst relative difference: {worst:.2e}");
    assert!(worst < 1e-5, "{worst:e}");
}

#[test]
fn a_non_finite_state_gives_nan_in_its_lane_only() {
    let (leg, water) = (presets::paper_leg::<f64>(), Water::default());
    let (lane_leg, lane_water) = (leg.splat::<WideF64x4>(), water.splat::<WideF64x4>());
    let mut rng = Rng(47);
    let mut state = |scale: f64| -> [SVector<f64, 3>; 4] { core::array::from_fn(|_| rng.vector(scale)) };
    let (mut q, mut qd, qdd) = (state(1.0), state(1.0), state(1.0));
    // Lane 1: a NaN angle of the first joint (which reaches the torques only through buoyancy
    // and gravity); lane 2: an infinite rate. Lanes 0 and 3 are finite.
    q[1][0] = f64::NAN;
    qd[2][2] = f64::INFINITY;
    let tau = hydro(&lane_leg, &lane_water, None, &lanes(&q), &lanes(&qd), &lanes(&qdd));
    let lane_regressors = regressors(&lane_leg, &lane_water, [&lanes(&q), &lanes(&qd), &lanes(&qdd)]);
    for l in 0..4 {
        let parts = |t: &Forces<WideF64x4, 3>| {
            [t.drag, t.added_mass, t.buoyancy, t.gravity].map(|v| lane(&v, l)).into_iter().flat_map(|v| v.data.0[0])
        };
        let regressor_values = lane_regressors.iter().map(|x| x.extract(l));
        if l == 1 || l == 2 {
            assert!(parts(&tau).chain(regressor_values).all(f64::is_nan), "lane {l}");
        } else {
            let scalar = hydro(&leg, &water, None, &q[l], &qd[l], &qdd[l]);
            assert!((lane(&tau.total(), l) - scalar.total()).amax() < 1e-12, "lane {l}");
            assert!(parts(&tau).chain(regressor_values).all(f64::is_finite), "lane {l}");
        }
    }
    // Every lane non-finite: NaN everywhere, as for a scalar.
    let nan = SVector::<WideF64x4, 3>::repeat(WideF64x4::splat(f64::NAN));
    let all = hydro(&lane_leg, &lane_water, None, &nan, &nan, &nan);
    assert!((0..4).all(|l| lane(&all.total(), l).iter().all(|x| x.is_nan())));
}

/// Whole robots over `WideF64x4` (`Robot::splat`, `BaseMotion::from_lanes`): every lane is the
/// scalar evaluation of its own state, motion and current, bit for bit (the lanes take the
/// sines and the joint losses lane by lane, `uwml_core::Real`), whatever its neighbours, in both
/// added-mass forms, joint forces and losses, base wrench and every body's wrench; a group of fewer than four repeats its
/// first state.
#[test]
fn robot_lanes_are_the_scalar_evaluation_bit_for_bit() {
    use uwml_core::{AddedMassForm, Current, JointLosses, LossState, robot_hydro};
    const J: usize = 9;
    const S: usize = 20;
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let water = Water::new(1030.0, 9.8).unwrap();
    let lane_water = water.splat::<WideF64x4>();
    // Losses on every other joint.
    let loss = JointLosses::<f64>::default().at(2.0e7, 6.0).unwrap();
    let losses: [Option<LossState<f64>>; J] = core::array::from_fn(|j| (j % 2 == 0).then_some(loss));
    let lane_losses = losses.map(|l| l.map(|l| l.splat::<WideF64x4>()));
    for n in 1..=J {
        let robot: Robot<f64, J, S> = common::trees::random_robot(&mut rng, n);
        let lanes_robot = robot.splat::<WideF64x4>();
        for form in [AddedMassForm::Morison, AddedMassForm::Kirchhoff] {
            for used in [4, 3, 1] {
                let states: Vec<[[f64; J]; 3]> = (0..used).map(|_| common::trees::states(&mut rng, n)).collect();
                let motions: Vec<_> = (0..used).map(|_| common::trees::random_motion(&mut rng)).collect();
                let currents: Vec<_> =
                    (0..used).map(|_| Current::new(rng.vector::<3>(1.0), rng.vector::<3>(1.0)).unwrap()).collect();
                let group = |k: usize| -> [WideF64x4; J] {
                    core::array::from_fn(|j| {
                        WideF64x4::from([0, 1, 2, 3].map(|l| states[if l < used { l } else { 0 }][k][j]))
                    })
                };
                let (q, qd, qdd) = (group(0), group(1), group(2));
                let (motion, current) = (BaseMotion::from_lanes(&motions), Current::from_lanes(&currents));
                let mut lanes = RobotData::new();
                robot_hydro(
                    &lanes_robot,
                    &Conditions {
                        water: lane_water,
                        motion,
                        current,
                        coefficients: None,
                        form,
                        losses: Some(&lane_losses),
                    },
                    [&q, &qd, &qdd],
                    &mut lanes,
                );
                for l in 0..used {
                    let [q, qd, qdd] = &states[l];
                    let mut scalar = RobotData::new();
                    robot_hydro(
                        &robot,
                        &Conditions {
                            motion: motions[l],
                            current: currents[l],
                            form,
                            losses: Some(&losses),
                            ..Conditions::new(water)
                        },
                        [q, qd, qdd],
                        &mut scalar,
                    );
                    let bits = |x: f64| x.to_bits();
                    for (a, b) in lanes.joint_forces().iter().zip(scalar.joint_forces()) {
                        let lane = [a.drag, a.added_mass, a.buoyancy, a.gravity].map(|x| bits(x.extract(l)));
                        assert_eq!(lane, [b.drag, b.added_mass, b.buoyancy, b.gravity].map(bits), "n {n} lane {l}");
                    }
                    for (a, b) in lanes.joint_losses().iter().zip(scalar.joint_losses()) {
                        let lane = [a.visc, a.seal, a.current].map(|x| bits(x.extract(l)));
                        assert_eq!(lane, [b.visc, b.seal, b.current].map(bits), "n {n} lane {l}: losses");
                    }
                    let (a, b) = (lanes.base_wrench(), scalar.base_wrench());
                    for (x, y) in [a.drag, a.added_mass, a.buoyancy, a.gravity]
                        .iter()
                        .flat_map(|w| w.to_array())
                        .zip([b.drag, b.added_mass, b.buoyancy, b.gravity].iter().flat_map(|w| w.to_array()))
                    {
                        assert_eq!(bits(x.extract(l)), bits(y), "n {n} lane {l}: base wrench");
                    }
                    for body in core::iter::once(None).chain((0..n).map(Some)) {
                        let a = lanes.body_wrench(&lanes_robot, body).unwrap().to_array();
                        let b = scalar.body_wrench(&robot, body).unwrap().to_array();
                        assert_eq!(a.map(|x| bits(x.extract(l))), b.map(bits), "n {n} lane {l}: body {body:?}");
                    }
                }
            }
        }
    }
}
