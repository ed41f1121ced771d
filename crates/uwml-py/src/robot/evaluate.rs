//! The one evaluation loop of `uwml._core.Robot`: samples evaluated into rows of numpy arrays,
//! one state per evaluation for a batch of one and four (one per SIMD lane) for larger batches:
//! each lane has exactly the bits of the scalar evaluation of its state, so a state's forces are
//! the same alone or in any batch. What is written (joints, the base wrench, the bodies' wrenches,
//! the joint losses) is what the caller asked for; the regressors' loop is here too.

use std::ops::Range;

use simba::simd::SimdValue;
use uwml_core::{
    AddedMassForm, BaseMotion, Conditions, Current, Real, Robot, RobotData, SegmentCoefficients, Water, robot_hydro,
    robot_hydro_regressors,
};

use super::conditions::{LossStates, PyConditions};
use super::{Data, MAX_LUMPED_BODIES, MAX_ROBOT_JOINTS, MAX_SEGMENTS};
use crate::arrays::Lanes;

/// A number type of the evaluation loop: `f64` (one state per evaluation) or [`Lanes`] (four).
pub(super) trait Lane: Real + SimdValue<Element = f64> + Send + Sync {
    /// The lanes' values `value(0)`, `value(1)`, ...
    fn gather(value: impl Fn(usize) -> f64) -> Self;
}

impl Lane for f64 {
    fn gather(value: impl Fn(usize) -> f64) -> Self {
        value(0)
    }
}

impl Lane for Lanes {
    fn gather(value: impl Fn(usize) -> f64) -> Self {
        Self::from([value(0), value(1), value(2), value(3)])
    }
}

/// The joint states of an evaluation: `n`-wide rows of `q`, `q̇`, `q̈`, one for every sample
/// (`broadcast`) or one per sample.
#[derive(Clone, Copy)]
pub(super) struct States<'a> {
    pub(super) values: [&'a [f64]; 3],
    pub(super) n: usize,
    pub(super) broadcast: bool,
}

impl States<'_> {
    /// Sample `sample`'s value of state `k` (0 `q`, 1 `q̇`, 2 `q̈`) of joint `j`.
    pub(super) fn at(&self, k: usize, sample: usize, j: usize) -> f64 {
        let row = if self.broadcast { 0 } else { sample };
        self.values.get(k).and_then(|v| v.get(row * self.n + j)).copied().unwrap_or(f64::NAN)
    }

    /// The largest `|q̇|` and `|q̈|` of sample `sample`, for an error's message.
    pub(super) fn largest_rates(&self, sample: usize) -> (f64, f64) {
        let largest = |k: usize| (0..self.n).map(|j| self.at(k, sample, j).abs()).fold(0.0, f64::max);
        (largest(1), largest(2))
    }
}

/// Up to `T::LANES` samples' joint states side by side (a group of fewer repeats its first
/// sample in the lanes left over).
pub(super) struct Row<T> {
    pub(super) q: [T; MAX_ROBOT_JOINTS],
    pub(super) qd: [T; MAX_ROBOT_JOINTS],
    pub(super) qdd: [T; MAX_ROBOT_JOINTS],
}

impl<T: Lane> Row<T> {
    pub(super) fn new() -> Self {
        let zero = T::splat(0.0);
        Self { q: [zero; MAX_ROBOT_JOINTS], qd: [zero; MAX_ROBOT_JOINTS], qdd: [zero; MAX_ROBOT_JOINTS] }
    }

    /// The states of `samples` (up to `T::LANES`).
    pub(super) fn load(&mut self, states: &States<'_>, samples: &Range<usize>) {
        let sample = |lane: usize| if lane < samples.len() { samples.start + lane } else { samples.start };
        for (k, out) in [&mut self.q, &mut self.qd, &mut self.qdd].into_iter().enumerate() {
            for (j, slot) in out.iter_mut().enumerate().take(states.n) {
                *slot = T::gather(|lane| states.at(k, sample(lane), j));
            }
        }
    }
}

/// The model, the water and the coefficients over one number type.
pub(super) struct Setting<'a, T: Lane> {
    pub(super) robot: &'a Robot<T, MAX_ROBOT_JOINTS, MAX_SEGMENTS, MAX_LUMPED_BODIES>,
    pub(super) coefficients: Option<&'a SegmentCoefficients<T, MAX_SEGMENTS>>,
    pub(super) conditions: &'a PyConditions,
    pub(super) states: States<'a>,
}

/// The first sample whose forces are not finite although its inputs are (forces beyond float64's
/// range, from speeds or accelerations far beyond any robot's).
pub(super) struct Overflow {
    pub(super) sample: usize,
}

/// Indices of the outputs of [`hydro_range`]: the joints' drag, added mass, buoyancy and gravity
/// (`n` wide each), the base's (6 wide each), the bodies' world wrenches about their centres of
/// mass (`(n + 1)·6`, base first), the joints' oil drag, seal friction and loss current (`n`
/// wide each). An empty output is not written (nor evaluated, for the losses).
pub(super) const OUTPUTS: usize = 12;
pub(super) const LOSSES: usize = 9;

/// The motion and current of each lane of the group `samples` (`constant`: those of every sample,
/// if they are one for all).
fn surroundings<T: Lane>(
    conditions: &PyConditions,
    constant: Option<(BaseMotion<T>, Current<T>)>,
    samples: &Range<usize>,
) -> (BaseMotion<T>, Current<T>) {
    if let Some(both) = constant {
        return both;
    }
    let mut motions = [BaseMotion::fixed(); 4];
    let mut currents = [Current::still(); 4];
    for ((m, c), sample) in motions.iter_mut().zip(currents.iter_mut()).zip(samples.clone()) {
        (*m, *c) = conditions.at(sample);
    }
    let used = samples.len().clamp(1, 4);
    (
        BaseMotion::from_lanes(motions.get(..used).unwrap_or(&motions)),
        Current::from_lanes(currents.get(..used).unwrap_or(&currents)),
    )
}

/// Evaluates samples `range` into `out` (see [`OUTPUTS`]; row 0 of each is sample
/// `range.start`), `T::LANES` per evaluation.
pub(super) fn hydro_range<T: Lane>(
    setting: &Setting<'_, T>,
    range: &Range<usize>,
    data: &mut RobotData<T, MAX_ROBOT_JOINTS>,
    out: [&mut [f64]; OUTPUTS],
) -> Result<(), Overflow> {
    let Setting { robot, coefficients, conditions, states } = setting;
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
    let water = conditions.water.splat::<T>();
    let losses = conditions.losses.as_ref().filter(|_| !visc.is_empty());
    let mut loss_states = losses.map(|_| LossStates::new());
    let mut lanes = Row::<T>::new();
    let mut overflow = None;
    let constant = conditions.constant().map(|(m, c)| (BaseMotion::from_lanes(&[m]), Current::from_lanes(&[c])));
    for (group, first_sample) in range.clone().step_by(T::LANES).enumerate() {
        let chunk = first_sample..(first_sample + T::LANES).min(range.end);
        lanes.load(states, &chunk);
        let (motion, current) = surroundings::<T>(conditions, constant, &chunk);
        let form: AddedMassForm = conditions.form;
        let conditions = Conditions { water, motion, current, coefficients: *coefficients, form, losses: None };
        robot_hydro(robot, &conditions, [&lanes.q, &lanes.qd, &lanes.qdd], data);
        // Each output's lanes once, then one row per sample of the group; `probe` (a sum of every
        // value times 0) is NaN in a lane where anything written is not finite.
        let first = group * T::LANES;
        let used = chunk.len();
        let zero = T::splat(0.0);
        let mut probe = zero;
        let mut put = |out: &mut [f64], width: usize, column: usize, value: T| {
            probe += value * zero;
            for lane in 0..used {
                if let Some(slot) = out.get_mut((first + lane) * width + column) {
                    *slot = value.extract(lane);
                }
            }
        };
        if !drag.is_empty() {
            for (j, f) in data.joint_forces().iter().enumerate() {
                put(drag, n, j, f.drag);
                put(added_mass, n, j, f.added_mass);
                put(buoyancy, n, j, f.buoyancy);
                put(gravity, n, j, f.gravity);
            }
        }
        if !base_drag.is_empty() {
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
        }
        if !wrenches.is_empty() {
            for (b, body) in core::iter::once(None).chain((0..n).map(Some)).enumerate() {
                let wrench = data.body_wrench(robot, body).map_or([T::splat(f64::NAN); 6], |w| w.to_array());
                for (column, x) in wrench.into_iter().enumerate() {
                    put(wrenches, bodies, b * 6 + column, x);
                }
            }
        }
        // The first lane whose losses are not finite.
        let mut bad_loss = None;
        if let (Some(losses), Some(loss_states)) = (losses, loss_states.as_mut()) {
            for (lane, sample) in chunk.clone().enumerate() {
                let row = (first + lane) * n;
                let states_here = loss_states.at(losses, sample);
                for (j, state) in states_here.iter().enumerate().take(n) {
                    let Some(state) = state else { continue };
                    let loss = state.evaluate(states.at(1, sample, j));
                    for (out, x) in
                        [(&mut *visc, loss.visc), (&mut *seal, loss.seal), (&mut *loss_current, loss.current)]
                    {
                        if let Some(slot) = out.get_mut(row + j) {
                            *slot = x;
                        }
                        if !x.is_finite() && bad_loss.is_none() {
                            bad_loss = Some(lane);
                        }
                    }
                }
            }
        }
        if overflow.is_none() {
            let bad = (0..used).find(|&lane| probe.extract(lane) != 0.0);
            overflow = bad.into_iter().chain(bad_loss).min().map(|lane| first_sample + lane);
        }
    }
    overflow.map_or(Ok(()), |sample| Err(Overflow { sample }))
}

/// The regressors' outputs, in the order of `uwml.Regressors`' fields: buoyancy and gravity on the
/// joints, drag and added mass per segment and direction on the joints, the same four on the
/// base, the axial drag per segment on the joints and on the base, the lumped models' columns on
/// the joints and on the base.
pub(super) const REGRESSOR_OUTPUTS: usize = 12;

/// The width of each regressor output (see [`REGRESSOR_OUTPUTS`]) of a robot of `n` joints, `s`
/// segments and `m` lumped models.
pub(super) const fn regressor_widths(n: usize, s: usize, m: usize) -> [usize; REGRESSOR_OUTPUTS] {
    let lumped = uwml_core::LUMPED_COLUMNS * m;
    [n, n, 2 * n * s, 2 * n * s, 6, 6, 12 * s, 12 * s, n * s, 6 * s, n * lumped, 6 * lumped]
}

/// The entries `start + picked` of `table`.
fn part_of(table: &[f64], start: usize, picked: Range<usize>) -> &[f64] {
    table.get(start + picked.start..start + picked.end).unwrap_or(&[])
}

/// Evaluates the regressors of samples `range` into `out` (see [`REGRESSOR_OUTPUTS`]; row 0 of
/// each is sample `range.start`), one state per evaluation, each sample's table of columns
/// (`robot_hydro_regressors`) taken apart into its outputs.
pub(super) fn regressor_range(
    setting: &Setting<'_, f64>,
    range: &Range<usize>,
    data: &mut Data,
    out: [&mut [f64]; REGRESSOR_OUTPUTS],
) -> Result<(), Overflow> {
    let Setting { robot, conditions, states, .. } = setting;
    let [
        buoyancy,
        gravity,
        drag,
        added_mass,
        base_buoyancy,
        base_gravity,
        base_drag,
        base_added_mass,
        axial,
        base_axial,
        lumped,
        base_lumped,
    ] = out;
    let n = robot.joint_count();
    let s = robot.segments().len();
    let columns = robot.regressor_column_count();
    let lumped_width = columns.saturating_sub(3 * s);
    let (mut drag_table, mut added_table) = (vec![0.0; (6 + n) * columns], vec![0.0; (6 + n) * columns]);
    let water: Water<f64> = conditions.water;
    let mut row = Row::<f64>::new();
    let mut overflow = None;
    for (k, sample) in range.clone().enumerate() {
        row.load(states, &(sample..sample + 1));
        let (motion, current) = conditions.at(sample);
        let form = conditions.form;
        let core = Conditions { water, motion, current, coefficients: None, form, losses: None };
        drag_table.fill(0.0);
        added_table.fill(0.0);
        robot_hydro_regressors(robot, &core, [&row.q, &row.qd, &row.qdd], data, &mut drag_table, &mut added_table);
        let finite = drag_table.iter().chain(added_table.iter()).all(|x| x.is_finite());
        // Each row of the tables (the base's six, then the joints) to its outputs.
        for r in 0..6 + n {
            let (at, rows, outputs) = if r < 6 {
                (r, 6, [&mut *base_drag, &mut *base_added_mass, &mut *base_axial, &mut *base_lumped])
            } else {
                (r - 6, n, [&mut *drag, &mut *added_mass, &mut *axial, &mut *lumped])
            };
            let [drag_out, added_out, axial_out, lumped_out] = outputs;
            let row_of = |table, picked| part_of(table, r * columns, picked);
            for (out, values, width) in [
                (&mut *drag_out, row_of(&drag_table, 0..2 * s), 2 * s),
                (&mut *added_out, row_of(&added_table, 0..2 * s), 2 * s),
                (&mut *axial_out, row_of(&drag_table, 2 * s..3 * s), s),
            ] {
                let start = (k * rows + at) * width;
                if let Some(slot) = out.get_mut(start..start + width) {
                    slot.copy_from_slice(values);
                }
            }
            // A lumped coefficient's column is in one of the two tables and zero in the other.
            let start = (k * rows + at) * lumped_width;
            let lumped_columns = 3 * s..columns;
            if let Some(slot) = lumped_out.get_mut(start..start + lumped_width) {
                for ((out, d), a) in slot
                    .iter_mut()
                    .zip(row_of(&drag_table, lumped_columns.clone()))
                    .zip(row_of(&added_table, lumped_columns.clone()))
                {
                    *out = d + a;
                }
            }
        }
        for (out, value) in [
            (&mut *buoyancy, (|f: &uwml_core::JointForces<f64>| f.buoyancy) as fn(&uwml_core::JointForces<f64>) -> f64),
            (&mut *gravity, |f: &uwml_core::JointForces<f64>| f.gravity),
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
        if !finite && overflow.is_none() {
            overflow = Some(sample);
        }
    }
    overflow.map_or(Ok(()), |sample| Err(Overflow { sample }))
}
