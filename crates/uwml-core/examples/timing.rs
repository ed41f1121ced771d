use std::hint::black_box;
use std::time::Instant;
use uwml_core::{Chain, Coefficients, Water, hydro_torques, link_motions, nalgebra::Vector3};
fn main() {
    let leg = Chain::<f64, 3>::paper();
    let w = Water::default();
    let c = Coefficients::default();
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(5_000_000);
    let t = Instant::now();
    let mut acc = 0.0;
    for i in 0..n {
        let x = i as f64 * 1e-7;
        let m = link_motions(
            black_box(&leg),
            &Vector3::new(0.3 + x, -0.4, 0.6),
            &Vector3::new(0.8, 0.5, -0.7),
            &Vector3::new(1.0, -2.0, 0.5),
        );
        acc += m[2].origin.x;
    }
    println!(
        "link_motions {:.1} ns {acc}",
        t.elapsed().as_nanos() as f64 / n as f64
    );
    let t = Instant::now();
    for i in 0..n {
        let x = i as f64 * 1e-7;
        let m = hydro_torques(
            black_box(&leg),
            &w,
            &c,
            &Vector3::new(0.3 + x, -0.4, 0.6),
            &Vector3::new(0.8, 0.5, -0.7),
            &Vector3::new(1.0, -2.0, 0.5),
        );
        acc += m.drag.x;
    }
    println!(
        "hydro_torques {:.1} ns {acc}",
        t.elapsed().as_nanos() as f64 / n as f64
    );
}
