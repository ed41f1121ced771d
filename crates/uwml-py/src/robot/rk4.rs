//! The classical Runge-Kutta step's bookkeeping for `uwml.sim.mujoco.Simulation` (its
//! `integrator="rk4"`), kept natively beside the coupling: the step's start, each stage's velocity
//! and acceleration, and their weighted averages. MuJoCo's own calls (the forward pass of each
//! stage, `mj_integratePos`) stay with the Python caller; the arithmetic between them is here, in
//! the operations (and so with the bits) of the numpy code it replaces.

use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;

use super::view::View;

/// One Runge-Kutta step under way.
pub(super) struct Rk4 {
    /// `qpos` and `qvel` at the step's start.
    qpos0: Vec<f64>,
    qvel0: Vec<f64>,
    /// Each stage's velocity (numpy arrays, handed to `mj_integratePos` as they are, with their
    /// views; and the same numbers here) and acceleration.
    velocities: [(Py<PyArray1<f64>>, View); 4],
    velocity_values: [Vec<f64>; 4],
    accelerations: [Vec<f64>; 4],
    /// The step's weighted velocity, `(v0 + 2 v1 + 2 v2 + v3) / 6`.
    average: (Py<PyArray1<f64>>, View),
    /// Scratch: a velocity as numbers.
    scratch: Vec<f64>,
}

/// A zero array of `nv` numbers and its view.
fn array(py: Python<'_>, nv: usize) -> PyResult<(Py<PyArray1<f64>>, View)> {
    let array = PyArray1::<f64>::zeros(py, nv, false);
    let view = View::new(&array.to_dyn().clone(), "a Runge-Kutta stage's velocity")?;
    Ok((array.unbind(), view))
}

impl Rk4 {
    /// Empty buffers for `nv` degrees of freedom.
    pub(super) fn new(py: Python<'_>, nv: usize) -> PyResult<Self> {
        Ok(Self {
            qpos0: Vec::new(),
            qvel0: vec![0.0; nv],
            velocities: [array(py, nv)?, array(py, nv)?, array(py, nv)?, array(py, nv)?],
            velocity_values: [vec![0.0; nv], vec![0.0; nv], vec![0.0; nv], vec![0.0; nv]],
            accelerations: [vec![0.0; nv], vec![0.0; nv], vec![0.0; nv], vec![0.0; nv]],
            average: array(py, nv)?,
            scratch: Vec::with_capacity(nv),
        })
    }

    /// The step's start: `qpos` and `qvel` now.
    pub(super) fn begin(&mut self, py: Python<'_>, qpos: &View, qvel: &View) -> PyResult<()> {
        qpos.copy_into(py, &mut self.qpos0)?;
        qvel.copy_into(py, &mut self.qvel0)
    }

    /// Stage `stage` (0-3), `offset` (the stage's fraction of the step times the step) into the
    /// step: `qpos` back to the start, `qvel` the stage's velocity `qvel0 + offset a_{stage−1}`.
    /// Returns the previous stage's velocity, with which the caller advances `qpos` by `offset`
    /// (`None` for the first stage).
    pub(super) fn stage<'py>(
        &mut self,
        py: Python<'py>,
        stage: usize,
        offset: f64,
        qpos: &View,
        qvel: &View,
    ) -> PyResult<Option<Bound<'py, PyArray1<f64>>>> {
        let (Some((_, view)), Some(velocity)) = (self.velocities.get(stage), self.velocity_values.get_mut(stage))
        else {
            return Err(pyo3::exceptions::PyValueError::new_err(format!("stage must be 0 to 3, got {stage}")));
        };
        velocity.clear();
        match stage.checked_sub(1).and_then(|k| self.accelerations.get(k)) {
            // qvel0 + fraction * h * a, as numpy evaluates it: (fraction * h) first.
            Some(acceleration) => velocity.extend(self.qvel0.iter().zip(acceleration).map(|(&v, &a)| v + offset * a)),
            None => velocity.extend_from_slice(&self.qvel0),
        }
        view.write(py, velocity)?;
        qpos.write(py, &self.qpos0)?;
        qvel.write(py, velocity)?;
        Ok(stage.checked_sub(1).and_then(|k| self.velocities.get(k)).map(|(v, _)| v.bind(py).clone()))
    }

    /// Keeps stage `stage`'s acceleration (`qacc` after its forward pass).
    pub(super) fn keep(&mut self, py: Python<'_>, stage: usize, qacc: &View) -> PyResult<()> {
        match self.accelerations.get_mut(stage) {
            Some(slot) => qacc.copy_into(py, slot),
            None => Ok(()),
        }
    }

    /// The step's end: `qpos` back to the start, `qvel` = `qvel0 + h (a0 + 2 a1 + 2 a2 + a3) / 6`.
    /// Returns the weighted velocity `(v0 + 2 v1 + 2 v2 + v3) / 6`, with which the caller
    /// advances `qpos` by `h`.
    pub(super) fn finish<'py>(
        &mut self,
        py: Python<'py>,
        h: f64,
        qpos: &View,
        qvel: &View,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let [v0, v1, v2, v3] = &self.velocity_values;
        let at = |v: &[f64], i: usize| v.get(i).copied().unwrap_or(0.0);
        self.scratch.clear();
        self.scratch
            .extend((0..self.qvel0.len()).map(|i| (at(v0, i) + 2.0 * at(v1, i) + 2.0 * at(v2, i) + at(v3, i)) / 6.0));
        let (average, average_view) = &self.average;
        average_view.write(py, &self.scratch)?;
        let [a0, a1, a2, a3] = &self.accelerations;
        let at = |v: &[f64], i: usize| v.get(i).copied().unwrap_or(0.0);
        self.scratch.clear();
        self.scratch.extend(
            (0..self.qvel0.len())
                .map(|i| at(&self.qvel0, i) + h * (at(a0, i) + 2.0 * at(a1, i) + 2.0 * at(a2, i) + at(a3, i)) / 6.0),
        );
        qpos.write(py, &self.qpos0)?;
        qvel.write(py, &self.scratch)?;
        Ok(average.bind(py).clone())
    }
}
