//! The parts a robot is described by (docs/model.md section 10): its joints (revolute or
//! prismatic, each with a parent), the bodies they move and the base's, and the straight segments
//! of those bodies that meet the water, rectangular or circular, each with its coefficients. Each
//! part is checked on its own here; [`crate::Robot::new`] checks how they fit together.
//!
//! Frames follow URDF without fixed rotations: every link frame is parallel to the base frame
//! when all joint positions are zero. Joint `i` sits at `origin` in its parent's frame (link
//! `parent`, or the base) and moves link `i`: a revolute joint turns it about `axis` by `q[i]`,
//! a prismatic joint slides it along `axis` by `q[i]`. A body's geometry is given in its own
//! frame, whose origin is its joint (the base origin for the base).

use nalgebra::{RealField, SimdRealField, Vector3};

use crate::bounds::{AXIS_TOLERANCE, MAX_AREA, MAX_MASS, MAX_VOLUME};
use crate::check::{
    check_at_most, check_coefficient, check_length, check_non_negative, check_normal, check_point, check_positive,
    check_unit, constant,
};
use crate::error::{ModelError, Problem};

/// How a joint moves its link.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum JointKind {
    /// Turns the link about the axis by `q` [rad]; the generalized force is a torque [N·m].
    #[default]
    Revolute,
    /// Slides the link along the axis by `q` [m]; the generalized force is a force [N].
    Prismatic,
}

/// A joint of a tree: its parent, kind, origin and unit axis in the parent's frame at `q = 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TreeJoint<T: SimdRealField + Copy> {
    /// The parent link (an earlier joint's link), or `None` for the base.
    pub parent: Option<usize>,
    /// Revolute or prismatic.
    pub kind: JointKind,
    /// Position of the joint in the parent frame [m].
    pub origin: Vector3<T>,
    /// Unit axis in the parent frame.
    pub axis: Vector3<T>,
}

/// The bulk of a rigid body: mass and centre of mass, displaced volume and centre of buoyancy,
/// in the body's frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RigidBody<T: SimdRealField + Copy> {
    /// Mass [kg], zero or positive.
    pub mass: T,
    /// Centre of mass [m].
    pub com: Vector3<T>,
    /// Displaced volume [m³], zero or positive.
    pub volume: T,
    /// Centre of buoyancy [m].
    pub cob: Vector3<T>,
}

/// The cross-section of a segment, and how the water's force on it is modelled (docs/model.md
/// section 10, "Describing a robot").
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Section<T: SimdRealField + Copy> {
    /// Independence principle: one drag and one added-mass term per principal normal direction
    /// (`normals`, orthonormal and perpendicular to the axis), with frontal width `widths[k]`
    /// for flow along `normals[k]`: the paper's model.
    Rectangular {
        /// The two principal normal directions, in the body frame.
        normals: [Vector3<T>; 2],
        /// Frontal width for flow along each normal [m], positive.
        widths: [T; 2],
    },
    /// Cross-flow principle: drag `−½ρ Cd D |v⊥| v⊥` on the whole normal velocity and added
    /// mass on the whole normal acceleration; no preferred normal direction.
    Circular {
        /// Diameter `D` [m], positive.
        diameter: T,
    },
}

/// Which body a segment belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Owner {
    /// The base's own body.
    Base,
    /// Link `i` (the link that joint `i` moves).
    Link(usize),
}

/// A straight piece of a body that meets the water (strip theory), in its body's frame, with its
/// own coefficients (used unless an evaluation is given others).
///
/// A slice at arc length `s ∈ [0, length]` lies at `start + s·axis`; `area` is the section area
/// for added mass. `cd` and `cm` are per normal direction for a rectangular section; a circular
/// section uses `cd[0]` and `cm[0]` (construction requires both entries equal).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RobotSegment<T: SimdRealField + Copy> {
    /// The body it belongs to.
    pub owner: Owner,
    /// Start point [m].
    pub start: Vector3<T>,
    /// Unit direction.
    pub axis: Vector3<T>,
    /// Length [m], positive.
    pub length: T,
    /// Cross-section area for added mass [m²], positive.
    pub area: T,
    /// The kind of section and its dimensions.
    pub section: Section<T>,
    /// Drag coefficients, zero or positive.
    pub cd: [T; 2],
    /// Added-mass coefficients, zero or positive.
    pub cm: [T; 2],
    /// Axial drag coefficient (docs/model.md section 12.2), zero or positive: the force
    /// `−½ ρ cd_axial A_axial |u·v| (u·v) u` along the axis, at the midpoint. Zero: none (strips
    /// have no force along their axis).
    pub cd_axial: T,
    /// The axial drag's reference area `A_axial` [m²], zero or positive (a description's default:
    /// the section area).
    pub axial_area: T,
}

impl<T: RealField + Copy> TreeJoint<T> {
    pub(crate) fn validated(self, index: usize) -> Result<Self, ModelError> {
        let i = Some(index);
        if self.parent.is_some_and(|parent| parent >= index) {
            return Err(ModelError::new("joint.parent", i, Problem::OutOfRange));
        }
        Ok(Self {
            origin: check_point(self.origin, "joint.origin", i)?,
            axis: check_unit(self.axis, "joint.axis", i)?,
            ..self
        })
    }
}

impl<T: RealField + Copy> RigidBody<T> {
    /// Validated: link `index`'s body, or the base's (`None`, fields `base.*`).
    pub(crate) fn validated(self, index: Option<usize>) -> Result<Self, ModelError> {
        let [mass, com, volume, cob] = match index {
            Some(_) => ["link.mass", "link.com", "link.volume", "link.cob"],
            None => ["base.mass", "base.com", "base.volume", "base.cob"],
        };
        Ok(Self {
            mass: check_at_most(check_non_negative(self.mass, mass, index)?, MAX_MASS, mass, index)?,
            com: check_point(self.com, com, index)?,
            volume: check_at_most(check_non_negative(self.volume, volume, index)?, MAX_VOLUME, volume, index)?,
            cob: check_point(self.cob, cob, index)?,
        })
    }

    /// A body without mass or volume (the default base).
    #[must_use]
    pub fn empty() -> Self {
        Self { mass: T::zero(), com: Vector3::zeros(), volume: T::zero(), cob: Vector3::zeros() }
    }
}

impl<T: RealField + Copy> RobotSegment<T> {
    /// Validated; normals made exactly orthonormal and perpendicular to the axis (Gram-Schmidt
    /// on the ones given, which must be within [`AXIS_TOLERANCE`] of that).
    pub(crate) fn validated(self, index: usize, joint_count: usize) -> Result<Self, ModelError> {
        let i = Some(index);
        if let Owner::Link(link) = self.owner
            && link >= joint_count
        {
            return Err(ModelError::new("segment.owner", i, Problem::OutOfRange));
        }
        let axis = check_unit(self.axis, "segment.axis", i)?;
        let section = match self.section {
            Section::Rectangular { normals: [n0, n1], widths: [w0, w1] } => {
                let n0 = check_normal(n0, &axis, "segment.normals[0]", i)?;
                let n1 = check_normal(n1, &axis, "segment.normals[1]", i)?;
                if n0.dot(&n1).abs() > constant(AXIS_TOLERANCE) {
                    return Err(ModelError::new("segment.normals[1]", i, Problem::NotPerpendicular));
                }
                // The second normal exactly perpendicular to both, on the side it was given.
                let n1 = axis.cross(&n0) * axis.cross(&n0).dot(&n1).signum();
                Section::Rectangular {
                    normals: [n0, n1],
                    widths: [check_length(w0, "segment.widths[0]", i)?, check_length(w1, "segment.widths[1]", i)?],
                }
            }
            Section::Circular { diameter } => {
                let [cd0, cd1] = self.cd;
                let [cm0, cm1] = self.cm;
                for x in [cd0, cd1] {
                    check_coefficient(x, "segment.cd", i)?;
                }
                for x in [cm0, cm1] {
                    check_coefficient(x, "segment.cm", i)?;
                }
                if cd0 != cd1 {
                    return Err(ModelError::new("segment.cd", i, Problem::OutOfRange));
                }
                if cm0 != cm1 {
                    return Err(ModelError::new("segment.cm", i, Problem::OutOfRange));
                }
                Section::Circular { diameter: check_length(diameter, "segment.diameter", i)? }
            }
        };
        let [cd0, cd1] = self.cd;
        let [cm0, cm1] = self.cm;
        Ok(Self {
            owner: self.owner,
            start: check_point(self.start, "segment.start", i)?,
            axis,
            length: check_length(self.length, "segment.length", i)?,
            area: check_at_most(check_positive(self.area, "segment.area", i)?, MAX_AREA, "segment.area", i)?,
            section,
            cd: [check_coefficient(cd0, "segment.cd", i)?, check_coefficient(cd1, "segment.cd", i)?],
            cm: [check_coefficient(cm0, "segment.cm", i)?, check_coefficient(cm1, "segment.cm", i)?],
            cd_axial: check_coefficient(self.cd_axial, "segment.cd_axial", i)?,
            axial_area: check_at_most(
                check_non_negative(self.axial_area, "segment.axial_area", i)?,
                MAX_AREA,
                "segment.axial_area",
                i,
            )?,
        })
    }
}

impl<T: SimdRealField + Copy> RobotSegment<T> {
    /// Every number mapped by `f` (which must keep values, as `Dual::constant` does).
    pub(crate) fn map_scalars<U: SimdRealField + Copy>(&self, f: impl Fn(T) -> U + Copy) -> RobotSegment<U> {
        RobotSegment {
            owner: self.owner,
            start: self.start.map(f),
            axis: self.axis.map(f),
            length: f(self.length),
            area: f(self.area),
            section: match self.section {
                Section::Rectangular { normals, widths } => {
                    Section::Rectangular { normals: normals.map(|n| n.map(f)), widths: widths.map(f) }
                }
                Section::Circular { diameter } => Section::Circular { diameter: f(diameter) },
            },
            cd: self.cd.map(f),
            cm: self.cm.map(f),
            cd_axial: f(self.cd_axial),
            axial_area: f(self.axial_area),
        }
    }
}

impl<T: SimdRealField + Copy> RigidBody<T> {
    /// Every number mapped by `f`.
    pub(crate) fn map_scalars<U: SimdRealField + Copy>(&self, f: impl Fn(T) -> U + Copy) -> RigidBody<U> {
        RigidBody { mass: f(self.mass), com: self.com.map(f), volume: f(self.volume), cob: self.cob.map(f) }
    }
}
