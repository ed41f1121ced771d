//! `uwml._core.Conditions`: what an evaluation takes besides the robot and its joint state (the
//! core's `Conditions`), read from a `uwml.Conditions` by attribute and checked once, for one
//! robot: the water, the coefficients as a table per segment, the added-mass form, the base
//! motion and current (one for every sample or one per sample), the joint losses and, from the
//! depth by the core's `pressure_at_depth`, their pressure and temperature per sample.

use std::sync::OnceLock;

use numpy::{PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::intern;
use pyo3::prelude::*;
use uwml_core::nalgebra::Vector3;
use uwml_core::{AddedMassForm, BaseMotion, Current, JointLosses, LossState, Section, Water, pressure_at_depth};

use super::{Coefficients, LaneCoefficients, MAX_ROBOT_JOINTS, Model, PyRobot};
use crate::{PyLosses, model_error, parse_losses};

/// A per-sample input: one row for every sample (`rows == 1`) or one per sample.
pub(super) struct Rows {
    values: Vec<f64>,
    width: usize,
    rows: usize,
}

impl Rows {
    /// A float64 array `(width,)` (one row for all) or `(rows, width)`, named `name` in errors.
    fn read(value: &Bound<'_, PyAny>, name: &str, width: usize) -> PyResult<Self> {
        let array = value.extract::<PyReadonlyArrayDyn<'_, f64>>().map_err(|_| {
            PyValueError::new_err(format!("{name} must be a float64 array of shape ({width},) or (n_samples, {width})"))
        })?;
        let rows = match array.shape() {
            [w] if *w == width => 1,
            [n, w] if *w == width && *n > 0 => *n,
            shape => {
                return Err(PyValueError::new_err(format!(
                    "{name} must have shape ({width},) or (n_samples, {width}), got {shape:?}"
                )));
            }
        };
        let values = array.as_array().iter().copied().collect();
        Ok(Self { values, width, rows })
    }

    /// One value for every sample.
    fn single(value: f64) -> Self {
        Self { values: vec![value], width: 1, rows: 1 }
    }

    /// A scalar (one value for all samples) or a 1-D float64 array (one per sample).
    fn read_scalar(value: &Bound<'_, PyAny>, name: &str) -> PyResult<Self> {
        if let Ok(x) = value.extract::<f64>() {
            return Ok(Self::single(x));
        }
        let array = value.extract::<PyReadonlyArrayDyn<'_, f64>>().map_err(|_| {
            PyValueError::new_err(format!("{name} must be a number or a 1-D float64 array, one per sample"))
        })?;
        match array.shape() {
            [] => Ok(Self::single(array.as_array().iter().copied().next().unwrap_or(f64::NAN))),
            [n] if *n > 0 => Ok(Self { values: array.as_array().iter().copied().collect(), width: 1, rows: *n }),
            shape => Err(PyValueError::new_err(format!(
                "{name} must be a number or one per sample (n_samples,), got shape {shape:?}"
            ))),
        }
    }

    /// Sample `sample`'s row (the one row when given once).
    pub(super) fn row(&self, sample: usize) -> &[f64] {
        let i = if self.rows == 1 { 0 } else { sample };
        self.values.get(i * self.width..(i + 1) * self.width).unwrap_or(&[])
    }

    /// Sample `sample`'s value of a one-wide input.
    fn value(&self, sample: usize) -> f64 {
        self.row(sample).first().copied().unwrap_or(f64::NAN)
    }
}

/// The first three values (NaN for missing ones) as a vector.
fn v3(x: &[f64]) -> Vector3<f64> {
    Vector3::from_iterator(x.iter().copied().chain(core::iter::repeat(f64::NAN)).take(3))
}

/// The names of the seven inputs of the base motion and current, as errors name them.
const MOTION_NAMES: [&str; 7] = [
    "base_motion.orientation",
    "base_motion.velocity",
    "base_motion.angular_velocity",
    "base_motion.acceleration",
    "base_motion.angular_acceleration",
    "current",
    "current_acceleration",
];

/// The conditions of a robot's evaluations (module docs), for the robot it was made with.
#[pyclass(frozen, module = "uwml._core", name = "Conditions")]
pub(crate) struct PyConditions {
    pub(super) water: Water<f64>,
    pub(super) form: AddedMassForm,
    /// Coefficients per segment and direction, or `None` for the segments' own.
    pub(super) coefficients: Option<Box<Coefficients>>,
    /// The same over SIMD lanes, made at the first batch.
    lane_coefficients: OnceLock<Option<Box<LaneCoefficients>>>,
    /// The base motion and current, in the order of [`MOTION_NAMES`].
    motion: [Rows; 7],
    /// The base motion and current when they are one for every sample.
    constant: Option<(BaseMotion<f64>, Current<f64>)>,
    /// Each joint's losses (`None` for a joint without), and the pressure [Pa] and temperature
    /// [°C] of every sample; `None` without losses.
    pub(super) losses: Option<Losses>,
    /// The number of samples of the inputs given per sample, if any.
    pub(super) samples: Option<usize>,
    /// The name of an input given per sample, for errors.
    per_sample: &'static str,
    /// The robot's joints and segments, to refuse another robot.
    shape: (usize, usize),
}

/// The joint losses of the conditions.
pub(super) struct Losses {
    pub(super) joints: [Option<JointLosses<f64>>; MAX_ROBOT_JOINTS],
    pressure: Rows,
    temperature: Rows,
}

impl Losses {
    /// Sample `sample`'s pressure and temperature.
    fn conditions(&self, sample: usize) -> (f64, f64) {
        (self.pressure.value(sample), self.temperature.value(sample))
    }
}

/// The joints' loss states at the last sample's pressure and temperature, made again only when
/// those change.
pub(super) struct LossStates {
    conditions: (f64, f64),
    states: [Option<LossState<f64>>; MAX_ROBOT_JOINTS],
}

impl LossStates {
    pub(super) fn new() -> Self {
        Self { conditions: (f64::NAN, f64::NAN), states: [None; MAX_ROBOT_JOINTS] }
    }

    /// Every joint's loss state at sample `sample` (checked when the conditions were made).
    pub(super) fn at(&mut self, losses: &Losses, sample: usize) -> &[Option<LossState<f64>>; MAX_ROBOT_JOINTS] {
        let here = losses.conditions(sample);
        if here != self.conditions {
            self.conditions = here;
            self.states = losses.joints.map(|l| l.and_then(|l| l.at(here.0, here.1).ok()));
        }
        &self.states
    }
}

#[pymethods]
impl PyConditions {
    /// The conditions `conditions` (a `uwml.Conditions`, read by attribute) for `robot`, in
    /// `water` (a `uwml.Water`: the conditions' or the robot's own) with the joint losses
    /// `losses` (the conditions' or the robot's own; None: none).
    #[new]
    fn new(
        robot: &PyRobot,
        conditions: &Bound<'_, PyAny>,
        water: &Bound<'_, PyAny>,
        losses: Option<PyRef<'_, PyLosses>>,
    ) -> PyResult<Self> {
        let py = conditions.py();
        let model = &*robot.robot;
        let water = crate::water(
            water.getattr(intern!(py, "density"))?.extract()?,
            water.getattr(intern!(py, "gravity"))?.extract()?,
        )?;
        let form = match conditions.getattr(intern!(py, "added_mass"))?.extract::<String>()?.as_str() {
            "morison" => AddedMassForm::Morison,
            "kirchhoff" => AddedMassForm::Kirchhoff,
            other => {
                return Err(PyValueError::new_err(format!(
                    "added_mass must be one of morison, kirchhoff, got {other:?}"
                )));
            }
        };
        let coefficients =
            coefficient_table(model, &conditions.getattr(intern!(py, "cd"))?, &conditions.getattr(intern!(py, "cm"))?)?;
        let base_motion = conditions.getattr(intern!(py, "base_motion"))?;
        let mut motion = Vec::with_capacity(7);
        for (k, name) in MOTION_NAMES.into_iter().enumerate() {
            let width = if k == 0 { 4 } else { 3 };
            motion.push(if k < 5 && base_motion.is_none() {
                // A fixed, upright base: the identity quaternion, no velocities.
                let values = if k == 0 { vec![1.0, 0.0, 0.0, 0.0] } else { vec![0.0; 3] };
                Rows { values, width, rows: 1 }
            } else if k < 5 {
                let attribute = name.trim_start_matches("base_motion.");
                Rows::read(&base_motion.getattr(attribute)?, name, width)?
            } else {
                Rows::read(&conditions.getattr(name)?, name, width)?
            });
        }
        let motion: [Rows; 7] = motion.try_into().map_err(|_| PyValueError::new_err("internal error: seven inputs"))?;
        let losses = match losses {
            None => None,
            Some(losses) => {
                let mut joints = [None; MAX_ROBOT_JOINTS];
                for (slot, l) in joints.iter_mut().zip(parse_losses(&losses, model.joint_count())?) {
                    *slot = *l;
                }
                let depth = Rows::read_scalar(&conditions.getattr(intern!(py, "depth"))?, "depth")?;
                let temperature =
                    Rows::read_scalar(&conditions.getattr(intern!(py, "temperature_c"))?, "temperature_c")?;
                let sea_density = conditions.getattr(intern!(py, "sea_density"))?;
                let sea_density = if sea_density.is_none() { water.density() } else { sea_density.extract()? };
                let mut pressure = Vec::with_capacity(depth.rows);
                // The pressure matters only to a joint with losses (a robot without any may be
                // evaluated in a water without gravity).
                let needed = joints.iter().any(Option::is_some);
                for sample in (0..depth.rows).filter(|_| needed) {
                    pressure.push(pressure_at_depth(depth.value(sample), sea_density, water.gravity()).map_err(
                        |error| {
                            let at = if depth.rows > 1 { format!("[{sample}]") } else { String::new() };
                            PyValueError::new_err(format!("{}{at}: {error}", error.field))
                        },
                    )?);
                }
                let values = if needed { pressure } else { vec![0.0; depth.rows] };
                let pressure = Rows { values, width: 1, rows: depth.rows };
                Some(Losses { joints, pressure, temperature })
            }
        };
        let mut counted: Vec<(&'static str, usize)> =
            MOTION_NAMES.into_iter().zip(&motion).filter(|(_, r)| r.rows > 1).map(|(n, r)| (n, r.rows)).collect();
        if let Some(l) = &losses {
            counted.extend(
                [("depth", l.pressure.rows), ("temperature_c", l.temperature.rows)].into_iter().filter(|(_, r)| *r > 1),
            );
        }
        if counted.iter().any(|(_, rows)| Some(rows) != counted.first().map(|(_, r)| r)) {
            let sizes: Vec<String> = counted.iter().map(|(name, rows)| format!("{name}: {rows}")).collect();
            return Err(PyValueError::new_err(format!(
                "arguments given per sample must agree on the number of samples; got {}",
                sizes.join(", ")
            )));
        }
        let (per_sample, samples) = counted.first().map_or(("", None), |(name, rows)| (*name, Some(*rows)));
        let mut this = Self {
            water,
            form,
            coefficients,
            lane_coefficients: OnceLock::new(),
            motion,
            constant: None,
            losses,
            samples,
            per_sample,
            shape: (model.joint_count(), model.segments().len()),
        };
        // Every sample's motion, current and loss conditions checked here, once.
        for sample in 0..samples.unwrap_or(1) {
            let fail = |e: uwml_core::ModelError| {
                let at = if samples.is_some() { format!("sample {sample}: ") } else { String::new() };
                PyValueError::new_err(format!("{at}{e}"))
            };
            let both = this.read_motion(sample).map_err(fail)?;
            if sample == 0 && samples.is_none() {
                this.constant = Some(both);
            }
            if let Some(losses) = this.losses.as_ref().filter(|l| l.joints.iter().any(Option::is_some)) {
                let (pressure, temperature) = losses.conditions(sample);
                uwml_core::check_conditions(pressure, temperature).map_err(fail)?;
            }
        }
        Ok(this)
    }

    /// The number of samples of the inputs given per sample, or None when every input is one
    /// for all samples.
    #[getter]
    fn n_samples(&self) -> Option<usize> {
        self.samples
    }
}

impl PyConditions {
    /// Sample `sample`'s base motion and current, checked.
    fn read_motion(&self, sample: usize) -> Result<(BaseMotion<f64>, Current<f64>), uwml_core::ModelError> {
        let [
            orientation,
            velocity,
            angular_velocity,
            acceleration,
            angular_acceleration,
            current,
            current_acceleration,
        ] = &self.motion;
        let o = orientation.row(sample);
        let quaternion = [0, 1, 2, 3].map(|k| o.get(k).copied().unwrap_or(f64::NAN));
        let motion = BaseMotion::new(
            quaternion,
            v3(velocity.row(sample)),
            v3(angular_velocity.row(sample)),
            v3(acceleration.row(sample)),
            v3(angular_acceleration.row(sample)),
        )?;
        let current = Current::new(v3(current.row(sample)), v3(current_acceleration.row(sample)))?;
        Ok((motion, current))
    }

    /// Sample `sample`'s base motion and current (checked when the conditions were made).
    pub(super) fn at(&self, sample: usize) -> (BaseMotion<f64>, Current<f64>) {
        self.constant.unwrap_or_else(|| self.read_motion(sample).unwrap_or((BaseMotion::fixed(), Current::still())))
    }

    /// The base motion and current of every sample, if they are one for all.
    pub(super) const fn constant(&self) -> Option<(BaseMotion<f64>, Current<f64>)> {
        self.constant
    }

    /// The coefficients over SIMD lanes.
    pub(super) fn lane_coefficients(&self) -> Option<&LaneCoefficients> {
        self.lane_coefficients.get_or_init(|| self.coefficients.as_ref().map(|c| Box::new(c.splat()))).as_deref()
    }

    /// The number of samples of an evaluation whose joint states have `state_rows` rows (`None`:
    /// one state for every sample), or an error naming both counts.
    pub(super) fn sample_count(&self, state_rows: Option<usize>) -> PyResult<usize> {
        match (state_rows, self.samples) {
            (Some(rows), Some(samples)) if rows != samples => Err(PyValueError::new_err(format!(
                "arguments given per sample must agree on the number of samples; got q: {rows}, {}: {samples}",
                self.per_sample
            ))),
            (Some(rows), _) => Ok(rows),
            (None, samples) => Ok(samples.unwrap_or(1)),
        }
    }

    /// An error unless these conditions were made for `robot`'s joints and segments.
    pub(super) fn check_robot(&self, robot: &Model) -> PyResult<()> {
        if self.shape == (robot.joint_count(), robot.segments().len()) {
            Ok(())
        } else {
            Err(PyValueError::new_err("internal error: conditions made for another robot"))
        }
    }
}

/// A coefficient argument (`cd` or `cm`) of `items` segments: None, or a float64 array, 0-D (one
/// value for all), `(items,)` (per segment, both directions alike) or `(items, 2)`.
fn coefficient_values(value: &Bound<'_, PyAny>, name: &str, items: usize) -> PyResult<Option<Vec<[f64; 2]>>> {
    if value.is_none() {
        return Ok(None);
    }
    let wrong = |shape: &[usize]| {
        PyValueError::new_err(format!(
            "{name} must be None, a scalar, shape ({items},) per segment, or ({items}, 2) per segment and direction; got shape {shape:?}"
        ))
    };
    let array = value.extract::<PyReadonlyArrayDyn<'_, f64>>().map_err(|_| wrong(&[]))?;
    let values: Vec<f64> = array.as_array().iter().copied().collect();
    let table = match array.shape() {
        [] => vec![[values.first().copied().unwrap_or(f64::NAN); 2]; items],
        [n] if *n == items => values.iter().map(|&x| [x, x]).collect(),
        [n, 2] if *n == items => values
            .chunks_exact(2)
            .map(|p| [p.first().copied().unwrap_or(f64::NAN), p.get(1).copied().unwrap_or(f64::NAN)])
            .collect(),
        shape => return Err(wrong(shape)),
    };
    Ok(Some(table))
}

/// The table of `cd` and `cm` (either None: the segments' own) for every segment of `robot`,
/// or `None` when both are None.
fn coefficient_table(
    robot: &Model,
    cd: &Bound<'_, PyAny>,
    cm: &Bound<'_, PyAny>,
) -> PyResult<Option<Box<Coefficients>>> {
    let items = robot.segments().len();
    let (cd, cm) = (coefficient_values(cd, "cd", items)?, coefficient_values(cm, "cm", items)?);
    if cd.is_none() && cm.is_none() {
        return Ok(None);
    }
    let mut table = Box::new(robot.coefficients());
    for (k, segment) in robot.segments().iter().enumerate() {
        let circular = matches!(segment.section, Section::Circular { .. });
        let pair = |values: &Option<Vec<[f64; 2]>>, own: [f64; 2], name: &str| -> PyResult<[f64; 2]> {
            let Some(values) = values else { return Ok(own) };
            let [a, b] = values.get(k).copied().unwrap_or([f64::NAN; 2]);
            if circular && a != b {
                return Err(PyValueError::new_err(format!(
                    "{name}: segment {k} is circular and takes one coefficient; got [{a:?}, {b:?}]"
                )));
            }
            Ok([a, b])
        };
        let (cd_pair, cm_pair) = (pair(&cd, segment.cd, "cd")?, pair(&cm, segment.cm, "cm")?);
        table.set(k, cd_pair, cm_pair).map_err(model_error)?;
    }
    Ok(Some(table))
}
