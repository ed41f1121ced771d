//! Whole robots: the paper's leg (`presets::paper_leg`; fixed, and on a moving base in a current),
//! and a 7-joint arm of 14 segments on an ROV, f64 and f32. Run: `cargo bench -p uwml-core --features std --bench robot`.
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used, clippy::panic, clippy::indexing_slicing)]

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use uwml_core::nalgebra::{RealField, convert};
use uwml_core::{BaseMotion, Conditions, Current, RobotData, Water, presets, robot_hydro};

#[path = "common/arm.rs"]
mod arm;

fn bench_for<T: RealField + uwml_core::Real>(c: &mut Criterion, name: &str) {
    let water = Water::<T>::default();
    let leg = presets::paper_leg::<T>();
    let s = |x: [f64; 3]| x.map(convert::<f64, T>);
    let (q, qd, qdd) = (s([0.3, -0.4, 0.6]), s([0.8, 0.5, -0.7]), s([1.0, -2.0, 0.5]));
    let (motion, current) = arm::rov_motion::<T>();
    let mut data = RobotData::<T, 3>::new();
    c.bench_function(&format!("paper leg, fixed/{name}"), |b| {
        let fixed = (BaseMotion::fixed(), Current::still());
        b.iter(|| {
            robot_hydro(
                black_box(&leg),
                &Conditions { motion: fixed.0, current: fixed.1, ..Conditions::new(water) },
                [black_box(&q), &qd, &qdd],
                &mut data,
            )
        })
    });
    c.bench_function(&format!("paper leg, moving base in a current/{name}"), |b| {
        b.iter(|| {
            robot_hydro(
                black_box(&leg),
                &Conditions { motion, current, ..Conditions::new(water) },
                [black_box(&q), &qd, &qdd],
                &mut data,
            )
        })
    });
    let arm = arm::arm_on_rov::<T, 7, 15>();
    let mut data = RobotData::<T, 7>::new();
    let s7 = |x: [f64; 7]| x.map(convert::<f64, T>);
    let (q, qd, qdd) =
        (s7([0.3, -0.4, 0.6, 0.2, -0.5, 0.1, 0.05]), s7([0.5, 0.3, -0.4, 0.8, 0.2, -0.6, 0.02]), s7([1.0; 7]));
    c.bench_function(&format!("7-joint arm, 14 segments, on a moving ROV in a current/{name}"), |b| {
        b.iter(|| {
            robot_hydro(
                black_box(&arm),
                &Conditions { motion, current, ..Conditions::new(water) },
                [black_box(&q), &qd, &qdd],
                &mut data,
            )
        })
    });
}

fn benches(c: &mut Criterion) {
    bench_for::<f64>(c, "f64");
    bench_for::<f32>(c, "f32");
}

criterion_group!(robot, benches);
criterion_main!(robot);
