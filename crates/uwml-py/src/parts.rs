//! The model's parts as the Python package hands them over: its own `uwml.Joint`, `uwml.Link`
//! and `uwml.Segment` objects (validated dataclasses), read attribute by attribute into the
//! core's types. No packed rows: the names are the dataclasses' fields.

use pyo3::prelude::*;
use pyo3::types::PyTuple;
use uwml_core::nalgebra::{Matrix3, Matrix6, Vector3};
use uwml_core::{
    JointKind, LumpedBody, ModelError, Owner, Problem, RigidBody, Robot, RobotSegment, Section, TreeJoint,
};

/// A `uwml.Joint` of a robot, its parent resolved (`-1`: the base).
#[derive(FromPyObject)]
pub(crate) struct JointSpec {
    parent: i64,
    kind: String,
    origin: [f64; 3],
    axis: [f64; 3],
}

/// A `uwml.Link` (or a robot's base) as a rigid body: its segments are read separately.
#[derive(FromPyObject)]
pub(crate) struct BodySpec {
    mass: f64,
    com: [f64; 3],
    volume: f64,
    cob: [f64; 3],
    lumped: Option<LumpedSpec>,
}

/// A `uwml.LumpedModel` (its reference point resolved by the `uwml.Link` that carries it).
#[derive(FromPyObject)]
pub(crate) struct LumpedSpec {
    point: [f64; 3],
    axes: [[f64; 3]; 3],
    added_mass: [[f64; 6]; 6],
    linear_damping: [[f64; 6]; 6],
    quadratic_damping: [f64; 6],
}

/// A `uwml.Segment`.
#[derive(FromPyObject)]
pub(crate) struct SegmentSpec {
    start: [f64; 3],
    axis: [f64; 3],
    length: f64,
    area: f64,
    section: String,
    normals: ([f64; 3], [f64; 3]),
    widths: (f64, f64),
    diameter: Option<f64>,
    cd: (f64, f64),
    cm: (f64, f64),
    cd_axial: f64,
    axial_area: f64,
}

/// A body index from Python: `-1` for the base, else a link's (checked against the joints by the
/// core).
fn owner_index(value: i64, field: &'static str, index: usize) -> Result<Option<usize>, ModelError> {
    if value == -1 {
        return Ok(None);
    }
    usize::try_from(value).map(Some).map_err(|_| ModelError { field, index: Some(index), problem: Problem::OutOfRange })
}

impl JointSpec {
    /// The core's joint `index`.
    pub(crate) fn tree_joint(&self, index: usize) -> Result<TreeJoint<f64>, ModelError> {
        let kind = match self.kind.as_str() {
            "revolute" => JointKind::Revolute,
            "prismatic" => JointKind::Prismatic,
            _ => return Err(ModelError { field: "joint.kind", index: Some(index), problem: Problem::OutOfRange }),
        };
        Ok(TreeJoint {
            parent: owner_index(self.parent, "joint.parent", index)?,
            kind,
            origin: self.origin.into(),
            axis: self.axis.into(),
        })
    }
}

impl BodySpec {
    pub(crate) fn rigid_body(&self) -> RigidBody<f64> {
        RigidBody { mass: self.mass, com: self.com.into(), volume: self.volume, cob: self.cob.into() }
    }

    /// The core's lumped model of this body, carried by `owner`, if it has one.
    pub(crate) fn lumped_body(&self, owner: Owner) -> Option<LumpedBody<f64>> {
        let spec = self.lumped.as_ref()?;
        let matrix = |rows: &[[f64; 6]; 6]| {
            Matrix6::from_fn(|r, c| rows.get(r).and_then(|row| row.get(c)).copied().unwrap_or(0.0))
        };
        Some(LumpedBody {
            owner,
            point: spec.point.into(),
            axes: Matrix3::from_fn(|r, c| spec.axes.get(r).and_then(|row| row.get(c)).copied().unwrap_or(0.0)),
            added_mass: matrix(&spec.added_mass),
            linear_damping: matrix(&spec.linear_damping),
            quadratic_damping: spec.quadratic_damping,
        })
    }
}

impl SegmentSpec {
    /// The core's segment `index`, carried by body `owner` (`-1`: the base).
    pub(crate) fn robot_segment(&self, owner: i64, index: usize) -> Result<RobotSegment<f64>, ModelError> {
        let section = match self.section.as_str() {
            "rectangular" => Section::Rectangular {
                normals: [self.normals.0.into(), self.normals.1.into()],
                widths: [self.widths.0, self.widths.1],
            },
            "circular" => Section::Circular { diameter: self.diameter.unwrap_or(f64::NAN) },
            _ => return Err(ModelError { field: "segment.section", index: Some(index), problem: Problem::OutOfRange }),
        };
        Ok(RobotSegment {
            owner: owner_index(owner, "segment.owner", index)?.map_or(Owner::Base, Owner::Link),
            start: self.start.into(),
            axis: self.axis.into(),
            length: self.length,
            area: self.area,
            section,
            cd: [self.cd.0, self.cd.1],
            cm: [self.cm.0, self.cm.1],
            cd_axial: self.cd_axial,
            axial_area: self.axial_area,
        })
    }
}

/// `v` as a Python tuple of three floats.
fn triple<'py>(py: Python<'py>, v: &Vector3<f64>) -> PyResult<Bound<'py, PyTuple>> {
    PyTuple::new(py, [v.x, v.y, v.z])
}

/// A robot's validated parts as Python tuples (`uwml._core.Robot.parts`): its joints as `(parent,
/// kind, origin, axis)` (`parent` -1 for the base), its links and its base as `(mass, com, volume,
/// cob)`, its segments as `(owner, start, axis, length, area, section, normals, widths, diameter,
/// cd, cm, cd_axial, axial_area)` (`owner` -1 for the base; `normals` and `widths` None for a
/// circular section, `diameter` None for a rectangular one).
pub(crate) type RobotParts<'py> =
    (Vec<Bound<'py, PyTuple>>, Vec<Bound<'py, PyTuple>>, Bound<'py, PyTuple>, Vec<Bound<'py, PyTuple>>);

/// A body index as Python has it: -1 for the base.
fn python_index(index: Option<usize>) -> i64 {
    index.and_then(|i| i64::try_from(i).ok()).unwrap_or(-1)
}

/// The validated parts of `robot` (see [`RobotParts`]).
pub(crate) fn robot_parts<'py, const J: usize, const S: usize, const B: usize>(
    py: Python<'py>,
    robot: &Robot<f64, J, S, B>,
) -> PyResult<RobotParts<'py>> {
    let body = |b: &RigidBody<f64>| -> PyResult<Bound<'py, PyTuple>> {
        let items: [Bound<'py, PyAny>; 4] = [
            b.mass.into_pyobject(py)?.into_any(),
            triple(py, &b.com)?.into_any(),
            b.volume.into_pyobject(py)?.into_any(),
            triple(py, &b.cob)?.into_any(),
        ];
        PyTuple::new(py, items)
    };
    let joints = robot
        .joints()
        .iter()
        .map(|j| {
            let kind = match j.kind {
                JointKind::Revolute => "revolute",
                JointKind::Prismatic => "prismatic",
            };
            let items: [Bound<'py, PyAny>; 4] = [
                python_index(j.parent).into_pyobject(py)?.into_any(),
                kind.into_pyobject(py)?.into_any(),
                triple(py, &j.origin)?.into_any(),
                triple(py, &j.axis)?.into_any(),
            ];
            PyTuple::new(py, items)
        })
        .collect::<PyResult<Vec<_>>>()?;
    let links = robot.links().iter().map(body).collect::<PyResult<Vec<_>>>()?;
    let segments = robot
        .segments()
        .iter()
        .map(|s| {
            let owner = match s.owner {
                Owner::Base => -1,
                Owner::Link(i) => python_index(Some(i)),
            };
            let none = || py.None().into_bound(py);
            let (section, normals, widths, diameter) = match s.section {
                Section::Rectangular { normals, widths } => (
                    "rectangular",
                    PyTuple::new(py, [triple(py, &normals[0])?, triple(py, &normals[1])?])?.into_any(),
                    PyTuple::new(py, widths)?.into_any(),
                    none(),
                ),
                Section::Circular { diameter } => ("circular", none(), none(), diameter.into_pyobject(py)?.into_any()),
            };
            let items: [Bound<'py, PyAny>; 13] = [
                owner.into_pyobject(py)?.into_any(),
                triple(py, &s.start)?.into_any(),
                triple(py, &s.axis)?.into_any(),
                s.length.into_pyobject(py)?.into_any(),
                s.area.into_pyobject(py)?.into_any(),
                section.into_pyobject(py)?.into_any(),
                normals,
                widths,
                diameter,
                PyTuple::new(py, s.cd)?.into_any(),
                PyTuple::new(py, s.cm)?.into_any(),
                s.cd_axial.into_pyobject(py)?.into_any(),
                s.axial_area.into_pyobject(py)?.into_any(),
            ];
            PyTuple::new(py, items)
        })
        .collect::<PyResult<Vec<_>>>()?;
    Ok((joints, links, body(robot.base())?, segments))
}
