//! Numpy arrays in and out of the batch loops: borrowing inputs, allocating outputs, splitting
//! a batch over threads, and the error of a non-finite input sample.

use std::ops::Range;

use numpy::ndarray::{Array, Dimension, IntoDimension};
use numpy::{IntoPyArray, PyArray, PyArray2, PyReadonlyArray1, PyReadonlyArray2, PyReadwriteArray2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// A 2-D float64 numpy array.
pub(crate) type Array2<'py> = Bound<'py, PyArray<f64, numpy::Ix2>>;

/// Four float64 samples side by side, one per SIMD lane (two SSE2 registers on baseline x86-64):
/// the robot's batch evaluates four states per call, each lane its own state's scalar evaluation.
pub(crate) type Lanes = simba::simd::WideF64x4;

/// The first non-finite joint state found in a batch.
pub(crate) struct NonFinite {
    pub(crate) argument: &'static str,
    pub(crate) sample: usize,
    pub(crate) joint: usize,
    pub(crate) value: f64,
}

/// A loss condition (pressure [Pa] or temperature [°C]) of one sample outside the core's domain
/// (`uwml_core::check_conditions`), raised as a ValueError naming the argument and the sample.
pub(crate) struct BadCondition {
    pub(crate) sample: usize,
    pub(crate) error: uwml_core::ModelError,
    pub(crate) value: f64,
}

impl From<BadCondition> for PyErr {
    fn from(e: BadCondition) -> Self {
        PyValueError::new_err(format!("{}[{}] is {}: {}", e.error.field, e.sample, e.value, e.error))
    }
}

/// Every sample's loss conditions within the core's domain: pressure [Pa] finite and from 0 to
/// `uwml_core::MAX_PRESSURE`, temperature [°C] finite and above absolute zero.
pub(crate) fn check_conditions(pressure: &[f64], temperature: &[f64]) -> Result<(), BadCondition> {
    for (sample, (&p, &t)) in pressure.iter().zip(temperature).enumerate() {
        uwml_core::check_conditions(p, t).map_err(|error| {
            let value = if error.field == "pressure" { p } else { t };
            BadCondition { sample, error, value }
        })?;
    }
    Ok(())
}

impl NonFinite {}

impl From<NonFinite> for PyErr {
    fn from(e: NonFinite) -> Self {
        PyValueError::new_err(format!(
            "{}[{}, {}] is {}: {} must be finite",
            e.argument,
            e.sample,
            e.joint,
            e.value,
            if e.argument.starts_with('q') { "joint states" } else { "every value" }
        ))
    }
}

/// Runs `batch` on `threads` contiguous parts of the samples `0..n_samples` at once, on scoped
/// threads (on this thread for `threads` ≤ 1), each part writing its rows of the `K` outputs
/// (`n_samples × widths[k]` each). `batch` gets a part's sample range and reports errors with
/// sample indices within the part; the first error in sample order is returned, with its index in
/// the whole batch.
pub(crate) fn in_parallel<const K: usize, E: Send>(
    n_samples: usize,
    widths: [usize; K],
    threads: usize,
    out: [&mut [f64]; K],
    batch: impl Fn(&Range<usize>, [&mut [f64]; K]) -> Result<(), E> + Sync,
    shift: impl Fn(E, usize) -> E + Sync,
) -> Result<(), E> {
    let threads = threads.clamp(1, n_samples.max(1));
    if threads == 1 {
        return batch(&(0..n_samples), out);
    }
    let size = n_samples.div_ceil(threads);
    let mut parts = core::array::from_fn::<_, K, _>(|_| None);
    for ((part, column), width) in parts.iter_mut().zip(out).zip(widths) {
        *part = Some(column.chunks_mut((size * width).max(1)));
    }
    let errors: Vec<_> = std::thread::scope(|scope| {
        let batch = &batch;
        let handles: Vec<_> = (0..threads)
            .map(|i| {
                let range = i * size..((i + 1) * size).min(n_samples);
                let part =
                    parts.each_mut().map(|columns| columns.as_mut().and_then(Iterator::next).unwrap_or_default());
                let shift = &shift;
                scope.spawn(move || batch(&range, part).map_err(|e| shift(e, range.start)))
            })
            .collect();
        handles
            .into_iter()
            .map(|handle| handle.join().unwrap_or_else(|payload| std::panic::resume_unwind(payload)))
            .collect()
    });
    errors.into_iter().collect()
}

/// `K` zeroed float64 arrays `rows × columns`, allocated by numpy (which asks for huge pages:
/// a fresh output then costs far fewer page faults than one from Rust's allocator).
pub(crate) fn zeroed<'py, const K: usize>(py: Python<'py>, rows: usize, columns: usize) -> [Array2<'py>; K] {
    core::array::from_fn(|_| PyArray2::zeros(py, (rows, columns), false))
}

/// Write access to `K` fresh arrays' data.
pub(crate) fn writable<'a, 'py, const K: usize>(
    guards: &'a mut [PyReadwriteArray2<'py, f64>; K],
) -> PyResult<[&'a mut [f64]; K]> {
    let mut slices = guards.each_mut().map(|guard| guard.as_slice_mut().ok());
    if slices.iter().any(Option::is_none) {
        return Err(PyValueError::new_err("internal error: a fresh output array is not contiguous"));
    }
    Ok(slices.each_mut().map(|slice| slice.take().unwrap_or_default()))
}

pub(crate) fn to_numpy<'py, D: Dimension>(
    py: Python<'py>,
    values: Vec<f64>,
    shape: impl IntoDimension<Dim = D>,
) -> PyResult<Bound<'py, PyArray<f64, D>>> {
    let array = Array::from_shape_vec(shape, values).map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(array.into_pyarray(py))
}

pub(crate) fn contiguous<'a>(array: &'a PyReadonlyArray2<'_, f64>, argument: &str) -> PyResult<&'a [f64]> {
    array.as_slice().map_err(|_| PyValueError::new_err(format!("{argument} must be a C-contiguous float64 array")))
}

pub(crate) fn contiguous1<'a>(array: &'a PyReadonlyArray1<'_, f64>, argument: &str, n: usize) -> PyResult<&'a [f64]> {
    let values = array
        .as_slice()
        .map_err(|_| PyValueError::new_err(format!("{argument} must be a C-contiguous float64 array")))?;
    if values.len() != n {
        return Err(PyValueError::new_err(format!("{argument} must have {n} entries, got {}", values.len())));
    }
    Ok(values)
}
