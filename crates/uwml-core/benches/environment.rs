//! Cost of the joint losses on top of the hydrodynamics: the paper leg (`presets::paper_leg`) with
//! losses on all three joints, f64 and f32. Run:
//! `cargo bench -p uwml-core --features std --bench environment`.
#![allow(missing_docs, clippy::unwrap_used)]

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use uwml_core::nalgebra::{RealField, convert};
use uwml_core::{
    Conditions, JointLosses, LossState, OilDrag, RobotData, Water, presets, pressure_at_depth, robot_hydro,
};

fn bench_for<T: RealField + uwml_core::Real>(c: &mut Criterion, name: &str) {
    let leg = presets::paper_leg::<T>();
    let water = Water::<T>::default();
    let s = |x: [f64; 3]| x.map(convert::<f64, T>);
    let (q, qd, qdd) = (s([0.3, -0.4, 0.6]), s([0.8, 0.5, -0.7]), s([1.0, -2.0, 0.5]));
    let pressure = pressure_at_depth::<T>(convert(1000.0), convert(1025.0), convert(9.81)).unwrap();
    let state = Some(JointLosses::<T>::default().at(pressure, convert(4.0)).unwrap());
    let mut data = RobotData::new();
    let mut evaluate = |c: &mut Criterion, what: &str, losses: Option<&[Option<LossState<T>>; 3]>| {
        let conditions = Conditions { losses, ..Conditions::new(water) };
        c.bench_function(&format!("robot_hydro/{what}/{name}"), |b| {
            b.iter(|| robot_hydro(black_box(&leg), &conditions, [black_box(&q), black_box(&qd), &qdd], &mut data))
        });
    };
    evaluate(c, "paper", None);
    evaluate(c, "paper+losses", Some(&[state; 3]));
    // The defaults are laminar (n = 1: no power function per call); a fitted n = 1.2 costs one
    // `powf` per joint.
    let defaults = JointLosses::<T>::default();
    let fitted_oil =
        OilDrag::new(convert(1.1933e-3), convert(1.2), convert(0.02e-6), convert(0.06), T::zero(), convert(20.0)).ok();
    let fitted = JointLosses::new(defaults.drive, fitted_oil, defaults.seal, defaults.epsilon())
        .map(|l| Some(l.at(pressure, convert(4.0)).unwrap()))
        .unwrap_or(state);
    evaluate(c, "paper+losses-n1.2", Some(&[fitted; 3]));
    let joint = JointLosses::<T>::default();
    c.bench_function(&format!("losses_at/pressure_change/{name}"), |b| {
        b.iter(|| joint.at(black_box(pressure), black_box(convert(4.0))).unwrap())
    });
}

fn benches(c: &mut Criterion) {
    bench_for::<f64>(c, "f64");
    bench_for::<f32>(c, "f32");
}

criterion_group!(environment, benches);
criterion_main!(environment);
