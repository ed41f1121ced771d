//! Cost of the derivatives for control: `environment_jacobians` on the paper leg with losses on
//! all three joints, f64 and f32, next to one `environment_torques` for scale.
//! Run: `cargo bench -p uwml-core --features std --bench derivatives`.
#![allow(missing_docs, clippy::unwrap_used)]

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use uwml_core::nalgebra::{RealField, Vector3, convert};
use uwml_core::{
    Chain, Coefficients, JointLosses, Water, environment_jacobians, environment_torques, hydro_jacobians,
    pressure_at_depth,
};

fn bench_for<T: RealField + uwml_core::Real>(c: &mut Criterion, name: &str) {
    let leg = Chain::<T, 3>::paper();
    let water = Water::<T>::default();
    let coefficients = Coefficients::<T, 3>::default();
    let v = |a: f64, b: f64, c: f64| Vector3::new(convert(a), convert(b), convert(c));
    let (q, qd, qdd) = (v(0.3, -0.4, 0.6), v(0.8, 0.5, -0.7), v(1.0, -2.0, 0.5));
    let pressure = pressure_at_depth::<T>(convert(1000.0), convert(1025.0), convert(9.81)).unwrap();
    let losses = [Some(JointLosses::<T>::default().at(pressure, convert(4.0)).unwrap()); 3];
    c.bench_function(&format!("environment_torques/paper+losses/{name}"), |b| {
        b.iter(|| {
            environment_torques(black_box(&leg), &water, &coefficients, &losses, black_box(&q), black_box(&qd), &qdd)
        })
    });
    c.bench_function(&format!("environment_jacobians/paper+losses/{name}"), |b| {
        b.iter(|| {
            environment_jacobians(black_box(&leg), &water, &coefficients, &losses, black_box(&q), black_box(&qd), &qdd)
        })
    });
    c.bench_function(&format!("hydro_jacobians/paper/{name}"), |b| {
        b.iter(|| hydro_jacobians(black_box(&leg), &water, &coefficients, black_box(&q), black_box(&qd), &qdd))
    });
}

fn benches(c: &mut Criterion) {
    bench_for::<f64>(c, "f64");
    bench_for::<f32>(c, "f32");
}

criterion_group!(derivatives, benches);
criterion_main!(derivatives);
