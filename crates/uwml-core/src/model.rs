//! The immutable, validated description of a whole robot (docs/model.md section 10): a
//! kinematic tree of revolute and prismatic joints ([`crate::parts`]) on a base that may carry a
//! body of its own, with any number of straight segments per body (up to a fixed capacity), and
//! lumped models on some bodies (section 12.1), checked once when it is built.
//!
//! A [`Robot`] holds up to `J` joints, `S` segments and `B` lumped models in fixed arrays: it
//! needs no allocation, and its evaluation costs what its actual joints and segments cost, not
//! its capacity.

use nalgebra::{Matrix3, RealField, SimdRealField, Vector3};

use crate::error::{ModelError, Problem};
use crate::frames::{BodyFrames, link_axes};
use crate::lumped::{LUMPED_COLUMNS, Lumped, LumpedBody, LumpedFrame};
use crate::parts::{JointKind, Owner, RigidBody, RobotSegment, Section, TreeJoint};
use crate::segment_coefficients::SegmentCoefficients;

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

impl<T: RealField + Copy, const J: usize, const S: usize, const B: usize> Robot<T, J, S, B> {
    /// Validates and builds a robot from its joints, the links they move (same length), the
    /// base's own body, and the segments of all bodies.
    ///
    /// # Errors
    /// More joints than `J` or segments than `S` (`"joints"`/`"segments"`, out of range), as many
    /// links as joints; a parent that is not an earlier link (`"joint.parent"`); a segment owned
    /// by a link that does not exist (`"segment.owner"`); a circular segment with different
    /// coefficients per direction; and every check of each part (non-finite, non-positive, negative, too large, non-unit or
    /// non-perpendicular values), naming the field and index.
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
