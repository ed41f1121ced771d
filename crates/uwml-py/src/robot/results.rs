//! The result objects of `uwml._core.Robot`'s evaluations: instances of the Python package's
//! own result classes (`uwml.robot.results`: `Torques`, `BaseWrench`, `Regressors`,
//! `Jacobians`), their fields set by name, built directly (no `__init__`).

use numpy::ndarray::IxDyn;
use numpy::{PyArrayDyn, PyUntypedArray, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyString, PyType};
use pyo3::{Py, intern};

use super::evaluate::OUTPUTS;
use crate::single::instance;

/// The module that defines the result classes.
const MODULE: &str = "uwml.robot.results";

static TORQUES: PyOnceLock<Py<PyType>> = PyOnceLock::new();
static BASE_WRENCH: PyOnceLock<Py<PyType>> = PyOnceLock::new();
static REGRESSORS: PyOnceLock<Py<PyType>> = PyOnceLock::new();
static JACOBIANS: PyOnceLock<Py<PyType>> = PyOnceLock::new();

/// A `uwml.robot.results.Torques` of the outputs of an evaluation (see `evaluate::OUTPUTS`):
/// the joints' forces, the joint losses (where not evaluated: `no_losses`, or zeros shaped like
/// the joints' forces, one read-only array) and the base wrench (a `BaseWrench`, or None where not
/// evaluated).
pub(super) fn torques<'py>(
    py: Python<'py>,
    outputs: [Option<Bound<'py, PyAny>>; OUTPUTS],
    no_losses: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    // The outputs in their order: the joints' four, the base's four, the bodies' wrenches, the
    // joint losses' three.
    let mut outputs = outputs.into_iter();
    let mut next = || outputs.next().flatten();
    let joints: [Option<Bound<'py, PyAny>>; 4] = core::array::from_fn(|_| next());
    let base_parts: [Option<Bound<'py, PyAny>>; 4] = core::array::from_fn(|_| next());
    let _wrenches = next();
    let losses: [Option<Bound<'py, PyAny>>; 3] = core::array::from_fn(|_| next());
    let none = || py.None().into_bound(py);
    let parts: [&Bound<'py, PyString>; 4] =
        [intern!(py, "drag"), intern!(py, "added_mass"), intern!(py, "buoyancy"), intern!(py, "gravity")];
    let base = match base_parts {
        [Some(d), Some(a), Some(b), Some(g)] => {
            instance(BASE_WRENCH.import(py, MODULE, "BaseWrench")?, parts.into_iter().zip([d, a, b, g]))?
        }
        _ => none(),
    };
    let joints = joints.map(|a| a.unwrap_or_else(none));
    let losses = match losses {
        [Some(visc), Some(seal), Some(current)] => [visc, seal, current],
        _ if no_losses.is_some() => {
            let zeros = no_losses.unwrap_or_else(none);
            [zeros.clone(), zeros.clone(), zeros]
        }
        // No losses evaluated: zeros shaped like the joints' forces, one read-only array.
        _ => {
            let shape = joints[0].cast::<PyUntypedArray>()?.shape().to_vec();
            let zeros = PyArrayDyn::<f64>::zeros(py, IxDyn(&shape), false).into_any();
            zeros.call_method1(intern!(py, "setflags"), (false,))?;
            [zeros.clone(), zeros.clone(), zeros]
        }
    };
    let loss_names = [intern!(py, "visc"), intern!(py, "seal"), intern!(py, "current")];
    let fields =
        parts.into_iter().zip(joints).chain(loss_names.into_iter().zip(losses)).chain([(intern!(py, "base"), base)]);
    instance(TORQUES.import(py, MODULE, "Torques")?, fields)
}

/// A `uwml.robot.results.Regressors` of its twelve fields, by name.
pub(super) fn regressors<'py>(py: Python<'py>, fields: [(&str, Bound<'py, PyAny>); 12]) -> PyResult<Bound<'py, PyAny>> {
    let named: Vec<(Bound<'py, PyString>, Bound<'py, PyAny>)> =
        fields.into_iter().map(|(name, value)| (PyString::intern(py, name), value)).collect();
    instance(REGRESSORS.import(py, MODULE, "Regressors")?, named.iter().map(|(n, v)| (n, v.clone())))
}

/// A `uwml.robot.results.Jacobians` of its four fields, by name.
pub(super) fn jacobians<'py>(py: Python<'py>, fields: [(&str, Bound<'py, PyAny>); 4]) -> PyResult<Bound<'py, PyAny>> {
    let named: Vec<(Bound<'py, PyString>, Bound<'py, PyAny>)> =
        fields.into_iter().map(|(name, value)| (PyString::intern(py, name), value)).collect();
    instance(JACOBIANS.import(py, MODULE, "Jacobians")?, named.iter().map(|(n, v)| (n, v.clone())))
}
