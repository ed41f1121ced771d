//! One evaluation of the paper leg's hydrodynamic torques, f64 and f32.
//! Run: `cargo bench -p uwml-core --bench hydro`.
#![allow(missing_docs)]

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use uwml_core::nalgebra::{RealField, Vector3};
use uwml_core::{Chain, Coefficients, Water, hydro_regressors, hydro_torques};

fn bench_for<T: RealField + uwml_core::Real>(c: &mut Criterion, name: &str) {
    let leg = Chain::<T, 3>::paper();
    let water = Water::<T>::default();
    let coefficients = Coefficients::<T, 3>::default();
    let v = |a: f64, b: f64, c: f64| {
        Vector3::new(uwml_core::nalgebra::convert(a), uwml_core::nalgebra::convert(b), uwml_core::nalgebra::convert(c))
    };
    let (q, qd, qdd) = (v(0.3, -0.4, 0.6), v(0.8, 0.5, -0.7), v(1.0, -2.0, 0.5));
    c.bench_function(&format!("hydro_torques/paper/{name}"), |b| {
        b.iter(|| {
            hydro_torques(
                black_box(&leg),
                black_box(&water),
                black_box(&coefficients),
                black_box(&q),
                black_box(&qd),
                black_box(&qdd),
            )
        })
    });
    c.bench_function(&format!("link_motions/paper/{name}"), |b| {
        b.iter(|| uwml_core::link_motions(black_box(&leg), black_box(&q), black_box(&qd), black_box(&qdd)))
    });
    c.bench_function(&format!("hydro_regressors/paper/{name}"), |b| {
        b.iter(|| hydro_regressors(black_box(&leg), black_box(&water), black_box(&q), black_box(&qd), black_box(&qdd)))
    });
}

fn benches(c: &mut Criterion) {
    bench_for::<f64>(c, "f64");
    bench_for::<f32>(c, "f32");
}

criterion_group!(hydro, benches);
criterion_main!(hydro);
