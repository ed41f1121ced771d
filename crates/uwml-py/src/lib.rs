//! `uwml._core`: thin Python bindings of `uwml-core`. All physics lives in the core; this
//! crate converts arrays, dispatches on the number of joints, and loops over samples with the
//! GIL released. The friendly, validated API is the Python package `uwml`.

mod arrays;
mod batch;
mod errors;
mod losses;
mod robot;
mod single;

pub(crate) use arrays::{
    NonFinite, check_conditions, contiguous, contiguous1, in_parallel, to_numpy, writable, zeroed,
};
use batch::*;
pub(crate) use losses::{joint_losses, parse_losses};

use numpy::{PyArray, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use uwml_core::nalgebra::Vector3;
use uwml_core::{Chain, Joint, Link, ModelError, Segment, Water};

/// Largest number of joints a chain built from Python may have.
const MAX_JOINTS: usize = 8;
/// Floats per joint in the packed layout: origin (3), axis (3).
const JOINT_WIDTH: usize = 6;
/// Floats per link in the packed layout: mass, com (3), volume, cob (3), has_segment (0/1),
/// segment start (3), axis (3), length, normals (2×3), widths (2), area.
const LINK_WIDTH: usize = 25;

/// Floats per joint's losses in the packed layout: has_oil (0/1), k_oil, exponent,
/// pressure_sensitivity [1/Pa], temperature_sensitivity [1/K], reference_pressure [Pa],
/// reference_temperature [°C], has_seal (0/1), c0, c1, s0, s1, d0, d1 (per Pa for c1, s1, d1),
/// stribeck_speed, torque_constant, ratio, efficiency, rated_current, epsilon, has_losses (0/1).
const LOSS_WIDTH: usize = 21;

fn model_error(error: ModelError) -> PyErr {
    errors::ModelError::new_err(error.to_string())
}

fn next3(values: &mut impl Iterator<Item = f64>) -> Vector3<f64> {
    let mut next = || values.next().unwrap_or(f64::NAN);
    Vector3::new(next(), next(), next())
}

fn unpack_joint(row: &[f64]) -> Joint<f64> {
    let mut values = row.iter().copied();
    Joint { origin: next3(&mut values), axis: next3(&mut values) }
}

fn unpack_link(row: &[f64]) -> Link<f64> {
    let mut values = row.iter().copied();
    let scalar = |values: &mut std::iter::Copied<std::slice::Iter<'_, f64>>| values.next().unwrap_or(f64::NAN);
    let mass = scalar(&mut values);
    let com = next3(&mut values);
    let volume = scalar(&mut values);
    let cob = next3(&mut values);
    let has_segment = scalar(&mut values) != 0.0;
    let start = next3(&mut values);
    let axis = next3(&mut values);
    let length = scalar(&mut values);
    let normals = [next3(&mut values), next3(&mut values)];
    let widths = [scalar(&mut values), scalar(&mut values)];
    let area = scalar(&mut values);
    let segment = has_segment.then_some(Segment { start, axis, length, normals, widths, area });
    Link { mass, com, volume, cob, segment }
}

fn pack_link(link: &Link<f64>) -> Vec<f64> {
    let mut row = Vec::with_capacity(LINK_WIDTH);
    row.push(link.mass);
    row.extend(link.com.iter());
    row.push(link.volume);
    row.extend(link.cob.iter());
    match &link.segment {
        Some(s) => {
            row.push(1.0);
            row.extend(s.start.iter());
            row.extend(s.axis.iter());
            row.push(s.length);
            row.extend(s.normals.iter().flat_map(|n| n.iter().copied()));
            row.extend(s.widths);
            row.push(s.area);
        }
        None => row.resize(LINK_WIDTH, 0.0),
    }
    row
}

fn build<const N: usize>(joints: &[f64], links: &[f64]) -> Result<Chain<f64, N>, ModelError> {
    let mut joint_array = [Joint { origin: Vector3::zeros(), axis: Vector3::z() }; N];
    for (joint, row) in joint_array.iter_mut().zip(joints.chunks_exact(JOINT_WIDTH)) {
        *joint = unpack_joint(row);
    }
    let empty = Link { mass: 0.0, com: Vector3::zeros(), volume: 0.0, cob: Vector3::zeros(), segment: None };
    let mut link_array = [empty; N];
    for (link, row) in link_array.iter_mut().zip(links.chunks_exact(LINK_WIDTH)) {
        *link = unpack_link(row);
    }
    Chain::new(joint_array, link_array)
}

/// A validated chain with its number of joints known at compile time inside. Built once per
/// `Leg`, so the size difference between variants does not matter.
#[derive(Clone, Copy)]
#[allow(clippy::large_enum_variant)]
enum AnyChain {
    N1(Chain<f64, 1>),
    N2(Chain<f64, 2>),
    N3(Chain<f64, 3>),
    N4(Chain<f64, 4>),
    N5(Chain<f64, 5>),
    N6(Chain<f64, 6>),
    N7(Chain<f64, 7>),
    N8(Chain<f64, 8>),
}

macro_rules! dispatch {
    ($chain:expr, $c:ident => $body:expr) => {
        match $chain {
            AnyChain::N1($c) => $body,
            AnyChain::N2($c) => $body,
            AnyChain::N3($c) => $body,
            AnyChain::N4($c) => $body,
            AnyChain::N5($c) => $body,
            AnyChain::N6($c) => $body,
            AnyChain::N7($c) => $body,
            AnyChain::N8($c) => $body,
        }
    };
}

/// A serial chain of revolute joints (validated, immutable). Build it with `Chain(joints,
/// links)` from packed arrays (see `uwml.Leg`), or `Chain.paper()`.
#[pyclass(frozen, module = "uwml._core", name = "Chain")]
struct PyChain {
    chain: AnyChain,
}

impl PyChain {
    const fn from_chain(chain: AnyChain) -> Self {
        Self { chain }
    }
}

impl PyChain {
    fn n_joints(&self) -> usize {
        dispatch!(&self.chain, c => c.joints().len())
    }

    fn check_states(
        &self,
        q: &PyReadonlyArray2<'_, f64>,
        qd: &PyReadonlyArray2<'_, f64>,
        qdd: &PyReadonlyArray2<'_, f64>,
    ) -> PyResult<usize> {
        let n = self.n_joints();
        let shape = q.shape();
        for (name, array) in [("q", q), ("qd", qd), ("qdd", qdd)] {
            if array.shape() != shape || shape.get(1) != Some(&n) {
                return Err(PyValueError::new_err(format!(
                    "{name} must have shape (n_samples, {n}) like q, got {:?} (q: {:?})",
                    array.shape(),
                    shape
                )));
            }
        }
        Ok(shape.first().copied().unwrap_or(0))
    }
}

/// Loss conditions the one-state paths take: depth from 0 to the deepest ocean, a positive sea
/// density, the pressure in the core's domain and the temperature within the oil model's range.
/// Anything else goes to the general path, which refuses it or warns, naming the argument.
fn usual_conditions(depth: f64, temperature: f64, sea_density: f64, pressure: f64) -> bool {
    let [low, high] = uwml_core::OIL_TEMPERATURE_RANGE_C;
    (0.0..=uwml_core::MAX_DEPTH).contains(&depth)
        && sea_density > 0.0
        && (low..=high).contains(&temperature)
        && uwml_core::check_conditions(pressure, temperature).is_ok()
}

fn water(density: f64, gravity: f64) -> PyResult<Water<f64>> {
    Water::new(density, gravity).map_err(model_error)
}

#[pymethods]
impl PyChain {
    #[new]
    fn new(joints: PyReadonlyArray2<'_, f64>, links: PyReadonlyArray2<'_, f64>) -> PyResult<Self> {
        let n = joints.shape().first().copied().unwrap_or(0);
        if !(1..=MAX_JOINTS).contains(&n) {
            return Err(PyValueError::new_err(format!("a chain must have 1 to {MAX_JOINTS} joints, got {n}")));
        }
        if joints.shape() != [n, JOINT_WIDTH] || links.shape() != [n, LINK_WIDTH] {
            return Err(PyValueError::new_err(format!(
                "packed joints must have shape ({n}, {JOINT_WIDTH}) and links ({n}, {LINK_WIDTH}), got {:?} and {:?}",
                joints.shape(),
                links.shape()
            )));
        }
        let (j, l) = (contiguous(&joints, "joints")?, contiguous(&links, "links")?);
        let chain = match n {
            1 => AnyChain::N1(build(j, l).map_err(model_error)?),
            2 => AnyChain::N2(build(j, l).map_err(model_error)?),
            3 => AnyChain::N3(build(j, l).map_err(model_error)?),
            4 => AnyChain::N4(build(j, l).map_err(model_error)?),
            5 => AnyChain::N5(build(j, l).map_err(model_error)?),
            6 => AnyChain::N6(build(j, l).map_err(model_error)?),
            7 => AnyChain::N7(build(j, l).map_err(model_error)?),
            _ => AnyChain::N8(build(j, l).map_err(model_error)?),
        };
        Ok(Self::from_chain(chain))
    }

    /// The paper's leg (Table II).
    #[staticmethod]
    fn paper() -> Self {
        Self::from_chain(AnyChain::N3(Chain::paper()))
    }

    /// Number of joints.
    #[getter(n_joints)]
    fn py_n_joints(&self) -> usize {
        self.n_joints()
    }

    /// The validated parameters, packed as `(joints (N, 6), links (N, 25))`.
    fn packed<'py>(&self, py: Python<'py>) -> PyResult<(Array2<'py>, Array2<'py>)> {
        let n = self.n_joints();
        let (joints, links): (Vec<f64>, Vec<f64>) = dispatch!(&self.chain, c => (
            c.joints().iter().flat_map(|j| j.origin.iter().chain(j.axis.iter()).copied().collect::<Vec<_>>()).collect(),
            c.links().iter().flat_map(pack_link).collect(),
        ));
        Ok((to_numpy(py, joints, (n, JOINT_WIDTH))?, to_numpy(py, links, (n, LINK_WIDTH))?))
    }

    /// The identification problem of the joints `joints` in one pass: `(len(joints), n_samples,
    /// P + 1)`, each row the regressors of one joint's torque (Cd columns then Cm columns;
    /// `per`: "leg" P = 2, "link" P = 2N, "direction" P = 4N, link-major then direction) and,
    /// last, the target `−delta − buoyancy`; `delta` `(n_samples, N)` is `τ_water − τ_land`.
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
    ) -> PyResult<Bound<'py, PyArray<f64, numpy::Ix3>>> {
        let n = self.n_joints();
        let per = Per::parse(per)?;
        if let Some(bad) = joints.iter().find(|&&j| j >= n) {
            return Err(PyValueError::new_err(format!("joints must be indices in 0..{}, got {bad}", n - 1)));
        }
        let n_samples = self.check_states(&q, &qd, &qdd)?;
        if delta.shape() != q.shape() {
            return Err(PyValueError::new_err(format!(
                "delta must have shape (n_samples, {n}) like q, got {:?} (q: {:?})",
                delta.shape(),
                q.shape()
            )));
        }
        let water = water(density, gravity)?;
        let states = States { q: contiguous(&q, "q")?, qd: contiguous(&qd, "qd")?, qdd: contiguous(&qdd, "qdd")? };
        let delta = contiguous(&delta, "delta")?;
        let chain = self.chain;
        let design = py.detach(|| dispatch!(&chain, c => design_batch(c, &water, &states, delta, &joints, per)))?;
        to_numpy(py, design, (joints.len(), n_samples, per.columns(n) + 1))
    }
    /// World positions `(n_samples, 3)` and geometric Jacobians `(n_samples, 6, N)` (rows 0-2
    /// linear, 3-5 angular; zero columns after `link`) of `point`, given in link `link`'s frame.
    fn point_jacobian<'py>(
        &self,
        py: Python<'py>,
        q: PyReadonlyArray2<'py, f64>,
        link: i64,
        point: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<(Array2<'py>, Bound<'py, PyArray<f64, numpy::Ix3>>)> {
        let n = self.n_joints();
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
        let chain = self.chain;
        let (positions, jacobians) = py.detach(|| dispatch!(&chain, c => jacobian_batch(c, q, link, &point)))?;
        Ok((to_numpy(py, positions, (n_samples, 3))?, to_numpy(py, jacobians, (n_samples, 6, n))?))
    }
}

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyChain>()?;
    m.add_class::<robot::PyRobot>()?;
    m.add_class::<robot::MujocoCoupling>()?;
    m.add("MAX_ROBOT_JOINTS", robot::MAX_ROBOT_JOINTS)?;
    m.add("MAX_DEPTH", uwml_core::MAX_DEPTH)?;
    m.add("MAX_PRESSURE", uwml_core::MAX_PRESSURE)?;
    m.add("MAX_LENGTH", uwml_core::MAX_LENGTH)?;
    m.add("MAX_MASS", uwml_core::MAX_MASS)?;
    m.add("MAX_VOLUME", uwml_core::MAX_VOLUME)?;
    m.add("MAX_AREA", uwml_core::MAX_AREA)?;
    m.add("MAX_COEFFICIENT", uwml_core::MAX_COEFFICIENT)?;
    m.add("MAX_DENSITY", uwml_core::MAX_DENSITY)?;
    m.add("MAX_GRAVITY", uwml_core::MAX_GRAVITY)?;
    m.add("ABSOLUTE_ZERO_C", uwml_core::ABSOLUTE_ZERO_C)?;
    m.add("OIL_TEMPERATURE_RANGE_C", (uwml_core::OIL_TEMPERATURE_RANGE_C[0], uwml_core::OIL_TEMPERATURE_RANGE_C[1]))?;
    m.add("MAX_SEGMENTS", robot::MAX_SEGMENTS)?;
    m.add("TREE_JOINT_WIDTH", robot::TREE_JOINT_WIDTH)?;
    m.add("BODY_WIDTH", robot::BODY_WIDTH)?;
    m.add("SEGMENT_WIDTH", robot::SEGMENT_WIDTH)?;
    m.add_function(wrap_pyfunction!(joint_losses, m)?)?;
    m.add("LOSS_WIDTH", LOSS_WIDTH)?;
    m.add("UwmlError", m.py().get_type::<errors::UwmlError>())?;
    m.add("ModelError", m.py().get_type::<errors::ModelError>())?;
    m.add("MAX_JOINTS", MAX_JOINTS)?;
    m.add("JOINT_WIDTH", JOINT_WIDTH)?;
    m.add("LINK_WIDTH", LINK_WIDTH)?;
    Ok(())
}
