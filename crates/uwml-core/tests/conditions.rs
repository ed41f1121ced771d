//! One `Conditions` value for every evaluation of a whole robot (docs/model.md section 10): its
//! defaults, and the joint losses it carries (docs/model.md section 7), combined with the
//! hydrodynamics in the core.
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing, clippy::expect_used)]

use uwml_core::{
    AddedMassForm, BaseMotion, Conditions, Current, JointLosses, LossState, Robot, RobotData, Water, robot_hydro,
    robot_hydro_regressors,
};

mod common;
use common::Rng;
use common::trees::{random_robot, states};

const J: usize = 8;
const S: usize = 12;

fn forces(data: &RobotData<f64, J>) -> Vec<u64> {
    let joints = data.joint_forces().iter().flat_map(|f| [f.drag, f.added_mass, f.buoyancy, f.gravity]);
    let base = data.base_wrench();
    let wrenches = [base.drag, base.added_mass, base.buoyancy, base.gravity].into_iter().flat_map(|w| w.to_array());
    joints.chain(wrenches).map(f64::to_bits).collect()
}

#[test]
fn the_defaults_are_a_fixed_upright_base_in_still_water_without_losses() {
    let mut rng = Rng(17);
    let robot: Robot<f64, J, S> = random_robot(&mut rng, 5);
    let water = Water::new(1030.0, 9.8).unwrap();
    let [q, qd, qdd] = states::<J>(&mut rng, 5);
    let explicit = Conditions {
        water,
        motion: BaseMotion::fixed(),
        current: Current::still(),
        coefficients: None,
        form: AddedMassForm::Morison,
        losses: None,
    };
    let (mut a, mut b) = (RobotData::new(), RobotData::new());
    robot_hydro(&robot, &Conditions::new(water), [&q, &qd, &qdd], &mut a);
    robot_hydro(&robot, &explicit, [&q, &qd, &qdd], &mut b);
    assert_eq!(forces(&a), forces(&b));
    assert!(a.joint_losses().iter().all(|l| [l.visc, l.seal, l.current] == [0.0; 3]));
}

#[test]
fn losses_in_the_conditions_are_each_joints_own_and_leave_the_forces_alone() {
    let mut rng = Rng(23);
    let n = 6;
    let robot: Robot<f64, J, S> = random_robot(&mut rng, n);
    let water = Water::default();
    let (pressure, temperature) = (3.0e7, 4.0);
    let state = JointLosses::default().at(pressure, temperature).unwrap();
    // Losses on joints 0, 2 and 5 only.
    let mut losses: [Option<LossState<f64>>; J] = [None; J];
    for i in [0, 2, 5] {
        losses[i] = Some(state);
    }
    let [q, qd, qdd] = states::<J>(&mut rng, n);
    let with = Conditions { losses: Some(&losses), ..Conditions::new(water) };
    let (mut a, mut b) = (RobotData::new(), RobotData::new());
    robot_hydro(&robot, &with, [&q, &qd, &qdd], &mut a);
    robot_hydro(&robot, &Conditions::new(water), [&q, &qd, &qdd], &mut b);
    assert_eq!(forces(&a), forces(&b), "the losses change no hydrodynamic force");
    for (i, loss) in a.joint_losses().iter().enumerate() {
        let expected = losses[i].map(|s| s.evaluate(qd[i]));
        match expected {
            Some(e) => {
                assert_eq!([loss.visc, loss.seal, loss.current], [e.visc, e.seal, e.current], "joint {i}");
                assert!(loss.visc * qd[i] < 0.0 && loss.seal * qd[i] < 0.0, "joint {i}: losses oppose the motion");
            }
            None => assert_eq!([loss.visc, loss.seal, loss.current], [0.0; 3], "joint {i}"),
        }
    }
    // An evaluation without losses (the regressors') leaves none behind in the workspace.
    let width = (6 + n) * robot.regressor_column_count();
    let (mut drag, mut added_mass) = (vec![0.0; width], vec![0.0; width]);
    robot_hydro_regressors(&robot, &with, [&q, &qd, &qdd], &mut a, &mut drag, &mut added_mass);
    assert!(a.joint_losses().iter().all(|l| [l.visc, l.seal, l.current] == [0.0; 3]));
}
