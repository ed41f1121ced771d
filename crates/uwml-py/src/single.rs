//! Plain Python objects read without numpy's conversions (one state of a controller or a
//! simulator stepping one state at a time, `robot::states`), and result objects built without
//! `__init__` (`robot::results`).
//!
//! Only the plain kinds of values are taken: lists or tuples of Python floats (or ints), or 1-D
//! float64 arrays. Anything else, and any value that is not finite, gives `None`: the caller then
//! has the Python package check the values (and raise the error of a bad one, naming it).

use numpy::{PyArray1, PyArrayDescrMethods, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::intern;
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyDict, PyFloat, PyInt, PyList, PyString, PyTuple, PyType};

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

/// `object.__new__`.
static OBJECT_NEW: PyOnceLock<Py<PyAny>> = PyOnceLock::new();

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
    // `object.__new__`, looked up once (not through `cls` at every call).
    let object_new = OBJECT_NEW.get_or_try_init(py, || {
        py.import(intern!(py, "builtins"))?
            .getattr(intern!(py, "object"))?
            .getattr(intern!(py, "__new__"))
            .map(Bound::unbind)
    })?;
    let object = object_new.bind(py).call1((cls,))?;
    let dict = object.getattr(intern!(py, "__dict__"))?;
    let dict = dict.cast::<PyDict>()?;
    for (name, value) in fields {
        dict.set_item(name, value)?;
    }
    Ok(object)
}
