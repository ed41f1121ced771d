//! Numpy arrays in and out of the batch loops: borrowing inputs, allocating outputs, splitting
//! a batch over threads, and the error of a non-finite input sample.

use std::ops::Range;

use numpy::ndarray::{Array, Dimension, IntoDimension};
use numpy::{IntoPyArray, PyArray, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

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

/// `values` as a numpy array of `shape` (an empty one made by numpy: ndarray gives an empty array
/// zero strides, which numpy's BLAS calls take as a leading dimension of 0).
pub(crate) fn to_numpy<'py, D: Dimension>(
    py: Python<'py>,
    values: Vec<f64>,
    shape: impl IntoDimension<Dim = D>,
) -> PyResult<Bound<'py, PyArray<f64, D>>> {
    let shape = shape.into_dimension();
    if values.is_empty() {
        return Ok(PyArray::zeros(py, shape, false));
    }
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

/// `x` as Python's `format(x, ".3g")` writes it: three significant digits, in exponent form
/// (`1e+300`) below 1e-4 and from 1e3 on, trailing zeros dropped.
pub(crate) fn general(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return if x.is_nan() {
            "nan".to_owned()
        } else if x == 0.0 {
            "0".to_owned()
        } else {
            format!("{}inf", if x < 0.0 { "-" } else { "" })
        };
    }
    let scientific = format!("{x:.2e}");
    let (mantissa, exponent) = scientific.split_once('e').unwrap_or((&scientific, "0"));
    let exponent: i32 = exponent.parse().unwrap_or(0);
    let trim = |s: &str| -> String {
        if s.contains('.') { s.trim_end_matches('0').trim_end_matches('.').to_owned() } else { s.to_owned() }
    };
    if (-4..3).contains(&exponent) {
        let decimals = usize::try_from(2 - exponent).unwrap_or(0);
        trim(&format!("{x:.decimals$}"))
    } else {
        format!("{}e{}{:02}", trim(mantissa), if exponent < 0 { '-' } else { '+' }, exponent.abs())
    }
}
