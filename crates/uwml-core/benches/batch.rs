//! A batch of 1024 evaluations of the paper leg at varied states, as a controller bank or an
//! offline tool runs them: hydrodynamics alone and with the default losses on all three joints,
//! f64 and f32. Criterion prints the time per batch and the states per second.
//! Run: `cargo bench -p uwml-core --features std --bench batch`.
#![allow(missing_docs, clippy::unwrap_used)]

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use uwml_core::nalgebra::{RealField, convert};
use uwml_core::{Conditions, JointLosses, RobotData, Water, presets, pressure_at_depth, robot_hydro};

const BATCH: usize = 1024;

/// Deterministic states spread over the joints' ranges (a fixed linear congruential sequence).
fn states<T: RealField + Copy>() -> Vec<[[T; 3]; 3]> {
    let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut uniform = |scale: f64| {
        x = x.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        convert::<f64, T>(scale * ((x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0))
    };
    (0..BATCH)
        .map(|_| {
            let mut v = |scale| [uniform(scale), uniform(scale), uniform(scale)];
            [v(3.0), v(2.0), v(9.0)]
        })
        .collect()
}

fn bench_for<T: RealField + uwml_core::Real>(c: &mut Criterion, name: &str) {
    let leg = presets::paper_leg::<T>();
    let water = Water::<T>::default();
    let pressure = pressure_at_depth::<T>(convert(1000.0), convert(1025.0), convert(9.81)).unwrap();
    let losses = [Some(JointLosses::<T>::default().at(pressure, convert(4.0)).unwrap()); 3];
    let states = states::<T>();
    let mut group = c.benchmark_group(format!("batch{BATCH}/{name}"));
    group.throughput(Throughput::Elements(BATCH as u64));
    let mut data = RobotData::new();
    for (what, conditions) in [
        ("robot_hydro", Conditions::new(water)),
        ("robot_hydro+losses", Conditions { losses: Some(&losses), ..Conditions::new(water) }),
    ] {
        group.bench_function(what, |b| {
            b.iter(|| {
                for [q, qd, qdd] in black_box(&states) {
                    robot_hydro(&leg, &conditions, [q, qd, qdd], &mut data);
                    black_box(data.joint_forces());
                }
            })
        });
    }
    group.finish();
}

fn bench_lanes(c: &mut Criterion) {
    use simba::simd::WideF64x4;
    let leg = presets::paper_leg::<f64>().splat::<WideF64x4>();
    let conditions = Conditions::new(Water::<f64>::default().splat());
    let states = states::<f64>();
    // Four states side by side, one per lane.
    let lanes: Vec<[[WideF64x4; 3]; 3]> = states
        .chunks_exact(4)
        .map(|four| {
            let lane = |k: usize, j: usize| {
                WideF64x4::from(
                    [0, 1, 2, 3].map(|l| four.get(l).and_then(|s| s.get(k)?.get(j).copied()).unwrap_or(0.0)),
                )
            };
            core::array::from_fn(|k| core::array::from_fn(|j| lane(k, j)))
        })
        .collect();
    let mut group = c.benchmark_group(format!("batch{BATCH}/f64x4 (WideF64x4, 4 states per call)"));
    group.throughput(Throughput::Elements(BATCH as u64));
    let mut data = RobotData::new();
    group.bench_function("robot_hydro", |b| {
        b.iter(|| {
            for [q, qd, qdd] in black_box(&lanes) {
                robot_hydro(&leg, &conditions, [q, qd, qdd], &mut data);
                black_box(data.joint_forces());
            }
        })
    });
    group.finish();
}

fn benches(c: &mut Criterion) {
    bench_for::<f64>(c, "f64");
    bench_for::<f32>(c, "f32");
    bench_lanes(c);
}

criterion_group!(batch, benches);
criterion_main!(batch);
