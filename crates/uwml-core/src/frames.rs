//! Every body of a robot in a body frame of its own, computed once when the robot is built: what
//! the evaluation (`crate::hydro`) needs that does not depend on the state.
//!
//! Body frame `F_i` is link `i`'s frame turned by a constant rotation `R_i` whose third column is
//! joint `i`'s axis. There the joint axis is `e_z`: a revolute joint turns `F_i` about z by `q`
//! (`F_parent ← F_i` is `T_i Rz(q)`, with `T_i` constant), the generalized force on a joint is
//! the z component of the moment (revolute) or force (prismatic) about its origin, and a body's
//! geometry is constant. `R_i` is its parent's wherever the axes agree (then `T_i` is the
//! identity and costs nothing), else the parent's turned as little as the axes allow. The base's
//! body frame is the base frame itself.

use nalgebra::{Matrix3, RealField, SimdRealField, Vector3};

use crate::parts::{Owner, RigidBody, RobotSegment, Section, TreeJoint};
use crate::segment_frame::{SegmentFrame, frame_about};

/// Joint `i` and its link, in the body frames `F_parent` and `F_i`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct JointFrame<T: SimdRealField + Copy> {
    /// `T_i`: `F_parent ← F_i` at `q = 0`; `None` where it is the identity.
    pub(crate) turn: Option<Matrix3<T>>,
    /// The joint's origin in `F_parent` [m].
    pub(crate) origin: Vector3<T>,
    /// The joint's axis in `F_parent`, `T_i e_z` (the direction of a prismatic joint's slide).
    pub(crate) axis: Vector3<T>,
    /// How `F_i`, before its joint moves, moves when `F_parent` turns about its z axis at unit
    /// rate (in those coordinates): angular velocity `Tᵢᵀ e_z`, velocity of the origin (and its
    /// acceleration per unit angular acceleration) `Tᵢᵀ (e_z × o)`, acceleration of the origin
    /// per unit angular velocity squared `Tᵢᵀ (e_z × (e_z × o))`.
    pub(crate) unit_turn: [Vector3<T>; 3],
    /// The link's own bulk in `F_i`.
    pub(crate) bulk: Bulk<T>,
    /// The volume [m³] and mass [kg] of the link and every link below it.
    pub(crate) subtree_volume: T,
    pub(crate) subtree_mass: T,
}

/// A body's volume and mass, and their first moments `V c_b` [m⁴] and `m c_m` [kg·m] about its
/// frame's origin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Bulk<T: SimdRealField + Copy> {
    pub(crate) volume: T,
    pub(crate) volume_moment: Vector3<T>,
    pub(crate) mass: T,
    pub(crate) mass_moment: Vector3<T>,
    /// The centre of mass [m].
    pub(crate) com: Vector3<T>,
}

/// The body frames of a robot of up to `J` joints and `S` segments.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct BodyFrames<T: SimdRealField + Copy, const J: usize, const S: usize> {
    pub(crate) joints: [JointFrame<T>; J],
    /// The base's bulk, in the base frame.
    pub(crate) base: Bulk<T>,
    /// The volume and mass of the whole robot, base included.
    pub(crate) total_volume: T,
    pub(crate) total_mass: T,
    /// Every segment's directions in its body's frame.
    pub(crate) segments: [SegmentGeometry<T>; S],
}

/// A segment's start, axis and (for a rectangular section) normals, in its body's frame; its
/// other numbers are the segment's own.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SegmentGeometry<T: SimdRealField + Copy> {
    pub(crate) start: Vector3<T>,
    /// The directions: along the body's axes (the segment along x, its normals along y and z,
    /// their signs dropped, as they change no force: projections are components), or any (the
    /// normals zero for a circular section).
    pub(crate) frame: SegmentFrame<T>,
    /// `σ = (axis × normals[0]) · normals[1] = ±1`: the moment directions `axis × normals[k]`
    /// are `σ normals[1]` and `−σ normals[0]`.
    pub(crate) sign: T,
    /// Whether the segment has an axial drag (docs/model.md section 12.2): known when the robot
    /// is built, so that the evaluation of the others skips it at no cost.
    pub(crate) axial: bool,
}

impl<T: SimdRealField + Copy> SegmentGeometry<T> {
    /// The segment's unit direction.
    pub(crate) fn axis(&self) -> Vector3<T> {
        match &self.frame {
            SegmentFrame::Aligned { .. } => Vector3::x(),
            SegmentFrame::General { axis, .. } => *axis,
        }
    }

    /// The normal directions (zero for a circular section).
    pub(crate) fn normals(&self) -> [Vector3<T>; 2] {
        match &self.frame {
            SegmentFrame::Aligned { swapped: false } => [Vector3::y(), Vector3::z()],
            SegmentFrame::Aligned { swapped: true } => [Vector3::z(), Vector3::y()],
            SegmentFrame::General { normals, .. } => *normals,
        }
    }
}

impl<T: RealField + Copy> Bulk<T> {
    /// `body` with its centres in the frame whose axes (columns, in the body's coordinates) are
    /// `frame`.
    fn new(body: &RigidBody<T>, frame: &Matrix3<T>) -> Self {
        Self {
            volume: body.volume,
            volume_moment: frame.transpose() * body.cob * body.volume,
            mass: body.mass,
            mass_moment: frame.transpose() * body.com * body.mass,
            com: frame.transpose() * body.com,
        }
    }
}

/// `segment`'s geometry in the body frame with axes `frame` (columns, in the body's coordinates).
fn geometry_in<T: RealField + Copy>(segment: &RobotSegment<T>, frame: &Matrix3<T>) -> SegmentGeometry<T> {
    let local = |v: &Vector3<T>| frame.transpose() * v;
    let (start, axis) = (local(&segment.start), local(&segment.axis));
    let axial = segment.cd_axial != T::zero() && segment.axial_area != T::zero();
    let normals = match segment.section {
        Section::Rectangular { normals, .. } => normals.map(|n| local(&n)),
        Section::Circular { .. } => [Vector3::zeros(); 2],
    };
    let along = |n: &Vector3<T>, d: &Vector3<T>| *n == *d || *n == -d;
    let [n0, n1] = normals;
    let (y, z) = (Vector3::y(), Vector3::z());
    let aligned = matches!(segment.section, Section::Rectangular { .. }) && axis == Vector3::x();
    if aligned && along(&n0, &y) && along(&n1, &z) {
        return SegmentGeometry { start, frame: SegmentFrame::Aligned { swapped: false }, sign: T::one(), axial };
    }
    if aligned && along(&n0, &z) && along(&n1, &y) {
        return SegmentGeometry { start, frame: SegmentFrame::Aligned { swapped: true }, sign: -T::one(), axial };
    }
    SegmentGeometry {
        start,
        frame: SegmentFrame::General { axis, normals },
        sign: if axis.cross(&n0).dot(&n1) < T::zero() { -T::one() } else { T::one() },
        axial,
    }
}

/// Each link's body-frame axes (columns) in the link's coordinates (validated joints, parents
/// first): all link frames agree at `q = 0`; a link's are its parent's where its joint's axis is
/// the parent's z (then the turn is exactly the identity, not `Pᵀ P` to rounding), else the
/// parent's turned as little as the axis allows.
pub(crate) fn link_axes<T: RealField + Copy, const J: usize>(joints: &[TreeJoint<T>]) -> [Matrix3<T>; J] {
    let identity = Matrix3::identity();
    let mut axes = [identity; J];
    for (i, joint) in joints.iter().enumerate() {
        let parent = joint.parent.and_then(|p| axes.get(p).copied()).unwrap_or(identity);
        let own = if parent.column(2).into_owned() == joint.axis { parent } else { frame_about(&joint.axis, &parent) };
        if let Some(slot) = axes.get_mut(i) {
            *slot = own;
        }
    }
    axes
}

impl<T: RealField + Copy, const J: usize, const S: usize> BodyFrames<T, J, S> {
    /// The body frames of validated joints, links, base and segments (parents before children).
    pub(crate) fn new(
        joints: &[TreeJoint<T>],
        links: &[RigidBody<T>],
        base: &RigidBody<T>,
        segments: &[RobotSegment<T>],
    ) -> Self {
        let identity = Matrix3::identity();
        let no_bulk = Bulk::new(&RigidBody::empty(), &identity);
        let mut frames = Self {
            joints: [JointFrame {
                turn: None,
                origin: Vector3::zeros(),
                axis: Vector3::z(),
                unit_turn: [Vector3::zeros(); 3],
                bulk: no_bulk,
                subtree_volume: T::zero(),
                subtree_mass: T::zero(),
            }; J],
            base: Bulk::new(base, &identity),
            total_volume: T::zero(),
            total_mass: T::zero(),
            segments: [SegmentGeometry {
                start: Vector3::zeros(),
                frame: SegmentFrame::General { axis: Vector3::x(), normals: [Vector3::zeros(); 2] },
                sign: T::one(),
                axial: false,
            }; S],
        };
        let axes = link_axes::<T, J>(joints);
        for (i, (joint, link)) in joints.iter().zip(links).enumerate() {
            let parent = joint.parent.and_then(|p| axes.get(p).copied()).unwrap_or(identity);
            let own = axes.get(i).copied().unwrap_or(identity);
            let same = parent.column(2).into_owned() == joint.axis;
            let turn = if same { identity } else { parent.transpose() * own };
            let origin = parent.transpose() * joint.origin;
            let tangential = Vector3::z().cross(&origin);
            let before_turn = |v: Vector3<T>| turn.transpose() * v;
            if let Some(frame) = frames.joints.get_mut(i) {
                *frame = JointFrame {
                    turn: (turn != identity).then_some(turn),
                    origin,
                    axis: turn.column(2).into_owned(),
                    unit_turn: [
                        before_turn(Vector3::z()),
                        before_turn(tangential),
                        before_turn(Vector3::z().cross(&tangential)),
                    ],
                    bulk: Bulk::new(link, &own),
                    subtree_volume: link.volume,
                    subtree_mass: link.mass,
                };
            }
        }
        // Subtree sums, children (later joints) first.
        for i in (0..joints.len()).rev() {
            let (Some(joint), Some(&frame)) = (joints.get(i), frames.joints.get(i)) else { continue };
            match joint.parent.and_then(|p| frames.joints.get_mut(p)) {
                Some(parent) => {
                    parent.subtree_volume += frame.subtree_volume;
                    parent.subtree_mass += frame.subtree_mass;
                }
                None => {
                    frames.total_volume += frame.subtree_volume;
                    frames.total_mass += frame.subtree_mass;
                }
            }
        }
        frames.total_volume += base.volume;
        frames.total_mass += base.mass;
        for (segment, slot) in segments.iter().zip(frames.segments.iter_mut()) {
            let axes = match segment.owner {
                Owner::Base => identity,
                Owner::Link(i) => axes.get(i).copied().unwrap_or(identity),
            };
            *slot = geometry_in(segment, &axes);
        }
        frames
    }
}

impl<T: SimdRealField + Copy> Bulk<T> {
    /// Every number mapped by `f`.
    fn map_scalars<U: SimdRealField + Copy>(&self, f: impl Fn(T) -> U + Copy) -> Bulk<U> {
        Bulk {
            volume: f(self.volume),
            volume_moment: self.volume_moment.map(f),
            mass: f(self.mass),
            mass_moment: self.mass_moment.map(f),
            com: self.com.map(f),
        }
    }
}

impl<T: SimdRealField + Copy, const J: usize, const S: usize> BodyFrames<T, J, S> {
    /// Every number mapped by `f` (see `Robot::map_scalars`).
    pub(crate) fn map_scalars<U: SimdRealField + Copy>(&self, f: impl Fn(T) -> U + Copy) -> BodyFrames<U, J, S> {
        BodyFrames {
            joints: self.joints.map(|j| JointFrame {
                turn: j.turn.map(|m| m.map(f)),
                origin: j.origin.map(f),
                axis: j.axis.map(f),
                unit_turn: j.unit_turn.map(|v| v.map(f)),
                bulk: j.bulk.map_scalars(f),
                subtree_volume: f(j.subtree_volume),
                subtree_mass: f(j.subtree_mass),
            }),
            base: self.base.map_scalars(f),
            total_volume: f(self.total_volume),
            total_mass: f(self.total_mass),
            segments: self.segments.map(|g| SegmentGeometry {
                start: g.start.map(f),
                frame: g.frame.map_scalars(f),
                sign: f(g.sign),
                axial: g.axial,
            }),
        }
    }
}
