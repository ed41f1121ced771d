//! Calls every public evaluation function of uwml-core, for `f32` and `f64` and for serial chains
//! of 1, 3 (the paper's leg, `presets::paper_leg`) and 6 joints and a tree with a prismatic joint
//! and circular segments on a moving base in a current, and the evaluation over SIMD lanes
//! (`WideF32x4`, `WideF64x4`), on inputs hidden from the optimizer by `black_box`, and counts the
//! results that are not what they should be (finite, or NaN for a NaN state).
//!
//! Shared by the no_std binary (src/main.rs: the link proof) and the hosted one
//! (src/bin/no_panic_proof.rs: the no-panic proof), so both prove the same instantiations.

use core::hint::black_box;

use simba::simd::{SimdRealField, WideF32x4, WideF64x4};
use uwml_core::nalgebra::{Matrix3, Matrix6, RealField, SVector, Vector3, Vector6, convert};
use uwml_core::strip::{added_mass_moments, circular_speed_moments, drag_moments};
use uwml_core::{AddedMassForm, BaseMotion, Conditions, Current, JointKind, JointLosses, KinematicsData, LossState, LumpedBody, OilDrag, Owner, RigidBody, Robot, RobotData, RobotJacobianData, RobotJacobians, RobotSegment, Section, SegmentCoefficients, TreeJoint, Water, check_conditions, forward_kinematics, loss_torques, point_jacobian, presets, pressure_at_depth, robot_added_mass_matrix, robot_hydro, robot_joint_added_mass_matrix, robot_hydro_regressors, robot_jacobians, smooth_sign};

/// Counts unexpected results.
struct Tally<T> {
    bad: u32,
    _real: core::marker::PhantomData<T>,
}

impl<T: RealField + Copy> Tally<T> {
    fn finite(&mut self, x: T) {
        if !black_box(x).is_finite() {
            self.bad += 1;
        }
    }

    fn all_finite<'a>(&mut self, xs: impl IntoIterator<Item = &'a T>)
    where
        T: 'a,
    {
        for &x in xs {
            self.finite(x);
        }
    }

    fn nan(&mut self, x: T) {
        let x = black_box(x);
        if x == x {
            self.bad += 1;
        }
    }

    fn expect(&mut self, ok: bool) {
        if !black_box(ok) {
            self.bad += 1;
        }
    }
}

fn c<T: RealField + Copy>(x: f64) -> T {
    convert(black_box(x))
}

fn vector<T: RealField + Copy, const N: usize>(base: f64, step: f64) -> SVector<T, N> {
    SVector::from_fn(|i, _| c(base + step * i as f64))
}

/// A serial chain of `N` revolute joints on a fixed base whose axes turn between z, −y and x,
/// with rectangular segments along and across them (aligned and general body frames) and every
/// third link without one.
fn chain<T: RealField + Copy, const N: usize>() -> Option<Robot<T, N, N>> {
    let v = |x: f64, y: f64, z: f64| Vector3::new(c(x), c(y), c(z));
    let joints: [TreeJoint<T>; N] = core::array::from_fn(|i| TreeJoint {
        parent: i.checked_sub(1),
        kind: JointKind::Revolute,
        origin: v(0.1 * i as f64, 0.02, -0.03 * i as f64),
        axis: match i % 3 {
            0 => v(0.0, 0.0, 1.0),
            1 => v(0.0, -1.0, 0.0),
            _ => v(1.0, 0.0, 0.0),
        },
    });
    let links: [RigidBody<T>; N] = core::array::from_fn(|i| {
        let mass = 2.0 + i as f64;
        RigidBody { mass: c(mass), com: v(0.2, 0.01 * i as f64, -0.05), volume: c(mass / 2700.0), cob: v(0.2, 0.0, -0.04) }
    });
    let segment = |i: usize| {
        let tilt = 0.25 * i as f64;
        let (s, co) = (sin_series(tilt), cos_series(tilt));
        RobotSegment {
            owner: Owner::Link(i),
            start: v(0.0, 0.0, 0.01 * i as f64),
            axis: v(co, 0.0, s),
            length: c(0.4 + 0.1 * i as f64),
            area: c(0.02),
            section: Section::Rectangular { normals: [v(0.0, 1.0, 0.0), v(-s, 0.0, co)], widths: [c(0.1), c(0.2)] },
            cd: [c(2.2); 2],
            cm: [c(0.5); 2],
            cd_axial: T::zero(),
            axial_area: T::zero(),
        }
    };
    // Every third link without a segment: the segments of the others, in link order.
    let mut used = [segment(0); N];
    let mut count = 0;
    for (slot, i) in used.iter_mut().zip((0..N).filter(|i| i % 3 != 2)) {
        *slot = segment(i);
        count += 1;
    }
    Robot::new(black_box(&joints), black_box(&links), RigidBody::empty(), used.get(..count).unwrap_or(&[])).ok()
}

/// `sin` by its Taylor series, for the small test angles here: the check crate itself needs no
/// float library.
fn sin_series(x: f64) -> f64 {
    let x2 = x * x;
    x * (1.0 - x2 / 6.0 * (1.0 - x2 / 20.0 * (1.0 - x2 / 42.0 * (1.0 - x2 / 72.0))))
}

fn cos_series(x: f64) -> f64 {
    let x2 = x * x;
    1.0 - x2 / 2.0 * (1.0 - x2 / 12.0 * (1.0 - x2 / 30.0 * (1.0 - x2 / 56.0 * (1.0 - x2 / 90.0))))
}

/// Per-joint losses: none, the default, and oil with exponents 1.2 (`powf`), 1.5 (`sqrt`) and 2, so
/// that every branch of `LossState::evaluate` is instantiated and, for 6 joints, taken.
fn losses<T: RealField + Copy, const N: usize>(pressure: T, temperature: T) -> [Option<LossState<T>>; N] {
    let oil = |n: f64| OilDrag::new(c(1e-3), c(n), c(2e-8), c(0.06), c(0.0), c(20.0)).ok();
    core::array::from_fn(|i| {
        let mut joint = JointLosses::<T>::default();
        match i % 6 {
            0 => return None,
            1 | 5 => {}
            2 => joint.oil = oil(1.2),
            3 => joint.oil = oil(1.5),
            _ => joint.oil = oil(2.0),
        }
        joint.at(pressure, temperature).ok()
    })
}

/// Every evaluation function at one joint state of one chain on a fixed base in still water.
fn evaluate<T: RealField + uwml_core::Real, const N: usize, const S: usize>(chain: &Robot<T, N, S>, tally: &mut Tally<T>) {
    let water = black_box(Water::<T>::default());
    let (q, qd, qdd): ([T; N], [T; N], [T; N]) =
        (vector::<T, N>(0.3, -0.2).into(), vector::<T, N>(0.8, -0.45).into(), vector::<T, N>(1.0, -0.7).into());
    let (q, qd, qdd) = (black_box(q), black_box(qd), black_box(qdd));
    let mut data = RobotData::<T, N>::new();
    let table = black_box(SegmentCoefficients::<T, S>::uniform(c(1.0), c(0.8)));
    let conditions = Conditions { coefficients: table.as_ref().ok(), ..Conditions::new(water) };
    robot_hydro(chain, &conditions, [&q, &qd, &qdd], &mut data);
    for forces in data.joint_forces() {
        tally.all_finite([forces.total(), forces.gravity].iter());
    }

    // Outside the domain the constructors refuse (a refusal counts as a failure here).
    let pressure = pressure_at_depth(c(1000.0), c(1025.0), c(9.81)).unwrap_or(c(f64::NAN));
    tally.finite(pressure);
    tally.finite(pressure_at_depth::<T>(black_box(c(-1.0)), c(1025.0), c(9.81)).map_or(c(0.0), |_| c(f64::NAN)));
    tally.finite(check_conditions::<T>(black_box(pressure), black_box(c(-300.0))).map_or(c(0.0), |()| c(f64::NAN)));
    let losses = black_box(losses::<T, N>(pressure, c(4.0)));
    robot_hydro(chain, &Conditions { losses: Some(&losses), ..Conditions::new(water) }, [&q, &qd, &qdd], &mut data);
    for loss in data.joint_losses() {
        tally.all_finite([loss.visc, loss.seal, loss.current].iter());
    }
    let (visc, seal, current) = loss_torques(&losses, &SVector::from(qd));
    let same = data.joint_losses().iter().enumerate().all(|(i, l)| {
        (Some(&l.visc), Some(&l.seal), Some(&l.current)) == (visc.get(i), seal.get(i), current.get(i))
    });
    tally.expect(same);
    for (state, &speed) in losses.iter().flatten().zip(qd.iter()) {
        let split = state.dry_friction_split(speed);
        tally.all_finite([split.friction, split.damping].iter());
        tally.expect(state.dry_friction_split(black_box(c(0.0))).friction >= c(0.0));
    }

    // A NaN state gives non-finite (NaN) forces everywhere, not only where the NaN reaches.
    let mut nan = q;
    if let Some(first) = nan.get_mut(0) {
        *first = c(f64::NAN);
    }
    robot_hydro(chain, &Conditions::new(water), [&black_box(nan), &qd, &qdd], &mut data);
    tally.expect(data.joint_forces().iter().all(|f| !f.total().is_finite()));

    // Kinematics: every link's pose, and the last link's point Jacobian.
    let mut kinematics = KinematicsData::<T, N>::new();
    forward_kinematics(chain, &q, &mut kinematics);
    let point = black_box(Vector3::new(c(0.1), c(-0.05), c(0.2)));
    for pose in kinematics.poses() {
        tally.all_finite(pose.point(&point).iter().chain(pose.rotation.iter()));
    }
    let mut jacobian = [c::<T>(f64::NAN); 36];
    match point_jacobian(chain, &kinematics, black_box(N - 1), &point, &mut jacobian) {
        Some(position) => tally.all_finite(position.iter().chain(jacobian.iter().take(6 * N))),
        None => tally.expect(false),
    }
    tally.expect(point_jacobian(chain, &kinematics, black_box(N), &point, &mut jacobian).is_none());
}

/// A tree of four joints (one prismatic, two from the base) with rectangular and circular
/// segments on a base body, and lumped models (docs/model.md section 12.1) on the base and a link.
fn robot<T: RealField + Copy>() -> Option<Robot<T, 6, 6, 2>> {
    let v = |x: f64, y: f64, z: f64| Vector3::new(c(x), c(y), c(z));
    let joint = |parent, kind, origin, axis| TreeJoint { parent, kind, origin, axis };
    let joints = [
        joint(None, JointKind::Revolute, v(0.3, 0.0, 0.0), v(0.0, 0.0, 1.0)),
        joint(Some(0), JointKind::Prismatic, v(0.2, 0.0, 0.0), v(1.0, 0.0, 0.0)),
        joint(None, JointKind::Revolute, v(-0.3, 0.0, 0.0), v(0.0, 1.0, 0.0)),
        joint(Some(2), JointKind::Revolute, v(0.0, 0.0, -0.4), v(0.6, 0.8, 0.0)),
    ];
    let body = |m: f64| RigidBody { mass: c(m), com: v(0.1, 0.0, -0.1), volume: c(m / 2700.0), cob: v(0.1, 0.0, -0.1) };
    let circular = |owner, axis| RobotSegment {
        owner,
        start: v(0.0, 0.0, 0.0),
        axis,
        length: c(0.4),
        area: c(0.005),
        section: Section::Circular { diameter: c(0.08) },
        cd: [c(1.2); 2],
        cm: [c(1.0); 2],
        cd_axial: T::zero(),
        axial_area: T::zero(),
    };
    let rectangular = |owner| RobotSegment {
        section: Section::Rectangular { normals: [v(0.0, 1.0, 0.0), v(0.0, 0.0, 1.0)], widths: [c(0.1), c(0.2)] },
        cd: [c(2.2); 2],
        cm: [c(0.5); 2],
        ..circular(owner, v(1.0, 0.0, 0.0))
    };
    let segments = [
        circular(Owner::Base, v(1.0, 0.0, 0.0)),
        rectangular(Owner::Link(0)),
        circular(Owner::Link(1), v(0.0, 0.0, -1.0)),
        circular(Owner::Link(3), v(0.0, 0.6, 0.8)),
    ];
    let diagonal = |d: [f64; 6]| Matrix6::from_diagonal(&Vector6::from(d.map(c::<T>)));
    let mut added_mass = diagonal([40.0, 60.0, 80.0, 2.0, 3.0, 4.0]);
    added_mass[(1, 5)] = c(1.5);
    added_mass[(5, 1)] = c(1.5);
    let hull = LumpedBody {
        owner: Owner::Base,
        point: v(0.0, 0.0, 0.05),
        axes: Matrix3::identity(),
        added_mass,
        linear_damping: diagonal([20.0, 30.0, 40.0, 1.0, 1.5, 2.0]),
        quadratic_damping: [100.0, 140.0, 170.0, 2.0, 3.0, 4.0].map(c::<T>),
    };
    let can = LumpedBody { owner: Owner::Link(3), point: v(0.1, 0.0, 0.0), ..hull };
    Robot::new(&joints, &[body(4.0), body(3.0), body(2.0), body(1.0)], body(50.0), &segments)
        .and_then(|robot| robot.with_lumped(&[hull, can]))
        .ok()
}

/// The whole-robot path on a moving base in a current, and a NaN state.
fn evaluate_robot<T: RealField + uwml_core::Real>(robot: &Robot<T, 6, 6, 2>, tally: &mut Tally<T>) {
    let water = black_box(Water::<T>::default());
    let (q, qd, qdd): ([T; 6], [T; 6], [T; 6]) =
        (vector::<T, 6>(0.3, -0.2).into(), vector::<T, 6>(0.8, -0.45).into(), vector::<T, 6>(1.0, -0.7).into());
    let (q, qd, qdd) = (black_box(q), black_box(qd), black_box(qdd));
    let v = |x: f64, y: f64, z: f64| Vector3::new(c(x), c(y), c(z));
    let half = c::<T>(0.5);
    let (Ok(motion), Ok(current)) = (
        BaseMotion::new(
            [half, half, half, half],
            v(0.5, 0.1, 0.0),
            v(0.0, 0.2, 0.1),
            v(0.1, 0.0, 0.3),
            v(0.0, 0.0, 0.2),
        ),
        Current::new(v(0.2, 0.0, 0.0), v(0.0, 0.05, 0.0)),
    ) else {
        return tally.expect(false);
    };
    let mut data = RobotData::<T, 6>::new();
    robot_hydro(robot, &Conditions { motion: black_box(motion), current: black_box(current), ..Conditions::new(water) }, [&q, &qd, &qdd], &mut data);
    for forces in data.joint_forces() {
        tally.all_finite([forces.total(), forces.gravity].iter());
    }
    let base = data.base_wrench();
    tally.all_finite(base.total().to_array().iter().chain(base.gravity.to_array().iter()));
    for body in [None, Some(0), Some(3)] {
        match data.body_wrench(robot, body) {
            Some(w) => tally.all_finite(w.to_array().iter()),
            None => tally.expect(false),
        }
    }
    tally.expect(data.body_wrench(robot, Some(4)).is_none());
    // Kirchhoff's added mass: the same forces but the added mass's velocity terms.
    let morison = data.base_wrench().total().to_array();
    let form = black_box(AddedMassForm::Kirchhoff);
    robot_hydro(robot, &Conditions { motion, current, form, ..Conditions::new(water) }, [&q, &qd, &qdd], &mut data);
    let kirchhoff = data.base_wrench().total().to_array();
    tally.all_finite(kirchhoff.iter());
    tally.expect(kirchhoff != morison);
    // Regressors, the added-mass matrix and the derivatives (10 = 6 + 4 rows).
    // Every column: the segments' (three each) and the lumped models' (63 each).
    let (mut drag, mut added_mass) = ([c::<T>(f64::NAN); 1500], [c::<T>(f64::NAN); 1500]);
    let width = 10 * robot.regressor_column_count();
    tally.expect(width > 10 * 3 * 4 && width <= 1500);
    robot_hydro_regressors(robot, &Conditions { motion, current, ..Conditions::new(water) }, [&q, &qd, &qdd], &mut data, &mut drag, &mut added_mass);
    tally.all_finite(drag.iter().take(width).chain(added_mass.iter().take(width)));
    let mut matrix = [c::<T>(f64::NAN); 100];
    robot_added_mass_matrix(robot, &water, None, &q, &mut matrix);
    tally.all_finite(matrix.iter());
    let mut block = [c::<T>(f64::NAN); 16];
    robot_joint_added_mass_matrix(robot, &water, None, &q, &mut block);
    tally.all_finite(block.iter());
    tally.expect(block[0] == matrix[66]);
    let (mut value, mut d_q, mut d_velocity, mut m_a) =
        ([c::<T>(f64::NAN); 10], [c::<T>(f64::NAN); 40], [c::<T>(f64::NAN); 100], [c::<T>(f64::NAN); 100]);
    let mut work = RobotJacobianData::new(robot);
    let out =
        RobotJacobians { value: &mut value, d_q: &mut d_q, d_velocity: &mut d_velocity, added_mass_matrix: &mut m_a };
    robot_jacobians(robot, &Conditions { motion, current, losses: Some(&[None; 6]), ..Conditions::new(water) }, [&q, &qd, &qdd], &mut work, out);
    tally.all_finite(value.iter().chain(d_q.iter()).chain(d_velocity.iter()).chain(m_a.iter()));
    tally.expect(m_a == matrix);
    let mut nan = q;
    nan[1] = c(f64::NAN);
    robot_hydro(robot, &Conditions { motion, current, ..Conditions::new(water) }, [&black_box(nan), &qd, &qdd], &mut data);
    tally.expect(data.joint_forces().iter().all(|f| !f.total().is_finite()));
    tally.expect(data.base_wrench().drag.to_array().iter().all(|x| !x.is_finite()));
}

/// The scalar functions, for one float type.
fn scalars<T: RealField + Copy>(tally: &mut Tally<T>) {
    for (x, epsilon) in [(0.3, 1e-3), (-2.0, 0.0), (0.0, 0.0), (1e-30, 1e-3)] {
        tally.finite(smooth_sign(c::<T>(x), c(epsilon)));
    }
    // With and without a sign change of the normal speed along the segment.
    for (v0, v1) in [(-1.0, 3.0), (0.5, 0.25), (0.0, 0.0)] {
        let (a, b) = drag_moments(c::<T>(v0), c(v1), c(0.7));
        let (m0, m1) = added_mass_moments(c::<T>(v0), c(v1), c(0.7));
        tally.all_finite([a, b, m0, m1].iter());
    }
    // The normal speed of a circular segment: through zero inside, nearly, and uniform.
    for (p, r) in
        [((-0.3, 0.1, 0.0), (1.0, 0.0, 0.0)), ((-0.3, 1e-9, 0.0), (1.0, 0.0, 0.0)), ((0.2, 0.1, 0.0), (0.0, 0.0, 0.0))]
    {
        let v = |(x, y, z): (f64, f64, f64)| Vector3::new(c::<T>(x), c(y), c(z));
        tally.all_finite(circular_speed_moments(&v(p), &v(r), c(0.7)).iter());
    }
    let oil = OilDrag::<T>::default();
    tally.finite(oil.scale(c(1e7), c(4.0)));
    let (running, breakaway, viscous) = uwml_core::Seal::<T>::default().levels(c(1e7));
    tally.all_finite([running, breakaway, viscous].iter());
}

fn for_type<T: RealField + uwml_core::Real>() -> u32 {
    let mut tally = Tally::<T> { bad: 0, _real: core::marker::PhantomData };
    scalars(&mut tally);
    match chain::<T, 1>() {
        Some(chain) => evaluate(&black_box(chain), &mut tally),
        None => tally.expect(false),
    }
    evaluate(&black_box(presets::paper_leg::<T>()), &mut tally);
    match chain::<T, 3>() {
        Some(chain) => evaluate(&black_box(chain), &mut tally),
        None => tally.expect(false),
    }
    match chain::<T, 6>() {
        Some(chain) => evaluate(&black_box(chain), &mut tally),
        None => tally.expect(false),
    }
    match robot::<T>() {
        Some(robot) => evaluate_robot(&black_box(robot), &mut tally),
        None => tally.expect(false),
    }
    tally.bad
}

/// The evaluation over SIMD lanes (four states per call, the batch path of the Python bindings),
/// with a NaN in one lane, which must give NaN in that lane only, and the regressors.
fn lanes<L: SimdRealField + uwml_core::Real, const N: usize, const S: usize>(
    chain: &Robot<L::Element, N, S>,
    tally: &mut Tally<L::Element>,
) where
    L::Element: RealField + uwml_core::Real,
{
    let (lane_chain, water) = (chain.splat::<L>(), Water::default().splat::<L>());
    let lanes = |base: f64, step: f64| -> [L; N] {
        core::array::from_fn(|i| {
            let mut lane = L::splat(c(base + step * i as f64));
            for l in 0..L::LANES {
                lane.replace(l, c(base + step * i as f64 + 0.1 * l as f64));
            }
            lane
        })
    };
    let (q, qd, qdd) = (black_box(lanes(0.3, -0.2)), black_box(lanes(0.8, -0.45)), black_box(lanes(1.0, -0.7)));
    let mut nan_q = q;
    if let Some(first) = nan_q.get_mut(0) {
        first.replace(0, c(f64::NAN));
    }
    let nan = black_box(nan_q);
    let mut data = RobotData::<L, N>::new();
    let (mut drag, mut added_mass) = ([L::zero(); 200], [L::zero(); 200]);
    let conditions = Conditions::new(water);
    robot_hydro_regressors(&lane_chain, &conditions, [&nan, &qd, &qdd], &mut data, &mut drag, &mut added_mass);
    let width = (6 + N) * chain.regressor_column_count();
    // Value by value, lane by lane (a short loop of a constant count: no bounds check left).
    let forces = data.joint_forces().iter().map(|f| f.buoyancy);
    for x in drag.iter().chain(added_mass.iter()).take(width).copied().chain(forces) {
        tally.nan(x.extract(0));
        for l in 1..L::LANES {
            tally.finite(x.extract(l));
        }
    }
    robot_hydro(&lane_chain, &conditions, [&q, &qd, &qdd], &mut data);
    for forces in data.joint_forces() {
        for l in 0..L::LANES {
            tally.finite(forces.total().extract(l));
        }
    }
}

fn for_lanes() -> u32 {
    let (mut single, mut double) = (
        Tally::<f32> { bad: 0, _real: core::marker::PhantomData },
        Tally::<f64> { bad: 0, _real: core::marker::PhantomData },
    );
    lanes::<WideF32x4, 3, 2>(&black_box(presets::paper_leg()), &mut single);
    lanes::<WideF64x4, 3, 2>(&black_box(presets::paper_leg()), &mut double);
    match chain::<f64, 6>() {
        Some(chain) => lanes::<WideF64x4, 6, 6>(&black_box(chain), &mut double),
        None => double.expect(false),
    }
    single.bad + double.bad
}

/// The number of unexpected results over all calls: 0 when everything is as it should be.
pub fn exercise() -> u32 {
    for_type::<f32>() + for_type::<f64>() + for_lanes()
}
