//! The C API's error records, as every API test reads them: a record filled with junk before a
//! call, its parts after, and the check that a call failed as expected. Shared by `helpers.rs`,
//! `robot_api.rs` and `robot_losses.rs`.
#![allow(dead_code, clippy::expect_used)]

use core::ffi::CStr;

use uwml_ffi::{UWML_ERROR_FIELD_LEN, UwmlError};

/// A record no call writes (every field junk), to see that a call writes it.
pub fn blank_error() -> UwmlError {
    UwmlError { code: -99, reserved: -99, index: -99, field: [b'x' as _; UWML_ERROR_FIELD_LEN] }
}

/// (code, index, field) of a filled `UwmlError`; the field must be NUL-terminated.
pub fn parts(e: &UwmlError) -> (i32, i64, String) {
    let bytes = e.field.map(|c| c as u8);
    let field = CStr::from_bytes_until_nul(&bytes).expect("NUL-terminated field");
    assert_eq!(e.reserved, 0, "reserved is written 0");
    (e.code, e.index, field.to_str().expect("UTF-8 field").to_owned())
}

/// The call returned `want.0` and wrote `want` (code, index, field) into its record.
pub fn expect_error(code: i32, e: &UwmlError, want: (i32, i64, &str)) {
    assert_eq!(code, want.0, "returned code ({:?})", parts(e));
    assert_eq!(parts(e), (want.0, want.1, want.2.to_owned()));
}
