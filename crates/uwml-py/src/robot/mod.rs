//! `uwml._core.Robot`: a whole robot (tree, base body, segments of any section) in moving water.
//! Thin: every evaluation takes the joint states and one `Conditions` (`conditions.rs`), reads
//! the states once (`states.rs`), loops over the samples in one loop (`evaluate.rs`: one state
//! alone, a batch four per evaluation with the GIL released, optionally on several threads) and
//! returns the Python package's result objects (`results.rs`).

use std::ops::Range;
use std::sync::{Mutex, OnceLock};

use numpy::{
    PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArray, PyUntypedArrayMethods,
};
use pyo3::exceptions::PyValueError;
use pyo3::intern;
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use uwml_core::nalgebra::Vector3;
use uwml_core::{Owner, Robot, RobotData, RobotJacobianData, SegmentCoefficients, presets, robot_added_mass_matrix};

mod conditions;
mod coupling;
mod derived;
mod design;
mod evaluate;
mod inputs;
mod kinematics;
mod one_state;
mod prescribed;
mod results;
mod rk4;
mod states;
mod view;

use crate::arrays::{Lanes, general};
use crate::parts::{BodySpec, JointSpec, RobotParts, SegmentSpec, robot_parts};
use crate::{NonFinite, contiguous, contiguous1, in_parallel, model_error, to_numpy};
pub(crate) use conditions::PyConditions;
pub(crate) use coupling::MujocoCoupling;
use evaluate::{OUTPUTS, Overflow, Setting, hydro_range};
use one_state::split;
use states::{Bounds, Read};

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
type LaneCoefficients = SegmentCoefficients<Lanes, MAX_SEGMENTS>;
/// A float64 numpy array of dimension `D`.
type Array<'py, D> = Bound<'py, numpy::PyArray<f64, D>>;

/// A whole robot (validated, immutable): `Robot(joints, links, base, segments)` from packed
/// arrays (see `uwml.Robot`).
#[pyclass(frozen, module = "uwml._core", name = "Robot")]
pub(crate) struct PyRobot {
    robot: Box<Model>,
    /// Each joint's plausible bounds (`uwml.plausibility.JointBounds.rows`): one plain state
    /// beyond them is left to the Python package, which checks it and warns.
    bounds: Vec<Bounds>,
    /// A workspace kept for one-thread calls, so that they do not set up a new one.
    data: Mutex<Box<Data>>,
    /// The robot over SIMD lanes, made at the first batch.
    lanes: OnceLock<Box<LaneModel>>,
    /// A lane workspace kept for one-thread batches.
    lane_data: Mutex<Option<Box<LaneData>>>,
    /// The derivatives' workspace (the robot over dual numbers), made at the first call.
    jacobian_data: Mutex<Option<Box<RobotJacobianData<f64, MAX_ROBOT_JOINTS, MAX_SEGMENTS, MAX_LUMPED_BODIES>>>>,
    /// The joint losses of one state's `hydro`: zeros, one read-only array made once.
    no_losses: PyOnceLock<Py<PyAny>>,
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
        bounds: Vec<Bounds>,
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
    /// unbounded (`uwml.paper_leg` builds its robot from these `parts`).
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
    ) -> PyResult<(Array<'py, numpy::Ix2>, Array<'py, numpy::Ix3>)> {
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

    /// The identification problem of the joints `joints` in one pass (docs/model.md section 4):
    /// `(len(joints), n_samples, P + 1)`, each row the regressors of one joint's force (Cd
    /// columns then Cm columns; `per`: "leg" P = 2, "link" P = 2N, "direction" P = 4N,
    /// link-major then direction, each segment's columns given to the link that carries it) and,
    /// last, the target `−delta − buoyancy`; `delta` `(n_samples, N)` is `τ_water − τ_land`. A
    /// fixed base in still water of `conditions`.
    #[allow(clippy::too_many_arguments)]
    fn hydro_design<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        qd: &Bound<'py, PyAny>,
        qdd: &Bound<'py, PyAny>,
        delta: PyReadonlyArray2<'py, f64>,
        conditions: PyRef<'py, PyConditions>,
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
        let read = Read::arrays([q, qd, qdd], n)?;
        let n_samples = read.rows().unwrap_or(1);
        if delta.shape() != [n_samples, n] {
            return Err(PyValueError::new_err(format!(
                "delta must have shape (n_samples, {n}) like q, got {:?}",
                delta.shape(),
            )));
        }
        let delta = contiguous(&delta, "delta")?;
        if let Some(index) = delta.iter().position(|v| !v.is_finite()) {
            let value = delta.get(index).copied().unwrap_or(f64::NAN);
            let (sample, joint) = (index / n.max(1), index % n.max(1));
            return Err(NonFinite { argument: "delta", sample, joint, value }.into());
        }
        let robot = &**self.lanes.get_or_init(|| Box::new(self.robot.splat()));
        let states = read.states(n);
        let water = conditions.water;
        let design = py.detach(|| design::design(robot, &water, &states, delta, &joints, per));
        to_numpy(py, design, (joints.len(), n_samples, per.columns(n) + 1))
    }

    /// Number of joints.
    #[getter]
    fn n_joints(&self) -> usize {
        self.robot.joint_count()
    }

    /// Drag, added mass, buoyancy and gravity on every joint and, with `base`, on the base: a
    /// `uwml.Torques` (its `base` a `uwml.BaseWrench`), for the joint states `q`, `qd`, `qdd` in
    /// `conditions` (a `Conditions` made for this robot). Unless `checked`, the states are one
    /// state as plain objects (lists or tuples of numbers, or 1-D float64 arrays) within the
    /// joints' bounds, or the answer is `None` (the Python package then checks them and calls
    /// again, `checked`, with float64 arrays `(N,)` or `(n_samples, N)`).
    #[pyo3(signature = (q, qd, qdd, conditions, threads = 1, base = false, checked = false))]
    #[allow(clippy::too_many_arguments)]
    fn hydro<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        qd: &Bound<'py, PyAny>,
        qdd: &Bound<'py, PyAny>,
        conditions: PyRef<'py, PyConditions>,
        threads: usize,
        base: bool,
        checked: bool,
    ) -> PyResult<Option<Bound<'py, PyAny>>> {
        let wanted = Wanted { joints: true, base, wrenches: false, losses: false };
        self.torques(py, [q, qd, qdd], &conditions, threads, wanted, checked)
    }

    /// [`PyRobot::hydro`] with the joint losses of `conditions` (`visc`, `seal`, `current`).
    #[pyo3(signature = (q, qd, qdd, conditions, threads = 1, base = false, checked = false))]
    #[allow(clippy::too_many_arguments)]
    fn environment<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        qd: &Bound<'py, PyAny>,
        qdd: &Bound<'py, PyAny>,
        conditions: PyRef<'py, PyConditions>,
        threads: usize,
        base: bool,
        checked: bool,
    ) -> PyResult<Option<Bound<'py, PyAny>>> {
        let wanted = Wanted { joints: true, base, wrenches: false, losses: true };
        self.torques(py, [q, qd, qdd], &conditions, threads, wanted, checked)
    }

    /// `hydro` (or, with `losses`, `environment`) of one plain state into `workspace`, a
    /// `uwml.Workspace`'s float64 array of `7 N + 24` values (the joints' drag, added mass,
    /// buoyancy, gravity, oil drag, seal friction and loss current, `N` each, then the base's
    /// drag, added mass, buoyancy and gravity, 6 each), the base's part evaluated where `base`
    /// (zeros otherwise, as the losses' part without `losses`): True, or False for what the
    /// Python package evaluates the general way (states not plain or beyond the joints' bounds,
    /// forces beyond a joint's effort bound, conditions with a sample axis).
    #[allow(clippy::too_many_arguments)]
    fn evaluate_into(
        &self,
        q: &Bound<'_, PyAny>,
        qd: &Bound<'_, PyAny>,
        qdd: &Bound<'_, PyAny>,
        conditions: PyRef<'_, PyConditions>,
        base: bool,
        losses: bool,
        workspace: &Bound<'_, PyArray1<f64>>,
    ) -> PyResult<bool> {
        self.evaluate_into_array([q, qd, qdd], &conditions, base, losses, workspace)
    }

    /// Every body's world wrench about its centre of mass, `(n_samples, N + 1, 6)` or `(N + 1, 6)`
    /// (base first); the states as float64 arrays.
    #[pyo3(signature = (q, qd, qdd, conditions, *, threads = 1))]
    fn link_wrenches<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        qd: &Bound<'py, PyAny>,
        qdd: &Bound<'py, PyAny>,
        conditions: PyRef<'py, PyConditions>,
        threads: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        let n = self.robot.joint_count();
        let read = Read::arrays([q, qd, qdd], n)?;
        let wanted = Wanted { joints: false, base: false, wrenches: true, losses: false };
        let outputs = self.evaluate(py, &read, &conditions, threads, wanted)?;
        let [.., Some(wrenches), _, _, _] = outputs.unwrap_or_default() else {
            return Err(PyValueError::new_err("internal error: no wrenches"));
        };
        let shape: Vec<usize> = wrenches.cast::<PyUntypedArray>()?.shape().to_vec();
        let mut shape = shape.split_last().map_or(vec![], |(_, lead)| lead.to_vec());
        shape.extend([n + 1, 6]);
        wrenches.call_method1(intern!(py, "reshape"), (shape,))
    }

    /// The regressors of the forces (a `uwml.Regressors`; docs/model.md sections 4, 10 and 12)
    /// for float64 arrays of states in `conditions` (its coefficients are not used).
    #[pyo3(signature = (q, qd, qdd, conditions, *, threads = 1))]
    fn regressors<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        qd: &Bound<'py, PyAny>,
        qdd: &Bound<'py, PyAny>,
        conditions: PyRef<'py, PyConditions>,
        threads: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        conditions.check_robot(&self.robot)?;
        let read = Read::arrays([q, qd, qdd], self.robot.joint_count())?;
        derived::regressors(py, &self.robot, &read, &conditions, threads)
    }

    /// The forces of `environment` on base and joints and their exact derivatives (a
    /// `uwml.Jacobians`), for float64 arrays of states in `conditions`.
    fn jacobians<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        qd: &Bound<'py, PyAny>,
        qdd: &Bound<'py, PyAny>,
        conditions: PyRef<'py, PyConditions>,
    ) -> PyResult<Bound<'py, PyAny>> {
        conditions.check_robot(&self.robot)?;
        let read = Read::arrays([q, qd, qdd], self.robot.joint_count())?;
        let robot = &*self.robot;
        derived::jacobians(py, robot, &self.jacobian_data, &read, &conditions)
    }

    /// The added-mass matrices `(n_samples, 6 + N, 6 + N)` (or one, for `q` of shape `(N,)`;
    /// base first) at the joint positions `q` (a float64 array), with the coefficients (`cm`)
    /// and water of `conditions`.
    fn added_mass_matrix<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        conditions: PyRef<'py, PyConditions>,
    ) -> PyResult<Bound<'py, PyAny>> {
        conditions.check_robot(&self.robot)?;
        let n = self.robot.joint_count();
        let read = Read::arrays([q, q, q], n)?;
        let states = read.states(n);
        let n_samples = conditions.sample_count(read.rows())?;
        let size = (6 + n) * (6 + n);
        let mut out = vec![0.0; n_samples * size];
        let robot = &*self.robot;
        let conditions = &*conditions;
        py.detach(|| {
            let mut row = evaluate::Row::<f64>::new();
            for (sample, matrix) in out.chunks_exact_mut(size).enumerate() {
                row.load(&states, &(sample..sample + 1));
                robot_added_mass_matrix(robot, &conditions.water, conditions.coefficients.as_deref(), &row.q, matrix);
            }
        });
        let lead: &[usize] = if read.rows().is_some() { &[n_samples] } else { &[] };
        derived::shaped(py, out, lead, &[6 + n, 6 + n])
    }
}

impl PyRobot {
    /// The binding of a validated robot whose joints have the plausible `bounds`.
    fn of(robot: Model, bounds: Vec<Bounds>) -> Self {
        Self {
            robot: Box::new(robot),
            bounds,
            data: Mutex::new(Box::new(Data::new())),
            lanes: OnceLock::new(),
            lane_data: Mutex::new(None),
            jacobian_data: Mutex::new(None),
            no_losses: PyOnceLock::new(),
        }
    }

    /// The result object of `hydro` or `environment` (see there): `None` for states not read
    /// (unless `checked`) or, for one plain state, forces beyond a joint's effort bound (the
    /// Python package then warns).
    fn torques<'py>(
        &self,
        py: Python<'py>,
        states: [&Bound<'py, PyAny>; 3],
        conditions: &PyConditions,
        threads: usize,
        wanted: Wanted,
        checked: bool,
    ) -> PyResult<Option<Bound<'py, PyAny>>> {
        let n = self.robot.joint_count();
        let read = if checked {
            Read::arrays(states, n)?
        } else {
            match Read::plain(states, n, &self.bounds) {
                Some(read) => read,
                None => return Ok(None),
            }
        };
        let Some(outputs) = self.evaluate(py, &read, conditions, threads, wanted)? else { return Ok(None) };
        // One state's zeros for the losses not evaluated are the robot's, made once.
        let one_state = read.rows().is_none() && conditions.samples.is_none();
        let no_losses = if one_state && !wanted.losses {
            let zeros = self.no_losses.get_or_try_init(py, || {
                let zeros = PyArray1::<f64>::zeros(py, n, false).into_any();
                zeros.call_method1(intern!(py, "setflags"), (false,))?;
                Ok::<_, PyErr>(zeros.unbind())
            })?;
            Some(zeros.bind(py).clone())
        } else {
            None
        };
        results::torques(py, outputs, no_losses).map(Some)
    }

    /// The outputs `wanted` (see `evaluate::OUTPUTS`; None where not wanted) of the states
    /// `read` in `conditions`: one state evaluated on this thread into arrays of its own shape
    /// (`(width,)`), a batch into `(n_samples, width)` arrays, four states per evaluation, with
    /// the GIL released, on `threads` threads. `None` for one plain state whose forces are
    /// beyond a joint's effort bound.
    fn evaluate<'py>(
        &self,
        py: Python<'py>,
        read: &Read<'py>,
        conditions: &PyConditions,
        threads: usize,
        wanted: Wanted,
    ) -> PyResult<Option<[Option<Bound<'py, PyAny>>; OUTPUTS]>> {
        conditions.check_robot(&self.robot)?;
        if threads == 0 {
            return Err(PyValueError::new_err("threads must be an integer >= 1, got 0"));
        }
        let n = self.robot.joint_count();
        let n_samples = conditions.sample_count(read.rows())?;
        let batched = read.rows().is_some() || conditions.samples.is_some();
        let states = read.states(n);
        let widths = wanted.widths(n);
        let overflow = |e: Overflow| overflow_error(&e, &states, batched);
        if !batched {
            let mut buffer = vec![0.0; widths.iter().sum()];
            let plain = matches!(read, Read::One(_));
            if !self.one_state(states, conditions, split(&mut buffer, widths), plain)? {
                return Ok(None);
            }
            let mut rest = buffer.as_slice();
            return Ok(Some(widths.map(|width| {
                let (values, after) = rest.split_at(width.min(rest.len()));
                rest = after;
                (width > 0).then(|| PyArray1::from_slice(py, values).into_any())
            })));
        }
        let arrays = widths.map(|width| (width > 0).then(|| PyArray2::<f64>::zeros(py, (n_samples, width), false)));
        let mut guards: Vec<_> = arrays.iter().flatten().map(|a| a.readwrite()).collect();
        let mut slices = guards.iter_mut().map(|g| g.as_slice_mut().ok());
        let out: [&mut [f64]; OUTPUTS] =
            arrays.each_ref().map(|a| if a.is_some() { slices.next().flatten().unwrap_or_default() } else { &mut [] });
        let robot = &**self.lanes.get_or_init(|| Box::new(self.robot.splat()));
        let setting = Setting { robot, coefficients: conditions.lane_coefficients(), conditions, states };
        let shared = &self.lane_data;
        let result = py.detach(|| {
            if threads <= 1 {
                let mut kept = shared.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
                let data = kept.get_or_insert_with(|| Box::new(LaneData::new()));
                hydro_range(&setting, &(0..n_samples), data, out)
            } else {
                // Samples are numbered in the whole batch already.
                let part = |range: &Range<usize>, out: [&mut [f64]; OUTPUTS]| {
                    hydro_range(&setting, range, &mut Box::new(LaneData::new()), out)
                };
                in_parallel(n_samples, widths, threads, out, part, |e, _| e)
            }
        });
        drop(guards);
        result.map_err(overflow)?;
        Ok(Some(arrays.map(|a| a.map(Bound::into_any))))
    }
}

/// Which outputs an evaluation writes (see `evaluate::OUTPUTS`).
#[derive(Clone, Copy)]
struct Wanted {
    joints: bool,
    base: bool,
    wrenches: bool,
    losses: bool,
}

impl Wanted {
    /// The width of each output for a robot of `n` joints (0: not wanted).
    fn widths(self, n: usize) -> [usize; OUTPUTS] {
        let [j, b, w, l] = [(self.joints, n), (self.base, 6), (self.wrenches, (n + 1) * 6), (self.losses, n)]
            .map(|(on, w)| if on { w } else { 0 });
        [j, j, j, j, b, b, b, b, w, l, l, l]
    }
}

/// The error of forces that overflow float64 from a finite state.
fn overflow_error(e: &Overflow, states: &evaluate::States<'_>, batched: bool) -> PyErr {
    let (speed, acceleration) = states.largest_rates(e.sample);
    let place = if batched { format!("sample {}", e.sample) } else { "the state".to_owned() };
    PyValueError::new_err(format!(
        "the forces of {place} overflow float64 (joint speeds up to {}, accelerations up to {}; or the base's motion, the current or the coefficients): the inputs are outside the physics' domain",
        general(speed),
        general(acceleration)
    ))
}
