//! `uwml._core.Robot`: a whole robot (tree, base body, segments of any section) in moving water.
//! Thin: unpacks the model, broadcasts the per-sample base motion and current, loops over samples
//! with the GIL released (optionally on several threads), writes numpy arrays.

use std::ops::{Deref, DerefMut};
use std::sync::{Mutex, MutexGuard, OnceLock, TryLockError};

use numpy::{PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyType;
use uwml_core::nalgebra::Vector3;
use uwml_core::{
    AddedMassForm, Conditions, Owner, Robot, RobotData, RobotJacobianData, RobotJacobians, SegmentCoefficients,
    presets, robot_added_mass_matrix, robot_jacobians,
};

mod batch;
mod coupling;
mod design;
mod inputs;
mod kinematics;
pub(crate) mod one;
mod rk4;
mod view;

use crate::arrays::Lanes;
use crate::parts::{BodySpec, JointSpec, RobotParts, SegmentSpec, robot_parts};
use crate::single::finite_number;
use crate::{
    Array2, NonFinite, PyLosses, contiguous, contiguous1, in_parallel, model_error, parse_losses, to_numpy, water,
    writable, zeroed,
};
use batch::{hydro_range, regressor_range};
pub(crate) use coupling::MujocoCoupling;
use inputs::{
    LossStates, SampleError, StateRow, Surroundings, check_losses, check_state_shapes, check_states, write_joint_losses,
};
use one::{Layout, OneState, one_result};

/// The added-mass form a call asks for (`kirchhoff=True`: Kirchhoff's, else the paper's Morison).
fn added_mass_form(kirchhoff: bool) -> AddedMassForm {
    if kirchhoff { AddedMassForm::Kirchhoff } else { AddedMassForm::Morison }
}

/// Largest number of joints of a robot built from Python.
pub(crate) const MAX_ROBOT_JOINTS: usize = 64;
/// Largest number of segments of a robot built from Python.
pub(crate) const MAX_SEGMENTS: usize = 256;
/// The most lumped models (docs/model.md section 12.1) a robot may carry, on all its bodies.
pub(crate) const MAX_LUMPED_BODIES: usize = 16;
type Model = Robot<f64, MAX_ROBOT_JOINTS, MAX_SEGMENTS, MAX_LUMPED_BODIES>;
type Data = RobotData<f64, MAX_ROBOT_JOINTS>;
/// The robot over SIMD lanes, for the batch: four states per evaluation.
type LaneModel = Robot<Lanes, MAX_ROBOT_JOINTS, MAX_SEGMENTS, MAX_LUMPED_BODIES>;
type LaneData = RobotData<Lanes, MAX_ROBOT_JOINTS>;
type Coefficients = SegmentCoefficients<f64, MAX_SEGMENTS>;

/// A whole robot (validated, immutable): `Robot(joints, links, base, segments)` from packed
/// arrays (see `uwml.Robot`).
#[pyclass(frozen, module = "uwml._core", name = "Robot")]
pub(crate) struct PyRobot {
    robot: Box<Model>,
    /// Each joint's plausible bounds (`uwml.plausibility.JointBounds.rows`): the one-state path
    /// leaves a state or a result beyond them to the general path, which warns.
    bounds: Vec<one::Bounds>,
    /// A workspace kept for one-thread calls, so that they do not set up a new one.
    data: Mutex<Box<Data>>,
    /// A coefficient table kept for one-state calls given `cd` or `cm` (8 kB: made once, and
    /// only the robot's segments' entries written by each call).
    coefficient_table: Mutex<Box<Coefficients>>,
    /// The robot over SIMD lanes, made at the first batch.
    lanes: OnceLock<Box<LaneModel>>,
    /// A lane workspace kept for one-thread batches.
    lane_data: Mutex<Option<Box<LaneData>>>,
    /// The derivatives' workspace (the robot over dual numbers), made at the first call.
    jacobian_data: Mutex<Option<Box<RobotJacobianData<f64, MAX_ROBOT_JOINTS, MAX_SEGMENTS, MAX_LUMPED_BODIES>>>>,
}

#[pymethods]
impl PyRobot {
    /// The robot of its `uwml.Joint`s (each `parent` resolved, `-1` for the base), its links'
    /// and base's bodies (`uwml.Link`s: mass, com, volume, cob) and its segments as `(owner,
    /// uwml.Segment)` pairs (`owner` `-1` for the base), and each joint's plausible bounds
    /// `(angle, speed, effort)`.
    #[new]
    fn new(
        joints: Vec<JointSpec>,
        links: Vec<BodySpec>,
        base: BodySpec,
        segments: Vec<(i64, SegmentSpec)>,
        bounds: Vec<one::Bounds>,
    ) -> PyResult<Self> {
        let (n, s) = (joints.len(), segments.len());
        if bounds.len() != n || bounds.iter().flatten().any(|x| x.is_nan()) {
            return Err(PyValueError::new_err(format!(
                "bounds must hold one (angle, speed, effort) of numbers per joint, got {} for {n} joints",
                bounds.len()
            )));
        }
        if n > MAX_ROBOT_JOINTS || s > MAX_SEGMENTS || links.len() != n {
            return Err(PyValueError::new_err(format!(
                "a robot may have up to {MAX_ROBOT_JOINTS} joints (and as many links) and {MAX_SEGMENTS} segments, got {n} joints, {} links and {s} segments",
                links.len()
            )));
        }
        let tree = joints.iter().enumerate().map(|(i, j)| j.tree_joint(i)).collect::<Result<Vec<_>, _>>();
        let pieces = segments
            .iter()
            .enumerate()
            .map(|(k, (owner, s))| s.robot_segment(*owner, k))
            .collect::<Result<Vec<_>, _>>();
        let bodies: Vec<_> = links.iter().map(BodySpec::rigid_body).collect();
        let lumped: Vec<_> = base
            .lumped_body(Owner::Base)
            .into_iter()
            .chain(links.iter().enumerate().filter_map(|(i, link)| link.lumped_body(Owner::Link(i))))
            .collect();
        let robot = Model::new(&tree.map_err(model_error)?, &bodies, base.rigid_body(), &pieces.map_err(model_error)?)
            .and_then(|robot| if lumped.is_empty() { Ok(robot) } else { robot.with_lumped(&lumped) })
            .map_err(model_error)?;
        Ok(Self::of(robot, bounds))
    }

    /// The paper's leg (`uwml_core::presets::paper_leg`: Table II, Cd 2.2 and Cm 0.5), its joints
    /// unbounded for the one-state path (`uwml.Leg.paper` builds its robot from these `parts`).
    #[staticmethod]
    fn paper_leg() -> PyResult<Self> {
        let robot = presets::paper_leg::<f64>().to_capacity().map_err(model_error)?;
        Ok(Self::of(robot, vec![[f64::INFINITY; 3]; 3]))
    }

    /// The validated parts (axes and normals as the core made them exact): `(joints, links, base,
    /// segments)`, each joint `(parent, kind, origin, axis)` (`parent` -1 for the base), each link
    /// and the base `(mass, com, volume, cob)`, each segment `(owner, start, axis, length, area,
    /// section, normals, widths, diameter, cd, cm, cd_axial, axial_area)` (`owner` -1 for the
    /// base; `normals`, `widths` None for a circular section, `diameter` None for a rectangular
    /// one). The lumped models are not among them.
    fn parts<'py>(&self, py: Python<'py>) -> PyResult<RobotParts<'py>> {
        robot_parts(py, &self.robot)
    }

    /// World positions `(n_samples, 3)` and geometric Jacobians `(n_samples, 6, N)` (rows 0-2
    /// linear, 3-5 angular; zero columns for the joints that do not carry the link) of `point`,
    /// given in link `link`'s frame, at the joint positions `q` `(n_samples, N)`, the base fixed
    /// and upright (`uwml_core::forward_kinematics`, `point_jacobian`).
    fn point_jacobian<'py>(
        &self,
        py: Python<'py>,
        q: PyReadonlyArray2<'py, f64>,
        link: i64,
        point: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<(Array2<'py>, Bound<'py, numpy::PyArray<f64, numpy::Ix3>>)> {
        let n = self.robot.joint_count();
        let n_samples = q.shape().first().copied().unwrap_or(0);
        if q.shape().get(1) != Some(&n) {
            return Err(PyValueError::new_err(format!("q must have shape (n_samples, {n}), got {:?}", q.shape())));
        }
        let link = usize::try_from(link).ok().filter(|&l| l < n).ok_or_else(|| {
            PyValueError::new_err(format!("link must be in 0..{n} (one of the {n} links), got {link}"))
        })?;
        let point = contiguous1(&point, "point", 3)?;
        if !point.iter().all(|v| v.is_finite()) {
            return Err(PyValueError::new_err(format!("point must be finite, got {point:?}")));
        }
        let point = Vector3::from_column_slice(point);
        let q = contiguous(&q, "q")?;
        let robot = &*self.robot;
        let (positions, jacobians) = py.detach(|| kinematics::jacobian_batch(robot, q, link, &point))?;
        Ok((to_numpy(py, positions, (n_samples, 3))?, to_numpy(py, jacobians, (n_samples, 6, n))?))
    }

    /// The identification problem of the joints `joints` in one pass (a leg's fit, docs/model.md
    /// section 4): `(len(joints), n_samples, P + 1)`, each row the regressors of one joint's force
    /// (Cd columns then Cm columns; `per`: "leg" P = 2, "link" P = 2N, "direction" P = 4N,
    /// link-major then direction, each segment's columns given to the link that carries it) and,
    /// last, the target `−delta − buoyancy`; `delta` `(n_samples, N)` is `τ_water − τ_land`. A
    /// fixed base in still water.
    #[allow(clippy::too_many_arguments)]
    fn hydro_design<'py>(
        &self,
        py: Python<'py>,
        q: PyReadonlyArray2<'py, f64>,
        qd: PyReadonlyArray2<'py, f64>,
        qdd: PyReadonlyArray2<'py, f64>,
        delta: PyReadonlyArray2<'py, f64>,
        density: f64,
        gravity: f64,
        joints: Vec<usize>,
        per: &str,
    ) -> PyResult<Bound<'py, numpy::PyArray<f64, numpy::Ix3>>> {
        let n = self.robot.joint_count();
        let per = design::Per::parse(per)?;
        if let Some(bad) = joints.iter().find(|&&j| j >= n) {
            return Err(PyValueError::new_err(format!(
                "joints must be indices in 0..{}, got {bad}",
                n.saturating_sub(1)
            )));
        }
        let n_samples = check_state_shapes([&q, &qd, &qdd], n)?;
        if delta.shape() != q.shape() {
            return Err(PyValueError::new_err(format!(
                "delta must have shape (n_samples, {n}) like q, got {:?} (q: {:?})",
                delta.shape(),
                q.shape()
            )));
        }
        let water = water(density, gravity)?;
        let states = [contiguous(&q, "q")?, contiguous(&qd, "qd")?, contiguous(&qdd, "qdd")?];
        check_states(&[("q", states[0]), ("qd", states[1]), ("qdd", states[2])], n)?;
        let delta = contiguous(&delta, "delta")?;
        if let Some(index) = delta.iter().position(|v| !v.is_finite()) {
            let value = delta.get(index).copied().unwrap_or(f64::NAN);
            let (sample, joint) = (index / n.max(1), index % n.max(1));
            return Err(NonFinite { argument: "delta", sample, joint, value }.into());
        }
        let robot = &**self.lanes.get_or_init(|| Box::new(self.robot.splat()));
        let design = py.detach(|| design::design(robot, &water, states, delta, &joints, per));
        to_numpy(py, design, (joints.len(), n_samples, per.columns(n) + 1))
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
    #[pyo3(signature = (q, qd, qdd, cd, cm, density, gravity, orientation, velocity, angular_velocity, acceleration, angular_acceleration, current, current_acceleration, threads, body_wrenches, losses=None, pressure=None, temperature=None, kirchhoff=false))]
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
        losses: Option<PyRef<'py, PyLosses>>,
        pressure: Option<PyReadonlyArray1<'py, f64>>,
        temperature: Option<PyReadonlyArray1<'py, f64>>,
        kirchhoff: bool,
    ) -> PyResult<Vec<Array2<'py>>> {
        let form = added_mass_form(kirchhoff);
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
        let robot = &**self.lanes.get_or_init(|| Box::new(self.robot.splat()));
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
        let shared = &self.lane_data;
        let result = py.detach(|| {
            if threads <= 1 {
                let mut kept = shared.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
                let data = kept.get_or_insert_with(|| Box::new(LaneData::new()));
                hydro_range(
                    robot,
                    &water,
                    coefficients,
                    form,
                    &surroundings,
                    states,
                    losses,
                    &(0..n_samples),
                    data,
                    out,
                )
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
                        let mut data = Box::new(LaneData::new());
                        hydro_range(
                            robot,
                            &water,
                            coefficients,
                            form,
                            &surroundings,
                            states,
                            losses,
                            range,
                            &mut data,
                            out,
                        )
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
    /// segments' own) or finite non-negative numbers, one for all, or one per segment (per link
    /// with `per_link`, each segment taking its link's) or per segment and direction, as lists,
    /// tuples or float64 arrays; `motion` None (a fixed, upright base) or
    /// the five 1-D arrays of a `uwml.BaseMotion`; `current`, `current_acceleration` like the
    /// states, of 3. Returns a `result_type` (`uwml.RobotTorques`) with a `base_type`
    /// (`uwml.BaseWrench`), the same bits as the batch path; or `None` when any argument is of
    /// another kind or fails a check (the general path then answers, with its errors).
    #[allow(clippy::too_many_arguments)]
    #[pyo3(signature = (result_type, base_type, q, qd, qdd, cd, cm, density, gravity, motion, current, current_acceleration, threads, kirchhoff=false, per_link=false))]
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
        kirchhoff: bool,
        per_link: bool,
    ) -> PyResult<Option<Bound<'py, PyAny>>> {
        let arguments = [q, qd, qdd, cd, cm, density, gravity, motion, current, current_acceleration, threads];
        let mut table = self.coefficient_workspace();
        let Some(one) = OneState::read(&self.robot, &self.bounds, layout(per_link), arguments, &mut table) else {
            return Ok(None);
        };
        let mut data = self.one_state_workspace();
        one.evaluate(&self.robot, added_mass_form(kirchhoff), &mut data, &table);
        if !one::answered(&data, &self.bounds, None) {
            return Ok(None); // forces that overflow: the general path names the sample
        }
        one_result(result_type, base_type, &data, None).map(Some)
    }

    /// [`PyRobot::hydro_one`] with the joint losses of `Robot.environment`: `depth` ≥ 0,
    /// `temperature`, `sea_density` > 0 numbers, `losses` None or a `Losses` of `N` joints;
    /// a `result_type` (`uwml.RobotEnvironment`) or `None`, as there.
    #[allow(clippy::too_many_arguments)]
    #[pyo3(signature = (result_type, base_type, q, qd, qdd, depth, temperature, losses, cd, cm, density, gravity, sea_density, motion, current, current_acceleration, threads, kirchhoff=false, per_link=false))]
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
        kirchhoff: bool,
        per_link: bool,
    ) -> PyResult<Option<Bound<'py, PyAny>>> {
        let n = self.robot.joint_count();
        let arguments = [q, qd, qdd, cd, cm, density, gravity, motion, current, current_acceleration, threads];
        let mut table = self.coefficient_workspace();
        let (Some(one), Some(depth), Some(temperature), Some(sea_density)) = (
            OneState::read(&self.robot, &self.bounds, layout(per_link), arguments, &mut table),
            finite_number(depth),
            finite_number(temperature),
            finite_number(sea_density),
        ) else {
            return Ok(None);
        };
        if !crate::usual_conditions(depth, temperature, sea_density, sea_density * one.water.gravity() * depth) {
            return Ok(None);
        }
        let compiled = if losses.is_none() {
            None
        } else {
            let Ok(compiled) = losses.cast::<PyLosses>() else { return Ok(None) };
            Some(compiled)
        };
        let parsed = match &compiled {
            Some(compiled) => match parse_losses(compiled.get(), n) {
                Ok(parsed) => parsed,
                Err(_) => return Ok(None),
            },
            None => &[],
        };
        let mut data = self.one_state_workspace();
        one.evaluate(&self.robot, added_mass_form(kirchhoff), &mut data, &table);
        // The batch path's pressure and loss states (the same operations), so that the bits are
        // its; the robot's joints only.
        let pressure = sea_density * one.water.gravity() * depth;
        let (mut visc, mut seal, mut loss_current) =
            ([0.0; MAX_ROBOT_JOINTS], [0.0; MAX_ROBOT_JOINTS], [0.0; MAX_ROBOT_JOINTS]);
        let states = parsed.iter().map(|losses| losses.and_then(|l| l.at(pressure, temperature).ok()));
        write_joint_losses(states, &one.row.qd, [&mut visc, &mut seal, &mut loss_current], 0);
        let losses = [&visc, &seal, &loss_current].map(|v| v.as_slice());
        if !one::answered(&data, &self.bounds, Some(losses)) {
            return Ok(None);
        }
        one_result(result_type, base_type, &data, Some(losses)).map(Some)
    }

    /// Regressors: buoyancy, gravity (`(n_samples, N)`), base buoyancy, base gravity
    /// (`(n_samples, 6)`), drag and added mass (`(n_samples, (6 + N)·2S)`: rows base then joints,
    /// columns segment and direction).
    #[allow(clippy::too_many_arguments)]
    #[pyo3(signature = (q, qd, qdd, density, gravity, orientation, velocity, angular_velocity, acceleration, angular_acceleration, current, current_acceleration, threads, kirchhoff=false))]
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
        kirchhoff: bool,
    ) -> PyResult<Vec<Array2<'py>>> {
        let form = added_mass_form(kirchhoff);
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
        let width = (6 + n) * self.robot.regressor_column_count();
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
                    regressor_range(robot, &water, form, &surroundings, states, range, &mut data, out)
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
    #[pyo3(signature = (q, qd, qdd, cd, cm, density, gravity, orientation, velocity, angular_velocity, acceleration, angular_acceleration, current, current_acceleration, losses, pressure, temperature, kirchhoff=false))]
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
        losses: PyRef<'py, PyLosses>,
        pressure: PyReadonlyArray1<'py, f64>,
        temperature: PyReadonlyArray1<'py, f64>,
        kirchhoff: bool,
    ) -> PyResult<Vec<Array2<'py>>> {
        let form = added_mass_form(kirchhoff);
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
        let shared = &self.jacobian_data;
        let result = py.detach(|| -> Result<(), SampleError> {
            // Locked only while detached: a thread that waits for the workspace holds no GIL
            // that the thread holding the workspace needs to return (no deadlock).
            let mut work = shared.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
            let work = work.get_or_insert_with(|| Box::new(RobotJacobianData::new(robot)));
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
                let conditions = Conditions {
                    water,
                    motion,
                    current,
                    coefficients: coefficients.as_ref(),
                    form,
                    losses: Some(loss_states.at(&losses, sample)),
                };
                robot_jacobians(robot, &conditions, [&row.q, &row.qd, &row.qdd], work, out);
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
        py.detach(|| {
            let mut qs = [0.0; MAX_ROBOT_JOINTS];
            for (row, matrix) in values.chunks_exact(n.max(1)).zip(out.chunks_exact_mut(size)) {
                for (slot, x) in qs.iter_mut().zip(row) {
                    *slot = *x;
                }
                robot_added_mass_matrix(robot, &water, coefficients.as_ref(), &qs, matrix);
            }
        });
        drop(guards);
        Ok(matrices)
    }
}

impl PyRobot {
    /// The binding of a validated robot whose joints have the plausible `bounds`.
    fn of(robot: Model, bounds: Vec<one::Bounds>) -> Self {
        Self {
            coefficient_table: Mutex::new(Box::new(robot.coefficients())),
            robot: Box::new(robot),
            bounds,
            data: Mutex::new(Box::new(Data::new())),
            lanes: OnceLock::new(),
            lane_data: Mutex::new(None),
            jacobian_data: Mutex::new(None),
        }
    }

    /// The kept workspace for a one-state call made with the GIL held, or a new one if another
    /// thread is using it: a thread holding the GIL never waits for a lock (no deadlock with a
    /// detached batch, none when the result's construction runs Python that calls back in).
    fn one_state_workspace(&self) -> Workspace<'_, Data> {
        Workspace::of(&self.data, || Box::new(Data::new()))
    }

    /// The kept coefficient table, or a new one while another thread holds it.
    fn coefficient_workspace(&self) -> Workspace<'_, Coefficients> {
        Workspace::of(&self.coefficient_table, || Box::new(self.robot.coefficients()))
    }

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

/// How a one-state call's coefficient arrays are laid out.
fn layout(per_link: bool) -> Layout {
    if per_link { Layout::Links } else { Layout::Segments }
}
