//! Links the no_std binary with no C runtime, no libc and no dynamic loader: any symbol that
//! std, libc or an allocator would provide is then undefined and fails the link.

fn main() {
    for arg in ["-nostartfiles", "-nostdlib", "-static", "-no-pie"] {
        println!("cargo:rustc-link-arg-bin=uwml-nostd-check={arg}");
    }
    println!("cargo:rerun-if-changed=build.rs");
}
