//! The batch loops: samples evaluated into rows of numpy arrays (the forces four states per
//! evaluation, on SIMD lanes; the regressors one).

use std::ops::Range;

use simba::simd::SimdValue;
use uwml_core::{AddedMassForm, BaseMotion, Conditions, Current, Water, robot_hydro, robot_hydro_regressors};

use super::inputs::{LaneRow, LossStates, Losses, SampleError, StateRow, Surroundings, write_joint_losses};
use super::{Coefficients, Data, LaneData, LaneModel, Model};
use crate::arrays::Lanes;

/// Evaluates samples `range` into `out`, four per evaluation (one per SIMD lane; a last group
/// of fewer repeats its first sample in the lanes left over): 4 joint arrays `n`-wide, 4 base
/// arrays 6-wide, and the bodies' world wrenches about their centres of mass (`(n + 1)·6` wide,
/// base first), unless that array is empty.
#[allow(clippy::too_many_arguments)]
pub(super) fn hydro_range(
    robot: &LaneModel,
    water: &Water<f64>,
    coefficients: Option<&Coefficients>,
    form: AddedMassForm,
    surroundings: &Surroundings<'_>,
    [q, qd, qdd]: [&[f64]; 3],
    losses: Option<&Losses<'_>>,
    range: &Range<usize>,
    data: &mut LaneData,
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
    let water = water.splat::<Lanes>();
    let coefficients = coefficients.map(|c| c.splat::<Lanes>());
    let mut loss_states = LossStates::new();
    let mut lanes = LaneRow::new();
    let fixed = if surroundings.constant() {
        let (motion, current) = surroundings.at(0)?;
        Some((BaseMotion::from_lanes(&[motion]), Current::from_lanes(&[current])))
    } else {
        None
    };
    for (group, first_sample) in range.clone().step_by(4).enumerate() {
        let chunk = first_sample..(first_sample + 4).min(range.end);
        lanes.load([q, qd, qdd], &chunk, n);
        let (motion, current) = match &fixed {
            Some(both) => *both,
            None => {
                let mut motions = [BaseMotion::fixed(); 4];
                let mut currents = [Current::still(); 4];
                for ((m, c), sample) in motions.iter_mut().zip(currents.iter_mut()).zip(chunk.clone()) {
                    (*m, *c) = surroundings.at(sample)?;
                }
                let used = chunk.len();
                (
                    BaseMotion::from_lanes(motions.get(..used).unwrap_or(&motions)),
                    Current::from_lanes(currents.get(..used).unwrap_or(&currents)),
                )
            }
        };
        let conditions = Conditions { water, motion, current, coefficients: coefficients.as_ref(), form, losses: None };
        robot_hydro(robot, &conditions, [&lanes.q, &lanes.qd, &lanes.qdd], data);
        // Each output's lanes once, then one row per sample of the group.
        let first = group * 4;
        let used = chunk.len();
        let put = |out: &mut [f64], width: usize, column: usize, value: Lanes| {
            let lanes: [f64; 4] = value.into();
            for (lane, x) in lanes.into_iter().enumerate().take(used) {
                if let Some(slot) = out.get_mut((first + lane) * width + column) {
                    *slot = x;
                }
            }
        };
        for (j, f) in data.joint_forces().iter().enumerate() {
            put(drag, n, j, f.drag);
            put(added_mass, n, j, f.added_mass);
            put(buoyancy, n, j, f.buoyancy);
            put(gravity, n, j, f.gravity);
        }
        let base = data.base_wrench();
        for (out, wrench) in [
            (&mut *base_drag, &base.drag),
            (&mut *base_added_mass, &base.added_mass),
            (&mut *base_buoyancy, &base.buoyancy),
            (&mut *base_gravity, &base.gravity),
        ] {
            for (column, x) in wrench.to_array().into_iter().enumerate() {
                put(out, 6, column, x);
            }
        }
        if !wrenches.is_empty() {
            for (b, body) in core::iter::once(None).chain((0..n).map(Some)).enumerate() {
                let wrench = data.body_wrench(robot, body).map_or([Lanes::splat(f64::NAN); 6], |w| w.to_array());
                for (column, x) in wrench.into_iter().enumerate() {
                    put(wrenches, bodies, b * 6 + column, x);
                }
            }
        }
        if let Some(losses) = losses {
            for (lane, sample) in chunk.clone().enumerate() {
                let k = first + lane;
                let speeds = qd.get(sample * n..(sample + 1) * n).unwrap_or(&[]);
                let states = loss_states.at(losses, sample).iter().copied();
                write_joint_losses(states, speeds, [&mut *visc, &mut *seal, &mut *loss_current], k * n);
            }
        }
    }
    Ok(())
}

/// Evaluates the regressors of samples `range` into `out`: buoyancy and gravity on the joints
/// (`n` wide) and on the base (6 wide), then the drag and added-mass regressors (`(6 + n) · c`
/// wide for `c` columns, see `robot_hydro_regressors`).
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
    let width = (6 + n) * robot.regressor_column_count();
    let mut row = StateRow::new();
    for (k, sample) in range.clone().enumerate() {
        row.load([q, qd, qdd], sample, n);
        let (motion, current) = surroundings.at(sample)?;
        let (Some(drag), Some(added_mass)) =
            (drag.get_mut(k * width..(k + 1) * width), added_mass.get_mut(k * width..(k + 1) * width))
        else {
            continue;
        };
        let conditions = Conditions { water: *water, motion, current, coefficients: None, form, losses: None };
        robot_hydro_regressors(robot, &conditions, [&row.q, &row.qd, &row.qdd], data, drag, added_mass);
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
