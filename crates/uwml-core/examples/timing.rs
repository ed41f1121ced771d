//! Wall-clock ns per call of the paper leg's evaluation, and a fixed-work target for callgrind.
//! Usage: `cargo run --release --example timing -- [n_calls] [kinematics|torques|regressors]`.
#![allow(missing_docs)]

use std::hint::black_box;
use std::time::Instant;

use uwml_core::nalgebra::Vector3;
use uwml_core::{Chain, Coefficients, Water, hydro_regressors, hydro_torques, link_motions};

fn main() {
    let mut args = std::env::args().skip(1);
    let n: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(5_000_000);
    let mode = args.next().unwrap_or_else(|| "torques".to_string());
    let leg = Chain::<f64, 3>::paper();
    let water = Water::default();
    let coefficients = Coefficients::default();
    let (qd, qdd) = (Vector3::new(0.8, 0.5, -0.7), Vector3::new(1.0, -2.0, 0.5));
    let start = Instant::now();
    let mut acc = 0.0;
    for i in 0..n {
        let q = Vector3::new(0.3 + i as f64 * 1e-7, -0.4, 0.6);
        acc += match mode.as_str() {
            "kinematics" => link_motions(black_box(&leg), &q, &qd, &qdd)[2].origin.x,
            "regressors" => hydro_regressors(black_box(&leg), &water, &q, &qd, &qdd).drag[2][1].x,
            _ => hydro_torques(black_box(&leg), &water, &coefficients, &q, &qd, &qdd).drag.x,
        };
    }
    let ns = start.elapsed().as_nanos() as f64 / n as f64;
    println!("{mode}: {ns:.1} ns per call ({acc:.3})");
}
