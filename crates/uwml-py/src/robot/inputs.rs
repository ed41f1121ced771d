//! The per-sample inputs of a batch, checked: joint states, base motion and current (given once
//! or per sample), joint losses with their conditions; and an error of one sample.

use std::ops::Range;

use numpy::{PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use uwml_core::nalgebra::Vector3;
use uwml_core::{BaseMotion, Current, JointLosses, LossState, ModelError};

use super::MAX_ROBOT_JOINTS;
use simba::simd::SimdValue;

use crate::arrays::Lanes;
use crate::{contiguous, contiguous1, parse_losses};

/// The first three values (NaN for missing ones) as a vector.
fn v3(x: &[f64]) -> Vector3<f64> {
    Vector3::from_iterator(x.iter().copied().chain(core::iter::repeat(f64::NAN)).take(3))
}

/// The joint losses of an environment evaluation: per joint, and the pressure [Pa] and
/// temperature [°C] of every sample (checked finite).
pub(super) struct Losses<'a> {
    pub(super) joints: [Option<JointLosses<f64>>; MAX_ROBOT_JOINTS],
    pub(super) pressure: &'a [f64],
    pub(super) temperature: &'a [f64],
}

/// A per-sample input given once (one row, broadcast) or per sample.
#[derive(Clone, Copy)]
pub(super) struct Rows<'a> {
    pub(super) values: &'a [f64],
    pub(super) width: usize,
    pub(super) broadcast: bool,
}

impl<'a> Rows<'a> {
    pub(super) fn new(
        array: &'a PyReadonlyArray2<'_, f64>,
        name: &str,
        width: usize,
        n_samples: usize,
    ) -> PyResult<Self> {
        let shape = array.shape();
        let rows = shape.first().copied().unwrap_or(0);
        if shape.get(1) != Some(&width) || !(rows == 1 || rows == n_samples) {
            return Err(PyValueError::new_err(format!(
                "{name} must have shape ({width},) or (n_samples, {width}) with n_samples = {n_samples}, got {shape:?}"
            )));
        }
        Ok(Self { values: contiguous(array, name)?, width, broadcast: rows == 1 })
    }

    pub(super) fn row(&self, sample: usize) -> &'a [f64] {
        let i = if self.broadcast { 0 } else { sample };
        self.values.get(i * self.width..(i + 1) * self.width).unwrap_or(&[])
    }
}

/// The base motion and current of every sample.
#[derive(Clone, Copy)]
pub(super) struct Surroundings<'a> {
    pub(super) orientation: Rows<'a>,
    pub(super) velocity: Rows<'a>,
    pub(super) angular_velocity: Rows<'a>,
    pub(super) acceleration: Rows<'a>,
    pub(super) angular_acceleration: Rows<'a>,
    pub(super) current: Rows<'a>,
    pub(super) current_acceleration: Rows<'a>,
}

/// One sample's joint states, in the core's fixed-size arrays.
pub(super) struct StateRow {
    pub(super) q: [f64; MAX_ROBOT_JOINTS],
    pub(super) qd: [f64; MAX_ROBOT_JOINTS],
    pub(super) qdd: [f64; MAX_ROBOT_JOINTS],
}

impl StateRow {
    pub(super) fn new() -> Self {
        Self { q: [0.0; MAX_ROBOT_JOINTS], qd: [0.0; MAX_ROBOT_JOINTS], qdd: [0.0; MAX_ROBOT_JOINTS] }
    }

    /// Sample `sample`'s rows of the batch `states` (`n` joints).
    pub(super) fn load(&mut self, states: [&[f64]; 3], sample: usize, n: usize) {
        for (values, out) in states.into_iter().zip([&mut self.q, &mut self.qd, &mut self.qdd]) {
            for (slot, x) in out.iter_mut().zip(values.get(sample * n..(sample + 1) * n).unwrap_or(&[])) {
                *slot = *x;
            }
        }
    }
}

/// Up to four samples' joint states side by side, one per SIMD lane (a group of fewer repeats
/// its first sample). The robot's lanes take each angle's sine lane by lane (`uwml_core::Real`),
/// so no angle needs reducing first.
pub(super) struct LaneRow {
    pub(super) q: [Lanes; MAX_ROBOT_JOINTS],
    pub(super) qd: [Lanes; MAX_ROBOT_JOINTS],
    pub(super) qdd: [Lanes; MAX_ROBOT_JOINTS],
}

impl LaneRow {
    pub(super) fn new() -> Self {
        let zero = Lanes::splat(0.0);
        Self { q: [zero; MAX_ROBOT_JOINTS], qd: [zero; MAX_ROBOT_JOINTS], qdd: [zero; MAX_ROBOT_JOINTS] }
    }

    /// The rows `samples` (up to four) of the batch `states` (`n` joints).
    pub(super) fn load(&mut self, states: [&[f64]; 3], samples: &Range<usize>, n: usize) {
        let sample = |lane: usize| if lane < samples.len() { samples.start + lane } else { samples.start };
        for (values, out) in states.into_iter().zip([&mut self.q, &mut self.qd, &mut self.qdd]) {
            for (j, slot) in out.iter_mut().enumerate().take(n) {
                let at = |lane: usize| values.get(sample(lane) * n + j).copied().unwrap_or(0.0);
                *slot = Lanes::from([at(0), at(1), at(2), at(3)]);
            }
        }
    }
}

/// The joints' loss states at the last sample's pressure and temperature, made again only when
/// those change.
pub(super) struct LossStates {
    pub(super) conditions: (f64, f64),
    pub(super) states: [Option<LossState<f64>>; MAX_ROBOT_JOINTS],
}

impl LossStates {
    pub(super) fn new() -> Self {
        Self { conditions: (f64::NAN, f64::NAN), states: [None; MAX_ROBOT_JOINTS] }
    }

    pub(super) fn at(&mut self, losses: &Losses<'_>, sample: usize) -> &[Option<LossState<f64>>; MAX_ROBOT_JOINTS] {
        let at = |values: &[f64]| values.get(sample).copied().unwrap_or(f64::NAN);
        let here = (at(losses.pressure), at(losses.temperature));
        if here != self.conditions {
            self.conditions = here;
            self.states = losses.joints.map(|l| l.and_then(|l| l.at(here.0, here.1).ok()));
        }
        &self.states
    }
}

/// Each joint's loss at its speed (`states`, `speeds`: the robot's joints, in order) into
/// `visc`, `seal` and `current` from index `start` on, where the joint has losses: what the core's
/// `loss_torques` evaluates, without its fixed-size vectors. The outputs are left as they are
/// (zero) for a joint without.
pub(super) fn write_joint_losses(
    states: impl IntoIterator<Item = Option<LossState<f64>>>,
    speeds: &[f64],
    [visc, seal, current]: [&mut [f64]; 3],
    start: usize,
) {
    for (j, (state, &speed)) in states.into_iter().zip(speeds).enumerate() {
        let Some(state) = state else { continue };
        let loss = state.evaluate(speed);
        for (out, x) in [(&mut *visc, loss.visc), (&mut *seal, loss.seal), (&mut *current, loss.current)] {
            if let Some(slot) = out.get_mut(start + j) {
                *slot = x;
            }
        }
    }
}

/// An input error of one sample, raised as a ValueError once the GIL is back.
pub(super) struct SampleError {
    pub(super) sample: usize,
    pub(super) message: String,
}

impl<'a> Surroundings<'a> {
    /// The seven per-sample inputs, in the order of the fields, checked against `n_samples`.
    pub(super) fn new(arrays: [&'a PyReadonlyArray2<'_, f64>; 7], n_samples: usize) -> PyResult<Self> {
        let names = [
            "orientation",
            "velocity",
            "angular_velocity",
            "acceleration",
            "angular_acceleration",
            "current",
            "current_acceleration",
        ];
        let mut rows = Vec::with_capacity(7);
        for (array, name) in arrays.into_iter().zip(names) {
            rows.push(Rows::new(array, name, if name == "orientation" { 4 } else { 3 }, n_samples)?);
        }
        let [
            orientation,
            velocity,
            angular_velocity,
            acceleration,
            angular_acceleration,
            current,
            current_acceleration,
        ] = <[Rows<'a>; 7]>::try_from(rows).map_err(|_| PyValueError::new_err("internal error: seven inputs"))?;
        Ok(Self {
            orientation,
            velocity,
            angular_velocity,
            acceleration,
            angular_acceleration,
            current,
            current_acceleration,
        })
    }

    pub(super) fn at(&self, sample: usize) -> Result<(BaseMotion<f64>, Current<f64>), SampleError> {
        let o = self.orientation.row(sample);
        let quaternion = [0, 1, 2, 3].map(|k| o.get(k).copied().unwrap_or(f64::NAN));
        let fail = |e: ModelError| SampleError { sample, message: e.to_string() };
        let motion = BaseMotion::new(
            quaternion,
            v3(self.velocity.row(sample)),
            v3(self.angular_velocity.row(sample)),
            v3(self.acceleration.row(sample)),
            v3(self.angular_acceleration.row(sample)),
        )
        .map_err(fail)?;
        let current =
            Current::new(v3(self.current.row(sample)), v3(self.current_acceleration.row(sample))).map_err(fail)?;
        Ok((motion, current))
    }

    /// Whether every input is one row for all samples.
    pub(super) fn constant(&self) -> bool {
        [
            self.orientation,
            self.velocity,
            self.angular_velocity,
            self.acceleration,
            self.angular_acceleration,
            self.current,
            self.current_acceleration,
        ]
        .iter()
        .all(|r| r.broadcast)
    }
}

/// The joint losses of `n` joints and the pressure and temperature of every sample.
pub(super) fn check_losses<'a>(
    losses: &crate::PyLosses,
    pressure: &'a PyReadonlyArray1<'_, f64>,
    temperature: &'a PyReadonlyArray1<'_, f64>,
    n: usize,
    n_samples: usize,
) -> PyResult<Losses<'a>> {
    let mut joints = [None; MAX_ROBOT_JOINTS];
    for (slot, l) in joints.iter_mut().zip(parse_losses(losses, n)?) {
        *slot = *l;
    }
    let pressure = contiguous1(pressure, "pressure", n_samples)?;
    let temperature = contiguous1(temperature, "temperature", n_samples)?;
    crate::arrays::check_conditions(pressure, temperature)?;
    Ok(Losses { joints, pressure, temperature })
}

/// The number of samples of `q`, `qd`, `qdd`, each `(n_samples, n)`.
pub(super) fn check_state_shapes(states: [&PyReadonlyArray2<'_, f64>; 3], n: usize) -> PyResult<usize> {
    let shape = states[0].shape();
    for (name, array) in ["q", "qd", "qdd"].into_iter().zip(states) {
        if array.shape() != shape || shape.get(1) != Some(&n) {
            return Err(PyValueError::new_err(format!(
                "{name} must have shape (n_samples, {n}) like q, got {:?} (q: {shape:?})",
                array.shape()
            )));
        }
    }
    Ok(shape.first().copied().unwrap_or(0))
}

/// The first non-finite joint state, naming the array, sample and joint.
pub(super) fn check_states(states: &[(&str, &[f64])], n: usize) -> PyResult<()> {
    for (name, values) in states {
        if let Some(i) = values.iter().position(|x| !x.is_finite()) {
            let value = values.get(i).copied().unwrap_or(f64::NAN);
            return Err(PyValueError::new_err(format!(
                "{name}[{}, {}] is {value}: joint states must be finite",
                i / n.max(1),
                i % n.max(1)
            )));
        }
    }
    Ok(())
}
