//! Cost of the joint losses on top of the hydrodynamics: the paper leg with losses on all
//! three joints, f64 and f32. Run: `cargo bench -p uwml-core --features std --bench environment`.
#![allow(missing_docs, clippy::unwrap_used)]

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use uwml_core::nalgebra::{RealField, Vector3, convert};
use uwml_core::{
    Chain, Coefficients, JointLosses, OilDrag, Water, environment_torques, hydro_torques, pressure_at_depth,
};

fn bench_for<T: RealField + uwml_core::Real>(c: &mut Criterion, name: &str) {
    let leg = Chain::<T, 3>::paper();
    let water = Water::<T>::default();
    let coefficients = Coefficients::<T, 3>::default();
    let v = |a: f64, b: f64, c: f64| Vector3::new(convert(a), convert(b), convert(c));
    let (q, qd, qdd) = (v(0.3, -0.4, 0.6), v(0.8, 0.5, -0.7), v(1.0, -2.0, 0.5));
    let pressure = pressure_at_depth::<T>(convert(1000.0), convert(1025.0), convert(9.81)).unwrap();
    let state = Some(JointLosses::<T>::default().at(pressure, convert(4.0)).unwrap());
    let losses = [state; 3];
    c.bench_function(&format!("hydro_torques/paper/{name}"), |b| {
        b.iter(|| hydro_torques(black_box(&leg), &water, &coefficients, black_box(&q), black_box(&qd), &qdd))
    });
    c.bench_function(&format!("environment_torques/paper+losses/{name}"), |b| {
        b.iter(|| {
            environment_torques(
                black_box(&leg),
                &water,
                &coefficients,
                black_box(&losses),
                black_box(&q),
                black_box(&qd),
                &qdd,
            )
        })
    });
    // The defaults are laminar (n = 1: no power function per call); a fitted n = 1.2 costs one
    // `powf` per joint.
    let defaults = JointLosses::<T>::default();
    let fitted_oil =
        OilDrag::new(convert(1.1933e-3), convert(1.2), convert(0.02e-6), convert(0.06), T::zero(), convert(20.0)).ok();
    let fitted = JointLosses::new(defaults.drive, fitted_oil, defaults.seal, defaults.epsilon())
        .map(|l| Some(l.at(pressure, convert(4.0)).unwrap()))
        .unwrap_or(state);
    let fitted = [fitted; 3];
    c.bench_function(&format!("environment_torques/paper+losses-n1.2/{name}"), |b| {
        b.iter(|| {
            environment_torques(
                black_box(&leg),
                &water,
                &coefficients,
                black_box(&fitted),
                black_box(&q),
                black_box(&qd),
                &qdd,
            )
        })
    });
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
