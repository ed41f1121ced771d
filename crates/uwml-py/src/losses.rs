//! The joint losses through the bindings: the Python package's `uwml.JointLosses` objects read
//! attribute by attribute and validated by the core once (`Losses`, one per joint, built once
//! and kept by the caller), and the batch of one joint's losses (`joint_losses`).

use numpy::{IntoPyArray, PyArray, PyReadonlyArray1, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use uwml_core::{Drive, JointLoss, JointLosses, ModelError, OilDrag, Seal};

use crate::errors::ModelError as PyModelError;
use crate::{NonFinite, check_conditions, contiguous1};

/// Pa per MPa: the Python objects give pressures in MPa, the core takes Pa.
const MPA: f64 = 1e6;

/// A `uwml.Drive`.
#[derive(FromPyObject)]
struct DriveSpec {
    torque_constant: f64,
    ratio: f64,
    efficiency: f64,
    rated_current: f64,
}

/// A `uwml.OilDrag`.
#[derive(FromPyObject)]
struct OilSpec {
    k_oil: f64,
    exponent: f64,
    pressure_sensitivity_per_mpa: f64,
    temperature_sensitivity_per_k: f64,
    reference_pressure_mpa: f64,
    reference_temperature_c: f64,
}

/// A `uwml.Seal`.
#[derive(FromPyObject)]
struct SealSpec {
    c0: f64,
    c1_per_mpa: f64,
    s0: f64,
    s1_per_mpa: f64,
    d0: f64,
    d1_per_mpa: f64,
    stribeck_speed: f64,
}

/// A `uwml.JointLosses`.
#[derive(FromPyObject)]
pub(crate) struct LossesSpec {
    drive: DriveSpec,
    oil: Option<OilSpec>,
    seal: Option<SealSpec>,
    epsilon: f64,
}

impl LossesSpec {
    /// The core's losses, in SI units (Pa).
    fn joint_losses(&self) -> Result<JointLosses<f64>, ModelError> {
        let d = &self.drive;
        let drive = Drive::new(d.torque_constant, d.ratio, d.efficiency, d.rated_current)?;
        let oil = match &self.oil {
            Some(o) => Some(OilDrag::new(
                o.k_oil,
                o.exponent,
                o.pressure_sensitivity_per_mpa / MPA,
                o.temperature_sensitivity_per_k,
                o.reference_pressure_mpa * MPA,
                o.reference_temperature_c,
            )?),
            None => None,
        };
        let seal = match &self.seal {
            Some(s) => Some(Seal::new(
                [s.c0, s.c1_per_mpa / MPA],
                [s.s0, s.s1_per_mpa / MPA],
                [s.d0, s.d1_per_mpa / MPA],
                s.stribeck_speed,
            )?),
            None => None,
        };
        JointLosses::new(drive, oil, seal, self.epsilon)
    }
}

/// Each joint's losses (None: none), read from `uwml.JointLosses` objects and validated once:
/// what the evaluations with losses take, built once per set of losses by the Python package.
#[pyclass(frozen, module = "uwml._core", name = "Losses")]
pub(crate) struct PyLosses {
    pub(crate) joints: Vec<Option<JointLosses<f64>>>,
}

#[pymethods]
impl PyLosses {
    #[new]
    fn new(per_joint: Vec<Option<LossesSpec>>) -> PyResult<Self> {
        let joints = per_joint
            .iter()
            .enumerate()
            .map(|(joint, spec)| {
                spec.as_ref()
                    .map(LossesSpec::joint_losses)
                    .transpose()
                    .map_err(|e| PyModelError::new_err(format!("losses of joint {joint}: {e}")))
            })
            .collect::<PyResult<Vec<_>>>()?;
        Ok(Self { joints })
    }

    /// Number of joints.
    #[getter]
    fn n_joints(&self) -> usize {
        self.joints.len()
    }
}

/// Joint losses of a batch of samples: visc, seal and current per sample, every input checked
/// already (finite speeds, conditions in the core's domain). The pressure-dependent part is
/// recomputed only when the pressure or temperature changes.
pub(crate) fn loss_batch(
    losses: &JointLosses<f64>,
    speed: &[f64],
    pressure: &[f64],
    temperature: &[f64],
) -> [Vec<f64>; 3] {
    let n = speed.len();
    let (mut visc, mut seal, mut current) = (Vec::with_capacity(n), Vec::with_capacity(n), Vec::with_capacity(n));
    let mut conditions = (f64::NAN, f64::NAN);
    let mut state = None;
    for ((&w, &p), &t) in speed.iter().zip(pressure).zip(temperature) {
        if conditions != (p, t) {
            conditions = (p, t);
            state = losses.at(p, t).ok();
        }
        // Conditions outside the domain were refused before: `state` is always there.
        let loss = state.map_or(JointLoss { visc: f64::NAN, seal: f64::NAN, current: f64::NAN }, |s| s.evaluate(w));
        visc.push(loss.visc);
        seal.push(loss.seal);
        current.push(loss.current);
    }
    [visc, seal, current]
}

/// The losses of a robot of `n` joints.
pub(crate) fn parse_losses(losses: &PyLosses, n: usize) -> PyResult<&[Option<JointLosses<f64>>]> {
    if losses.joints.len() != n {
        return Err(PyValueError::new_err(format!(
            "losses must have one entry per joint ({n}), got {}",
            losses.joints.len()
        )));
    }
    Ok(&losses.joints)
}

/// Oil, seal and current of one joint's losses over a batch (speed [rad/s], pressure [Pa],
/// temperature [°C], all 1-D of one length). `losses`: one joint's, or None for the core's
/// defaults.
#[pyfunction]
#[pyo3(signature = (losses, speed, pressure, temperature))]
pub(crate) fn joint_losses<'py>(
    py: Python<'py>,
    losses: Option<PyRef<'py, PyLosses>>,
    speed: PyReadonlyArray1<'py, f64>,
    pressure: PyReadonlyArray1<'py, f64>,
    temperature: PyReadonlyArray1<'py, f64>,
) -> PyResult<Vec<Bound<'py, PyArray<f64, numpy::Ix1>>>> {
    let model = match losses {
        Some(losses) => parse_losses(&losses, 1)?.first().copied().flatten().unwrap_or_default(),
        None => JointLosses::default(),
    };
    let n = speed.len();
    let (w, p, t) = (
        contiguous1(&speed, "speed", n)?,
        contiguous1(&pressure, "pressure", n)?,
        contiguous1(&temperature, "temperature", n)?,
    );
    for (sample, value) in w.iter().enumerate() {
        if !value.is_finite() {
            return Err(NonFinite { argument: "speed", sample, joint: 0, value: *value }.into());
        }
    }
    check_conditions(p, t)?;
    let columns = py.detach(|| loss_batch(&model, w, p, t));
    Ok(columns.into_iter().map(|c| c.into_pyarray(py)).collect())
}
