//! The classical Runge-Kutta step's bookkeeping for `uwml.sim.mujoco.Simulation` (its
//! `integrator="rk4"`), kept natively beside the coupling: the step's start, each stage's velocity
//! and acceleration, and their weighted averages. MuJoCo's own calls (the forward pass of each
//! stage, `mj_integratePos`) stay with the Python caller; the arithmetic between them is here, in
//! the operations (and so with the bits) of the numpy code it replaces.

use numpy::{PyArray1, PyArrayDyn, PyArrayMethods};
use pyo3::prelude::*;

/// One Runge-Kutta step under way.
pub(super) struct Rk4 {
    /// `qpos` and `qvel` at the step's start.
    qpos0: Vec<f64>,
    qvel0: Vec<f64>,
    /// Each stage's velocity (numpy arrays, handed to `mj_integratePos` as they are) and
    /// acceleration.
    velocities: [Py<PyArray1<f64>>; 4],
    accelerations: [Vec<f64>; 4],
    /// The step's weighted velocity, `(v0 + 2 v1 + 2 v2 + v3) / 6`.
    average: Py<PyArray1<f64>>,
}

/// `array`'s values (an `MjData` array: C-contiguous).
fn read(array: &Bound<'_, PyArrayDyn<f64>>) -> PyResult<Vec<f64>> {
    Ok(array.try_readonly()?.as_slice()?.to_vec())
}

/// `values` into `array`.
fn write(array: &Bound<'_, PyArrayDyn<f64>>, values: &[f64]) -> PyResult<()> {
    let mut out = array.try_readwrite()?;
    for (slot, &x) in out.as_slice_mut()?.iter_mut().zip(values) {
        *slot = x;
    }
    Ok(())
}

impl Rk4 {
    /// Empty buffers for `nv` degrees of freedom.
    pub(super) fn new(py: Python<'_>, nv: usize) -> Self {
        let array = || PyArray1::<f64>::zeros(py, nv, false).unbind();
        Self {
            qpos0: Vec::new(),
            qvel0: vec![0.0; nv],
            velocities: [array(), array(), array(), array()],
            accelerations: [vec![0.0; nv], vec![0.0; nv], vec![0.0; nv], vec![0.0; nv]],
            average: array(),
        }
    }

    /// The step's start: `qpos` and `qvel` now.
    pub(super) fn begin(
        &mut self,
        qpos: &Bound<'_, PyArrayDyn<f64>>,
        qvel: &Bound<'_, PyArrayDyn<f64>>,
    ) -> PyResult<()> {
        self.qpos0 = read(qpos)?;
        self.qvel0 = read(qvel)?;
        Ok(())
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
        qpos: &Bound<'py, PyArrayDyn<f64>>,
        qvel: &Bound<'py, PyArrayDyn<f64>>,
    ) -> PyResult<Option<Bound<'py, PyArray1<f64>>>> {
        let Some(velocity) = self.velocities.get(stage) else {
            return Err(pyo3::exceptions::PyValueError::new_err(format!("stage must be 0 to 3, got {stage}")));
        };
        let velocity = velocity.bind(py);
        {
            let mut out = velocity.try_readwrite()?;
            let out = out.as_slice_mut()?;
            match stage.checked_sub(1).and_then(|k| self.accelerations.get(k)) {
                // qvel0 + fraction * h * a, as numpy evaluates it: (fraction * h) first.
                Some(acceleration) => {
                    for ((slot, &v), &a) in out.iter_mut().zip(&self.qvel0).zip(acceleration) {
                        *slot = v + offset * a;
                    }
                }
                None => out.copy_from_slice(&self.qvel0),
            }
        }
        write(qpos, &self.qpos0)?;
        write(qvel, velocity.try_readonly()?.as_slice()?)?;
        Ok(stage.checked_sub(1).and_then(|k| self.velocities.get(k)).map(|v| v.bind(py).clone()))
    }

    /// Keeps stage `stage`'s acceleration (`qacc` after its forward pass).
    pub(super) fn keep(&mut self, stage: usize, qacc: &Bound<'_, PyArrayDyn<f64>>) -> PyResult<()> {
        let qacc = qacc.try_readonly()?;
        if let Some(slot) = self.accelerations.get_mut(stage) {
            slot.clear();
            slot.extend_from_slice(qacc.as_slice()?);
        }
        Ok(())
    }

    /// The step's end: `qpos` back to the start, `qvel` = `qvel0 + h (a0 + 2 a1 + 2 a2 + a3) / 6`.
    /// Returns the weighted velocity `(v0 + 2 v1 + 2 v2 + v3) / 6`, with which the caller
    /// advances `qpos` by `h`.
    pub(super) fn finish<'py>(
        &mut self,
        py: Python<'py>,
        h: f64,
        qpos: &Bound<'py, PyArrayDyn<f64>>,
        qvel: &Bound<'py, PyArrayDyn<f64>>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let average = self.average.bind(py);
        {
            let velocities = self.velocities.each_ref().map(|v| v.bind(py).try_readonly());
            let [v0, v1, v2, v3] = velocities;
            let (v0, v1, v2, v3) = (v0?, v1?, v2?, v3?);
            let (v0, v1, v2, v3) = (v0.as_slice()?, v1.as_slice()?, v2.as_slice()?, v3.as_slice()?);
            let mut out = average.try_readwrite()?;
            for (i, slot) in out.as_slice_mut()?.iter_mut().enumerate() {
                let at = |v: &[f64]| v.get(i).copied().unwrap_or(0.0);
                *slot = (at(v0) + 2.0 * at(v1) + 2.0 * at(v2) + at(v3)) / 6.0;
            }
        }
        let [a0, a1, a2, a3] = &self.accelerations;
        let at = |v: &[f64], i: usize| v.get(i).copied().unwrap_or(0.0);
        let velocity: Vec<f64> = (0..self.qvel0.len())
            .map(|i| at(&self.qvel0, i) + h * (at(a0, i) + 2.0 * at(a1, i) + 2.0 * at(a2, i) + at(a3, i)) / 6.0)
            .collect();
        write(qpos, &self.qpos0)?;
        write(qvel, &velocity)?;
        Ok(average.clone())
    }
}
