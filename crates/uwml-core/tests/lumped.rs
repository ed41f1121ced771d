//! Fossen's lumped model of a body (docs/model.md section 12.1) in the whole-robot evaluation:
//! the invariants of section 12.3 that hold at one state (the added mass does no work but
//! `−d/dt ½ νᵀ M_A ν`; a body moving with the water feels nothing; the damping's closed form per
//! axis; rotating the world changes nothing in body components), the cross-check with strip
//! theory (a lumped `M_A` equal to a slender segment's gives that segment's added-mass matrix and
//! forces), lanes against scalars (the checks at construction: `lumped_validation.rs`). The whole evaluation is held
//! against the independent numpy reference in the Python tests.
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing, clippy::expect_used)]

mod common;

use common::trees::{random_motion, random_robot, states};
use common::{Rng, random_psd};
use simba::simd::{SimdValue, WideF64x4};
use uwml_core::nalgebra::{Matrix3, Matrix6, UnitQuaternion, Vector3, Vector6};
use uwml_core::{
    BaseMotion, Conditions, Current, JointKind, LumpedBody, Owner, RigidBody, Robot, RobotData, RobotSegment, Section,
    TreeJoint, Water, robot_added_mass_matrix, robot_hydro,
};

const J: usize = 12;
const S: usize = 16;
type Model = Robot<f64, J, S, 4>;

/// A random lumped model on `owner`: `M_A`, a linear damping whose symmetric part is positive
/// semi-definite (plus a skew part), quadratic damping.
fn random_lumped(rng: &mut Rng, owner: Owner) -> LumpedBody<f64> {
    let skew = {
        let a: Matrix6<f64> = Matrix6::from_fn(|_, _| rng.next());
        a - a.transpose()
    };
    LumpedBody {
        owner,
        point: rng.vector(0.3),
        axes: *UnitQuaternion::from_scaled_axis(rng.vector::<3>(2.0)).to_rotation_matrix().matrix(),
        added_mass: random_psd(rng, 6, 20.0),
        linear_damping: random_psd(rng, 4, 10.0) + skew,
        quadratic_damping: core::array::from_fn(|_| 5.0 * rng.next().abs()),
    }
}

fn evaluate(
    robot: &Model,
    motion: &BaseMotion<f64>,
    current: &Current<f64>,
    state: &[[f64; J]; 3],
) -> RobotData<f64, J> {
    let mut data = RobotData::new();
    let conditions = Conditions { motion: *motion, current: *current, ..Conditions::new(Water::default()) };
    robot_hydro(robot, &conditions, [&state[0], &state[1], &state[2]], &mut data);
    data
}

/// A base and nothing else (one fixed-in-place joint-less robot), with `lumped` on the base.
fn base_only(lumped: LumpedBody<f64>) -> Model {
    Model::new(&[], &[], RigidBody::empty(), &[]).unwrap().with_lumped(&[lumped]).unwrap()
}

fn six(w: &uwml_core::Wrench<f64>) -> Vector6<f64> {
    let [a, b, c, d, e, f] = w.to_array();
    Vector6::new(a, b, c, d, e, f)
}

#[test]
fn the_added_mass_of_a_lumped_base_does_no_work_but_its_energy_rate() {
    // Still water: the power of the added-mass wrench is −ν_Pᵀ M_A ν̇_P (Fossen's C_A does no
    // work), with ν_P = (v + ω × P, ω) and ν̇_P = (v̇ + ω̇ × P, ω̇) for P fixed in the base.
    let mut rng = Rng(3);
    for _ in 0..20 {
        let lumped = LumpedBody {
            linear_damping: Matrix6::zeros(),
            quadratic_damping: [0.0; 6],
            ..random_lumped(&mut rng, Owner::Base)
        };
        let robot = base_only(lumped);
        let motion = random_motion(&mut rng);
        let ((v, w), (v_dot, w_dot)) = (motion.twist(), motion.twist_derivative());
        let data = evaluate(&robot, &motion, &Current::still(), &[[0.0; J]; 3]);
        let wrench = data.base_wrench().added_mass;
        let power = wrench.force.dot(&v) + wrench.moment.dot(&w);
        let p = lumped.point;
        let nu = Vector6::from_iterator((v + w.cross(&p)).iter().chain(w.iter()).copied());
        let nu_dot = Vector6::from_iterator((v_dot + w_dot.cross(&p)).iter().chain(w_dot.iter()).copied());
        // In the model's axes: ν_model = blockdiag(Aᵀ, Aᵀ) ν.
        let mut into_model = Matrix6::zeros();
        into_model.fixed_view_mut::<3, 3>(0, 0).copy_from(&lumped.axes.transpose());
        into_model.fixed_view_mut::<3, 3>(3, 3).copy_from(&lumped.axes.transpose());
        let (nu, nu_dot) = (into_model * nu, into_model * nu_dot);
        let expected = -(nu.transpose() * lumped.added_mass * nu_dot)[0];
        let scale = 1.0 + (nu.norm() * lumped.added_mass.norm() * (nu.norm() + nu_dot.norm()));
        assert!((power - expected).abs() <= 1e-12 * scale, "{power} vs {expected}");
        assert_eq!(data.base_wrench().drag.to_array(), [0.0; 6]);
    }
}

#[test]
fn the_damping_has_its_closed_form_on_each_axis_and_balances_a_force_at_the_terminal_speed() {
    // D_L = diag(d), D_Q = diag(q), a speed u along axis k only: the damping is −(d_k u + q_k u²)
    // on that axis and nothing elsewhere; a force F is balanced at u = (−d + √(d² + 4qF)) / 2q.
    let d = [40.0, 60.0, 80.0, 5.0, 6.0, 7.0];
    let q = [100.0, 140.0, 170.0, 2.0, 3.0, 4.0];
    let lumped = LumpedBody {
        owner: Owner::Base,
        point: Vector3::zeros(),
        axes: Matrix3::identity(),
        added_mass: Matrix6::from_diagonal(&Vector6::new(5.0, 7.0, 9.0, 0.1, 0.2, 0.3)),
        linear_damping: Matrix6::from_diagonal(&Vector6::from(d)),
        quadratic_damping: q,
    };
    let robot = base_only(lumped);
    let force = 75.0;
    for k in 0..6 {
        let u = (-d[k] + (d[k] * d[k] + 4.0 * q[k] * force).sqrt()) / (2.0 * q[k]);
        let mut twist = [0.0; 6];
        twist[k] = u;
        let (v, w) = (Vector3::new(twist[0], twist[1], twist[2]), Vector3::new(twist[3], twist[4], twist[5]));
        // Steady in the body's components, as a body at its terminal speed is (ν̇ = 0).
        let motion = BaseMotion::new([1.0, 0.0, 0.0, 0.0], v, w, Vector3::zeros(), Vector3::zeros()).unwrap();
        let drag = six(&evaluate(&robot, &motion, &Current::still(), &[[0.0; J]; 3]).base_wrench().drag);
        for (i, value) in drag.iter().enumerate() {
            let expected = if i == k { -force } else { 0.0 };
            assert!((value - expected).abs() <= 1e-12 * force, "axis {k}, component {i}: {value}");
        }
    }
}

#[test]
fn a_body_moving_with_the_water_feels_no_damping_and_no_added_mass() {
    let mut rng = Rng(5);
    for _ in 0..10 {
        let lumped = random_lumped(&mut rng, Owner::Base);
        let robot = base_only(lumped);
        let rotation = UnitQuaternion::from_scaled_axis(rng.vector::<3>(2.0));
        let body_velocity: Vector3<f64> = rng.vector(1.5);
        let motion = BaseMotion::new(
            [rotation.w, rotation.i, rotation.j, rotation.k],
            body_velocity,
            Vector3::zeros(),
            Vector3::zeros(),
            Vector3::zeros(),
        )
        .unwrap();
        let current = Current::new(rotation * body_velocity, Vector3::zeros()).unwrap();
        let data = evaluate(&robot, &motion, &current, &[[0.0; J]; 3]);
        let base = data.base_wrench();
        for value in base.drag.to_array().iter().chain(&base.added_mass.to_array()) {
            assert!(value.abs() <= 1e-12, "{value}");
        }
    }
}

/// A robot of random joints with lumped models on the base and on some links.
fn random_lumped_robot(rng: &mut Rng, n: usize) -> Model {
    random_lumped_robot_and_models(rng, n).0
}

/// [`random_lumped_robot`] and its lumped models as given.
fn random_lumped_robot_and_models(rng: &mut Rng, n: usize) -> (Model, Vec<LumpedBody<f64>>) {
    let robot: Model = random_robot(rng, n);
    let mut bodies = vec![random_lumped(rng, Owner::Base)];
    bodies.extend((0..n).filter(|i| i % 2 == 0).map(|i| random_lumped(rng, Owner::Link(i))));
    (robot.with_lumped(&bodies).unwrap(), bodies)
}

#[test]
fn turning_the_world_turns_nothing_in_the_bodies() {
    // The base's orientation, the current and its acceleration turned together: the joint forces
    // and the base wrench (base components) stay (buoyancy and gravity turn with gravity, which
    // stays: they are left out).
    let mut rng = Rng(9);
    for n in [1, 3, 5] {
        let robot = random_lumped_robot(&mut rng, n);
        let state = states::<J>(&mut rng, n);
        let motion = random_motion(&mut rng);
        let current = Current::new(rng.vector(0.5), rng.vector(0.5)).unwrap();
        let turn = UnitQuaternion::from_scaled_axis(rng.vector::<3>(2.0));
        let orientation = turn * UnitQuaternion::from_matrix(motion.rotation());
        let ((v, w), (v_dot, w_dot)) = (motion.twist(), motion.twist_derivative());
        let turned_motion =
            BaseMotion::new([orientation.w, orientation.i, orientation.j, orientation.k], v, w, v_dot, w_dot).unwrap();
        let turned_current = Current::new(turn * current.velocity(), turn * current.acceleration()).unwrap();
        let (a, b) =
            (evaluate(&robot, &motion, &current, &state), evaluate(&robot, &turned_motion, &turned_current, &state));
        for (x, y) in a.joint_forces().iter().zip(b.joint_forces()) {
            let scale = 1.0 + x.drag.abs() + x.added_mass.abs();
            assert!((x.drag - y.drag).abs() <= 1e-9 * scale && (x.added_mass - y.added_mass).abs() <= 1e-9 * scale);
        }
        for (x, y) in
            [(a.base_wrench().drag, b.base_wrench().drag), (a.base_wrench().added_mass, b.base_wrench().added_mass)]
        {
            let (x, y) = (six(&x), six(&y));
            assert!((x - y).amax() <= 1e-9 * (1.0 + x.amax()), "{x} vs {y}");
        }
    }
}

#[test]
fn a_lumped_added_mass_equal_to_a_slender_segments_gives_its_matrix_and_forces() {
    // A rectangular segment along x from `start`, length L, normals y and z: per length
    // m_k = ρ A cm_k along normal k; about its midpoint M_A = diag(0, m_y L, m_z L, 0, m_z L³/12,
    // m_y L³/12). With its drag off, the same added-mass matrix and, at zero velocity, the same
    // added-mass forces.
    let mut rng = Rng(13);
    let water = Water::default();
    let (length, area, cm) = (0.6, 0.004, [0.7, 1.3]);
    let start = Vector3::new(0.05, -0.02, 0.01);
    let joints = [
        TreeJoint { parent: None, kind: JointKind::Revolute, origin: Vector3::new(0.1, 0.0, 0.2), axis: Vector3::z() },
        TreeJoint {
            parent: Some(0),
            kind: JointKind::Revolute,
            origin: Vector3::new(0.3, 0.0, 0.0),
            axis: Vector3::y(),
        },
    ];
    let links = [RigidBody::empty(); 2];
    let segment = RobotSegment {
        owner: Owner::Link(1),
        start,
        axis: Vector3::x(),
        length,
        area,
        section: Section::Rectangular { normals: [Vector3::y(), Vector3::z()], widths: [0.05, 0.08] },
        cd: [0.0; 2],
        cm,
        cd_axial: 0.0,
        axial_area: 0.0,
    };
    let strips = Model::new(&joints, &links, RigidBody::empty(), &[segment]).unwrap();
    let (my, mz) = (water.density() * area * cm[0], water.density() * area * cm[1]);
    let l3 = length * length * length / 12.0;
    let lumped = LumpedBody {
        owner: Owner::Link(1),
        point: start + Vector3::x() * (length / 2.0),
        axes: Matrix3::identity(),
        added_mass: Matrix6::from_diagonal(&Vector6::new(0.0, my * length, mz * length, 0.0, mz * l3, my * l3)),
        linear_damping: Matrix6::zeros(),
        quadratic_damping: [0.0; 6],
    };
    let lumped_robot = Model::new(&joints, &links, RigidBody::empty(), &[]).unwrap().with_lumped(&[lumped]).unwrap();
    for _ in 0..10 {
        let mut state = states::<J>(&mut rng, 2);
        state[1] = [0.0; J];
        let (mut a, mut b) = ([0.0; 64], [0.0; 64]);
        robot_added_mass_matrix(&strips, &water, None, &state[0], &mut a);
        robot_added_mass_matrix(&lumped_robot, &water, None, &state[0], &mut b);
        let scale = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for (x, y) in a.iter().zip(&b) {
            assert!((x - y).abs() <= 1e-12 * scale, "{x} vs {y}");
        }
        // At rest in still water with accelerations: the same added-mass forces.
        let motion =
            BaseMotion::new([1.0, 0.0, 0.0, 0.0], Vector3::zeros(), Vector3::zeros(), rng.vector(1.0), rng.vector(1.0))
                .unwrap();
        let (x, y) = (
            evaluate(&strips, &motion, &Current::still(), &state),
            evaluate(&lumped_robot, &motion, &Current::still(), &state),
        );
        for (f, g) in x.joint_forces().iter().zip(y.joint_forces()) {
            assert!((f.added_mass - g.added_mass).abs() <= 1e-12 * (1.0 + f.added_mass.abs()));
        }
        let (f, g) = (six(&x.base_wrench().added_mass), six(&y.base_wrench().added_mass));
        assert!((f - g).amax() <= 1e-12 * (1.0 + f.amax()), "{f} vs {g}");
    }
}

#[test]
fn four_states_on_lanes_are_the_scalar_evaluations_bit_for_bit() {
    let mut rng = Rng(17);
    let robot = random_lumped_robot(&mut rng, 4);
    let lanes_robot = robot.splat::<WideF64x4>();
    let motions: [BaseMotion<f64>; 4] = core::array::from_fn(|_| random_motion(&mut rng));
    let currents: [Current<f64>; 4] = core::array::from_fn(|_| Current::new(rng.vector(0.5), rng.vector(0.5)).unwrap());
    let state: [[[f64; J]; 3]; 4] = core::array::from_fn(|_| states::<J>(&mut rng, 4));
    let gather = |k: usize| -> [WideF64x4; J] { core::array::from_fn(|j| WideF64x4::from(state.map(|s| s[k][j]))) };
    let (q, qd, qdd) = (gather(0), gather(1), gather(2));
    let conditions = Conditions {
        motion: BaseMotion::from_lanes(&motions),
        current: Current::from_lanes(&currents),
        ..Conditions::new(Water::default().splat())
    };
    let mut data = RobotData::<WideF64x4, J>::new();
    robot_hydro(&lanes_robot, &conditions, [&q, &qd, &qdd], &mut data);
    for l in 0..4 {
        let scalar = evaluate(&robot, &motions[l], &currents[l], &state[l]);
        for (x, y) in data.joint_forces().iter().zip(scalar.joint_forces()) {
            assert_eq!((x.drag.extract(l), x.added_mass.extract(l)), (y.drag, y.added_mass));
        }
        let (x, y) = (data.base_wrench().drag.to_array(), scalar.base_wrench().drag.to_array());
        assert_eq!(x.map(|v| v.extract(l)), y);
    }
}

#[test]
fn regressors_times_every_coefficient_are_the_forces_of_lumped_models_and_axial_drag() {
    // docs/model.md section 12.1: the forces are linear in each entry of M_A, D_L and D_Q (in the
    // model's own axes), and 12.2 in cd_axial; Σ columns × coefficients is the evaluation's drag
    // and added mass on every row, in both added-mass forms, on moving bases in a current.
    use uwml_core::{AddedMassForm, LUMPED_COLUMNS, robot_hydro_regressors};
    let mut rng = Rng(83);
    for round in 0..40 {
        let n = 1 + round % 6;
        let (robot, models) = random_lumped_robot_and_models(&mut rng, n);
        let s = states(&mut rng, n);
        let motion = random_motion(&mut rng);
        let current = Current::new(rng.vector::<3>(1.0), rng.vector::<3>(1.0)).unwrap();
        let form = if round % 2 == 0 { AddedMassForm::Morison } else { AddedMassForm::Kirchhoff };
        let conditions = Conditions { motion, current, form, ..Conditions::new(Water::default()) };
        let columns = robot.regressor_column_count();
        let segments = robot.segments().len();
        let rows = 6 + n;
        let (mut drag, mut added_mass) = (vec![f64::NAN; rows * columns], vec![f64::NAN; rows * columns]);
        let mut data = RobotData::new();
        robot_hydro_regressors(&robot, &conditions, [&s[0], &s[1], &s[2]], &mut data, &mut drag, &mut added_mass);
        let mut expected = RobotData::new();
        robot_hydro(&robot, &conditions, [&s[0], &s[1], &s[2]], &mut expected);
        assert_eq!(columns, 3 * segments + LUMPED_COLUMNS * models.len());
        // Every coefficient, in the layout of the columns.
        let mut coefficients = vec![0.0; columns];
        for (k, segment) in robot.segments().iter().enumerate() {
            coefficients[2 * k] = segment.cd[0];
            coefficients[2 * k + 1] = segment.cd[1];
            coefficients[2 * segments + k] = segment.cd_axial;
        }
        let mut added = coefficients.clone();
        for (k, segment) in robot.segments().iter().enumerate() {
            added[2 * k] = segment.cm[0];
            added[2 * k + 1] = segment.cm[1];
            added[2 * segments + k] = 0.0;
        }
        for (b, model) in models.iter().enumerate() {
            let first = 3 * segments + LUMPED_COLUMNS * b;
            let mut i = first;
            for r in 0..6 {
                for c in r..6 {
                    added[i] = model.added_mass[(r, c)];
                    coefficients[i] = 0.0;
                    i += 1;
                }
            }
            for r in 0..6 {
                for c in 0..6 {
                    coefficients[i] = model.linear_damping[(r, c)];
                    added[i] = 0.0;
                    i += 1;
                }
            }
            for r in 0..6 {
                coefficients[i] = model.quadratic_damping[r];
                added[i] = 0.0;
                i += 1;
            }
            assert_eq!(i, first + LUMPED_COLUMNS);
        }
        let sum = |table: &[f64], c: &[f64], row: usize| -> f64 {
            (0..columns).map(|k| table[row * columns + k] * c[k]).sum()
        };
        let base = expected.base_wrench();
        let mut want: Vec<(f64, f64)> =
            base.drag.to_array().iter().zip(base.added_mass.to_array()).map(|(d, m)| (*d, m)).collect();
        want.extend(expected.joint_forces().iter().map(|f| (f.drag, f.added_mass)));
        let scale = want.iter().fold(1.0_f64, |m, (d, a)| m.max(d.abs()).max(a.abs()));
        for (row, (d, m)) in want.iter().enumerate() {
            let (got_d, got_m) = (sum(&drag, &coefficients, row), sum(&added_mass, &added, row));
            assert!((got_d - d).abs() <= 1e-11 * scale, "round {round}, row {row}: drag {got_d} vs {d}");
            assert!((got_m - m).abs() <= 1e-11 * scale, "round {round}, row {row}: added mass {got_m} vs {m}");
        }
        // The axial columns have no added mass; the lumped damping none either, and the added
        // mass no drag.
        for row in 0..rows {
            for k in 0..segments {
                assert_eq!(added_mass[row * columns + 2 * segments + k], 0.0);
            }
            for b in 0..models.len() {
                let first = 3 * segments + LUMPED_COLUMNS * b;
                assert!((first..first + 21).all(|c| drag[row * columns + c] == 0.0));
                assert!((first + 21..first + LUMPED_COLUMNS).all(|c| added_mass[row * columns + c] == 0.0));
            }
        }
    }
}
