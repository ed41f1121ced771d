//! Cost of the derivatives for control: `robot_jacobians` of the paper leg
//! (`presets::paper_leg`) with losses on all three joints and without, f64 and f32.
//! Run: `cargo bench -p uwml-core --features std --bench derivatives`.
#![allow(missing_docs, clippy::unwrap_used)]

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use uwml_core::nalgebra::{RealField, convert};
use uwml_core::{
    Conditions, JointLosses, RobotJacobianData, RobotJacobians, Water, presets, pressure_at_depth, robot_jacobians,
};

fn bench_for<T: RealField + uwml_core::Real>(c: &mut Criterion, name: &str) {
    let leg = presets::paper_leg::<T>();
    let water = Water::<T>::default();
    let s = |x: [f64; 3]| x.map(convert::<f64, T>);
    let (q, qd, qdd) = (s([0.3, -0.4, 0.6]), s([0.8, 0.5, -0.7]), s([1.0, -2.0, 0.5]));
    let pressure = pressure_at_depth::<T>(convert(1000.0), convert(1025.0), convert(9.81)).unwrap();
    let losses = [Some(JointLosses::<T>::default().at(pressure, convert(4.0)).unwrap()); 3];
    let mut work = RobotJacobianData::new(&leg);
    let (mut value, mut d_q, mut d_velocity, mut matrix) =
        ([T::zero(); 9], [T::zero(); 27], [T::zero(); 81], [T::zero(); 81]);
    for (what, conditions) in [
        ("paper+losses", Conditions { losses: Some(&losses), ..Conditions::new(water) }),
        ("paper", Conditions::new(water)),
    ] {
        c.bench_function(&format!("robot_jacobians/{what}/{name}"), |b| {
            b.iter(|| {
                let out = RobotJacobians {
                    value: &mut value,
                    d_q: &mut d_q,
                    d_velocity: &mut d_velocity,
                    added_mass_matrix: &mut matrix,
                };
                robot_jacobians(black_box(&leg), &conditions, [black_box(&q), black_box(&qd), &qdd], &mut work, out)
            })
        });
    }
}

fn benches(c: &mut Criterion) {
    bench_for::<f64>(c, "f64");
    bench_for::<f32>(c, "f32");
}

criterion_group!(derivatives, benches);
criterion_main!(derivatives);
