//! The exceptions of `uwml._core`. `UwmlError` is the base of every uwml exception, the
//! Python package's own included (`uwml.errors`), so one `except uwml.UwmlError` catches
//! them all; it extends `ValueError`, as each of them is a bad value or file.

use pyo3::create_exception;
use pyo3::exceptions::PyValueError;

create_exception!(uwml, UwmlError, PyValueError, "The base of every uwml exception: a bad value, model or file.");
create_exception!(uwml, ModelError, UwmlError, "A non-physical or malformed model parameter.");
