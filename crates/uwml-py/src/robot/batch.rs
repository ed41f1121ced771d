//! The batch loops: samples evaluated into rows of numpy arrays (one state per evaluation).

use std::ops::Range;

use uwml_core::{AddedMassForm, Water, loss_torques, robot_hydro_regressors_with, robot_hydro_with};

use super::inputs::{LossStates, Losses, SampleError, StateRow, Surroundings};
use super::{Coefficients, Data, Model};

/// Evaluates samples `range` into `out`: 4 joint arrays `n`-wide, 4 base arrays 6-wide, and the
/// bodies' world wrenches about their centres of mass (`(n + 1)·6` wide, base first), unless that
/// array is empty.
#[allow(clippy::too_many_arguments)]
pub(super) fn hydro_range(
    robot: &Model,
    water: &Water<f64>,
    coefficients: Option<&Coefficients>,
    form: AddedMassForm,
    surroundings: &Surroundings<'_>,
    [q, qd, qdd]: [&[f64]; 3],
    losses: Option<&Losses<'_>>,
    range: &Range<usize>,
    data: &mut Data,
    out: [&mut [f64]; 12],
) -> Result<(), SampleError> {
    let n = robot.joint_count();
    let [
        drag,
        added_mass,
        buoyancy,
        gravity,
        base_drag,
        base_added_mass,
        base_buoyancy,
        base_gravity,
        wrenches,
        visc,
        seal,
        loss_current,
    ] = out;
    let bodies = (n + 1) * 6;
    let mut loss_states = LossStates::new();
    let mut row = StateRow::new();
    let fixed = if surroundings.constant() { Some(surroundings.at(0)?) } else { None };
    for (k, sample) in range.clone().enumerate() {
        row.load([q, qd, qdd], sample, n);
        let (motion, current) = match fixed {
            Some(both) => both,
            None => surroundings.at(sample)?,
        };
        robot_hydro_with(robot, water, coefficients, form, &motion, &current, &row.q, &row.qd, &row.qdd, data);
        let joint_row = |out: &mut [f64], value: &dyn Fn(&uwml_core::JointForces<f64>) -> f64| {
            if let Some(row) = out.get_mut(k * n..(k + 1) * n) {
                for (slot, forces) in row.iter_mut().zip(data.joint_forces()) {
                    *slot = value(forces);
                }
            }
        };
        joint_row(drag, &|f| f.drag);
        joint_row(added_mass, &|f| f.added_mass);
        joint_row(buoyancy, &|f| f.buoyancy);
        joint_row(gravity, &|f| f.gravity);
        let base = data.base_wrench();
        for (out, wrench) in [
            (&mut *base_drag, &base.drag),
            (&mut *base_added_mass, &base.added_mass),
            (&mut *base_buoyancy, &base.buoyancy),
            (&mut *base_gravity, &base.gravity),
        ] {
            if let Some(row) = out.get_mut(k * 6..(k + 1) * 6) {
                row.copy_from_slice(&wrench.to_array());
            }
        }
        if let Some(row) = wrenches.get_mut(k * bodies..(k + 1) * bodies) {
            for (body, slot) in core::iter::once(None).chain((0..n).map(Some)).zip(row.chunks_exact_mut(6)) {
                let wrench = data.body_wrench(robot, body).map_or([f64::NAN; 6], |w| w.to_array());
                slot.copy_from_slice(&wrench);
            }
        }
        if let Some(losses) = losses {
            let (v, f, c) = loss_torques(loss_states.at(losses, sample), &row.qd.into());
            for (out, values) in [(&mut *visc, v), (&mut *seal, f), (&mut *loss_current, c)] {
                if let Some(row) = out.get_mut(k * n..(k + 1) * n) {
                    for (slot, x) in row.iter_mut().zip(values.iter()) {
                        *slot = *x;
                    }
                }
            }
        }
    }
    Ok(())
}

/// Evaluates the regressors of samples `range` into `out`: buoyancy and gravity on the joints
/// (`n` wide) and on the base (6 wide), then the drag and added-mass regressors (`(6 + n) · 2s`
/// wide, see `robot_hydro_regressors`).
#[allow(clippy::too_many_arguments)]
pub(super) fn regressor_range(
    robot: &Model,
    water: &Water<f64>,
    form: AddedMassForm,
    surroundings: &Surroundings<'_>,
    [q, qd, qdd]: [&[f64]; 3],
    range: &Range<usize>,
    data: &mut Data,
    [buoyancy, gravity, base_buoyancy, base_gravity, drag, added_mass]: [&mut [f64]; 6],
) -> Result<(), SampleError> {
    let n = robot.joint_count();
    let width = (6 + n) * 2 * robot.segments().len();
    let mut row = StateRow::new();
    for (k, sample) in range.clone().enumerate() {
        row.load([q, qd, qdd], sample, n);
        let (motion, current) = surroundings.at(sample)?;
        let (Some(drag), Some(added_mass)) =
            (drag.get_mut(k * width..(k + 1) * width), added_mass.get_mut(k * width..(k + 1) * width))
        else {
            continue;
        };
        robot_hydro_regressors_with(
            robot, water, form, &motion, &current, &row.q, &row.qd, &row.qdd, data, drag, added_mass,
        );
        for (out, value) in [
            (
                &mut *buoyancy,
                &(|f: &uwml_core::JointForces<f64>| f.buoyancy) as &dyn Fn(&uwml_core::JointForces<f64>) -> f64,
            ),
            (&mut *gravity, &|f: &uwml_core::JointForces<f64>| f.gravity),
        ] {
            if let Some(row) = out.get_mut(k * n..(k + 1) * n) {
                for (slot, forces) in row.iter_mut().zip(data.joint_forces()) {
                    *slot = value(forces);
                }
            }
        }
        let base = data.base_wrench();
        for (out, wrench) in [(&mut *base_buoyancy, &base.buoyancy), (&mut *base_gravity, &base.gravity)] {
            if let Some(row) = out.get_mut(k * 6..(k + 1) * 6) {
                row.copy_from_slice(&wrench.to_array());
            }
        }
    }
    Ok(())
}
