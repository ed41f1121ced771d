//! One state per call: the Python arguments read and checked in one pass, one evaluation, the
//! result object built directly (see `crate::single`).

use numpy::{PyArray2, PyArrayDescrMethods, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::intern;
use pyo3::prelude::*;
use pyo3::types::{PyList, PyString, PyTuple, PyType};
use uwml_core::nalgebra::Vector3;
use uwml_core::{AddedMassForm, BaseMotion, Conditions, Current, Owner, Section, Water, robot_hydro};

use super::inputs::StateRow;
use super::{Coefficients, Data, MAX_ROBOT_JOINTS, Model};
use crate::single::{fill_values, finite_number, instance, threads_ok};

/// The five arrays of a `uwml.BaseMotion` of one state.
pub(super) type MotionArrays<'py> =
    (Bound<'py, PyAny>, Bound<'py, PyAny>, Bound<'py, PyAny>, Bound<'py, PyAny>, Bound<'py, PyAny>);

/// One state's arguments of `hydro_one`, read and checked.
pub(super) struct OneState {
    pub(super) row: StateRow,
    pub(super) water: Water<f64>,
    /// Whether the call's coefficient table holds the coefficients (checked), or the segments'
    /// own are taken.
    pub(super) coefficients: bool,
    pub(super) motion: BaseMotion<f64>,
    pub(super) current: Current<f64>,
}

/// What a `cd` or `cm` array's entries are for: the robot's segments (`uwml.Robot`), or its
/// links, each segment taking its link's (`uwml.Leg`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Layout {
    Segments,
    Links,
}

/// A coefficient argument, `[item][direction]` for `items` items: a number for all; one per item
/// (a list, tuple or 1-D float64 array), both directions alike; or one per item and direction
/// (a list or tuple of pairs, or an `(items, 2)` float64 array). Finite numbers, or `None` (not
/// taken here: the general path answers, with its checks).
fn coefficient_values(value: &Bound<'_, PyAny>, items: usize) -> Option<Vec<[f64; 2]>> {
    if let Some(x) = finite_number(value) {
        return Some(vec![[x, x]; items]);
    }
    if let Ok(array) = value.cast::<PyArray2<f64>>() {
        if array.shape() != [items, 2] || !array.is_aligned() || array.dtype().is_native_byteorder() == Some(false) {
            return None;
        }
        let at = |i: usize, k: usize| array.get_owned([i, k]).filter(|x| x.is_finite());
        return (0..items).map(|i| Some([at(i, 0)?, at(i, 1)?])).collect();
    }
    let mut single = vec![0.0; items];
    if fill_values(value, &mut single).is_some() {
        return Some(single.into_iter().map(|x| [x, x]).collect());
    }
    let pairs: Vec<Bound<'_, PyAny>> = if let Ok(list) = value.cast_exact::<PyList>() {
        list.iter().collect()
    } else if let Ok(tuple) = value.cast_exact::<PyTuple>() {
        tuple.iter().collect()
    } else {
        return None;
    };
    if pairs.len() != items {
        return None;
    }
    pairs
        .iter()
        .map(|item| {
            let mut pair = [0.0; 2];
            fill_values(item, &mut pair).map(|()| pair)
        })
        .collect()
}

/// `cd` and `cm` (either None: the segments' own) written into `table` for every segment of
/// the robot, read by `layout` (the other entries are never read); `Some(false)` when both are
/// None (the table untouched); `None` when either is not taken here or fails a check (a
/// circular segment takes one coefficient).
fn coefficient_table(
    robot: &Model,
    layout: Layout,
    cd: &Bound<'_, PyAny>,
    cm: &Bound<'_, PyAny>,
    table: &mut Coefficients,
) -> Option<bool> {
    if cd.is_none() && cm.is_none() {
        return Some(false);
    }
    let items = match layout {
        Layout::Segments => robot.segments().len(),
        Layout::Links => robot.joint_count(),
    };
    let read = |value: &Bound<'_, PyAny>| {
        if value.is_none() { Some(None) } else { coefficient_values(value, items).map(Some) }
    };
    let (cd, cm) = (read(cd)?, read(cm)?);
    for (k, segment) in robot.segments().iter().enumerate() {
        let item = match (layout, segment.owner) {
            (Layout::Segments, _) => k,
            (Layout::Links, Owner::Link(i)) => i,
            (Layout::Links, Owner::Base) => return None,
        };
        let given = |values: &Option<Vec<[f64; 2]>>, own: [f64; 2]| match values {
            Some(values) => values.get(item).copied().filter(|[a, b]| a == b || !circular(segment)),
            None => Some(own),
        };
        table.set(k, given(&cd, segment.cd)?, given(&cm, segment.cm)?).ok()?;
    }
    Some(true)
}

/// A joint's plausible bounds, `[angle, speed, effort]` (`uwml.plausibility.JointBounds.rows`:
/// the largest plausible `|q|`, `|q̇|` and environment force; infinite where unbounded).
pub(crate) type Bounds = [f64; 3];

/// Whether every joint's angle and speed is within its bounds (else the general path answers,
/// and warns).
fn plausible(bounds: &[Bounds], q: &[f64], qd: &[f64]) -> bool {
    bounds.iter().zip(q).zip(qd).all(|((&[angle, speed, _], q), qd)| q.abs() <= angle && qd.abs() <= speed)
}

/// Whether `segment` has a circular section (one coefficient for every direction).
fn circular(segment: &uwml_core::RobotSegment<f64>) -> bool {
    matches!(segment.section, Section::Circular { .. })
}

impl OneState {
    /// `None` unless every argument (in the order of `hydro_one`'s) is of a kind taken there
    /// and passes its check; `cd` and `cm` arrays laid out by `layout`.
    pub(super) fn read(
        robot: &Model,
        bounds: &[Bounds],
        layout: Layout,
        arguments: [&Bound<'_, PyAny>; 11],
        table: &mut Coefficients,
    ) -> Option<Self> {
        let [q, qd, qdd, cd, cm, density, gravity, motion, current, current_acceleration, threads] = arguments;
        let n = robot.joint_count();
        let mut row = StateRow::new();
        fill_values(q, row.q.get_mut(..n)?)?;
        fill_values(qd, row.qd.get_mut(..n)?)?;
        fill_values(qdd, row.qdd.get_mut(..n)?)?;
        // A state that looks like a unit mistake goes to the general path, which warns.
        if !plausible(bounds, &row.q, &row.qd) {
            return None;
        }
        if !threads_ok(threads) {
            return None;
        }
        let water = Water::new(finite_number(density)?, finite_number(gravity)?).ok()?;
        let coefficients = coefficient_table(robot, layout, cd, cm, table)?;
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

    /// The evaluation, with `table`'s coefficients if [`OneState::read`] wrote them there.
    pub(super) fn evaluate(&self, robot: &Model, form: AddedMassForm, data: &mut Data, table: &Coefficients) {
        let Self { row, water, coefficients, motion, current } = self;
        let conditions = Conditions {
            water: *water,
            motion: *motion,
            current: *current,
            coefficients: coefficients.then_some(table),
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
    // Each array made and filled by numpy (`from_slice`), not over a Rust vector (`from_iter`
    // keeps one, with an owner object of its own).
    let column = |value: fn(&uwml_core::JointForces<f64>) -> f64| {
        let mut values = [0.0; MAX_ROBOT_JOINTS];
        for (slot, force) in values.iter_mut().zip(forces) {
            *slot = value(force);
        }
        numpy::PyArray1::from_slice(py, values.get(..n).unwrap_or_default()).into_any()
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

/// Every force of one evaluation in `data` finite, and with `losses` (`[visc, seal, current]`,
/// each of every joint) every loss, and every joint's environment force (the water's, plus
/// `visc + seal`) within its effort bound: else the general path answers, naming the sample
/// whose forces overflow, or warning of the effort.
pub(super) fn answered(data: &Data, bounds: &[Bounds], losses: Option<[&[f64]; 3]>) -> bool {
    let joints = data.joint_forces().iter().enumerate().all(|(i, f)| {
        let lost = losses
            .map_or(0.0, |[visc, seal, _]| visc.get(i).copied().unwrap_or(0.0) + seal.get(i).copied().unwrap_or(0.0));
        let total = f.total() + lost;
        total.is_finite() && bounds.get(i).is_none_or(|&[_, _, effort]| total.abs() <= effort)
    });
    let base = data.base_wrench().total().to_array().iter().all(|x| x.is_finite());
    let losses_finite = losses.is_none_or(|all| all.iter().all(|values| values.iter().all(|x| x.is_finite())));
    joints && base && losses_finite
}
