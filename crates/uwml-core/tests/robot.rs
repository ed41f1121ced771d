//! Whole robots (docs/model.md section 10): the invariants (its "Invariants"), the regressors and
//! jacobians. (The checks at construction are in `robot_validation.rs`, the added-mass matrix in
//! `added_mass.rs`, the circular strip integrals against dense quadrature in `strip.rs`.)
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing, clippy::expect_used)]

use uwml_core::nalgebra::{UnitQuaternion, Vector3};
use uwml_core::{
    BaseMotion, Conditions, Current, EnvironmentWrench, JointKind, Owner, RigidBody, Robot, RobotData,
    RobotJacobianData, RobotJacobians, RobotSegment, SegmentCoefficients, TreeJoint, Water, robot_hydro,
    robot_hydro_regressors, robot_jacobians,
};

mod common;
use common::Rng;
use common::trees::{added_mass_matrix, assert_close, evaluate, random_motion};

const J: usize = 12;
const S: usize = 16;
type Model = Robot<f64, J, S>;

fn random_robot(rng: &mut Rng, n: usize) -> Model {
    common::trees::random_robot(rng, n)
}

fn states(rng: &mut Rng, n: usize) -> [[f64; J]; 3] {
    common::trees::states(rng, n)
}

fn wrench_scale(w: &EnvironmentWrench<f64>) -> f64 {
    [w.drag, w.added_mass, w.buoyancy, w.gravity]
        .iter()
        .flat_map(|w| w.to_array())
        .fold(1e-300_f64, |m, x| m.max(x.abs()))
}

#[test]
fn frame_invariance_rotating_the_base_and_the_current_together() {
    let mut rng = Rng(21);
    for trial in 0..200 {
        let n = 1 + (rng.next().abs() * 8.0) as usize;
        let robot = random_robot(&mut rng, n);
        let s = states(&mut rng, n);
        let motion = random_motion(&mut rng);
        let current = Current::new(rng.vector::<3>(1.0), rng.vector::<3>(1.0)).unwrap();
        // Gravity stays put: buoyancy and gravity are invariant under turns about the vertical
        // only; drag and added mass under any turn.
        let vertical = trial % 2 == 0;
        let turn = if vertical {
            UnitQuaternion::from_scaled_axis(Vector3::z() * (3.0 * rng.next()))
        } else {
            UnitQuaternion::from_scaled_axis(rng.vector::<3>(3.0))
        };
        let q = turn * UnitQuaternion::from_matrix(motion.rotation());
        let (v, w) = motion.twist();
        let (vd, wd) = motion.twist_derivative();
        let turned = BaseMotion::new([q.w, q.i, q.j, q.k], v, w, vd, wd).unwrap();
        let turned_current = Current::new(turn * current.velocity(), turn * current.acceleration()).unwrap();
        let a = evaluate(&robot, None, &motion, &current, &s);
        let b = evaluate(&robot, None, &turned, &turned_current, &s);
        let scale = wrench_scale(a.base_wrench());
        let (wa, wb) = (a.base_wrench(), b.base_wrench());
        let mut pairs = vec![(wa.drag, wb.drag), (wa.added_mass, wb.added_mass)];
        if vertical {
            pairs.extend([(wa.buoyancy, wb.buoyancy), (wa.gravity, wb.gravity)]);
        }
        for (x, y) in pairs {
            for (x, y) in x.to_array().iter().zip(y.to_array()) {
                assert_close(*x, y, scale, 1e-12, "base wrench");
            }
        }
        for (x, y) in a.joint_forces().iter().zip(b.joint_forces()) {
            assert_close(x.drag, y.drag, scale, 1e-12, "joint drag");
            assert_close(x.added_mass, y.added_mass, scale, 1e-12, "joint added mass");
            if vertical {
                assert_close(x.buoyancy, y.buoyancy, scale, 1e-12, "joint buoyancy");
                assert_close(x.gravity, y.gravity, scale, 1e-12, "joint gravity");
            }
        }
        if !vertical {
            // And a turn off the vertical does change the static part (the test can fail).
            assert!((wa.buoyancy.moment - wb.buoyancy.moment).norm() > 0.0 || wa.buoyancy.moment.norm() == 0.0);
        }
    }
}

#[test]
fn galilean_a_base_moving_with_the_current_feels_no_drag() {
    let mut rng = Rng(3);
    for _ in 0..200 {
        let n = 1 + (rng.next().abs() * 8.0) as usize;
        let robot = random_robot(&mut rng, n);
        let mut s = states(&mut rng, n);
        s[1] = [0.0; J];
        let moving = random_motion(&mut rng);
        let drift = rng.vector::<3>(2.0);
        // The base translates with the water, without turning.
        let q = UnitQuaternion::from_matrix(moving.rotation());
        let motion = BaseMotion::new(
            [q.w, q.i, q.j, q.k],
            q.inverse() * drift,
            Vector3::zeros(),
            Vector3::zeros(),
            Vector3::zeros(),
        )
        .unwrap();
        let data = evaluate(&robot, None, &motion, &Current::new(drift, Vector3::zeros()).unwrap(), &s);
        let still = evaluate(&robot, None, &BaseMotion::fixed(), &Current::still(), &[s[0], [0.0; J], [0.0; J]]);
        let scale = wrench_scale(still.base_wrench()).max(1.0);
        for x in data.base_wrench().drag.to_array() {
            assert!(x.abs() <= 1e-13 * scale, "base drag {x}");
        }
        for f in data.joint_forces() {
            assert!(f.drag.abs() <= 1e-13 * scale, "joint drag {}", f.drag);
        }
        // Moving at the current's velocity with the joints at rest: drag zero, but moving
        // without current is not.
        let dry = evaluate(&robot, None, &motion, &Current::still(), &s);
        assert!(dry.base_wrench().drag.force.norm() > 0.0);
    }
}

#[test]
fn drag_is_dissipative_in_still_water() {
    let mut rng = Rng(8);
    for _ in 0..300 {
        let n = 1 + (rng.next().abs() * 8.0) as usize;
        let robot = random_robot(&mut rng, n);
        let s = states(&mut rng, n);
        let motion = random_motion(&mut rng);
        let data = evaluate(&robot, None, &motion, &Current::still(), &s);
        let (v, w) = motion.twist();
        let power = data.joint_forces().iter().zip(s[1]).map(|(f, qd)| f.drag * qd).sum::<f64>()
            + data.base_wrench().drag.force.dot(&v)
            + data.base_wrench().drag.moment.dot(&w);
        let scale = wrench_scale(data.base_wrench());
        assert!(power <= 1e-12 * scale, "drag power {power}");
    }
}

/// The robot on six virtual joints at the base (prismatic along x, y, z, then revolute about x,
/// y, z, at zero displacement): their generalized forces are the base wrench (velocity level).
#[test]
fn six_virtual_joints_give_the_base_wrench() {
    let mut rng = Rng(31);
    for _ in 0..100 {
        let n = 1 + (rng.next().abs() * 5.0) as usize;
        let robot = random_robot(&mut rng, n);
        let s = states(&mut rng, n);
        let (v, w) = (rng.vector::<3>(1.0), rng.vector::<3>(1.0));
        // Translations first (their axes stay the base axes), then rotations about x, y, z at
        // zero angle: the rotation rates, composed, give the angular velocity ω with components
        // taken about axes that the earlier rotations do not move at zero angle.
        let axes = [Vector3::x(), Vector3::y(), Vector3::z()];
        let mut joints: Vec<TreeJoint<f64>> = Vec::new();
        for (k, kind) in [JointKind::Prismatic, JointKind::Revolute].into_iter().enumerate() {
            for (i, axis) in axes.iter().enumerate() {
                let index = 3 * k + i;
                joints.push(TreeJoint { parent: index.checked_sub(1), kind, origin: Vector3::zeros(), axis: *axis });
            }
        }
        let mut links = vec![RigidBody::empty(); 5];
        links.push(*robot.base());
        for joint in robot.joints() {
            joints.push(TreeJoint { parent: Some(joint.parent.map_or(5, |p| p + 6)), ..*joint });
        }
        links.extend_from_slice(robot.links());
        let segments: Vec<_> = robot
            .segments()
            .iter()
            .map(|s| RobotSegment {
                owner: match s.owner {
                    Owner::Base => Owner::Link(5),
                    Owner::Link(i) => Owner::Link(i + 6),
                },
                ..*s
            })
            .collect();
        let virtual_robot = Robot::<f64, 18, S>::new(&joints, &links, RigidBody::empty(), &segments).unwrap();
        let mut q = [0.0; 18];
        let mut qd = [0.0; 18];
        let qdd = [0.0; 18];
        q[6..6 + n].copy_from_slice(&s[0][..n]);
        qd[6..6 + n].copy_from_slice(&s[1][..n]);
        qd[..3].copy_from_slice(v.as_slice());
        qd[3..6].copy_from_slice(w.as_slice());
        // The same motion as a base twist, zero base acceleration and joint accelerations: the
        // virtual joints' chain has the same velocities (drag, buoyancy and gravity agree).
        let motion = BaseMotion::new([1.0, 0.0, 0.0, 0.0], v, w, Vector3::zeros(), Vector3::zeros()).unwrap();
        let mut s_zero = s;
        s_zero[2] = [0.0; J];
        let on_base = evaluate(&robot, None, &motion, &Current::still(), &s_zero);
        let mut data = RobotData::<f64, 18>::new();
        robot_hydro(&virtual_robot, &Conditions::new(Water::default()), [&q, &qd, &qdd], &mut data);
        let scale = wrench_scale(on_base.base_wrench());
        let virtual_forces = data.joint_forces();
        let base = on_base.base_wrench();
        let (drag, buoyancy, gravity) = (base.drag.to_array(), base.buoyancy.to_array(), base.gravity.to_array());
        for (k, forces) in virtual_forces.iter().take(6).enumerate() {
            assert_close(forces.drag, drag[k], scale, 1e-12, "drag");
            assert_close(forces.buoyancy, buoyancy[k], scale, 1e-12, "buoyancy");
            assert_close(forces.gravity, gravity[k], scale, 1e-12, "gravity");
        }
        for (a, b) in on_base.joint_forces().iter().zip(&virtual_forces[6..]) {
            assert_close(a.drag, b.drag, scale, 1e-12, "joint drag");
            assert_close(a.buoyancy, b.buoyancy, scale, 1e-12, "joint buoyancy");
        }
    }
}

#[test]
fn everything_is_linear_in_each_coefficient() {
    let mut rng = Rng(41);
    for _ in 0..50 {
        let n = 1 + (rng.next().abs() * 6.0) as usize;
        let robot = random_robot(&mut rng, n);
        let s = states(&mut rng, n);
        let motion = random_motion(&mut rng);
        let current = Current::new(rng.vector::<3>(1.0), rng.vector::<3>(1.0)).unwrap();
        let k = (rng.next().abs() * robot.segments().len() as f64) as usize % robot.segments().len();
        let with = |cd: f64, cm: f64| {
            let mut c = robot.coefficients();
            let (mut cds, mut cms) = (*c.cd(), *c.cm());
            cds[k] = [cd; 2];
            cms[k] = [cm; 2];
            c = SegmentCoefficients::per_segment(cds, cms).unwrap();
            evaluate(&robot, Some(&c), &motion, &current, &s)
        };
        let (zero, one, three) = (with(0.0, 0.0), with(1.0, 1.0), with(3.0, 3.0));
        let scale = wrench_scale(three.base_wrench());
        for ((z, o), t) in zero.joint_forces().iter().zip(one.joint_forces()).zip(three.joint_forces()) {
            assert_close(t.drag - z.drag, 3.0 * (o.drag - z.drag), scale, 1e-12, "drag");
            assert_close(t.added_mass - z.added_mass, 3.0 * (o.added_mass - z.added_mass), scale, 1e-12, "added mass");
        }
    }
}

#[test]
fn a_non_finite_state_gives_nan_and_nothing_else_fails() {
    let mut rng = Rng(2);
    let robot = random_robot(&mut rng, 4);
    let mut s = states(&mut rng, 4);
    s[1][2] = f64::INFINITY;
    let data = evaluate(&robot, None, &random_motion(&mut rng), &Current::still(), &s);
    assert!(data.joint_forces().iter().all(|f| f.drag.is_nan() && f.buoyancy.is_nan()));
    assert!(data.base_wrench().drag.to_array().iter().all(|x| x.is_nan()));
}

#[test]
fn regressors_times_coefficients_are_the_forces() {
    let mut rng = Rng(61);
    for _ in 0..100 {
        let n = 1 + (rng.next().abs() * 8.0) as usize;
        let robot = random_robot(&mut rng, n);
        let s = states(&mut rng, n);
        let motion = random_motion(&mut rng);
        let current = Current::new(rng.vector::<3>(1.0), rng.vector::<3>(1.0)).unwrap();
        let segments = robot.segments().len();
        let columns = robot.regressor_column_count();
        assert_eq!(columns, 3 * segments, "no lumped models: two normal directions and the axial drag per segment");
        let rows = 6 + n;
        let (mut drag, mut added_mass) = (vec![f64::NAN; rows * columns], vec![f64::NAN; rows * columns]);
        let mut data = RobotData::new();
        robot_hydro_regressors(
            &robot,
            &Conditions { motion, current, ..Conditions::new(Water::default()) },
            [&s[0], &s[1], &s[2]],
            &mut data,
            &mut drag,
            &mut added_mass,
        );
        let statics = (data.base_wrench().buoyancy, data.joint_forces().iter().map(|f| f.buoyancy).collect::<Vec<_>>());
        let axial = |row: usize| -> f64 {
            robot.segments().iter().enumerate().map(|(k, s)| s.cd_axial * drag[row * columns + 2 * segments + k]).sum()
        };
        assert!(
            (0..rows).all(|row| (0..segments).all(|k| added_mass[row * columns + 2 * segments + k] == 0.0)),
            "the axial columns have no added mass"
        );
        let coefficients = robot.coefficients();
        let expected = evaluate(&robot, None, &motion, &current, &s);
        let scale = wrench_scale(expected.base_wrench());
        let apply = |table: &[f64], c: &[[f64; 2]; S], row: usize| -> f64 {
            (0..segments)
                .map(|k| c[k][0] * table[row * columns + 2 * k] + c[k][1] * table[row * columns + 2 * k + 1])
                .sum()
        };
        let base = expected.base_wrench();
        for (row, (d, m)) in base.drag.to_array().iter().zip(base.added_mass.to_array()).enumerate() {
            assert_close(apply(&drag, coefficients.cd(), row) + axial(row), *d, scale, 1e-12, "base drag");
            assert_close(apply(&added_mass, coefficients.cm(), row), m, scale, 1e-12, "base added mass");
        }
        for (j, forces) in expected.joint_forces().iter().enumerate() {
            assert_close(
                apply(&drag, coefficients.cd(), 6 + j) + axial(6 + j),
                forces.drag,
                scale,
                1e-12,
                "joint drag",
            );
            assert_close(
                apply(&added_mass, coefficients.cm(), 6 + j),
                forces.added_mass,
                scale,
                1e-12,
                "joint added mass",
            );
            assert_eq!(statics.1[j], forces.buoyancy);
        }
        assert_eq!(statics.0, base.buoyancy);
    }
}

/// `(W, τ)` hydrodynamic totals, base first.
fn totals(data: &RobotData<f64, J>) -> Vec<f64> {
    data.base_wrench().total().to_array().into_iter().chain(data.joint_forces().iter().map(|f| f.total())).collect()
}

#[test]
fn jacobians_are_the_slopes_of_the_forces() {
    let mut rng = Rng(71);
    for _ in 0..40 {
        let n = 1 + (rng.next().abs() * 7.0) as usize;
        let robot = random_robot(&mut rng, n);
        let s = states(&mut rng, n);
        let motion = random_motion(&mut rng);
        let current = Current::new(rng.vector::<3>(1.0), rng.vector::<3>(1.0)).unwrap();
        let m = 6 + n;
        let (mut value, mut d_q, mut d_velocity, mut matrix) =
            (vec![0.0; m], vec![0.0; m * n], vec![0.0; m * m], vec![0.0; m * m]);
        let mut work = Box::new(RobotJacobianData::new(&robot));
        let out = RobotJacobians {
            value: &mut value,
            d_q: &mut d_q,
            d_velocity: &mut d_velocity,
            added_mass_matrix: &mut matrix,
        };
        robot_jacobians(
            &robot,
            &Conditions { motion, current, losses: Some(&[None; J]), ..Conditions::new(Water::default()) },
            [&s[0], &s[1], &s[2]],
            &mut work,
            out,
        );
        let here = totals(&evaluate(&robot, None, &motion, &current, &s));
        let scale = here.iter().fold(1.0_f64, |a, x| a.max(x.abs()));
        for (a, b) in value.iter().zip(&here) {
            assert_close(*a, *b, scale, 1e-14, "value");
        }
        assert_eq!(matrix, added_mass_matrix(&robot, &s[0]));
        // Central differences, step h: error O(h²) from the smooth parts.
        let h = 1e-6;
        for k in 0..n {
            let (mut plus, mut minus) = (s, s);
            plus[0][k] += h;
            minus[0][k] -= h;
            let (p, mi) = (
                totals(&evaluate(&robot, None, &motion, &current, &plus)),
                totals(&evaluate(&robot, None, &motion, &current, &minus)),
            );
            for row in 0..m {
                assert_close(d_q[row * n + k], (p[row] - mi[row]) / (2.0 * h), scale, 1e-6, "d_q");
            }
            (plus, minus) = (s, s);
            plus[1][k] += h;
            minus[1][k] -= h;
            let (p, mi) = (
                totals(&evaluate(&robot, None, &motion, &current, &plus)),
                totals(&evaluate(&robot, None, &motion, &current, &minus)),
            );
            for row in 0..m {
                assert_close(d_velocity[row * m + 6 + k], (p[row] - mi[row]) / (2.0 * h), scale, 1e-6, "d_qd");
            }
        }
        let (v, w) = motion.twist();
        let (vd, wd) = motion.twist_derivative();
        let q = UnitQuaternion::from_matrix(motion.rotation());
        for k in 0..6 {
            let shifted = |step: f64| {
                let (mut v, mut w) = (v, w);
                if k < 3 {
                    v[k] += step
                } else {
                    w[k - 3] += step
                }
                BaseMotion::new([q.w, q.i, q.j, q.k], v, w, vd, wd).unwrap()
            };
            let p = totals(&evaluate(&robot, None, &shifted(h), &current, &s));
            let mi = totals(&evaluate(&robot, None, &shifted(-h), &current, &s));
            for row in 0..m {
                assert_close(d_velocity[row * m + k], (p[row] - mi[row]) / (2.0 * h), scale, 1e-6, "d_nu");
            }
        }
    }
}

/// Joint 0 frozen into the base motion: a robot whose every link hangs from link 0 (an empty
/// base at rest), and the same robot with link 0 as its moving base, at the motion joint 0 gives
/// it. The other joints' forces agree, and joint 0's is the new base wrench along its axis.
#[test]
fn a_joint_frozen_into_the_base_motion_leaves_the_other_joints_alone() {
    let mut rng = Rng(81);
    for trial in 0..60 {
        let n = 2 + (rng.next().abs() * 6.0) as usize;
        let drawn = random_robot(&mut rng, n);
        let kind = if trial % 2 == 0 { JointKind::Revolute } else { JointKind::Prismatic };
        let mut joints: Vec<TreeJoint<f64>> = drawn.joints().to_vec();
        joints[0] = TreeJoint { parent: None, kind, ..joints[0] };
        for (j, joint) in joints.iter_mut().enumerate().skip(1) {
            if joint.parent.is_none() {
                joint.parent = Some(((rng.next() + 1.0) / 2.0 * j as f64) as usize % j);
            }
        }
        let segments: Vec<_> = drawn.segments().iter().filter(|s| s.owner != Owner::Base).copied().collect();
        let whole = Model::new(&joints, drawn.links(), RigidBody::empty(), &segments).unwrap();
        let s = states(&mut rng, n);
        let current = Current::new(rng.vector::<3>(0.5), rng.vector::<3>(0.5)).unwrap();
        let full = evaluate(&whole, None, &BaseMotion::fixed(), &current, &s);
        // Link 0's frame: orientation, twist and twist derivative in its own components.
        let (axis, (q0, qd0, qdd0)) = (joints[0].axis, (s[0][0], s[1][0], s[2][0]));
        let (orientation, v, w, v_dot, w_dot) = match kind {
            JointKind::Revolute => {
                let turn = UnitQuaternion::from_scaled_axis(axis * q0);
                (turn, Vector3::zeros(), axis * qd0, Vector3::zeros(), axis * qdd0)
            }
            JointKind::Prismatic => {
                (UnitQuaternion::identity(), axis * qd0, Vector3::zeros(), axis * qdd0, Vector3::zeros())
            }
        };
        let motion =
            BaseMotion::new([orientation.w, orientation.i, orientation.j, orientation.k], v, w, v_dot, w_dot).unwrap();
        let frozen_joints: Vec<TreeJoint<f64>> =
            joints[1..].iter().map(|j| TreeJoint { parent: j.parent.and_then(|p| p.checked_sub(1)), ..*j }).collect();
        let frozen_segments: Vec<_> = segments
            .iter()
            .map(|s| RobotSegment {
                owner: match s.owner {
                    Owner::Link(0) | Owner::Base => Owner::Base,
                    Owner::Link(i) => Owner::Link(i - 1),
                },
                ..*s
            })
            .collect();
        let frozen = Model::new(&frozen_joints, &whole.links()[1..], whole.links()[0], &frozen_segments).unwrap();
        let mut shifted = [[0.0; J]; 3];
        for k in 0..3 {
            shifted[k][..n - 1].copy_from_slice(&s[k][1..n]);
        }
        let part = evaluate(&frozen, None, &motion, &current, &shifted);
        let scale = full
            .joint_forces()
            .iter()
            .fold(1e-300_f64, |m, f| m.max(f.drag.abs()).max(f.added_mass.abs()).max(f.buoyancy.abs()));
        for (a, b) in full.joint_forces()[1..].iter().zip(part.joint_forces()) {
            assert_close(b.drag, a.drag, scale, 1e-12, "frozen: drag");
            assert_close(b.added_mass, a.added_mass, scale, 1e-12, "frozen: added mass");
            assert_close(b.buoyancy, a.buoyancy, scale, 1e-12, "frozen: buoyancy");
            assert_close(b.gravity, a.gravity, scale.max(a.gravity.abs()), 1e-12, "frozen: gravity");
        }
        // Joint 0's force is the frozen robot's base wrench along the axis (link 0's frame).
        let base = part.base_wrench();
        let along = |w: &uwml_core::Wrench<f64>| match kind {
            JointKind::Revolute => axis.dot(&w.moment),
            JointKind::Prismatic => axis.dot(&w.force),
        };
        let first = full.joint_forces()[0];
        assert_close(along(&base.drag), first.drag, scale, 1e-12, "frozen: joint 0 drag");
        assert_close(along(&base.added_mass), first.added_mass, scale, 1e-12, "frozen: joint 0 added mass");
        assert_close(along(&base.buoyancy), first.buoyancy, scale, 1e-12, "frozen: joint 0 buoyancy");
    }
}
