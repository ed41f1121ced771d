//! One of MuJoCo's arrays (an `MjData` or `MjModel` field), held by the coupling for its life as
//! a Python buffer, copied from and to while the GIL is held.
//!
//! A numpy borrow (`try_readonly`, `try_readwrite`) registers and releases itself in rust-numpy's
//! borrow table on every call: for a small robot that cost more than the step's arithmetic
//! (measured by `benches/simulation.py`). A buffer held for the coupling's life is copied from and
//! to (CPython's `PyBuffer_ToContiguous`/`FromContiguous`, a `memcpy` for these arrays) without
//! that bookkeeping.

use numpy::PyArrayDyn;
use pyo3::buffer::PyBuffer;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// A C-contiguous, writable float64 array, kept as a buffer.
pub(super) struct View {
    buffer: PyBuffer<f64>,
    name: &'static str,
}

impl View {
    /// `array` (named `name` in errors) as a view; refused unless C-contiguous and writable.
    pub(super) fn new(array: &Bound<'_, PyArrayDyn<f64>>, name: &'static str) -> PyResult<Self> {
        let buffer = PyBuffer::<f64>::get(array.as_any())?;
        if !buffer.is_c_contiguous() || buffer.readonly() {
            return Err(PyValueError::new_err(format!("{name} must be a writable, C-contiguous float64 array")));
        }
        Ok(Self { buffer, name })
    }

    /// How many numbers it holds.
    pub(super) fn len(&self) -> usize {
        self.buffer.item_count()
    }

    /// Its numbers into `out`, which becomes as long.
    pub(super) fn copy_into(&self, py: Python<'_>, out: &mut Vec<f64>) -> PyResult<()> {
        out.resize(self.len(), 0.0);
        self.buffer.copy_to_slice(py, out).map_err(|_| self.not_contiguous())
    }

    /// `values`, exactly as many as it holds, into it.
    pub(super) fn write(&self, py: Python<'_>, values: &[f64]) -> PyResult<()> {
        self.buffer.copy_from_slice(py, values).map_err(|_| self.not_contiguous())
    }

    fn not_contiguous(&self) -> PyErr {
        PyValueError::new_err(format!(
            "{} must stay a writable, C-contiguous float64 array of {} numbers",
            self.name,
            self.len()
        ))
    }
}
