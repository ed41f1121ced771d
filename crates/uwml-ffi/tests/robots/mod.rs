//! The robots of the robot API's tests, as the core describes them and as C gives them: a 6-joint
//! arm (a tree: five joints in a chain, one prismatic, and a camera on a side branch; circular
//! and rectangular segments) on a vehicle with a body and a circular hull, moving in a current,
//! with joint losses on four of its joints; and the paper's leg. Shared by `robot_api.rs` and
//! `robot_losses.rs` (the C API against the core, bit for bit) and `robot_expected.rs` (the
//! core's values for `tests/c/robot.c`).
#![allow(dead_code, clippy::indexing_slicing, clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use core::ptr::{null, null_mut};

use uwml_core::nalgebra::{UnitQuaternion, Vector3};
use uwml_core::{
    AddedMassForm, BaseMotion, Conditions, Current, Drive, JointForces, JointKind, JointLosses, LossState, OilDrag,
    Owner, RigidBody, Robot, RobotData, RobotSegment, Seal, Section, TreeJoint, Water, loss_torques, presets,
    robot_hydro,
};
use uwml_ffi::{
    UWML_BASE, UWML_JOINT_PRISMATIC, UWML_JOINT_REVOLUTE, UWML_OK, UWML_ROBOT_F32_WORDS, UWML_ROBOT_F64_WORDS,
    UWML_SECTION_CIRCULAR, UWML_SECTION_RECTANGULAR, UWML_WORKSPACE_F32_WORDS, UWML_WORKSPACE_F64_WORDS,
    UwmlBaseMotionF32, UwmlBaseMotionF64, UwmlBaseWrenchF32, UwmlBaseWrenchF64, UwmlBodyF32, UwmlBodyF64,
    UwmlCurrentF32, UwmlCurrentF64, UwmlDriveParamsF32, UwmlDriveParamsF64, UwmlJointEnvironmentF32,
    UwmlJointEnvironmentF64, UwmlJointForcesF32, UwmlJointForcesF64, UwmlJointLossParamsF32, UwmlJointLossParamsF64,
    UwmlOilParamsF32, UwmlOilParamsF64, UwmlRobotF32, UwmlRobotF64, UwmlRobotSegmentF32, UwmlRobotSegmentF64,
    UwmlSealParamsF32, UwmlSealParamsF64, UwmlTreeJointF32, UwmlTreeJointF64, UwmlWorkspaceF32, UwmlWorkspaceF64,
    uwml_robot_new_f32, uwml_robot_new_f64, uwml_robot_workspace_init_f32, uwml_robot_workspace_init_f64,
};

mod c_api;
mod single;
pub use c_api::*;
pub use single::*;

pub const J: usize = 16;
pub const S: usize = 32;

/// Sea water.
pub const DENSITY: f64 = 1025.0;
pub const GRAVITY: f64 = 9.81;

/// A robot as C gives it.
#[derive(Clone, Debug)]
pub struct Params {
    pub joints: Vec<UwmlTreeJointF64>,
    pub links: Vec<UwmlBodyF64>,
    pub base: Option<UwmlBodyF64>,
    pub segments: Vec<UwmlRobotSegmentF64>,
}

/// The direction of the forearm, in the elbow's frame: (0.8, 0, -0.6).
const FORE: [f64; 3] = [0.8, 0.0, -0.6];

fn along(axis: [f64; 3], s: f64) -> [f64; 3] {
    axis.map(|x| x * s)
}

fn joint(parent: i32, kind: i32, origin: [f64; 3], axis: [f64; 3]) -> UwmlTreeJointF64 {
    UwmlTreeJointF64 { parent, kind, origin, axis }
}

fn body(mass: f64, com: [f64; 3], volume: f64, cob: [f64; 3]) -> UwmlBodyF64 {
    UwmlBodyF64 { mass, com, volume, cob }
}

fn circular(
    owner: i32,
    start: [f64; 3],
    axis: [f64; 3],
    length: f64,
    diameter: f64,
    cd: f64,
    cm: f64,
) -> UwmlRobotSegmentF64 {
    UwmlRobotSegmentF64 {
        owner,
        section: UWML_SECTION_CIRCULAR,
        start,
        axis,
        length,
        area: core::f64::consts::PI * diameter * diameter / 4.0,
        diameter,
        cd: [cd; 2],
        cm: [cm; 2],
        ..Default::default()
    }
}

#[allow(clippy::too_many_arguments)]
fn rectangular(
    owner: i32,
    start: [f64; 3],
    axis: [f64; 3],
    length: f64,
    normals: [[f64; 3]; 2],
    widths: [f64; 2],
    cd: [f64; 2],
    cm: [f64; 2],
) -> UwmlRobotSegmentF64 {
    UwmlRobotSegmentF64 {
        owner,
        section: UWML_SECTION_RECTANGULAR,
        start,
        axis,
        length,
        area: widths[0] * widths[1],
        normals,
        widths,
        cd,
        cm,
        ..Default::default()
    }
}

/// The arm on its vehicle. Joints: 0 turret (yaw, on the vehicle's belly), 1 shoulder (pitch),
/// 2 elbow (pitch), 3 telescope (prismatic along the forearm), 4 wrist roll, 5 a camera's tilt
/// on the turret (a side branch).
pub fn arm() -> Params {
    let (r, p) = (UWML_JOINT_REVOLUTE, UWML_JOINT_PRISMATIC);
    let joints = vec![
        joint(UWML_BASE, r, [0.40, 0.0, -0.25], [0.0, 0.0, 1.0]),
        joint(0, r, [0.0, 0.0, -0.10], [0.0, 1.0, 0.0]),
        joint(1, r, [0.45, 0.0, 0.0], [0.0, 1.0, 0.0]),
        joint(2, p, along(FORE, 0.35), FORE),
        joint(3, r, along(FORE, 0.20), FORE),
        joint(0, r, [0.05, 0.06, -0.04], [1.0, 0.0, 0.0]),
    ];
    let links = vec![
        body(3.0, [0.0, 0.0, -0.05], 0.0012, [0.0, 0.0, -0.045]),
        body(4.2, [0.22, 0.0, 0.0], 0.0030, [0.21, 0.0, 0.01]),
        body(2.5, along(FORE, 0.17), 0.0014, along(FORE, 0.16)),
        body(1.1, along(FORE, 0.10), 0.0004, along(FORE, 0.10)),
        body(0.9, along(FORE, 0.04), 0.0005, along(FORE, 0.05)),
        body(0.8, [0.0, 0.03, 0.0], 0.0006, [0.0, 0.035, 0.0]),
    ];
    let base = body(140.0, [0.02, 0.0, -0.06], 0.138, [0.0, 0.0, 0.05]);
    let segments = vec![
        // The hull, and a rectangular skid under it.
        circular(UWML_BASE, [-0.7, 0.0, 0.0], [1.0, 0.0, 0.0], 1.4, 0.5, 0.9, 1.0),
        rectangular(
            UWML_BASE,
            [-0.5, 0.0, -0.28],
            [1.0, 0.0, 0.0],
            1.0,
            [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            [0.06, 0.3],
            [2.0, 1.8],
            [0.8, 1.2],
        ),
        circular(0, [0.0, 0.0, 0.0], [0.0, 0.0, -1.0], 0.10, 0.12, 1.1, 1.0),
        rectangular(
            1,
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            0.45,
            [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            [0.08, 0.10],
            [1.9, 2.1],
            [0.9, 1.1],
        ),
        circular(2, [0.0, 0.0, 0.0], FORE, 0.35, 0.07, 1.2, 1.0),
        circular(3, along(FORE, -0.05), FORE, 0.25, 0.05, 1.2, 1.0),
        rectangular(
            4,
            [0.0, 0.0, 0.0],
            FORE,
            0.12,
            [[0.0, 1.0, 0.0], [0.6, 0.0, 0.8]],
            [0.06, 0.04],
            [2.2, 1.6],
            [1.0, 0.7],
        ),
        circular(5, [0.0, -0.02, 0.0], [0.0, 1.0, 0.0], 0.10, 0.06, 1.0, 1.0),
    ];
    Params { joints, links, base: Some(base), segments }
}

/// The arm's joint state: q [rad, m for joint 3], qd, qdd.
pub const ARM_STATE: [[f64; 6]; 3] =
    [[0.4, -0.7, 1.1, 0.12, -0.5, 0.3], [0.5, -0.3, 0.8, 0.1, 1.5, -0.6], [1.0, -0.5, 0.3, 0.2, -2.0, 0.7]];

/// A rotation as a unit quaternion `(w, x, y, z)`.
/// The arm's states of the tests: the reference state, rest, and one far from both.
pub fn arm_states() -> Vec<[Vec<f64>; 3]> {
    let [q, qd, qdd] = ARM_STATE;
    vec![
        [q.to_vec(), qd.to_vec(), qdd.to_vec()],
        [vec![0.0; 6], vec![0.0; 6], vec![0.0; 6]],
        [
            vec![-1.3, 0.4, -0.2, -0.05, 2.5, -1.0],
            vec![-0.2, 1.1, -0.6, -0.3, 0.0, 2.0],
            vec![0.0, 3.0, -1.0, 0.0, 0.5, -0.4],
        ],
    ]
}

pub fn quaternion(scaled_axis: [f64; 3]) -> [f64; 4] {
    let q = UnitQuaternion::from_scaled_axis(Vector3::from(scaled_axis));
    [q.w, q.i, q.j, q.k]
}

/// The vehicle pitched, rolled and turned, surging forward while turning and heaving.
pub fn arm_motion() -> UwmlBaseMotionF64 {
    UwmlBaseMotionF64 {
        orientation: quaternion([0.12, -0.25, 0.8]),
        velocity: [0.6, -0.1, 0.05],
        angular_velocity: [0.05, -0.1, 0.2],
        acceleration: [0.2, 0.05, -0.1],
        angular_acceleration: [-0.1, 0.3, 0.05],
    }
}

/// A current across the vehicle's path, speeding up.
pub const ARM_CURRENT: UwmlCurrentF64 = UwmlCurrentF64 { velocity: [0.3, -0.4, 0.05], acceleration: [0.02, 0.01, 0.0] };

/// The core's illustrative default losses (`JointLosses::default()`, what
/// `uwml_leg3_default_losses_f64` writes), as C gives them.
pub fn default_losses() -> UwmlJointLossParamsF64 {
    let d = JointLosses::<f64>::default();
    let (drive, oil, seal) = (d.drive, d.oil.unwrap(), d.seal.unwrap());
    UwmlJointLossParamsF64 {
        drive: UwmlDriveParamsF64 {
            torque_constant: drive.torque_constant(),
            ratio: drive.ratio(),
            efficiency: drive.efficiency(),
            rated_current: drive.rated_current(),
        },
        oil: UwmlOilParamsF64 {
            k_oil: oil.k_oil(),
            exponent: oil.exponent(),
            pressure_sensitivity: oil.pressure_sensitivity(),
            temperature_sensitivity: oil.temperature_sensitivity(),
            reference_pressure: oil.reference_pressure(),
            reference_temperature: oil.reference_temperature(),
        },
        seal: UwmlSealParamsF64 {
            c: seal.running(),
            s: seal.breakaway(),
            d: seal.viscous(),
            stribeck_speed: seal.stribeck_speed(),
        },
        epsilon: d.epsilon(),
        has_oil: 1,
        has_seal: 1,
    }
}

/// The arm's joint losses, `(joint, losses)`: a seal only on the turret (0); the defaults on the
/// shoulder (1); on the elbow (2) Taylor-vortex oil (n = 1.5) and a hard sign (ε = 0); oil only,
/// n = 2, on the telescope (3, prismatic: a ball screw of 2π·500 rad/m); none on the wrist (4)
/// and the camera (5).
pub fn arm_losses() -> Vec<(u32, UwmlJointLossParamsF64)> {
    let defaults = default_losses();
    let mut turret = defaults;
    turret.has_oil = 0;
    turret.seal.c = [2.0, 3e-7];
    turret.seal.s = [3.5, 5e-7];
    let mut elbow = defaults;
    elbow.oil.exponent = 1.5;
    elbow.oil.k_oil = 2e-4;
    elbow.epsilon = 0.0;
    let mut telescope = defaults;
    telescope.has_seal = 0;
    telescope.drive.ratio = 2.0 * core::f64::consts::PI * 500.0;
    telescope.oil.exponent = 2.0;
    telescope.oil.k_oil = 1e-7;
    vec![(0, turret), (1, defaults), (2, elbow), (3, telescope)]
}

/// The arm's loss conditions: the gauge pressure at 3000 m in sea water [Pa] and 4 °C.
pub fn arm_conditions() -> (f64, f64) {
    (uwml_core::pressure_at_depth(3000.0, DENSITY, GRAVITY).unwrap(), 4.0)
}

/// The core's losses of a joint given as C gives them, in `T` (every field rounded as C's
/// `(float)x` does), through the core's constructors.
pub fn core_losses<T: Real>(p: &UwmlJointLossParamsF64) -> JointLosses<T> {
    let (d, o, s) = (&p.drive, &p.oil, &p.seal);
    let n = T::narrow;
    let drive = Drive::new(n(d.torque_constant), n(d.ratio), n(d.efficiency), n(d.rated_current)).unwrap();
    let oil = (p.has_oil != 0).then(|| {
        OilDrag::new(
            n(o.k_oil),
            n(o.exponent),
            n(o.pressure_sensitivity),
            n(o.temperature_sensitivity),
            n(o.reference_pressure),
            n(o.reference_temperature),
        )
        .unwrap()
    });
    let seal = (p.has_seal != 0).then(|| Seal::new(s.c.map(n), s.s.map(n), s.d.map(n), n(s.stribeck_speed)).unwrap());
    JointLosses::new(drive, oil, seal, n(p.epsilon)).unwrap()
}

/// Every joint's loss state at `(pressure, temperature)`: the core's, from `losses`.
pub fn core_loss_states<T: Real>(
    losses: &[(u32, UwmlJointLossParamsF64)],
    (pressure, temperature): (f64, f64),
) -> [Option<LossState<T>>; J] {
    let mut states = [None; J];
    for (joint, p) in losses {
        states[*joint as usize] = Some(core_losses::<T>(p).at(T::narrow(pressure), T::narrow(temperature)).unwrap());
    }
    states
}

/// What `uwml_robot_environment_*` must give: the core's `robot_hydro` forces (`data`) and
/// its `loss_torques` at the joint speeds `qd`, `total` summed as `EnvironmentTorques::total`
/// sums it, `(hydro total + visc) + seal`.
pub fn core_environment<T: Real>(
    data: &RobotData<T, J>,
    states: &[Option<LossState<T>>; J],
    qd: &[T],
) -> Vec<(JointForces<T>, [T; 4])> {
    let mut speeds = [T::narrow(0.0); J];
    speeds[..qd.len()].copy_from_slice(qd);
    let (visc, seal, current) = loss_torques(states, &speeds.into());
    data.joint_forces()
        .iter()
        .enumerate()
        .map(|(i, f)| (*f, [visc[i], seal[i], current[i], f.total() + visc[i] + seal[i]]))
        .collect()
}

pub fn environment64(e: &[(JointForces<f64>, [f64; 4])]) -> Vec<UwmlJointEnvironmentF64> {
    e.iter()
        .map(|(f, [visc, seal, current, total])| UwmlJointEnvironmentF64 {
            drag: f.drag,
            added_mass: f.added_mass,
            buoyancy: f.buoyancy,
            gravity: f.gravity,
            visc: *visc,
            seal: *seal,
            current: *current,
            total: *total,
        })
        .collect()
}

pub fn environment32(e: &[(JointForces<f32>, [f32; 4])]) -> Vec<UwmlJointEnvironmentF32> {
    e.iter()
        .map(|(f, [visc, seal, current, total])| UwmlJointEnvironmentF32 {
            drag: f.drag,
            added_mass: f.added_mass,
            buoyancy: f.buoyancy,
            gravity: f.gravity,
            visc: *visc,
            seal: *seal,
            current: *current,
            total: *total,
        })
        .collect()
}

/// The paper's leg as C would give it (what `uwml_robot_paper_leg_*` holds: the core's preset,
/// `presets::paper_leg`): 3 revolute joints in a chain, rectangular segments with Cd 2.2, Cm 0.5,
/// no base body.
pub fn paper() -> Params {
    let leg = presets::paper_leg::<f64>();
    let index = |i: Option<usize>| i.map_or(UWML_BASE, |i| i32::try_from(i).unwrap());
    let joints = leg
        .joints()
        .iter()
        .map(|j| UwmlTreeJointF64 {
            parent: index(j.parent),
            kind: UWML_JOINT_REVOLUTE,
            origin: j.origin.into(),
            axis: j.axis.into(),
        })
        .collect();
    let links = leg.links().iter().map(|l| UwmlBodyF64 {
        mass: l.mass,
        com: l.com.into(),
        volume: l.volume,
        cob: l.cob.into(),
    });
    let segments = leg
        .segments()
        .iter()
        .map(|s| {
            let Section::Rectangular { normals, widths } = s.section else {
                panic!("the paper's segments are rectangular")
            };
            let Owner::Link(owner) = s.owner else { panic!("on links") };
            UwmlRobotSegmentF64 {
                owner: index(Some(owner)),
                section: UWML_SECTION_RECTANGULAR,
                start: s.start.into(),
                axis: s.axis.into(),
                length: s.length,
                area: s.area,
                normals: normals.map(Into::into),
                widths,
                cd: s.cd,
                cm: s.cm,
                ..Default::default()
            }
        })
        .collect();
    Params { joints, links: links.collect(), base: None, segments }
}

/// The state of the paper's leg whose torques docs/model.md section 5 publishes.
pub const PAPER_STATE: [[f64; 3]; 3] = [[0.3, -0.4, 0.6], [0.8, 0.5, -0.7], [1.0, -2.0, 0.5]];

/// The leg on a body that heaves and rolls a little.
pub fn paper_motion() -> UwmlBaseMotionF64 {
    UwmlBaseMotionF64 {
        orientation: quaternion([0.05, 0.1, 0.0]),
        velocity: [0.1, 0.0, -0.2],
        angular_velocity: [0.1, 0.05, 0.0],
        acceleration: [0.0, 0.3, 0.1],
        angular_acceleration: [0.2, 0.0, -0.1],
    }
}

pub const PAPER_CURRENT: UwmlCurrentF64 = UwmlCurrentF64 { velocity: [0.2, 0.1, 0.0], acceleration: [0.0, 0.05, 0.0] };

/// The core's description of a robot given as C gives it (every field copied, nothing checked).
pub fn core_robot<T: Real>(params: &Params) -> Robot<T, J, S> {
    let v = |x: [f64; 3]| Vector3::from(x.map(T::narrow));
    let index = |i: i32| usize::try_from(i).ok();
    let joints: Vec<_> = params
        .joints
        .iter()
        .map(|j| TreeJoint {
            parent: index(j.parent),
            kind: if j.kind == UWML_JOINT_PRISMATIC { JointKind::Prismatic } else { JointKind::Revolute },
            origin: v(j.origin),
            axis: v(j.axis),
        })
        .collect();
    let body = |b: &UwmlBodyF64| RigidBody {
        mass: T::narrow(b.mass),
        com: v(b.com),
        volume: T::narrow(b.volume),
        cob: v(b.cob),
    };
    let links: Vec<_> = params.links.iter().map(body).collect();
    let segments: Vec<_> = params
        .segments
        .iter()
        .map(|s| RobotSegment {
            owner: index(s.owner).map_or(Owner::Base, Owner::Link),
            start: v(s.start),
            axis: v(s.axis),
            length: T::narrow(s.length),
            area: T::narrow(s.area),
            section: if s.section == UWML_SECTION_CIRCULAR {
                Section::Circular { diameter: T::narrow(s.diameter) }
            } else {
                Section::Rectangular { normals: s.normals.map(v), widths: s.widths.map(T::narrow) }
            },
            cd: s.cd.map(T::narrow),
            cm: s.cm.map(T::narrow),
            cd_axial: T::zero(),
            axial_area: T::zero(),
        })
        .collect();
    let base = params.base.as_ref().map_or(RigidBody::empty(), body);
    Robot::new(&joints, &links, base, &segments).expect("a valid robot")
}

pub fn core_motion<T: Real>(m: Option<&UwmlBaseMotionF64>) -> BaseMotion<T> {
    let v = |x: [f64; 3]| Vector3::from(x.map(T::narrow));
    m.map_or(BaseMotion::fixed(), |m| {
        BaseMotion::new(
            m.orientation.map(T::narrow),
            v(m.velocity),
            v(m.angular_velocity),
            v(m.acceleration),
            v(m.angular_acceleration),
        )
        .expect("a valid motion")
    })
}

pub fn core_current<T: Real>(c: Option<&UwmlCurrentF64>) -> Current<T> {
    let v = |x: [f64; 3]| Vector3::from(x.map(T::narrow));
    c.map_or(Current::still(), |c| Current::new(v(c.velocity), v(c.acceleration)).expect("a valid current"))
}

/// The core's evaluation, on `q`, `qd`, `qdd` (the robot's joints only).
pub fn core_hydro<T: Real, const B: usize>(
    robot: &Robot<T, J, S, B>,
    water: &Water<T>,
    motion: &BaseMotion<T>,
    current: &Current<T>,
    state: [&[T]; 3],
) -> RobotData<T, J> {
    core_hydro_with(robot, water, AddedMassForm::Morison, motion, current, state)
}

/// As [`core_hydro`], with the added-mass forces in `form`.
pub fn core_hydro_with<T: Real, const B: usize>(
    robot: &Robot<T, J, S, B>,
    water: &Water<T>,
    form: AddedMassForm,
    motion: &BaseMotion<T>,
    current: &Current<T>,
    state: [&[T]; 3],
) -> RobotData<T, J> {
    let padded = |x: &[T]| {
        let mut out = [T::narrow(0.0); J];
        out[..x.len()].copy_from_slice(x);
        out
    };
    let (q, qd, qdd) = (padded(state[0]), padded(state[1]), padded(state[2]));
    let mut data = RobotData::new();
    let conditions = Conditions { motion: *motion, current: *current, form, ..Conditions::new(*water) };
    robot_hydro(robot, &conditions, [&q, &qd, &qdd], &mut data);
    data
}

/// f64 or f32, converted from the f64 parameters as C's `(float)x` does.
pub trait Real: uwml_core::nalgebra::RealField + uwml_core::Real {
    fn narrow(x: f64) -> Self;
}

impl Real for f64 {
    fn narrow(x: f64) -> Self {
        x
    }
}

impl Real for f32 {
    #[allow(clippy::cast_possible_truncation)]
    fn narrow(x: f64) -> Self {
        x as f32
    }
}
