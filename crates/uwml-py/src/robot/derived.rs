//! What the robot's evaluation gives besides its forces: the regressors of the forces in the
//! coefficients (`uwml.Regressors`) and the forces' exact derivatives (`uwml.Jacobians`), for
//! the states `read` in `conditions`, laid out in arrays of their own shapes.

use std::sync::Mutex;

use numpy::ndarray::IxDyn;
use pyo3::prelude::*;
use uwml_core::{Conditions, RobotJacobianData, RobotJacobians, robot_jacobians};

use super::conditions::{LossStates, PyConditions};
use super::evaluate::{Overflow, Row, Setting, regressor_range};
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

/// The entries `[sample][row][column]` of `table` (each sample `rows_per_sample × columns`) for
/// the rows `rows` and columns `picked`, sample-major.
fn gather(
    table: &[f64],
    n_samples: usize,
    (rows_per_sample, columns): (usize, usize),
    rows: std::ops::Range<usize>,
    picked: std::ops::Range<usize>,
) -> Vec<f64> {
    let mut out = Vec::with_capacity(n_samples * rows.len() * picked.len());
    for sample in 0..n_samples {
        for row in rows.clone() {
            let start = (sample * rows_per_sample + row) * columns;
            out.extend_from_slice(table.get(start + picked.start..start + picked.end).unwrap_or(&[]));
        }
    }
    out
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
    let columns = robot.regressor_column_count();
    let width = (6 + n) * columns;
    let widths = [n, n, 6, 6, width, width];
    let mut buffers: [Vec<f64>; 6] = widths.map(|w| vec![0.0; n_samples * w]);
    let setting = Setting { robot, coefficients: None, conditions, states };
    let result = py.detach(|| {
        let out = buffers.each_mut().map(Vec::as_mut_slice);
        let part = |range: &std::ops::Range<usize>, out: [&mut [f64]; 6]| {
            regressor_range(&setting, range, &mut Box::new(Data::new()), out)
        };
        in_parallel(n_samples, widths, threads.max(1), out, part, |e, _| e)
    });
    result.map_err(|e| overflow_error(&e, &states, batched))?;
    let [buoyancy, gravity, base_buoyancy, base_gravity, drag, added_mass] = buffers;
    let s = robot.segments().len();
    let m = columns.saturating_sub(3 * s) / uwml_core::LUMPED_COLUMNS;
    let lead: &[usize] = if batched { &[n_samples] } else { &[] };
    let layout = (6 + n, columns);
    let part = |table: &[f64], base: bool, picked: std::ops::Range<usize>| {
        gather(table, n_samples, layout, if base { 0..6 } else { 6..6 + n }, picked)
    };
    // A lumped coefficient's column is in one of the two tables and zero in the other.
    let lumped = |base: bool| -> Vec<f64> {
        let (d, a) = (
            part(&drag, base, 3 * s..3 * s + uwml_core::LUMPED_COLUMNS * m),
            part(&added_mass, base, 3 * s..3 * s + uwml_core::LUMPED_COLUMNS * m),
        );
        d.iter().zip(&a).map(|(x, y)| x + y).collect()
    };
    let fields = [
        ("buoyancy", shaped(py, buoyancy, lead, &[n])?),
        ("gravity", shaped(py, gravity, lead, &[n])?),
        ("drag", shaped(py, part(&drag, false, 0..2 * s), lead, &[n, s, 2])?),
        ("added_mass", shaped(py, part(&added_mass, false, 0..2 * s), lead, &[n, s, 2])?),
        ("base_buoyancy", shaped(py, base_buoyancy, lead, &[6])?),
        ("base_gravity", shaped(py, base_gravity, lead, &[6])?),
        ("base_drag", shaped(py, part(&drag, true, 0..2 * s), lead, &[6, s, 2])?),
        ("base_added_mass", shaped(py, part(&added_mass, true, 0..2 * s), lead, &[6, s, 2])?),
        ("axial_drag", shaped(py, part(&drag, false, 2 * s..3 * s), lead, &[n, s])?),
        ("base_axial_drag", shaped(py, part(&drag, true, 2 * s..3 * s), lead, &[6, s])?),
        ("lumped", shaped(py, lumped(false), lead, &[n, m, 63])?),
        ("base_lumped", shaped(py, lumped(true), lead, &[6, m, 63])?),
    ];
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
