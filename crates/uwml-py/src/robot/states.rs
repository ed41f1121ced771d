//! The joint states of a call, read once for both ways in: one state as plain Python objects
//! (lists or tuples of numbers, or 1-D float64 arrays: read without numpy's conversions), or the
//! arrays the Python package made and checked (`(N,)` for one state, `(n_samples, N)`).

use numpy::{PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use super::evaluate::States;
use super::inputs::StateRow;
use crate::single::fill_values;

/// A joint's plausible bounds, `[angle, speed, effort]` (`uwml.plausibility.JointBounds.rows`:
/// the largest plausible `|q|`, `|q̇|` and environment force; infinite where unbounded).
pub(crate) type Bounds = [f64; 3];

/// Whether every joint's angle and speed is within its bounds (else the Python package checks
/// the state, and warns).
fn plausible(bounds: &[Bounds], q: &[f64], qd: &[f64]) -> bool {
    bounds.iter().zip(q).zip(qd).all(|((&[angle, speed, _], q), qd)| q.abs() <= angle && qd.abs() <= speed)
}

/// The joint states of a call, as read (one state on the stack: no allocation per call).
#[allow(clippy::large_enum_variant)]
pub(super) enum Read<'py> {
    /// One state read from plain objects.
    One(StateRow),
    /// Arrays `(N,)` or `(n_samples, N)`.
    Arrays([PyReadonlyArrayDyn<'py, f64>; 3]),
}

impl<'py> Read<'py> {
    /// One plain state of `n` joints within `bounds` (each joint's angle and speed), or `None`
    /// for anything else: the Python package then checks the arguments (and warns of a state
    /// beyond its bounds) and calls again with arrays ([`Read::arrays`]).
    pub(super) fn plain(states: [&Bound<'py, PyAny>; 3], n: usize, bounds: &[Bounds]) -> Option<Self> {
        let mut row = StateRow::new();
        for (value, out) in states.into_iter().zip([&mut row.q, &mut row.qd, &mut row.qdd]) {
            fill_values(value, out.get_mut(..n)?)?;
        }
        plausible(bounds, &row.q, &row.qd).then_some(Self::One(row))
    }

    /// Three float64 arrays of one shape, `(n,)` or `(n_samples, n)`, C-contiguous and finite.
    pub(super) fn arrays(states: [&Bound<'py, PyAny>; 3], n: usize) -> PyResult<Self> {
        let names = ["q", "qd", "qdd"];
        let mut arrays = Vec::with_capacity(3);
        for (value, name) in states.into_iter().zip(names) {
            let array = value.extract::<PyReadonlyArrayDyn<'py, f64>>().map_err(|_| {
                PyValueError::new_err(format!("{name} must be a float64 array (n_samples, {n}) or ({n},)"))
            })?;
            arrays.push(array);
        }
        let [q, qd, qdd]: [PyReadonlyArrayDyn<'py, f64>; 3] =
            arrays.try_into().map_err(|_| PyValueError::new_err("internal error: three states"))?;
        let shape = q.shape().to_vec();
        for (name, array) in names.into_iter().zip([&q, &qd, &qdd]) {
            let ok = match array.shape() {
                [w] | [_, w] => *w == n,
                _ => false,
            };
            if !ok || array.shape() != shape.as_slice() {
                return Err(PyValueError::new_err(format!(
                    "{name} must have shape (n_samples, {n}) or ({n},) like q, got {:?} (q: {shape:?})",
                    array.shape()
                )));
            }
            let values = array
                .as_slice()
                .map_err(|_| PyValueError::new_err(format!("{name} must be a C-contiguous float64 array")))?;
            if let Some(i) = values.iter().position(|x| !x.is_finite()) {
                let value = values.get(i).copied().unwrap_or(f64::NAN);
                return Err(PyValueError::new_err(format!(
                    "{name}[{}, {}] is {value}: joint states must be finite",
                    i / n.max(1),
                    i % n.max(1)
                )));
            }
        }
        Ok(Self::Arrays([q, qd, qdd]))
    }

    /// The number of rows given per sample (`None`: one state for every sample).
    pub(super) fn rows(&self) -> Option<usize> {
        match self {
            Self::One(_) => None,
            Self::Arrays([q, ..]) => match q.shape() {
                [rows, _] => Some(*rows),
                _ => None,
            },
        }
    }

    /// The states as the evaluation reads them.
    pub(super) fn states(&self, n: usize) -> States<'_> {
        match self {
            Self::One(row) => {
                States { values: [&row.q, &row.qd, &row.qdd].map(|v| v.get(..n).unwrap_or(&[])), n, broadcast: true }
            }
            Self::Arrays(arrays) => States {
                values: arrays.each_ref().map(|a| a.as_slice().unwrap_or(&[])),
                n,
                broadcast: self.rows().is_none(),
            },
        }
    }
}
