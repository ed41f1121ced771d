//! The joint losses through the bindings: unpacking the packed layout `uwml.JointLosses` sends,
//! and the batch of one joint's losses (`joint_losses`).

use numpy::{IntoPyArray, PyArray, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use uwml_core::{Drive, JointLoss, JointLosses, ModelError, OilDrag, Seal};

use crate::errors::ModelError as PyModelError;
use crate::{LOSS_WIDTH, NonFinite, check_conditions, contiguous, contiguous1};

pub(crate) fn unpack_losses(row: &[f64]) -> Result<Option<JointLosses<f64>>, ModelError> {
    let mut values = row.iter().copied();
    let mut next = || values.next().unwrap_or(f64::NAN);
    let has_oil = next() != 0.0;
    let oil = [next(), next(), next(), next(), next(), next()];
    let has_seal = next() != 0.0;
    let seal = [next(), next(), next(), next(), next(), next(), next()];
    let drive = [next(), next(), next(), next()];
    let epsilon = next();
    if next() == 0.0 {
        return Ok(None);
    }
    let [k, n, a_p, a_t, p_ref, t_ref] = oil;
    let oil = if has_oil { Some(OilDrag::new(k, n, a_p, a_t, p_ref, t_ref)?) } else { None };
    let [c0, c1, s0, s1, d0, d1, w_s] = seal;
    let seal = if has_seal { Some(Seal::new([c0, c1], [s0, s1], [d0, d1], w_s)?) } else { None };
    let [kt, ratio, efficiency, rated] = drive;
    Ok(Some(JointLosses::new(Drive::new(kt, ratio, efficiency, rated)?, oil, seal, epsilon)?))
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

pub(crate) fn parse_losses(losses: &PyReadonlyArray2<'_, f64>, n: usize) -> PyResult<Vec<Option<JointLosses<f64>>>> {
    if losses.shape() != [n, LOSS_WIDTH] {
        return Err(PyValueError::new_err(format!(
            "packed losses must have shape ({n}, {LOSS_WIDTH}), got {:?}",
            losses.shape()
        )));
    }
    contiguous(losses, "losses")?
        .chunks_exact(LOSS_WIDTH)
        .enumerate()
        .map(|(joint, row)| {
            unpack_losses(row).map_err(|e| PyModelError::new_err(format!("losses of joint {joint}: {e}")))
        })
        .collect()
}

/// Oil, seal and current of one joint's losses over a batch (speed [rad/s], pressure [Pa],
/// temperature [°C], all 1-D of one length). `losses`: packed (1, LOSS_WIDTH), or None for
/// the core's defaults.
#[pyfunction]
#[pyo3(signature = (losses, speed, pressure, temperature))]
pub(crate) fn joint_losses<'py>(
    py: Python<'py>,
    losses: Option<PyReadonlyArray2<'py, f64>>,
    speed: PyReadonlyArray1<'py, f64>,
    pressure: PyReadonlyArray1<'py, f64>,
    temperature: PyReadonlyArray1<'py, f64>,
) -> PyResult<Vec<Bound<'py, PyArray<f64, numpy::Ix1>>>> {
    let model = match losses {
        Some(packed) => parse_losses(&packed, 1)?.into_iter().next().flatten().unwrap_or_default(),
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
