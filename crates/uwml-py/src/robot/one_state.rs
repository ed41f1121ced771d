//! One state per call, with the GIL held (a controller or a simulator stepping one state at a
//! time): the robot's kept workspace, the evaluation of one state into the outputs' slices, the
//! effort check that leaves a state beyond a joint's bound to the Python package, and the
//! evaluation into a `uwml.Workspace`'s array (no result objects made per call).

use std::ops::{Deref, DerefMut};
use std::sync::{Mutex, MutexGuard, TryLockError};

use numpy::{PyArray1, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use super::evaluate::{LOSSES, OUTPUTS, Overflow, Setting, States, hydro_range};
use super::states::{Bounds, Read};
use super::{Data, PyConditions, PyRobot, overflow_error};

/// The layout of a `uwml.Workspace`'s array for a robot of `n` joints: the joints' drag, added
/// mass, buoyancy and gravity, the joint losses' oil drag, seal friction and current (`n` each),
/// then the base's drag, added mass, buoyancy and gravity (6 each).
pub(super) const fn workspace_len(n: usize) -> usize {
    7 * n + 24
}

impl PyRobot {
    /// The kept workspace for a one-state call made with the GIL held, or a new one if another
    /// thread is using it: a thread holding the GIL never waits for a lock (no deadlock with a
    /// detached batch, none when the result's construction runs Python that calls back in).
    fn one_state_workspace(&self) -> Workspace<'_, Data> {
        Workspace::of(&self.data, || Box::new(Data::new()))
    }

    /// Evaluates one state (`states`, broadcast) into `out` (see `evaluate::OUTPUTS`; an empty
    /// output is not written): false where `plain` (read from plain objects, unchecked by the
    /// Python package) and a joint's environment force is beyond its effort bound (the package
    /// then checks, and warns).
    pub(super) fn one_state(
        &self,
        states: States<'_>,
        conditions: &PyConditions,
        mut out: [&mut [f64]; OUTPUTS],
        plain: bool,
    ) -> PyResult<bool> {
        let setting =
            Setting { robot: &self.robot, coefficients: conditions.coefficients.as_deref(), conditions, states };
        let mut data = self.one_state_workspace();
        let done = hydro_range(&setting, &(0..1), &mut data, out.each_mut().map(|o| &mut **o));
        drop(data);
        done.map_err(|e: Overflow| overflow_error(&e, &states, false))?;
        Ok(!plain || within_effort(&out, &self.bounds))
    }

    /// `hydro` (or with `losses`, `environment`) of one plain state into a workspace's `array`
    /// (laid out as [`workspace_len`] says; the losses' part zeros without `losses`, the base's
    /// without `base`): false for states not read (see `Read::plain`), conditions
    /// with a sample axis, or forces beyond a joint's effort bound, which the Python package
    /// then evaluates the general way. Everything is done with the GIL held: another thread
    /// never sees a workspace half written.
    pub(super) fn evaluate_into_array(
        &self,
        states: [&Bound<'_, PyAny>; 3],
        conditions: &PyConditions,
        base: bool,
        losses: bool,
        array: &Bound<'_, PyArray1<f64>>,
    ) -> PyResult<bool> {
        conditions.check_robot(&self.robot)?;
        let n = self.robot.joint_count();
        if conditions.samples.is_some() {
            return Ok(false);
        }
        let Some(read) = Read::plain(states, n, &self.bounds) else { return Ok(false) };
        let mut guard = array.try_readwrite().map_err(|_| in_use())?;
        let values = guard.as_slice_mut().map_err(|_| in_use())?;
        if values.len() != workspace_len(n) {
            return Err(PyValueError::new_err(format!(
                "the workspace holds {} values, not the {} of this robot's {n} joints: make it with this robot's workspace()",
                values.len(),
                workspace_len(n)
            )));
        }
        // The workspace's parts in its order, then in the outputs' (see `evaluate::OUTPUTS`).
        let [
            drag,
            added_mass,
            buoyancy,
            gravity,
            visc,
            seal,
            current,
            base_drag,
            base_added_mass,
            base_buoyancy,
            base_gravity,
            _,
        ] = split(values, [n, n, n, n, n, n, n, 6, 6, 6, 6, 0]);
        let out = [
            drag,
            added_mass,
            buoyancy,
            gravity,
            evaluated(base, base_drag),
            evaluated(base, base_added_mass),
            evaluated(base, base_buoyancy),
            evaluated(base, base_gravity),
            &mut [][..],
            evaluated(losses, visc),
            evaluated(losses, seal),
            evaluated(losses, current),
        ];
        self.one_state(read.states(n), conditions, out, true)
    }
}

/// `part` as an output to evaluate where `wanted`; else zeroed, and an empty output (not
/// evaluated).
fn evaluated(wanted: bool, part: &mut [f64]) -> &mut [f64] {
    if wanted {
        return part;
    }
    part.fill(0.0);
    &mut []
}

/// The error of a workspace another evaluation holds.
fn in_use() -> PyErr {
    PyValueError::new_err("the workspace is in use (a workspace is for one evaluation at a time: one per thread)")
}

/// `buffer` cut into consecutive parts of `widths` (the last parts empty where it is short).
pub(super) fn split(buffer: &mut [f64], widths: [usize; OUTPUTS]) -> [&mut [f64]; OUTPUTS] {
    let mut rest = buffer;
    widths.map(|width| {
        let all = core::mem::take(&mut rest);
        let (part, after) = all.split_at_mut(width.min(all.len()));
        rest = after;
        part
    })
}

/// Whether every joint's environment force in one state's outputs `out` (the water's, and the
/// losses' where evaluated: an empty output counts as zero) is within its effort bound.
fn within_effort(out: &[&mut [f64]; OUTPUTS], bounds: &[Bounds]) -> bool {
    let value = |output: usize, j: usize| out.get(output).and_then(|o| o.get(j)).copied().unwrap_or(0.0);
    bounds.iter().enumerate().all(|(j, &[_, _, effort])| {
        let total = value(0, j) + value(1, j) + value(2, j) + value(LOSSES, j) + value(LOSSES + 1, j);
        total.abs() <= effort
    })
}

/// A one-state call's workspace: the robot's kept one, or a new one (see `one_state_workspace`).
enum Workspace<'a, T> {
    Kept(MutexGuard<'a, Box<T>>),
    New(Box<T>),
}

impl<'a, T> Workspace<'a, T> {
    /// The one kept in `kept`, or `make()`'s while another thread holds it (a poisoned lock's
    /// workspace is as good: every call writes what it reads).
    fn of(kept: &'a Mutex<Box<T>>, make: impl FnOnce() -> Box<T>) -> Self {
        match kept.try_lock() {
            Ok(guard) => Self::Kept(guard),
            Err(TryLockError::Poisoned(poisoned)) => Self::Kept(poisoned.into_inner()),
            Err(TryLockError::WouldBlock) => Self::New(make()),
        }
    }
}

impl<T> Deref for Workspace<'_, T> {
    type Target = T;
    fn deref(&self) -> &T {
        match self {
            Self::Kept(guard) => guard,
            Self::New(value) => value,
        }
    }
}

impl<T> DerefMut for Workspace<'_, T> {
    fn deref_mut(&mut self) -> &mut T {
        match self {
            Self::Kept(guard) => guard,
            Self::New(value) => value,
        }
    }
}
