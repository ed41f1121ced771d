//! `uwml._core.Robot`: a whole robot (tree, base body, segments of any section) in moving water.
//! Thin: unpacks the model, broadcasts the per-sample base motion and current, loops over samples
//! with the GIL released (optionally on several threads), writes numpy arrays.

use std::ops::Range;
use std::sync::Mutex;

use numpy::{PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::intern;
use pyo3::prelude::*;
use pyo3::types::{PyString, PyType};
use uwml_core::nalgebra::Vector3;
use uwml_core::{
    BaseMotion, Current, JointKind, JointLosses, LossState, ModelError, Owner, Problem, RigidBody, Robot, RobotData,
    RobotJacobianData, RobotJacobians, RobotSegment, Section, SegmentCoefficients, TreeJoint, Water, loss_torques,
    robot_added_mass_matrix, robot_hydro, robot_hydro_regressors, robot_jacobians,
};

use crate::single::{fill_values, finite_number, instance, threads_ok};
use crate::{Array2, contiguous, contiguous1, in_parallel, model_error, parse_losses, water, writable, zeroed};

/// The joint losses of an environment evaluation: per joint, and the pressure [Pa] and
/// temperature [°C] of every sample (checked finite).
struct Losses<'a> {
    joints: [Option<JointLosses<f64>>; MAX_ROBOT_JOINTS],
    pressure: &'a [f64],
    temperature: &'a [f64],
}

/// Largest number of joints of a robot built from Python.
pub(crate) const MAX_ROBOT_JOINTS: usize = 64;
/// Largest number of segments of a robot built from Python.
pub(crate) const MAX_SEGMENTS: usize = 256;
/// Floats per joint in the packed layout: parent (−1 for the base), kind (0 revolute,
/// 1 prismatic), origin (3), axis (3).
pub(crate) const TREE_JOINT_WIDTH: usize = 8;
/// Floats per body: mass, com (3), volume, cob (3).
pub(crate) const BODY_WIDTH: usize = 8;
/// Floats per segment: owner (−1 base, else link), section (0 rectangular, 1 circular),
/// start (3), axis (3), length, area, normals (2×3), widths (2), diameter, cd (2), cm (2).
pub(crate) const SEGMENT_WIDTH: usize = 23;

type Model = Robot<f64, MAX_ROBOT_JOINTS, MAX_SEGMENTS>;
type Data = RobotData<f64, MAX_ROBOT_JOINTS>;
type Coefficients = SegmentCoefficients<f64, MAX_SEGMENTS>;

fn v3(x: &[f64]) -> Vector3<f64> {
    Vector3::from_iterator(x.iter().copied().chain(core::iter::repeat(f64::NAN)).take(3))
}

fn body(row: &[f64]) -> RigidBody<f64> {
    let at = |i: usize| row.get(i).copied().unwrap_or(f64::NAN);
    let tail = |i: usize| row.get(i..).unwrap_or(&[]);
    RigidBody { mass: at(0), com: v3(tail(1)), volume: at(4), cob: v3(tail(5)) }
}

/// An index from a float, or an error naming the field.
fn index(x: f64, field: &'static str, i: usize) -> Result<Option<usize>, ModelError> {
    if x == -1.0 {
        Ok(None)
    } else if x >= 0.0 && x.fract() == 0.0 && x < 1e9 {
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        Ok(Some(x as usize))
    } else {
        Err(ModelError { field, index: Some(i), problem: Problem::OutOfRange })
    }
}

fn build(joints: &[f64], links: &[f64], base: &[f64], segments: &[f64]) -> Result<Model, ModelError> {
    let joint_list = joints
        .chunks_exact(TREE_JOINT_WIDTH)
        .enumerate()
        .map(|(i, r)| {
            let tail = |k: usize| r.get(k..).unwrap_or(&[]);
            Ok(TreeJoint {
                parent: index(r.first().copied().unwrap_or(f64::NAN), "joint.parent", i)?,
                kind: match r.get(1) {
                    Some(&0.0) => JointKind::Revolute,
                    Some(&1.0) => JointKind::Prismatic,
                    _ => return Err(ModelError { field: "joint.kind", index: Some(i), problem: Problem::OutOfRange }),
                },
                origin: v3(tail(2)),
                axis: v3(tail(5)),
            })
        })
        .collect::<Result<Vec<_>, ModelError>>()?;
    let link_list: Vec<_> = links.chunks_exact(BODY_WIDTH).map(body).collect();
    let segment_list = segments
        .chunks_exact(SEGMENT_WIDTH)
        .enumerate()
        .map(|(i, r)| {
            let at = |k: usize| r.get(k).copied().unwrap_or(f64::NAN);
            let tail = |k: usize| r.get(k..).unwrap_or(&[]);
            let section = match at(1) {
                0.0 => Section::Rectangular { normals: [v3(tail(10)), v3(tail(13))], widths: [at(16), at(17)] },
                1.0 => Section::Circular { diameter: at(18) },
                _ => return Err(ModelError { field: "segment.section", index: Some(i), problem: Problem::OutOfRange }),
            };
            Ok(RobotSegment {
                owner: index(at(0), "segment.owner", i)?.map_or(Owner::Base, Owner::Link),
                start: v3(tail(2)),
                axis: v3(tail(5)),
                length: at(8),
                area: at(9),
                section,
                cd: [at(19), at(20)],
                cm: [at(21), at(22)],
            })
        })
        .collect::<Result<Vec<_>, ModelError>>()?;
    Model::new(&joint_list, &link_list, body(base), &segment_list)
}

/// A per-sample input given once (one row, broadcast) or per sample.
#[derive(Clone, Copy)]
struct Rows<'a> {
    values: &'a [f64],
    width: usize,
    broadcast: bool,
}

impl<'a> Rows<'a> {
    fn new(array: &'a PyReadonlyArray2<'_, f64>, name: &str, width: usize, n_samples: usize) -> PyResult<Self> {
        let shape = array.shape();
        let rows = shape.first().copied().unwrap_or(0);
        if shape.get(1) != Some(&width) || !(rows == 1 || rows == n_samples) {
            return Err(PyValueError::new_err(format!(
                "{name} must have shape ({width},) or (n_samples, {width}) with n_samples = {n_samples}, got {shape:?}"
            )));
        }
        Ok(Self { values: contiguous(array, name)?, width, broadcast: rows == 1 })
    }

    fn row(&self, sample: usize) -> &'a [f64] {
        let i = if self.broadcast { 0 } else { sample };
        self.values.get(i * self.width..(i + 1) * self.width).unwrap_or(&[])
    }
}

/// The base motion and current of every sample.
#[derive(Clone, Copy)]
struct Surroundings<'a> {
    orientation: Rows<'a>,
    velocity: Rows<'a>,
    angular_velocity: Rows<'a>,
    acceleration: Rows<'a>,
    angular_acceleration: Rows<'a>,
    current: Rows<'a>,
    current_acceleration: Rows<'a>,
}

/// One sample's joint states, in the core's fixed-size arrays.
struct StateRow {
    q: [f64; MAX_ROBOT_JOINTS],
    qd: [f64; MAX_ROBOT_JOINTS],
    qdd: [f64; MAX_ROBOT_JOINTS],
}

impl StateRow {
    fn new() -> Self {
        Self { q: [0.0; MAX_ROBOT_JOINTS], qd: [0.0; MAX_ROBOT_JOINTS], qdd: [0.0; MAX_ROBOT_JOINTS] }
    }

    /// Sample `sample`'s rows of the batch `states` (`n` joints).
    fn load(&mut self, states: [&[f64]; 3], sample: usize, n: usize) {
        for (values, out) in states.into_iter().zip([&mut self.q, &mut self.qd, &mut self.qdd]) {
            for (slot, x) in out.iter_mut().zip(values.get(sample * n..(sample + 1) * n).unwrap_or(&[])) {
                *slot = *x;
            }
        }
    }
}

/// The joints' loss states at the last sample's pressure and temperature, made again only when
/// those change.
struct LossStates {
    conditions: (f64, f64),
    states: [Option<LossState<f64>>; MAX_ROBOT_JOINTS],
}

impl LossStates {
    fn new() -> Self {
        Self { conditions: (f64::NAN, f64::NAN), states: [None; MAX_ROBOT_JOINTS] }
    }

    fn at(&mut self, losses: &Losses<'_>, sample: usize) -> &[Option<LossState<f64>>; MAX_ROBOT_JOINTS] {
        let at = |values: &[f64]| values.get(sample).copied().unwrap_or(f64::NAN);
        let here = (at(losses.pressure), at(losses.temperature));
        if here != self.conditions {
            self.conditions = here;
            self.states = losses.joints.map(|l| l.map(|l| l.at(here.0, here.1)));
        }
        &self.states
    }
}

/// An input error of one sample, raised as a ValueError once the GIL is back.
struct SampleError {
    sample: usize,
    message: String,
}

impl<'a> Surroundings<'a> {
    /// The seven per-sample inputs, in the order of the fields, checked against `n_samples`.
    fn new(arrays: [&'a PyReadonlyArray2<'_, f64>; 7], n_samples: usize) -> PyResult<Self> {
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

    fn at(&self, sample: usize) -> Result<(BaseMotion<f64>, Current<f64>), SampleError> {
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
    fn constant(&self) -> bool {
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

/// A whole robot (validated, immutable): `Robot(joints, links, base, segments)` from packed
/// arrays (see `uwml.Robot`).
#[pyclass(frozen, module = "uwml._core", name = "Robot")]
pub(crate) struct PyRobot {
    robot: Box<Model>,
    /// A workspace kept for one-thread calls, so that they do not set up a new one.
    data: Mutex<Box<Data>>,
    /// The derivatives' workspace (the robot over dual numbers), made at the first call.
    jacobian_data: Mutex<Option<Box<RobotJacobianData<f64, MAX_ROBOT_JOINTS, MAX_SEGMENTS>>>>,
}

/// Evaluates samples `range` into `out`: 4 joint arrays `n`-wide, 4 base arrays 6-wide, and the
/// bodies' world wrenches about their centres of mass (`(n + 1)·6` wide, base first), unless that
/// array is empty.
#[allow(clippy::too_many_arguments)]
fn hydro_range(
    robot: &Model,
    water: &Water<f64>,
    coefficients: Option<&Coefficients>,
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
        robot_hydro(robot, water, coefficients, &motion, &current, &row.q, &row.qd, &row.qdd, data);
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
fn regressor_range(
    robot: &Model,
    water: &Water<f64>,
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
        robot_hydro_regressors(robot, water, &motion, &current, &row.q, &row.qd, &row.qdd, data, drag, added_mass);
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

/// The five arrays of a `uwml.BaseMotion` of one state.
type MotionArrays<'py> =
    (Bound<'py, PyAny>, Bound<'py, PyAny>, Bound<'py, PyAny>, Bound<'py, PyAny>, Bound<'py, PyAny>);

/// One state's arguments of `hydro_one`, read and checked.
struct OneState {
    row: StateRow,
    water: Water<f64>,
    coefficients: Option<Coefficients>,
    motion: BaseMotion<f64>,
    current: Current<f64>,
}

impl OneState {
    /// `None` unless every argument (in the order of `hydro_one`'s) is of a kind taken there
    /// and passes its check.
    fn read(n: usize, arguments: [&Bound<'_, PyAny>; 11]) -> Option<Self> {
        let [q, qd, qdd, cd, cm, density, gravity, motion, current, current_acceleration, threads] = arguments;
        let mut row = StateRow::new();
        fill_values(q, row.q.get_mut(..n)?)?;
        fill_values(qd, row.qd.get_mut(..n)?)?;
        fill_values(qdd, row.qdd.get_mut(..n)?)?;
        if !threads_ok(threads) {
            return None;
        }
        let water = Water::new(finite_number(density)?, finite_number(gravity)?).ok()?;
        let coefficient = |c: &Bound<'_, PyAny>| -> Option<Option<f64>> {
            if c.is_none() { Some(None) } else { finite_number(c).filter(|x| *x >= 0.0).map(Some) }
        };
        let coefficients = match (coefficient(cd)?, coefficient(cm)?) {
            (None, None) => None,
            (Some(cd), Some(cm)) => Some(Coefficients::uniform(cd, cm).ok()?),
            _ => return None,
        };
        let vector = |value: &Bound<'_, PyAny>| {
            let mut out = [0.0; 3];
            fill_values(value, &mut out).map(|()| Vector3::from(out))
        };
        let motion = if motion.is_none() {
            BaseMotion::fixed()
        } else {
            let (orientation, velocity, angular_velocity, acceleration, angular_acceleration): MotionArrays<'_> =
                motion.extract().ok()?;
            let mut quaternion = [0.0; 4];
            fill_values(&orientation, &mut quaternion)?;
            let twist = (vector(&velocity)?, vector(&angular_velocity)?);
            let derivative = (vector(&acceleration)?, vector(&angular_acceleration)?);
            BaseMotion::new(quaternion, twist.0, twist.1, derivative.0, derivative.1).ok()?
        };
        let current = Current::new(vector(current)?, vector(current_acceleration)?).ok()?;
        Some(Self { row, water, coefficients, motion, current })
    }

    fn evaluate(&self, robot: &Model, data: &mut Data) {
        let Self { row, water, coefficients, motion, current } = self;
        robot_hydro(robot, water, coefficients.as_ref(), motion, current, &row.q, &row.qd, &row.qdd, data);
    }
}

/// The `result_type` of one evaluation in `data` (with `losses`, `(visc, seal, current)`, when
/// given), its `base` a `base_type`, built directly (no `__init__`).
fn one_result<'py>(
    result_type: &Bound<'py, PyType>,
    base_type: &Bound<'py, PyType>,
    data: &Data,
    losses: Option<[&[f64]; 3]>,
) -> PyResult<Bound<'py, PyAny>> {
    let py = result_type.py();
    let forces = data.joint_forces();
    let n = forces.len();
    let column = |value: fn(&uwml_core::JointForces<f64>) -> f64| {
        numpy::PyArray1::from_iter(py, forces.iter().map(value)).into_any()
    };
    let base = data.base_wrench();
    let wrench = |w: &uwml_core::Wrench<f64>| numpy::PyArray1::from_slice(py, &w.to_array()).into_any();
    let names: [&Bound<'py, PyString>; 4] =
        [intern!(py, "drag"), intern!(py, "added_mass"), intern!(py, "buoyancy"), intern!(py, "gravity")];
    let base_object = instance(
        base_type,
        names.into_iter().zip([
            wrench(&base.drag),
            wrench(&base.added_mass),
            wrench(&base.buoyancy),
            wrench(&base.gravity),
        ]),
    )?;
    let joint_columns = [column(|f| f.drag), column(|f| f.added_mass), column(|f| f.buoyancy), column(|f| f.gravity)];
    let mut fields: Vec<(&Bound<'py, PyString>, Bound<'py, PyAny>)> = names.into_iter().zip(joint_columns).collect();
    if let Some(losses) = losses {
        let loss_names = [intern!(py, "visc"), intern!(py, "seal"), intern!(py, "current")];
        for (name, values) in loss_names.into_iter().zip(losses) {
            fields.push((name, numpy::PyArray1::from_slice(py, values.get(..n).unwrap_or(&[])).into_any()));
        }
    }
    fields.push((intern!(py, "base"), base_object));
    instance(result_type, fields)
}

#[pymethods]
impl PyRobot {
    #[new]
    fn new(
        joints: PyReadonlyArray2<'_, f64>,
        links: PyReadonlyArray2<'_, f64>,
        base: PyReadonlyArray2<'_, f64>,
        segments: PyReadonlyArray2<'_, f64>,
    ) -> PyResult<Self> {
        let n = joints.shape().first().copied().unwrap_or(0);
        let s = segments.shape().first().copied().unwrap_or(0);
        if n > MAX_ROBOT_JOINTS || s > MAX_SEGMENTS {
            return Err(PyValueError::new_err(format!(
                "a robot may have up to {MAX_ROBOT_JOINTS} joints and {MAX_SEGMENTS} segments, got {n} and {s}"
            )));
        }
        let expected = [[n, TREE_JOINT_WIDTH], [n, BODY_WIDTH], [1, BODY_WIDTH], [s, SEGMENT_WIDTH]];
        let given = [joints.shape(), links.shape(), base.shape(), segments.shape()];
        if given.iter().zip(expected.iter()).any(|(g, e)| *g != e.as_slice()) {
            return Err(PyValueError::new_err(format!(
                "packed robot arrays must have shapes {expected:?}, got {given:?}"
            )));
        }
        let robot = build(
            contiguous(&joints, "joints")?,
            contiguous(&links, "links")?,
            contiguous(&base, "base")?,
            contiguous(&segments, "segments")?,
        )
        .map_err(model_error)?;
        Ok(Self { robot: Box::new(robot), data: Mutex::new(Box::new(Data::new())), jacobian_data: Mutex::new(None) })
    }

    /// Number of joints.
    #[getter]
    fn n_joints(&self) -> usize {
        self.robot.joint_count()
    }

    /// Drag, added mass, buoyancy, gravity on the joints (each `(n_samples, N)`), then on the
    /// base (each `(n_samples, 6)`). Base motion and current: `(1, k)` for all samples or
    /// `(n_samples, k)`. `cd`, `cm`: `(S, 2)`, or `(0, 2)` for the segments' own.
    #[allow(clippy::too_many_arguments)]
    #[pyo3(signature = (q, qd, qdd, cd, cm, density, gravity, orientation, velocity, angular_velocity, acceleration, angular_acceleration, current, current_acceleration, threads, body_wrenches, losses=None, pressure=None, temperature=None))]
    fn hydro<'py>(
        &self,
        py: Python<'py>,
        q: PyReadonlyArray2<'py, f64>,
        qd: PyReadonlyArray2<'py, f64>,
        qdd: PyReadonlyArray2<'py, f64>,
        cd: PyReadonlyArray2<'py, f64>,
        cm: PyReadonlyArray2<'py, f64>,
        density: f64,
        gravity: f64,
        orientation: PyReadonlyArray2<'py, f64>,
        velocity: PyReadonlyArray2<'py, f64>,
        angular_velocity: PyReadonlyArray2<'py, f64>,
        acceleration: PyReadonlyArray2<'py, f64>,
        angular_acceleration: PyReadonlyArray2<'py, f64>,
        current: PyReadonlyArray2<'py, f64>,
        current_acceleration: PyReadonlyArray2<'py, f64>,
        threads: usize,
        body_wrenches: bool,
        losses: Option<PyReadonlyArray2<'py, f64>>,
        pressure: Option<PyReadonlyArray1<'py, f64>>,
        temperature: Option<PyReadonlyArray1<'py, f64>>,
    ) -> PyResult<Vec<Array2<'py>>> {
        let n = self.robot.joint_count();
        let n_samples = check_state_shapes([&q, &qd, &qdd], n)?;
        let states = [contiguous(&q, "q")?, contiguous(&qd, "qd")?, contiguous(&qdd, "qdd")?];
        check_states(&[("q", states[0]), ("qd", states[1]), ("qdd", states[2])], n)?;
        let surroundings = Surroundings::new(
            [
                &orientation,
                &velocity,
                &angular_velocity,
                &acceleration,
                &angular_acceleration,
                &current,
                &current_acceleration,
            ],
            n_samples,
        )?;
        let coefficients = self.coefficients(&cd, &cm)?;
        let water = water(density, gravity)?;
        let losses = match (&losses, &pressure, &temperature) {
            (Some(losses), Some(pressure), Some(temperature)) => {
                Some(check_losses(losses, pressure, temperature, n, n_samples)?)
            }
            (None, None, None) => None,
            _ => return Err(PyValueError::new_err("losses, pressure and temperature come together")),
        };
        let loss_width = if losses.is_some() { n } else { 0 };
        let robot = &*self.robot;
        let [drag, added_mass, buoyancy, weight] = zeroed::<4>(py, n_samples, n);
        let [base_drag, base_added_mass, base_buoyancy, base_weight] = zeroed::<4>(py, n_samples, 6);
        let wrench_width = if body_wrenches { (n + 1) * 6 } else { 0 };
        let [wrenches] = zeroed::<1>(py, n_samples, wrench_width);
        let [visc, seal, loss_current] = zeroed::<3>(py, n_samples, loss_width);
        let arrays = [
            drag,
            added_mass,
            buoyancy,
            weight,
            base_drag,
            base_added_mass,
            base_buoyancy,
            base_weight,
            wrenches,
            visc,
            seal,
            loss_current,
        ];
        let mut guards = arrays.each_ref().map(|a| a.readwrite());
        let out = writable(&mut guards)?;
        let coefficients = coefficients.as_ref();
        let losses = losses.as_ref();
        let shared = &self.data;
        let result = py.detach(|| {
            if threads <= 1 {
                let mut data = shared.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
                hydro_range(robot, &water, coefficients, &surroundings, states, losses, &(0..n_samples), &mut data, out)
            } else {
                // Samples are numbered in the whole batch already.
                let shift = |e: SampleError, _start: usize| e;
                let widths = [n, n, n, n, 6, 6, 6, 6, wrench_width, loss_width, loss_width, loss_width];
                in_parallel(
                    n_samples,
                    widths,
                    threads,
                    out,
                    |range, out| {
                        let mut data = Box::new(Data::new());
                        hydro_range(robot, &water, coefficients, &surroundings, states, losses, range, &mut data, out)
                    },
                    shift,
                )
            }
        });
        drop(guards);
        result.map_err(|e| PyValueError::new_err(format!("sample {}: {}", e.sample, e.message)))?;
        Ok(arrays.into())
    }

    /// One state, for a controller or a simulator stepping one state at a time: `q`, `qd`,
    /// `qdd` lists, tuples or 1-D float64 arrays of N finite numbers; `cd`, `cm` None (the
    /// segments' own) or finite non-negative numbers; `motion` None (a fixed, upright base) or
    /// the five 1-D arrays of a `uwml.BaseMotion`; `current`, `current_acceleration` like the
    /// states, of 3. Returns a `result_type` (`uwml.RobotTorques`) with a `base_type`
    /// (`uwml.BaseWrench`), the same bits as the batch path; or `None` when any argument is of
    /// another kind or fails a check (the general path then answers, with its errors).
    #[allow(clippy::too_many_arguments)]
    fn hydro_one<'py>(
        &self,
        result_type: &Bound<'py, PyType>,
        base_type: &Bound<'py, PyType>,
        q: &Bound<'py, PyAny>,
        qd: &Bound<'py, PyAny>,
        qdd: &Bound<'py, PyAny>,
        cd: &Bound<'py, PyAny>,
        cm: &Bound<'py, PyAny>,
        density: &Bound<'py, PyAny>,
        gravity: &Bound<'py, PyAny>,
        motion: &Bound<'py, PyAny>,
        current: &Bound<'py, PyAny>,
        current_acceleration: &Bound<'py, PyAny>,
        threads: &Bound<'py, PyAny>,
    ) -> PyResult<Option<Bound<'py, PyAny>>> {
        let arguments = [q, qd, qdd, cd, cm, density, gravity, motion, current, current_acceleration, threads];
        let Some(one) = OneState::read(self.robot.joint_count(), arguments) else { return Ok(None) };
        let mut data = self.data.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        one.evaluate(&self.robot, &mut data);
        one_result(result_type, base_type, &data, None).map(Some)
    }

    /// [`PyRobot::hydro_one`] with the joint losses of `Robot.environment`: `depth` ≥ 0,
    /// `temperature`, `sea_density` > 0 numbers, `losses` None or packed `(N, LOSS_WIDTH)`;
    /// a `result_type` (`uwml.RobotEnvironment`) or `None`, as there.
    #[allow(clippy::too_many_arguments)]
    fn environment_one<'py>(
        &self,
        result_type: &Bound<'py, PyType>,
        base_type: &Bound<'py, PyType>,
        q: &Bound<'py, PyAny>,
        qd: &Bound<'py, PyAny>,
        qdd: &Bound<'py, PyAny>,
        depth: &Bound<'py, PyAny>,
        temperature: &Bound<'py, PyAny>,
        losses: &Bound<'py, PyAny>,
        cd: &Bound<'py, PyAny>,
        cm: &Bound<'py, PyAny>,
        density: &Bound<'py, PyAny>,
        gravity: &Bound<'py, PyAny>,
        sea_density: &Bound<'py, PyAny>,
        motion: &Bound<'py, PyAny>,
        current: &Bound<'py, PyAny>,
        current_acceleration: &Bound<'py, PyAny>,
        threads: &Bound<'py, PyAny>,
    ) -> PyResult<Option<Bound<'py, PyAny>>> {
        let n = self.robot.joint_count();
        let arguments = [q, qd, qdd, cd, cm, density, gravity, motion, current, current_acceleration, threads];
        let (Some(one), Some(depth), Some(temperature), Some(sea_density)) = (
            OneState::read(n, arguments),
            finite_number(depth),
            finite_number(temperature),
            finite_number(sea_density),
        ) else {
            return Ok(None);
        };
        if depth < 0.0 || sea_density <= 0.0 {
            return Ok(None);
        }
        let mut joints = [None; MAX_ROBOT_JOINTS];
        if !losses.is_none() {
            let Ok(packed) = losses.cast::<numpy::PyArray2<f64>>() else { return Ok(None) };
            let Ok(packed) = packed.try_readonly() else { return Ok(None) };
            let Ok(parsed) = parse_losses(&packed, n) else { return Ok(None) };
            for (slot, l) in joints.iter_mut().zip(parsed) {
                *slot = l;
            }
        }
        // The batch path's pressure and loss states, so that the bits are its.
        let (pressure, temperature) = ([sea_density * one.water.gravity() * depth], [temperature]);
        let conditions = Losses { joints, pressure: &pressure, temperature: &temperature };
        let mut data = self.data.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        one.evaluate(&self.robot, &mut data);
        let (visc, seal, loss_current) = loss_torques(LossStates::new().at(&conditions, 0), &one.row.qd.into());
        one_result(result_type, base_type, &data, Some([&visc, &seal, &loss_current].map(|v| v.as_slice()))).map(Some)
    }

    /// Regressors: buoyancy, gravity (`(n_samples, N)`), base buoyancy, base gravity
    /// (`(n_samples, 6)`), drag and added mass (`(n_samples, (6 + N)·2S)`: rows base then joints,
    /// columns segment and direction).
    #[allow(clippy::too_many_arguments)]
    fn regressors<'py>(
        &self,
        py: Python<'py>,
        q: PyReadonlyArray2<'py, f64>,
        qd: PyReadonlyArray2<'py, f64>,
        qdd: PyReadonlyArray2<'py, f64>,
        density: f64,
        gravity: f64,
        orientation: PyReadonlyArray2<'py, f64>,
        velocity: PyReadonlyArray2<'py, f64>,
        angular_velocity: PyReadonlyArray2<'py, f64>,
        acceleration: PyReadonlyArray2<'py, f64>,
        angular_acceleration: PyReadonlyArray2<'py, f64>,
        current: PyReadonlyArray2<'py, f64>,
        current_acceleration: PyReadonlyArray2<'py, f64>,
        threads: usize,
    ) -> PyResult<Vec<Array2<'py>>> {
        let n = self.robot.joint_count();
        let n_samples = check_state_shapes([&q, &qd, &qdd], n)?;
        let states = [contiguous(&q, "q")?, contiguous(&qd, "qd")?, contiguous(&qdd, "qdd")?];
        check_states(&[("q", states[0]), ("qd", states[1]), ("qdd", states[2])], n)?;
        let surroundings = Surroundings::new(
            [
                &orientation,
                &velocity,
                &angular_velocity,
                &acceleration,
                &angular_acceleration,
                &current,
                &current_acceleration,
            ],
            n_samples,
        )?;
        let water = water(density, gravity)?;
        let width = (6 + n) * 2 * self.robot.segments().len();
        let [buoyancy, weight] = zeroed::<2>(py, n_samples, n);
        let [base_buoyancy, base_weight] = zeroed::<2>(py, n_samples, 6);
        let [drag, added_mass] = zeroed::<2>(py, n_samples, width);
        let arrays = [buoyancy, weight, base_buoyancy, base_weight, drag, added_mass];
        let mut guards = arrays.each_ref().map(|a| a.readwrite());
        let out = writable(&mut guards)?;
        let robot = &*self.robot;
        let result = py.detach(|| {
            let shift = |e: SampleError, _start: usize| e;
            in_parallel(
                n_samples,
                [n, n, 6, 6, width, width],
                threads,
                out,
                |range, out| {
                    let mut data = Box::new(Data::new());
                    regressor_range(robot, &water, &surroundings, states, range, &mut data, out)
                },
                shift,
            )
        });
        drop(guards);
        result.map_err(|e| PyValueError::new_err(format!("sample {}: {}", e.sample, e.message)))?;
        Ok(arrays.into())
    }

    /// `(value (m), d_q (m·N), d_velocity (m²), added_mass_matrix (m²))` per sample, `m = 6 + N`,
    /// rows base then joints, velocity columns `(ν, q̇)`; arguments as for `hydro` with losses.
    #[allow(clippy::too_many_arguments)]
    fn jacobians<'py>(
        &self,
        py: Python<'py>,
        q: PyReadonlyArray2<'py, f64>,
        qd: PyReadonlyArray2<'py, f64>,
        qdd: PyReadonlyArray2<'py, f64>,
        cd: PyReadonlyArray2<'py, f64>,
        cm: PyReadonlyArray2<'py, f64>,
        density: f64,
        gravity: f64,
        orientation: PyReadonlyArray2<'py, f64>,
        velocity: PyReadonlyArray2<'py, f64>,
        angular_velocity: PyReadonlyArray2<'py, f64>,
        acceleration: PyReadonlyArray2<'py, f64>,
        angular_acceleration: PyReadonlyArray2<'py, f64>,
        current: PyReadonlyArray2<'py, f64>,
        current_acceleration: PyReadonlyArray2<'py, f64>,
        losses: PyReadonlyArray2<'py, f64>,
        pressure: PyReadonlyArray1<'py, f64>,
        temperature: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Vec<Array2<'py>>> {
        let n = self.robot.joint_count();
        let m = 6 + n;
        let n_samples = check_state_shapes([&q, &qd, &qdd], n)?;
        let states = [contiguous(&q, "q")?, contiguous(&qd, "qd")?, contiguous(&qdd, "qdd")?];
        check_states(&[("q", states[0]), ("qd", states[1]), ("qdd", states[2])], n)?;
        let surroundings = Surroundings::new(
            [
                &orientation,
                &velocity,
                &angular_velocity,
                &acceleration,
                &angular_acceleration,
                &current,
                &current_acceleration,
            ],
            n_samples,
        )?;
        let coefficients = self.coefficients(&cd, &cm)?;
        let water = water(density, gravity)?;
        let losses = check_losses(&losses, &pressure, &temperature, n, n_samples)?;
        let [value] = zeroed::<1>(py, n_samples, m);
        let [d_q] = zeroed::<1>(py, n_samples, m * n);
        let [d_velocity, matrix] = zeroed::<2>(py, n_samples, m * m);
        let arrays = [value, d_q, d_velocity, matrix];
        let mut guards = arrays.each_ref().map(|a| a.readwrite());
        let [value, d_q, d_velocity, matrix] = writable(&mut guards)?;
        let robot = &*self.robot;
        let mut work = self.jacobian_data.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        let work = work.get_or_insert_with(|| Box::new(RobotJacobianData::new(robot)));
        let result = py.detach(|| -> Result<(), SampleError> {
            let mut row = StateRow::new();
            let mut loss_states = LossStates::new();
            let rows = value
                .chunks_exact_mut(m)
                .zip(d_q.chunks_exact_mut(m * n))
                .zip(d_velocity.chunks_exact_mut(m * m).zip(matrix.chunks_exact_mut(m * m)));
            for (sample, ((value, d_q), (d_velocity, added_mass_matrix))) in rows.enumerate() {
                row.load(states, sample, n);
                let (motion, current) = surroundings.at(sample)?;
                let out = RobotJacobians { value, d_q, d_velocity, added_mass_matrix };
                robot_jacobians(
                    robot,
                    &water,
                    coefficients.as_ref(),
                    loss_states.at(&losses, sample),
                    &motion,
                    &current,
                    &row.q,
                    &row.qd,
                    &row.qdd,
                    work,
                    out,
                );
            }
            Ok(())
        });
        drop(guards);
        result.map_err(|e| PyValueError::new_err(format!("sample {}: {}", e.sample, e.message)))?;
        Ok(arrays.into())
    }

    /// The added-mass matrices `(n_samples, (6 + N)²)` (row-major, base first) at joint
    /// positions `q` `(n_samples, N)`; `cm` as for `hydro` (`(0, 2)`: the segments' own).
    fn added_mass_matrix<'py>(
        &self,
        py: Python<'py>,
        q: PyReadonlyArray2<'py, f64>,
        cm: PyReadonlyArray2<'py, f64>,
        density: f64,
    ) -> PyResult<Array2<'py>> {
        let n = self.robot.joint_count();
        let shape = q.shape();
        if shape.get(1) != Some(&n) {
            return Err(PyValueError::new_err(format!("q must have shape (n_samples, {n}), got {shape:?}")));
        }
        let n_samples = shape.first().copied().unwrap_or(0);
        let values = contiguous(&q, "q")?;
        check_states(&[("q", values)], n)?;
        let coefficients = self.coefficients(&cm, &cm)?;
        let water = water(density, 0.0)?;
        let size = (6 + n) * (6 + n);
        let [matrices] = zeroed::<1>(py, n_samples, size);
        let mut guards = [matrices.readwrite()];
        let [out] = writable(&mut guards)?;
        let robot = &*self.robot;
        let shared = &self.data;
        py.detach(|| {
            let mut data = shared.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
            let mut qs = [0.0; MAX_ROBOT_JOINTS];
            for (row, matrix) in values.chunks_exact(n.max(1)).zip(out.chunks_exact_mut(size)) {
                for (slot, x) in qs.iter_mut().zip(row) {
                    *slot = *x;
                }
                robot_added_mass_matrix(robot, &water, coefficients.as_ref(), &qs, &mut data, matrix);
            }
        });
        drop(guards);
        Ok(matrices)
    }
}

/// Packed joint losses `(n, LOSS_WIDTH)` and the pressure and temperature of every sample.
fn check_losses<'a>(
    losses: &PyReadonlyArray2<'_, f64>,
    pressure: &'a PyReadonlyArray1<'_, f64>,
    temperature: &'a PyReadonlyArray1<'_, f64>,
    n: usize,
    n_samples: usize,
) -> PyResult<Losses<'a>> {
    let mut joints = [None; MAX_ROBOT_JOINTS];
    for (slot, l) in joints.iter_mut().zip(parse_losses(losses, n)?) {
        *slot = l;
    }
    let pressure = contiguous1(pressure, "pressure", n_samples)?;
    let temperature = contiguous1(temperature, "temperature", n_samples)?;
    for (name, values) in [("pressure", pressure), ("temperature", temperature)] {
        if let Some(i) = values.iter().position(|x| !x.is_finite()) {
            return Err(PyValueError::new_err(format!("{name}[{i}] must be finite")));
        }
    }
    Ok(Losses { joints, pressure, temperature })
}

/// The number of samples of `q`, `qd`, `qdd`, each `(n_samples, n)`.
fn check_state_shapes(states: [&PyReadonlyArray2<'_, f64>; 3], n: usize) -> PyResult<usize> {
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
fn check_states(states: &[(&str, &[f64])], n: usize) -> PyResult<()> {
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

impl PyRobot {
    /// Per-segment coefficients `(S, 2)`, or `None` for `(0, 2)` (the segments' own).
    fn coefficients(
        &self,
        cd: &PyReadonlyArray2<'_, f64>,
        cm: &PyReadonlyArray2<'_, f64>,
    ) -> PyResult<Option<Coefficients>> {
        let segments = self.robot.segments().len();
        match (cd.shape(), cm.shape()) {
            ([0, 2], [0, 2]) => Ok(None),
            (a, b) if a == [segments, 2] && b == [segments, 2] => {
                let (mut cd_table, mut cm_table) = ([[0.0; 2]; MAX_SEGMENTS], [[0.0; 2]; MAX_SEGMENTS]);
                for (slot, pair) in cd_table.iter_mut().zip(contiguous(cd, "cd")?.chunks_exact(2)) {
                    slot.copy_from_slice(pair);
                }
                for (slot, pair) in cm_table.iter_mut().zip(contiguous(cm, "cm")?.chunks_exact(2)) {
                    slot.copy_from_slice(pair);
                }
                Ok(Some(Coefficients::per_segment(cd_table, cm_table).map_err(model_error)?))
            }
            (a, b) => Err(PyValueError::new_err(format!(
                "cd and cm must have shape ({segments}, 2) (one pair per segment), got {a:?} and {b:?}"
            ))),
        }
    }
}
