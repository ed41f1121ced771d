//! `include/uwml.h` is what cbindgen makes of `src/lib.rs` with `cbindgen.toml`, and the Python
//! package ships the same file (`python/uwml/include/uwml.h`, the folder `uwml.get_include()`
//! names).
//!
//! After a change of the C API: `UWML_BLESS=1 cargo test -p uwml-ffi --test header` rewrites the
//! header and its copy; review the diff and commit both with the change.
#![allow(missing_docs, clippy::expect_used)]

use std::path::Path;

#[test]
fn header_is_up_to_date() {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let config = cbindgen::Config::from_file(crate_dir.join("cbindgen.toml")).expect("cbindgen.toml parses");
    let bindings = cbindgen::Builder::new()
        .with_config(config)
        .with_src(crate_dir.join("src/lib.rs"))
        .generate()
        .expect("cbindgen generates the header");
    let mut generated = Vec::new();
    bindings.write(&mut generated);
    let generated = String::from_utf8(generated).expect("the header is UTF-8");

    let path = crate_dir.join("include/uwml.h");
    let python_copy = crate_dir.join("../../python/uwml/include/uwml.h");
    if std::env::var_os("UWML_BLESS").is_some() {
        std::fs::write(&path, &generated).expect("include/uwml.h is writable");
        std::fs::write(&python_copy, &generated).expect("python/uwml/include/uwml.h is writable");
        return;
    }
    for (name, file) in [("crates/uwml-ffi/include/uwml.h", &path), ("python/uwml/include/uwml.h", &python_copy)] {
        let checked_in = std::fs::read_to_string(file).unwrap_or_default();
        assert!(
            checked_in == generated,
            "{name} is out of date with src/lib.rs: regenerate it with\n    \
             UWML_BLESS=1 cargo test -p uwml-ffi --test header\nand commit the result"
        );
    }
}
