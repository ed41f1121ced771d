//! The immutable, validated description of a whole robot: a kinematic tree of revolute and
//! prismatic joints on a base that may carry a body of its own, with any number of straight
//! segments per body (up to a fixed capacity), rectangular or circular (docs/model.md section 10).
//!
//! Frames follow URDF without fixed rotations: every link frame is parallel to the base frame
//! when all joint positions are zero. Joint `i` sits at `origin` in its parent's frame (link
//! `parent`, or the base) and moves link `i`: a revolute joint turns it about `axis` by `q[i]`,
//! a prismatic joint slides it along `axis` by `q[i]`. A body's geometry is given in its own
//! frame, whose origin is its joint (the base origin for the base).
//!
//! A [`Robot`] holds up to `J` joints and `S` segments in fixed arrays: it needs no allocation,
//! and its evaluation costs what its actual joints and segments cost, not its capacity.

use nalgebra::{Matrix3, RealField, SimdRealField, Vector3};

use crate::error::{ModelError, Problem};
use crate::frames::{BodyFrames, link_axes};
use crate::lumped::{LUMPED_COLUMNS, Lumped, LumpedBody, LumpedFrame};
use crate::model::{
    AXIS_TOLERANCE, Chain, MAX_AREA, MAX_MASS, MAX_VOLUME, check_at_most, check_coefficient, check_length,
    check_non_negative, check_normal, check_point, check_positive, check_unit, constant,
};
pub use crate::segment_coefficients::SegmentCoefficients;

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

/// A validated robot of up to `J` joints (each moving its own link) and `S` segments.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Robot<T: SimdRealField + Copy, const J: usize, const S: usize, const B: usize = 0> {
    joints: [TreeJoint<T>; J],
    links: [RigidBody<T>; J],
    base: RigidBody<T>,
    segments: [RobotSegment<T>; S],
    joint_count: usize,
    segment_count: usize,
    /// Every body in its own body frame, for the evaluation.
    frames: BodyFrames<T, J, S>,
    /// The bodies' lumped models (docs/model.md section 12.1), in their body frames.
    lumped: Lumped<T, B>,
}

impl<T: RealField + Copy> TreeJoint<T> {
    fn validated(self, index: usize) -> Result<Self, ModelError> {
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
    fn validated(self, index: Option<usize>) -> Result<Self, ModelError> {
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
    fn validated(self, index: usize, joint_count: usize) -> Result<Self, ModelError> {
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

impl<T: RealField + Copy, const J: usize, const S: usize, const B: usize> Robot<T, J, S, B> {
    /// Validates and builds a robot from its joints, the links they move (same length), the
    /// base's own body, and the segments of all bodies.
    ///
    /// # Errors
    /// More joints than `J` or segments than `S` (`"joints"`/`"segments"`, out of range), as many
    /// links as joints; a parent that is not an earlier link (`"joint.parent"`); a segment owned
    /// by a link that does not exist (`"segment.owner"`); a circular segment with different
    /// coefficients per direction; and every check of [`Chain::new`], naming the field and index.
    pub fn new(
        joints: &[TreeJoint<T>],
        links: &[RigidBody<T>],
        base: RigidBody<T>,
        segments: &[RobotSegment<T>],
    ) -> Result<Self, ModelError> {
        if joints.len() > J {
            return Err(ModelError::new("joints", None, Problem::OutOfRange));
        }
        if links.len() != joints.len() {
            return Err(ModelError::new("links", None, Problem::OutOfRange));
        }
        if segments.len() > S {
            return Err(ModelError::new("segments", None, Problem::OutOfRange));
        }
        let mut robot = Self::empty();
        robot.base = base.validated(None)?;
        for (index, ((joint, link), (slot, link_slot))) in
            joints.iter().zip(links).zip(robot.joints.iter_mut().zip(robot.links.iter_mut())).enumerate()
        {
            *slot = joint.validated(index)?;
            *link_slot = link.validated(Some(index))?;
        }
        for (index, (segment, slot)) in segments.iter().zip(robot.segments.iter_mut()).enumerate() {
            *slot = segment.validated(index, joints.len())?;
        }
        robot.joint_count = joints.len();
        robot.segment_count = segments.len();
        Ok(robot.with_frames())
    }

    /// The robot with its body frames computed.
    fn with_frames(self) -> Self {
        Self { frames: BodyFrames::new(self.joints(), self.links(), &self.base, self.segments()), ..self }
    }

    /// No joints, no segments, an empty base.
    fn empty() -> Self {
        let zero = Vector3::zeros();
        let joint = TreeJoint { parent: None, kind: JointKind::Revolute, origin: zero, axis: Vector3::z() };
        let segment = RobotSegment {
            owner: Owner::Base,
            start: zero,
            axis: Vector3::x(),
            length: T::one(),
            area: T::one(),
            section: Section::Circular { diameter: T::one() },
            cd: [T::zero(); 2],
            cm: [T::zero(); 2],
            cd_axial: T::zero(),
            axial_area: T::zero(),
        };
        Self {
            joints: [joint; J],
            links: [RigidBody::empty(); J],
            base: RigidBody::empty(),
            segments: [segment; S],
            joint_count: 0,
            segment_count: 0,
            frames: BodyFrames::new(&[], &[], &RigidBody::empty(), &[]),
            lumped: Lumped::none(),
        }
    }

    /// The robot with lumped models (docs/model.md section 12.1) on some of its bodies, at most
    /// one per body and `B` in all (they replace any it had).
    ///
    /// # Errors
    /// More than `B` models (`"lumped"`, out of range); a model's owner that is not a link of the
    /// robot, or a body given two (`"lumped.owner"`, out of range); and every check of a
    /// [`LumpedBody`]: finite entries at
    /// most [`crate::MAX_LUMPED`] in magnitude, a reference point within [`crate::MAX_LENGTH`], a
    /// symmetric positive semi-definite added-mass matrix, a linear damping whose symmetric part
    /// is positive semi-definite, and non-negative quadratic damping, naming the field and the
    /// model's index in `bodies`.
    pub fn with_lumped(&self, bodies: &[LumpedBody<T>]) -> Result<Self, ModelError> {
        if bodies.len() > B {
            return Err(ModelError::new("lumped", None, Problem::OutOfRange));
        }
        let mut lumped = Lumped::none();
        let link_axes = link_axes::<T, J>(self.joints());
        for (index, body) in bodies.iter().enumerate() {
            let body = body.validated(index, self.joint_count)?;
            let axes = match body.owner {
                Owner::Base => Some(Matrix3::identity()),
                Owner::Link(i) => link_axes.get(i).copied().filter(|_| i < self.joint_count),
            };
            let placed = match axes {
                Some(axes) if !lumped.has(body.owner) => lumped.push(body.owner, LumpedFrame::new(&body, &axes)),
                _ => false,
            };
            if !placed {
                return Err(ModelError::new("lumped.owner", Some(index), Problem::OutOfRange));
            }
        }
        Ok(Self { lumped, ..*self })
    }

    /// The same robot in another capacity: `J2` joints, `S2` segments, `B2` lumped models (a
    /// preset's robot as the C ABI's or the Python package's, which have room for more). Nothing
    /// is validated again; the body frames are derived as [`Robot::new`] derives them.
    ///
    /// # Errors
    /// More joints than `J2` (`"joints"`), segments than `S2` (`"segments"`) or lumped models than
    /// `B2` (`"lumped"`), out of range.
    pub fn to_capacity<const J2: usize, const S2: usize, const B2: usize>(
        &self,
    ) -> Result<Robot<T, J2, S2, B2>, ModelError> {
        if self.joint_count > J2 {
            return Err(ModelError::new("joints", None, Problem::OutOfRange));
        }
        if self.segment_count > S2 {
            return Err(ModelError::new("segments", None, Problem::OutOfRange));
        }
        if self.lumped.len() > B2 {
            return Err(ModelError::new("lumped", None, Problem::OutOfRange));
        }
        let mut robot =
            Robot::<T, J2, S2, B2>::from_valid_parts(self.joints(), self.links(), self.base, self.segments());
        for (owner, model) in self.lumped.iter() {
            robot.lumped.push(*owner, *model);
        }
        Ok(robot)
    }

    /// A robot of parts that are valid (validated, or a preset's), as many as fit.
    pub(crate) fn from_valid_parts(
        joints: &[TreeJoint<T>],
        links: &[RigidBody<T>],
        base: RigidBody<T>,
        segments: &[RobotSegment<T>],
    ) -> Self {
        let mut robot = Self::empty();
        robot.base = base;
        for (slot, joint) in robot.joints.iter_mut().zip(joints) {
            *slot = *joint;
        }
        for (slot, link) in robot.links.iter_mut().zip(links) {
            *slot = *link;
        }
        for (slot, segment) in robot.segments.iter_mut().zip(segments) {
            *slot = *segment;
        }
        robot.joint_count = joints.len().min(links.len()).min(J);
        robot.segment_count = segments.len().min(S);
        robot.with_frames()
    }

    /// A serial chain as a robot on a fixed base without a body of its own: joint `i`'s parent is
    /// link `i − 1`, every joint is revolute, every link's segment (if any) rectangular, with
    /// `coefficients` as its own.
    ///
    /// # Errors
    /// More joints than `J` or links with segments than `S`.
    pub fn from_chain<const N: usize>(
        chain: &Chain<T, N>,
        coefficients: &crate::model::Coefficients<T, N>,
    ) -> Result<Self, ModelError> {
        if N > J {
            return Err(ModelError::new("joints", None, Problem::OutOfRange));
        }
        if chain.links().iter().filter(|link| link.segment.is_some()).count() > S {
            return Err(ModelError::new("segments", None, Problem::OutOfRange));
        }
        Ok(Self::serial(chain.joints(), chain.links(), coefficients))
    }

    /// [`Robot::from_chain`] of valid joints and links, for a robot with room for them (joints
    /// and segments beyond its capacity are left out).
    pub(crate) fn serial<const N: usize>(
        joints: &[crate::model::Joint<T>; N],
        links: &[crate::model::Link<T>; N],
        coefficients: &crate::model::Coefficients<T, N>,
    ) -> Self {
        let mut robot = Self::empty();
        let mut segment_count = 0;
        let mut free = robot.segments.iter_mut();
        let per_link = joints.iter().zip(links).zip(coefficients.cd().iter().zip(coefficients.cm()));
        for (index, ((joint, link), (cd, cm))) in per_link.enumerate().take(J) {
            if let Some(slot) = robot.joints.get_mut(index) {
                *slot = TreeJoint {
                    parent: index.checked_sub(1),
                    kind: JointKind::Revolute,
                    origin: joint.origin,
                    axis: joint.axis,
                };
            }
            if let Some(slot) = robot.links.get_mut(index) {
                *slot = RigidBody { mass: link.mass, com: link.com, volume: link.volume, cob: link.cob };
            }
            if let Some(segment) = &link.segment
                && let Some(slot) = free.next()
            {
                *slot = RobotSegment {
                    owner: Owner::Link(index),
                    start: segment.start,
                    axis: segment.axis,
                    length: segment.length,
                    area: segment.area,
                    section: Section::Rectangular { normals: segment.normals, widths: segment.widths },
                    cd: *cd,
                    cm: *cm,
                    cd_axial: T::zero(),
                    axial_area: T::zero(),
                };
                segment_count += 1;
            }
        }
        robot.joint_count = N.min(J);
        robot.segment_count = segment_count;
        robot.with_frames()
    }
}

impl<T: SimdRealField + Copy, const J: usize, const S: usize, const B: usize> Robot<T, J, S, B> {
    /// The same robot with `table`'s coefficients as its segments' own (segment `k` takes row
    /// `k`); nothing else changes.
    #[must_use]
    pub fn with_coefficients(&self, table: &SegmentCoefficients<T, S>) -> Self {
        let mut robot = *self;
        for ((segment, cd), cm) in robot.segments.iter_mut().zip(table.cd).zip(table.cm) {
            (segment.cd, segment.cm) = (cd, cm);
        }
        robot
    }

    /// Per-link coefficients (`per_link`, validated) as this robot's segment table: each segment
    /// on link `i` takes link `i`'s; a segment on the base, or on a link beyond `per_link`, its
    /// own. A chain's coefficients for its robot ([`crate::Chain::robot`]).
    #[must_use]
    pub fn link_coefficients<const N: usize>(
        &self,
        per_link: &crate::model::Coefficients<T, N>,
    ) -> SegmentCoefficients<T, S> {
        let mut table = SegmentCoefficients { cd: [[T::zero(); 2]; S], cm: [[T::zero(); 2]; S] };
        for ((cd, cm), segment) in table.cd.iter_mut().zip(table.cm.iter_mut()).zip(&self.segments) {
            (*cd, *cm) = match segment.owner {
                Owner::Link(i) => match (per_link.cd().get(i), per_link.cm().get(i)) {
                    (Some(&link_cd), Some(&link_cm)) => (link_cd, link_cm),
                    _ => (segment.cd, segment.cm),
                },
                Owner::Base => (segment.cd, segment.cm),
            };
        }
        table
    }

    /// The joints, as validated.
    pub fn joints(&self) -> &[TreeJoint<T>] {
        self.joints.get(..self.joint_count).unwrap_or(&[])
    }

    /// The links (link `i` is moved by joint `i`), as validated.
    pub fn links(&self) -> &[RigidBody<T>] {
        self.links.get(..self.joint_count).unwrap_or(&[])
    }

    /// The base's own body.
    pub const fn base(&self) -> &RigidBody<T> {
        &self.base
    }

    /// The segments, as validated (normals exactly orthonormal).
    pub fn segments(&self) -> &[RobotSegment<T>] {
        self.segments.get(..self.segment_count).unwrap_or(&[])
    }

    /// The number of joints (and links).
    pub const fn joint_count(&self) -> usize {
        self.joint_count
    }

    /// The segments' own coefficients.
    #[must_use]
    pub fn coefficients(&self) -> SegmentCoefficients<T, S> {
        SegmentCoefficients { cd: self.segments.map(|s| s.cd), cm: self.segments.map(|s| s.cm) }
    }

    /// Every body in its own body frame, for the evaluation.
    pub(crate) const fn frames(&self) -> &BodyFrames<T, J, S> {
        &self.frames
    }

    /// The bodies' lumped models, in their body frames.
    pub(crate) const fn lumped(&self) -> &Lumped<T, B> {
        &self.lumped
    }

    /// The number of columns of the robot's regressors ([`crate::tree::robot_hydro_regressors`]):
    /// `3s + 63l` for `s` segments and `l` lumped models.
    #[must_use]
    pub fn regressor_column_count(&self) -> usize {
        3 * self.segments().len() + LUMPED_COLUMNS * self.lumped.len()
    }
}

impl<T: SimdRealField + Copy> RobotSegment<T> {
    /// Every number mapped by `f` (which must keep values, as `Dual::constant` does).
    fn map_scalars<U: SimdRealField + Copy>(&self, f: impl Fn(T) -> U + Copy) -> RobotSegment<U> {
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
    fn map_scalars<U: SimdRealField + Copy>(&self, f: impl Fn(T) -> U + Copy) -> RigidBody<U> {
        RigidBody { mass: f(self.mass), com: self.com.map(f), volume: f(self.volume), cob: self.cob.map(f) }
    }
}

impl<T: SimdRealField + Copy, const J: usize, const S: usize, const B: usize> Robot<T, J, S, B> {
    /// The same robot over another scalar type, every number mapped by `f`, which must keep
    /// values (as `Dual::constant` does): nothing is validated again.
    pub(crate) fn map_scalars<U: SimdRealField + Copy>(&self, f: impl Fn(T) -> U + Copy) -> Robot<U, J, S, B> {
        Robot {
            joints: self.joints.map(|j| TreeJoint {
                parent: j.parent,
                kind: j.kind,
                origin: j.origin.map(f),
                axis: j.axis.map(f),
            }),
            links: self.links.map(|l| l.map_scalars(f)),
            base: self.base.map_scalars(f),
            segments: self.segments.map(|s| s.map_scalars(f)),
            joint_count: self.joint_count,
            segment_count: self.segment_count,
            frames: self.frames.map_scalars(f),
            lumped: self.lumped.map_scalars(f),
        }
    }
}

impl<T: RealField + Copy, const J: usize, const S: usize, const B: usize> Robot<T, J, S, B> {
    /// The same robot over a SIMD type, every number splat across the lanes: the evaluation then
    /// takes one state per lane in one call, with the same operations as for `T`.
    #[must_use]
    pub fn splat<L: SimdRealField<Element = T> + Copy>(&self) -> Robot<L, J, S, B> {
        self.map_scalars(L::splat)
    }
}
