//! One state per call, for a controller or a simulator that steps one state at a time: the
//! Python objects read and checked here in one pass (no numpy conversion), one evaluation of
//! exactly the batch path's code (a batch of one sample: the same four-lane evaluation, so the
//! same bits as that state's row of any batch), and the result object built here.
//!
//! Only the plain kinds of arguments are taken: joint states as lists or tuples of Python floats
//! (or ints), or 1-D float64 arrays; scalar coefficients, depth and temperature as Python floats
//! (or ints). Anything else, and any value that fails a check, gives `None`: the caller then
//! takes its general path, which accepts every other valid kind and raises the error of a bad
//! one, so that the errors and their messages are the general path's, whichever path an
//! argument first reached.

use numpy::{PyArray1, PyArray2, PyArrayDescrMethods, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::intern;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyFloat, PyInt, PyList, PyString, PyTuple, PyType};
use uwml_core::{Chain, Coefficients, JointLosses, Water};

use super::{LOSS_WIDTH, Lanes, States, environment_into, hydro_lane_rows, unpack_losses};

/// A finite Python float (or int: `float(value)` is what numpy's conversion gives too).
#[inline]
pub(crate) fn finite_number(value: &Bound<'_, PyAny>) -> Option<f64> {
    let x = if let Ok(float) = value.cast::<PyFloat>() {
        float.value()
    } else if value.is_exact_instance_of::<PyInt>() {
        value.extract::<f64>().ok()?
    } else {
        return None;
    };
    x.is_finite().then_some(x)
}

/// `value` as N finite joint values: a list or tuple of N Python floats (or ints), or a 1-D
/// float64 array of N entries (native byte order, aligned, any stride); `None` for anything
/// else. Any other kind or any other shape, including a batch, is the general path's.
pub(crate) fn joint_values<const N: usize>(value: &Bound<'_, PyAny>) -> Option<[f64; N]> {
    let mut out = [0.0; N];
    fill_values(value, &mut out)?;
    Some(out)
}

/// [`joint_values`] for a length known at run time: fills all of `out`, or gives `None`.
pub(crate) fn fill_values(value: &Bound<'_, PyAny>, out: &mut [f64]) -> Option<()> {
    let n = out.len();
    if let Ok(list) = value.cast_exact::<PyList>() {
        if list.len() != n {
            return None;
        }
        for (slot, item) in out.iter_mut().zip(list.iter()) {
            *slot = finite_number(&item)?;
        }
    } else if let Ok(tuple) = value.cast_exact::<PyTuple>() {
        if tuple.len() != n {
            return None;
        }
        for (slot, item) in out.iter_mut().zip(tuple.iter_borrowed()) {
            *slot = finite_number(&item)?;
        }
    } else if let Ok(array) = value.cast::<PyArray1<f64>>() {
        if array.len() != n || !array.is_aligned() || array.dtype().is_native_byteorder() == Some(false) {
            return None;
        }
        for (index, slot) in out.iter_mut().enumerate() {
            *slot = array.get_owned([index]).filter(|x| x.is_finite())?;
        }
    } else {
        return None;
    }
    Some(())
}

/// `threads` as the general path takes it without conversion: an int ≥ 1 (not a bool).
pub(crate) fn threads_ok(threads: &Bound<'_, PyAny>) -> bool {
    threads.is_exact_instance_of::<PyInt>() && threads.extract::<i64>().is_ok_and(|t| t >= 1)
}

/// A new instance of the (dataclass) type `cls` with `fields` as its attributes, set directly
/// in its `__dict__` (as `object.__new__(cls)` then `object.__setattr__` would: no
/// `__init__`, no `__post_init__`).
pub(crate) fn instance<'py, 'a>(
    cls: &Bound<'py, PyType>,
    fields: impl IntoIterator<Item = (&'a Bound<'py, PyString>, Bound<'py, PyAny>)>,
) -> PyResult<Bound<'py, PyAny>>
where
    'py: 'a,
{
    let py = cls.py();
    let object = cls.call_method1(intern!(py, "__new__"), (cls,))?;
    let dict = object.getattr(intern!(py, "__dict__"))?;
    let dict = dict.cast::<PyDict>()?;
    for (name, value) in fields {
        dict.set_item(name, value)?;
    }
    Ok(object)
}

/// The arguments every one-state evaluation shares, read and checked.
pub(crate) struct Common<const N: usize> {
    pub(crate) q: [f64; N],
    pub(crate) qd: [f64; N],
    pub(crate) qdd: [f64; N],
    pub(crate) water: Water<f64>,
    pub(crate) coefficients: Coefficients<f64, N>,
}

impl<const N: usize> Common<N> {
    /// `None` unless every argument is of a kind taken here and passes its check.
    pub(crate) fn read(
        [q, qd, qdd]: [&Bound<'_, PyAny>; 3],
        [cd, cm]: [&Bound<'_, PyAny>; 2],
        [density, gravity]: [&Bound<'_, PyAny>; 2],
    ) -> Option<Self> {
        let (cd, cm) = (finite_number(cd)?, finite_number(cm)?);
        Some(Self {
            q: joint_values(q)?,
            qd: joint_values(qd)?,
            qdd: joint_values(qdd)?,
            water: Water::new(finite_number(density)?, finite_number(gravity)?).ok()?,
            // The batch path's table: one value per link and direction.
            coefficients: Coefficients::per_direction([[cd; 2]; N], [[cm; 2]; N]).ok()?,
        })
    }

    fn states(&self) -> States<'_> {
        States { q: &self.q, qd: &self.qd, qdd: &self.qdd }
    }
}

/// The field names of `uwml.HydroTorques`, in the core's column order (interned once).
fn hydro_fields(py: Python<'_>) -> [&Bound<'_, PyString>; 4] {
    [intern!(py, "drag"), intern!(py, "added_mass"), intern!(py, "buoyancy"), intern!(py, "gravity")]
}

/// The field names of `uwml.EnvironmentTorques`, in the core's column order.
fn environment_fields(py: Python<'_>) -> [&Bound<'_, PyString>; 7] {
    let [drag, added_mass, buoyancy, gravity] = hydro_fields(py);
    [drag, added_mass, buoyancy, gravity, intern!(py, "visc"), intern!(py, "seal"), intern!(py, "current")]
}

/// One state's drag, added mass, buoyancy and gravity as a `result_type` (`uwml.HydroTorques`)
/// of 1-D arrays, exactly as the batch path computes them.
pub(crate) fn hydro<'py, const N: usize>(
    chain: &Chain<Lanes, N>,
    result_type: &Bound<'py, PyType>,
    common: &Common<N>,
) -> PyResult<Option<Bound<'py, PyAny>>> {
    let mut out = [[0.0; N]; 4];
    let [drag, added_mass, buoyancy, gravity] = &mut out;
    hydro_lane_rows(
        chain,
        &common.water,
        &common.coefficients,
        &common.states(),
        [drag, added_mass, buoyancy, gravity],
    );
    if !all_finite(&out) {
        return Ok(None); // forces that overflow: the general path names the sample
    }
    result(result_type, hydro_fields(result_type.py()), &out).map(Some)
}

/// The joint losses: `None` for none, or packed `(N, LOSS_WIDTH)` in a C-contiguous float64
/// array; `None` (not taken here) for anything else or a bad entry.
fn losses<const N: usize>(losses: &Bound<'_, PyAny>) -> Option<[Option<JointLosses<f64>>; N]> {
    let mut out = [None; N];
    if losses.is_none() {
        return Some(out);
    }
    let array = losses.cast::<PyArray2<f64>>().ok()?;
    if array.shape() != [N, LOSS_WIDTH] {
        return None;
    }
    let values = array.to_vec().ok()?;
    for (slot, row) in out.iter_mut().zip(values.chunks_exact(LOSS_WIDTH)) {
        *slot = unpack_losses(row).ok()?;
    }
    Some(out)
}

/// One state's environment torques (drag, added mass, buoyancy, gravity, visc, seal, current)
/// as a `result_type` (`uwml.EnvironmentTorques`) of 1-D arrays, exactly as the batch path
/// computes them; the pressure is the batch path's `sea_density · gravity · depth`. `None` as
/// the module says.
pub(crate) fn environment<'py, const N: usize>(
    chain: &Chain<Lanes, N>,
    result_type: &Bound<'py, PyType>,
    common: &Common<N>,
    [depth, temperature, sea_density]: [&Bound<'py, PyAny>; 3],
    joint_losses: &Bound<'py, PyAny>,
) -> PyResult<Option<Bound<'py, PyAny>>> {
    let (Some(depth), Some(temperature), Some(sea_density), Some(joint_losses)) =
        (finite_number(depth), finite_number(temperature), finite_number(sea_density), losses::<N>(joint_losses))
    else {
        return Ok(None);
    };
    let pressure = sea_density * common.water.gravity() * depth;
    if !crate::usual_conditions(depth, temperature, sea_density, pressure) {
        return Ok(None);
    }
    let mut out = [[0.0; N]; 7];
    let [drag, added_mass, buoyancy, gravity, visc, seal, current] = &mut out;
    let evaluated = environment_into(
        chain,
        &common.water,
        &common.coefficients,
        &joint_losses,
        &common.states(),
        (&[pressure], &[temperature]),
        [drag, added_mass, buoyancy, gravity, visc, seal, current],
    );
    if evaluated.is_err() || !all_finite(&out) {
        return Ok(None);
    }
    result(result_type, environment_fields(result_type.py()), &out).map(Some)
}

/// Every output finite (else the general path answers, naming the sample whose forces overflow).
fn all_finite<const N: usize, const K: usize>(out: &[[f64; N]; K]) -> bool {
    out.iter().flatten().all(|x| x.is_finite())
}

/// A `result_type` with `rows` as 1-D float64 arrays under the names `fields`.
fn result<'py, const N: usize, const K: usize>(
    result_type: &Bound<'py, PyType>,
    fields: [&Bound<'py, PyString>; K],
    rows: &[[f64; N]; K],
) -> PyResult<Bound<'py, PyAny>> {
    let py = result_type.py();
    instance(
        result_type,
        fields.into_iter().zip(rows).map(|(name, row)| (name, PyArray1::from_slice(py, row).into_any())),
    )
}
