//! `uwml._core`: thin Python bindings of `uwml-core`. All physics lives in the core; this
//! crate converts arrays and loops over samples with the GIL released. One model, the robot
//! (`uwml._core.Robot`); the friendly, validated API is the Python package `uwml`.

mod arrays;
mod errors;
mod losses;
mod parts;
mod robot;
mod single;

pub(crate) use arrays::{NonFinite, check_conditions, contiguous, contiguous1, in_parallel, to_numpy};
pub(crate) use losses::{PyLosses, joint_losses, parse_losses};

use pyo3::prelude::*;
use uwml_core::{ModelError, Water};

fn model_error(error: ModelError) -> PyErr {
    errors::ModelError::new_err(error.to_string())
}

fn water(density: f64, gravity: f64) -> PyResult<Water<f64>> {
    Water::new(density, gravity).map_err(model_error)
}

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<robot::PyRobot>()?;
    m.add_class::<robot::PyConditions>()?;
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
    Ok(())
}
