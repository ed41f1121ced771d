//! The paper leg's regressors and kinematics (`robot_hydro_regressors`, `forward_kinematics` and
//! `point_jacobian` of the foot), f64 and f32; its forces are in `benches/robot.rs`.
//! Run: `cargo bench -p uwml-core --features std --bench hydro`.
#![allow(missing_docs)]

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use uwml_core::nalgebra::{RealField, Vector3, convert};
use uwml_core::{
    Conditions, KinematicsData, RobotData, Water, forward_kinematics, point_jacobian, presets, robot_hydro_regressors,
};

fn bench_for<T: RealField + uwml_core::Real>(c: &mut Criterion, name: &str) {
    let leg = presets::paper_leg::<T>();
    let conditions = Conditions::new(Water::<T>::default());
    let s = |x: [f64; 3]| x.map(convert::<f64, T>);
    let (q, qd, qdd) = (s([0.3, -0.4, 0.6]), s([0.8, 0.5, -0.7]), s([1.0, -2.0, 0.5]));
    let mut kinematics = KinematicsData::new();
    let foot = Vector3::new(T::zero(), T::zero(), convert(-presets::paper::L3));
    let mut jacobian = [T::zero(); 18];
    c.bench_function(&format!("kinematics/paper foot/{name}"), |b| {
        b.iter(|| {
            forward_kinematics(black_box(&leg), black_box(&q), &mut kinematics);
            point_jacobian(&leg, &kinematics, 2, &foot, &mut jacobian)
        })
    });
    let mut data = RobotData::new();
    let (mut drag, mut added_mass) = ([T::zero(); 54], [T::zero(); 54]);
    c.bench_function(&format!("robot_hydro_regressors/paper/{name}"), |b| {
        b.iter(|| {
            robot_hydro_regressors(
                black_box(&leg),
                &conditions,
                [black_box(&q), &qd, &qdd],
                &mut data,
                &mut drag,
                &mut added_mass,
            )
        })
    });
}

fn benches(c: &mut Criterion) {
    bench_for::<f64>(c, "f64");
    bench_for::<f32>(c, "f32");
}

criterion_group!(hydro, benches);
criterion_main!(hydro);
