//! The no-panic proof: built with `--cfg uwml_no_panic` (every evaluation function of uwml-core
//! then carries `#[no_panic]`), the `no-panic` feature, and the `no-panic` profile (fat LTO, one
//! codegen unit, `panic = "unwind"`), this binary links only if no instantiation it calls can
//! panic; see docs/proofs.md. Hosted, because unwinding, which no-panic detects panics by, needs
//! std; the calls are the no_std binary's (src/exercise.rs).

#[cfg(not(feature = "canary-panic"))]
#[path = "../exercise.rs"]
mod exercise;

fn main() {
    // The canary leaves out the calls, which take most of the build.
    #[cfg(not(feature = "canary-panic"))]
    let bad = exercise::exercise();
    #[cfg(feature = "canary-panic")]
    let bad = 0;
    #[cfg(feature = "canary-panic")]
    let bad = bad + u32::from(canary_panic(std::hint::black_box(5)));
    if cfg!(not(uwml_no_panic)) {
        eprintln!("warning: built without --cfg uwml_no_panic: nothing was proven");
    }
    std::process::exit(bad.min(255) as i32)
}

/// Must fail to link: indexes out of bounds for `index` ≥ 3.
#[cfg(feature = "canary-panic")]
#[no_panic::no_panic]
fn canary_panic(index: usize) -> u8 {
    [1, 2, 3][index]
}
