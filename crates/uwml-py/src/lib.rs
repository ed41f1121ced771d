//! `uwml._core`: thin Python bindings of `uwml-core`. All physics lives in the core; this
//! crate converts arrays, dispatches on the number of joints, and loops over samples with the
//! GIL released. The friendly, validated API is the Python package `uwml`.

mod arrays;
mod batch;
mod errors;
mod losses;
mod parts;
mod robot;
mod single;

pub(crate) use arrays::{
    NonFinite, check_conditions, contiguous, contiguous1, in_parallel, to_numpy, writable, zeroed,
};
use batch::*;
pub(crate) use losses::{PyLosses, joint_losses, parse_losses};
use parts::{LegJointSpec, LegLinkSpec, joint_tuple, link_tuple};

use numpy::{PyArray, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use uwml_core::nalgebra::Vector3;
use uwml_core::{Chain, Joint, Link, ModelError, Water};

/// Largest number of joints a chain built from Python may have.
const MAX_JOINTS: usize = 8;

fn model_error(error: ModelError) -> PyErr {
    errors::ModelError::new_err(error.to_string())
}

/// The chain of `joints` and `links` (exactly `N` of each: checked by the caller).
fn build<const N: usize>(joints: &[LegJointSpec], links: &[LegLinkSpec]) -> Result<Chain<f64, N>, ModelError> {
    let mut joint_array = [Joint { origin: Vector3::zeros(), axis: Vector3::z() }; N];
    for (joint, spec) in joint_array.iter_mut().zip(joints) {
        *joint = spec.chain_joint();
    }
    let empty = Link { mass: 0.0, com: Vector3::zeros(), volume: 0.0, cob: Vector3::zeros(), segment: None };
    let mut link_array = [empty; N];
    for (link, spec) in link_array.iter_mut().zip(links) {
        *link = spec.chain_link();
    }
    Chain::new(joint_array, link_array)
}

/// A chain's joints and links as Python tuples (`PyChain::parts`).
type Parts<'py> = (Vec<Bound<'py, PyTuple>>, Vec<Bound<'py, PyTuple>>);

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
    /// The chain of a leg's `uwml.Joint`s (their `origin` and `axis`) and `uwml.Link`s (body and
    /// one `segment` or None).
    #[new]
    fn new(joints: Vec<LegJointSpec>, links: Vec<LegLinkSpec>) -> PyResult<Self> {
        let n = joints.len();
        if !(1..=MAX_JOINTS).contains(&n) || links.len() != n {
            return Err(PyValueError::new_err(format!(
                "a chain must have 1 to {MAX_JOINTS} joints and as many links, got {n} and {}",
                links.len()
            )));
        }
        let (j, l) = (joints.as_slice(), links.as_slice());
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

    /// The validated parameters: `(joints, links)`, each joint `(origin, axis)` and each link
    /// `(mass, com, volume, cob, segment)` (`segment` None or `(start, axis, length, normals,
    /// widths, area)`), as `uwml.Leg` rebuilds its `Joint`s and `Link`s.
    fn parts<'py>(&self, py: Python<'py>) -> PyResult<Parts<'py>> {
        dispatch!(&self.chain, c => Ok((
            c.joints().iter().map(|j| joint_tuple(py, j)).collect::<PyResult<Vec<_>>>()?,
            c.links().iter().map(|l| link_tuple(py, l)).collect::<PyResult<Vec<_>>>()?,
        )))
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
    m.add_class::<PyLosses>()?;
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
    m.add("MAX_LUMPED_BODIES", robot::MAX_LUMPED_BODIES)?;
    m.add_function(wrap_pyfunction!(joint_losses, m)?)?;
    m.add("UwmlError", m.py().get_type::<errors::UwmlError>())?;
    m.add("ModelError", m.py().get_type::<errors::ModelError>())?;
    m.add("MAX_JOINTS", MAX_JOINTS)?;
    Ok(())
}
