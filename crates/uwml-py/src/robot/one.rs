//! One state per call: the Python arguments read and checked in one pass, one evaluation, the
//! result object built directly (see `crate::single`).

use pyo3::intern;
use pyo3::prelude::*;
use pyo3::types::{PyString, PyType};
use uwml_core::nalgebra::Vector3;
use uwml_core::{AddedMassForm, BaseMotion, Conditions, Current, SegmentCoefficients, Water, robot_hydro};

use super::inputs::StateRow;
use super::{Coefficients, Data, Model};
use crate::single::{fill_values, finite_number, instance, threads_ok};

/// The five arrays of a `uwml.BaseMotion` of one state.
pub(super) type MotionArrays<'py> =
    (Bound<'py, PyAny>, Bound<'py, PyAny>, Bound<'py, PyAny>, Bound<'py, PyAny>, Bound<'py, PyAny>);

/// One state's arguments of `hydro_one`, read and checked.
pub(super) struct OneState {
    pub(super) row: StateRow,
    pub(super) water: Water<f64>,
    /// One drag and one added-mass coefficient for every segment (checked), or `None` for the
    /// segments' own.
    pub(super) coefficients: Option<(f64, f64)>,
    pub(super) motion: BaseMotion<f64>,
    pub(super) current: Current<f64>,
}

impl OneState {
    /// `None` unless every argument (in the order of `hydro_one`'s) is of a kind taken there
    /// and passes its check.
    pub(super) fn read(n: usize, arguments: [&Bound<'_, PyAny>; 11]) -> Option<Self> {
        let [q, qd, qdd, cd, cm, density, gravity, motion, current, current_acceleration, threads] = arguments;
        let mut row = StateRow::new();
        fill_values(q, row.q.get_mut(..n)?)?;
        fill_values(qd, row.qd.get_mut(..n)?)?;
        fill_values(qdd, row.qdd.get_mut(..n)?)?;
        if !threads_ok(threads) {
            return None;
        }
        let water = Water::new(finite_number(density)?, finite_number(gravity)?).ok()?;
        let coefficient = |c: &Bound<'_, PyAny>| -> Option<Option<f64>> {
            if c.is_none() { Some(None) } else { finite_number(c).filter(|x| *x >= 0.0).map(Some) }
        };
        let coefficients = match (coefficient(cd)?, coefficient(cm)?) {
            (None, None) => None,
            // Checked on a table of one segment: the same checks, without filling the robot's.
            (Some(cd), Some(cm)) => SegmentCoefficients::<f64, 1>::uniform(cd, cm).ok().map(|_| Some((cd, cm)))?,
            _ => return None,
        };
        let vector = |value: &Bound<'_, PyAny>| {
            let mut out = [0.0; 3];
            fill_values(value, &mut out).map(|()| Vector3::from(out))
        };
        let motion = if motion.is_none() {
            BaseMotion::fixed()
        } else {
            let (orientation, velocity, angular_velocity, acceleration, angular_acceleration): MotionArrays<'_> =
                motion.extract().ok()?;
            let mut quaternion = [0.0; 4];
            fill_values(&orientation, &mut quaternion)?;
            let twist = (vector(&velocity)?, vector(&angular_velocity)?);
            let derivative = (vector(&acceleration)?, vector(&angular_acceleration)?);
            BaseMotion::new(quaternion, twist.0, twist.1, derivative.0, derivative.1).ok()?
        };
        let current = Current::new(vector(current)?, vector(current_acceleration)?).ok()?;
        Some(Self { row, water, coefficients, motion, current })
    }

    pub(super) fn evaluate(&self, robot: &Model, form: AddedMassForm, data: &mut Data) {
        let Self { row, water, coefficients, motion, current } = self;
        // The table is made here, once, not carried in `Self` (it is as large as the robot's
        // segment capacity); the values were checked by `read`.
        let table = coefficients.and_then(|(cd, cm)| Coefficients::uniform(cd, cm).ok());
        let conditions = Conditions {
            water: *water,
            motion: *motion,
            current: *current,
            coefficients: table.as_ref(),
            form,
            losses: None,
        };
        robot_hydro(robot, &conditions, [&row.q, &row.qd, &row.qdd], data);
    }
}

/// The `result_type` of one evaluation in `data` (with `losses`, `(visc, seal, current)`, when
/// given), its `base` a `base_type`, built directly (no `__init__`).
pub(super) fn one_result<'py>(
    result_type: &Bound<'py, PyType>,
    base_type: &Bound<'py, PyType>,
    data: &Data,
    losses: Option<[&[f64]; 3]>,
) -> PyResult<Bound<'py, PyAny>> {
    let py = result_type.py();
    let forces = data.joint_forces();
    let n = forces.len();
    let column = |value: fn(&uwml_core::JointForces<f64>) -> f64| {
        numpy::PyArray1::from_iter(py, forces.iter().map(value)).into_any()
    };
    let base = data.base_wrench();
    let wrench = |w: &uwml_core::Wrench<f64>| numpy::PyArray1::from_slice(py, &w.to_array()).into_any();
    let names: [&Bound<'py, PyString>; 4] =
        [intern!(py, "drag"), intern!(py, "added_mass"), intern!(py, "buoyancy"), intern!(py, "gravity")];
    let base_object = instance(
        base_type,
        names.into_iter().zip([
            wrench(&base.drag),
            wrench(&base.added_mass),
            wrench(&base.buoyancy),
            wrench(&base.gravity),
        ]),
    )?;
    let joint_columns = [column(|f| f.drag), column(|f| f.added_mass), column(|f| f.buoyancy), column(|f| f.gravity)];
    let mut fields: Vec<(&Bound<'py, PyString>, Bound<'py, PyAny>)> = names.into_iter().zip(joint_columns).collect();
    if let Some(losses) = losses {
        let loss_names = [intern!(py, "visc"), intern!(py, "seal"), intern!(py, "current")];
        for (name, values) in loss_names.into_iter().zip(losses) {
            fields.push((name, numpy::PyArray1::from_slice(py, values.get(..n).unwrap_or(&[])).into_any()));
        }
    }
    fields.push((intern!(py, "base"), base_object));
    instance(result_type, fields)
}

/// Every force of one evaluation in `data`, and every value of `more`, finite (else the general
/// path answers, naming the sample whose forces overflow).
pub(super) fn finite(data: &Data, more: &[&[f64]]) -> bool {
    let joints = data.joint_forces().iter().all(|f| f.total().is_finite());
    let base = data.base_wrench().total().to_array().iter().all(|x| x.is_finite());
    joints && base && more.iter().all(|values| values.iter().all(|x| x.is_finite()))
}
