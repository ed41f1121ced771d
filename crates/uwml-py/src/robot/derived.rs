//! What the robot's evaluation gives besides its forces: the regressors of the forces in the
//! coefficients (`uwml.Regressors`) and the forces' exact derivatives (`uwml.Jacobians`), for
//! the states `read` in `conditions`, laid out in arrays of their own shapes.

use std::sync::Mutex;

use numpy::ndarray::IxDyn;
use numpy::{PyArrayDyn, PyArrayMethods};
use pyo3::prelude::*;
use uwml_core::{Conditions, RobotJacobianData, RobotJacobians, robot_jacobians};

use super::conditions::{LossStates, PyConditions};
use super::evaluate::{Overflow, REGRESSOR_OUTPUTS, Row, Setting, regressor_range, regressor_widths};
use super::states::Read;
use super::{Data, MAX_LUMPED_BODIES, MAX_ROBOT_JOINTS, MAX_SEGMENTS, Model, overflow_error, results};
use crate::{in_parallel, to_numpy};

/// `values` as an array of shape `lead + shape`.
pub(super) fn shaped<'py>(
    py: Python<'py>,
    values: Vec<f64>,
    lead: &[usize],
    shape: &[usize],
) -> PyResult<Bound<'py, PyAny>> {
    let full: Vec<usize> = lead.iter().chain(shape).copied().collect();
    to_numpy(py, values, IxDyn(&full)).map(Bound::into_any)
}

/// A `uwml.Regressors` (see `uwml.robot.results`), one state per evaluation, on `threads`
/// threads with the GIL released.
pub(super) fn regressors<'py>(
    py: Python<'py>,
    robot: &Model,
    read: &Read<'py>,
    conditions: &PyConditions,
    threads: usize,
) -> PyResult<Bound<'py, PyAny>> {
    let n = robot.joint_count();
    let n_samples = conditions.sample_count(read.rows())?;
    let batched = read.rows().is_some() || conditions.samples.is_some();
    let states = read.states(n);
    let s = robot.segments().len();
    let m = robot.regressor_column_count().saturating_sub(3 * s) / uwml_core::LUMPED_COLUMNS;
    let widths = regressor_widths(n, s, m);
    let lead: &[usize] = if batched { &[n_samples] } else { &[] };
    let shapes: [&[usize]; REGRESSOR_OUTPUTS] = [
        &[n],
        &[n],
        &[n, s, 2],
        &[n, s, 2],
        &[6],
        &[6],
        &[6, s, 2],
        &[6, s, 2],
        &[n, s],
        &[6, s],
        &[n, m, uwml_core::LUMPED_COLUMNS],
        &[6, m, uwml_core::LUMPED_COLUMNS],
    ];
    // The outputs allocated by numpy (a fresh output then costs fewer page faults), written in
    // place.
    let arrays = shapes.map(|shape| {
        let full: Vec<usize> = lead.iter().chain(shape).copied().collect();
        PyArrayDyn::<f64>::zeros(py, IxDyn(&full), false)
    });
    let mut guards = arrays.each_ref().map(|a| a.readwrite());
    let mut slices = guards.iter_mut().map(|g| g.as_slice_mut().ok());
    let out: [&mut [f64]; REGRESSOR_OUTPUTS] = core::array::from_fn(|_| slices.next().flatten().unwrap_or_default());
    let setting = Setting { robot, coefficients: None, conditions, states };
    let result = py.detach(|| {
        let part = |range: &std::ops::Range<usize>, out: [&mut [f64]; REGRESSOR_OUTPUTS]| {
            regressor_range(&setting, range, &mut Box::new(Data::new()), out)
        };
        in_parallel(n_samples, widths, threads.max(1), out, part, |e, _| e)
    });
    drop(guards);
    result.map_err(|e| overflow_error(&e, &states, batched))?;
    let names = [
        "buoyancy",
        "gravity",
        "drag",
        "added_mass",
        "base_buoyancy",
        "base_gravity",
        "base_drag",
        "base_added_mass",
        "axial_drag",
        "base_axial_drag",
        "lumped",
        "base_lumped",
    ];
    let mut arrays = arrays.into_iter();
    let fields: [(&str, Bound<'py, PyAny>); REGRESSOR_OUTPUTS] =
        names.map(|name| (name, arrays.next().map_or_else(|| py.None().into_bound(py), Bound::into_any)));
    results::regressors(py, fields)
}

type JacobianData = RobotJacobianData<f64, MAX_ROBOT_JOINTS, MAX_SEGMENTS, MAX_LUMPED_BODIES>;

/// A `uwml.Jacobians`: the forces of `environment` on base and joints (with the conditions' joint
/// losses) and their exact derivatives, in the workspace kept in `shared`.
pub(super) fn jacobians<'py>(
    py: Python<'py>,
    robot: &Model,
    shared: &Mutex<Option<Box<JacobianData>>>,
    read: &Read<'py>,
    conditions: &PyConditions,
) -> PyResult<Bound<'py, PyAny>> {
    let n = robot.joint_count();
    let m = 6 + n;
    let n_samples = conditions.sample_count(read.rows())?;
    let batched = read.rows().is_some() || conditions.samples.is_some();
    let states = read.states(n);
    let (mut value, mut d_q, mut d_velocity, mut matrix) = (
        vec![0.0; n_samples * m],
        vec![0.0; n_samples * m * n],
        vec![0.0; n_samples * m * m],
        vec![0.0; n_samples * m * m],
    );
    let result = py.detach(|| -> Result<(), Overflow> {
        // Locked only while detached: a thread that waits for the workspace holds no GIL that
        // the thread holding the workspace needs to return (no deadlock).
        let mut work = shared.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        let work = work.get_or_insert_with(|| Box::new(RobotJacobianData::new(robot)));
        let mut row = Row::<f64>::new();
        let mut loss_states = LossStates::new();
        let rows = value
            .chunks_exact_mut(m)
            .zip(d_q.chunks_exact_mut((m * n).max(1)))
            .zip(d_velocity.chunks_exact_mut(m * m).zip(matrix.chunks_exact_mut(m * m)));
        let mut overflow = None;
        for (sample, ((value, d_q), (d_velocity, added_mass_matrix))) in rows.enumerate() {
            row.load(&states, &(sample..sample + 1));
            let (motion, current) = conditions.at(sample);
            let losses = conditions.losses.as_ref().map(|l| loss_states.at(l, sample));
            let core = Conditions {
                water: conditions.water,
                motion,
                current,
                coefficients: conditions.coefficients.as_deref(),
                form: conditions.form,
                losses,
            };
            robot_jacobians(
                robot,
                &core,
                [&row.q, &row.qd, &row.qdd],
                work,
                RobotJacobians { value, d_q, d_velocity, added_mass_matrix },
            );
            let finite = value.iter().chain(d_q.iter()).chain(d_velocity.iter()).all(|x| x.is_finite());
            if !finite && overflow.is_none() {
                overflow = Some(sample);
            }
        }
        overflow.map_or(Ok(()), |sample| Err(Overflow { sample }))
    });
    result.map_err(|e| overflow_error(&e, &states, batched))?;
    let lead: &[usize] = if batched { &[n_samples] } else { &[] };
    let fields = [
        ("value", shaped(py, value, lead, &[m])?),
        ("d_q", shaped(py, d_q, lead, &[m, n])?),
        ("d_velocity", shaped(py, d_velocity, lead, &[m, m])?),
        ("added_mass_matrix", shaped(py, matrix, lead, &[m, m])?),
    ];
    results::jacobians(py, fields)
}
