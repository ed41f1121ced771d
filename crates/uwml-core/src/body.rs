//! The chain in body frames, and its forward recursion for the torque paths.
//!
//! Body frame `F_i` is link `i`'s frame turned by a constant rotation so that joint `i`'s axis is
//! its local z and, where the link's segment allows, the segment runs along x with its normals
//! along y and z. There a joint rotation only mixes x and y, the joint axis is `e_z`, the
//! generalized force on a joint is the z component of the moment about its origin, a link's
//! geometry is constant, and an aligned segment's projections are plain components. Everything
//! that does not depend on the joint state is computed once, when the [`Chain`] is built.

use nalgebra::{Matrix3, RealField, SVector, SimdRealField, Vector3};

use crate::kinematics::{dot, rotate, rotate_back};
use crate::model::{Chain, Joint, Link, Segment};

/// Link `i` and the joint that moves it, in the body frame `F_i`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Body<T: SimdRealField + Copy> {
    /// `F_i` at `q_i = 0` in `F_{i-1}` (the world frame for the first joint), where the two
    /// differ by more than a turn about the joint axis.
    pub(crate) turn: Option<Matrix3<T>>,
    /// Where `turn` is `None`: `(sin β, cos β)` of the angle `β` about z that takes `F_{i-1}` to
    /// `F_i` at `q_i = 0`, added to the joint angle (by composing sines and cosines, so that quarter
    /// turns stay exact).
    pub(crate) angle_offset: (T, T),
    /// Where the joint sits in `F_{i-1}`; `None` at its origin (the axes meet there).
    pub(crate) origin: Option<Origin<T>>,
    /// The motion of `F_i` per unit rate of the parent joint, used for the second joint.
    pub(crate) unit_turn: UnitTurn<T>,
    /// Displaced volume times centre of buoyancy, in `F_i` [m⁴].
    pub(crate) volume_moment: Vector3<T>,
    /// Mass times centre of mass, in `F_i` [kg·m].
    pub(crate) mass_moment: Vector3<T>,
    pub(crate) segment: Option<BodySegment<T>>,
}

/// A joint origin off the parent frame's origin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Origin<T: SimdRealField + Copy> {
    /// Position in `F_{i-1}` [m].
    pub(crate) position: Vector3<T>,
    /// The volume of this link and all links after it, times `position`: what the first moment
    /// of their volume gains from this origin to the parent's.
    pub(crate) carried_volume_moment: Vector3<T>,
    /// The same for their mass.
    pub(crate) carried_mass_moment: Vector3<T>,
}

/// How `F_i`, before joint `i` turns, moves when the parent frame turns about its z axis at unit
/// rate, in those coordinates. The second joint's motion is this scaled by the first joint's
/// rates (the world is at rest). By duality, the same vectors give the moment about the parent
/// joint's axis of a wrench at this joint.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct UnitTurn<T: SimdRealField + Copy> {
    /// Angular velocity: the parent's axis, `e_z`.
    axis: Vector3<T>,
    /// Velocity of the origin, and its acceleration per unit angular acceleration: `e_z × p`.
    tangential: Vector3<T>,
    /// Acceleration of the origin per unit angular velocity squared: `e_z × (e_z × p)`.
    centripetal: Vector3<T>,
}

/// A link's [`Segment`] in its body frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct BodySegment<T: SimdRealField + Copy> {
    /// Start point; `None` at the body origin.
    pub(crate) start: Option<Vector3<T>>,
    pub(crate) frame: SegmentFrame<T>,
    /// `σ = (axis × normals[0]) · normals[1] = ±1`, so that the moment directions
    /// `axis × normals[k]` are `σ normals[1]` and `−σ normals[0]`.
    pub(crate) sign: T,
    pub(crate) length: T,
    pub(crate) widths: [T; 2],
    pub(crate) area: T,
}

/// The directions of a segment in its body frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum SegmentFrame<T: SimdRealField + Copy> {
    /// Along the body axes, as for most links: the segment along x, one normal along the joint
    /// axis z and the other along y (`normals[0]` along z where `swapped`). A normal's sign does
    /// not matter: flipping it flips the normal speed, acceleration and moment direction, and the
    /// force stays the same.
    Aligned { swapped: bool },
    /// Any directions.
    General { axis: Vector3<T>, normals: [Vector3<T>; 2] },
}

impl<T: SimdRealField + Copy> SegmentFrame<T> {
    /// `(v · normals[0], v · normals[1])`.
    #[inline(always)]
    pub(crate) fn normal_components(&self, v: &Vector3<T>) -> [T; 2] {
        match self {
            Self::Aligned { swapped: false } => [v.y, v.z],
            Self::Aligned { swapped: true } => [v.z, v.y],
            Self::General { normals: [n0, n1], .. } => [dot(n0, v), dot(n1, v)],
        }
    }

    /// `v · axis`.
    #[inline(always)]
    pub(crate) fn axial_component(&self, v: &Vector3<T>) -> T {
        match self {
            Self::Aligned { .. } => v.x,
            Self::General { axis, .. } => dot(axis, v),
        }
    }

    /// `c[0] normals[0] + c[1] normals[1]`.
    #[inline(always)]
    pub(crate) fn along_normals(&self, [c0, c1]: [T; 2]) -> Vector3<T> {
        match self {
            Self::Aligned { swapped: false } => Vector3::new(T::zero(), c0, c1),
            Self::Aligned { swapped: true } => Vector3::new(T::zero(), c1, c0),
            Self::General { normals: [n0, n1], .. } => n0 * c0 + n1 * c1,
        }
    }
}

/// For a segment exactly along the axes of a frame about the joint `axis`: that frame (columns:
/// the segment axis, the direction across it, the joint axis), and whether `normals[0]` is the
/// normal along the joint axis. `None` for any other segment.
fn aligned_frame<T: RealField + Copy>(axis: &Vector3<T>, segment: &Segment<T>) -> Option<(Matrix3<T>, bool)> {
    let [n0, n1] = segment.normals;
    let across = axis.cross(&segment.axis);
    let along = |n: &Vector3<T>, d: &Vector3<T>| *n == *d || *n == -d;
    let swapped = if along(&n0, axis) && along(&n1, &across) {
        true
    } else if along(&n1, axis) && along(&n0, &across) {
        false
    } else {
        return None;
    };
    let frame = Matrix3::from_columns(&[segment.axis, across, *axis]);
    (segment.axis.dot(axis) == T::zero()).then_some((frame, swapped))
}

/// An orthonormal frame (columns) whose z column is the unit `axis` and whose x column is the
/// column of `previous` most perpendicular to it, made perpendicular (exact for axis-aligned axes).
pub(crate) fn frame_about<T: RealField + Copy>(axis: &Vector3<T>, previous: &Matrix3<T>) -> Matrix3<T> {
    let mut x = previous.column(0).into_owned();
    for c in [previous.column(1).into_owned(), previous.column(2).into_owned()] {
        if c.dot(axis).abs() < x.dot(axis).abs() {
            x = c;
        }
    }
    let x = (x - axis * x.dot(axis)).normalize();
    Matrix3::from_columns(&[x, axis.cross(&x), *axis])
}

impl<T: SimdRealField + Copy> Body<T> {
    /// `(sin, cos)` of the joint angle plus its offset, from those of the joint angle.
    #[inline(always)]
    fn offset(&self, (sin, cos): (T, T)) -> (T, T) {
        let (sin_offset, cos_offset) = self.angle_offset;
        (sin * cos_offset + cos * sin_offset, cos * cos_offset - sin * sin_offset)
    }
}

impl<T: RealField + Copy> Body<T> {
    /// Joint `i` and link `i` in `F_i`, whose axes (columns, in link coordinates) are `frame`,
    /// given those of `F_{i-1}`; `carried`: the volume and mass of link `i` and all after it.
    fn new(joint: &Joint<T>, link: &Link<T>, previous: &Matrix3<T>, frame: &Matrix3<T>, carried: (T, T)) -> Self {
        // From F_i at q_i = 0 to F_{i-1}. A turn about the joint axis itself is no more than an
        // offset of the joint angle.
        let relative = previous.transpose() * frame;
        let (turn, angle_offset) = if relative.column(2).into_owned() == Vector3::z() {
            (None, (relative.m21, relative.m11))
        } else {
            (Some(relative), (T::zero(), T::one()))
        };
        let local = |v: &Vector3<T>| frame.transpose() * v;
        let position = previous.transpose() * joint.origin;
        let before_turn = |v: Vector3<T>| turn.map_or(v, |turn| turn.transpose() * v);
        let tangential = Vector3::z().cross(&position);
        Self {
            turn,
            angle_offset,
            origin: (position != Vector3::zeros()).then_some(Origin {
                position,
                carried_volume_moment: position * carried.0,
                carried_mass_moment: position * carried.1,
            }),
            unit_turn: UnitTurn {
                axis: before_turn(Vector3::z()),
                tangential: before_turn(tangential),
                centripetal: before_turn(Vector3::z().cross(&tangential)),
            },
            volume_moment: local(&link.cob) * link.volume,
            mass_moment: local(&link.com) * link.mass,
            segment: link.segment.map(|segment| {
                let (frame, sign) = match aligned_frame(&joint.axis, &segment) {
                    // (e_x × e_y) · e_z = 1 and (e_x × e_z) · e_y = −1.
                    Some((_, swapped)) => {
                        (SegmentFrame::Aligned { swapped }, if swapped { -T::one() } else { T::one() })
                    }
                    None => {
                        let (axis, [n0, n1]) = (local(&segment.axis), segment.normals.map(|n| local(&n)));
                        (SegmentFrame::General { axis, normals: [n0, n1] }, axis.cross(&n0).dot(&n1).signum())
                    }
                };
                let start = local(&segment.start);
                BodySegment {
                    start: (start != Vector3::zeros()).then_some(start),
                    frame,
                    sign,
                    length: segment.length,
                    widths: segment.widths,
                    area: segment.area,
                }
            }),
        }
    }
}

/// The body frames of a chain (its joints and links must be validated).
pub(crate) fn bodies<T: RealField + Copy, const N: usize>(
    joints: &[Joint<T>; N],
    links: &[Link<T>; N],
) -> [Body<T>; N] {
    let mut carried = [(T::zero(), T::zero()); N];
    let mut total = (T::zero(), T::zero());
    for (carried, link) in carried.iter_mut().zip(links.iter()).rev() {
        total = (total.0 + link.volume, total.1 + link.mass);
        *carried = total;
    }
    let zero = Vector3::zeros();
    let unit_turn = UnitTurn { axis: zero, tangential: zero, centripetal: zero };
    let placeholder = Body {
        turn: None,
        angle_offset: (T::zero(), T::one()),
        origin: None,
        unit_turn,
        volume_moment: zero,
        mass_moment: zero,
        segment: None,
    };
    let mut bodies = [placeholder; N];
    // F_{i-1}'s axes (columns) in link coordinates: all link frames agree at q = 0.
    let mut previous = Matrix3::identity();
    for (((body, joint), link), &carried) in bodies.iter_mut().zip(joints.iter()).zip(links.iter()).zip(carried.iter())
    {
        let aligned = link.segment.as_ref().and_then(|segment| aligned_frame(&joint.axis, segment));
        let frame = match aligned {
            Some((frame, _)) => frame,
            None if joint.axis == previous.column(2).into_owned() => previous,
            None => frame_about(&joint.axis, &previous),
        };
        *body = Body::new(joint, link, &previous, &frame, carried);
        previous = frame;
    }
    bodies
}

/// The motion of a link in its body frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct BodyMotion<T: SimdRealField + Copy> {
    pub(crate) angular_velocity: Vector3<T>,
    pub(crate) angular_acceleration: Vector3<T>,
    /// Velocity of the joint origin.
    pub(crate) velocity: Vector3<T>,
    /// Acceleration of the joint origin.
    pub(crate) acceleration: Vector3<T>,
}

impl<T: SimdRealField + Copy> BodyMotion<T> {
    /// Velocity `v + ω × r` and acceleration `a + α × r + ω × (ω × r)` of the material point at `r`.
    #[inline(always)]
    pub(crate) fn point_motion(&self, r: &Vector3<T>) -> (Vector3<T>, Vector3<T>) {
        let w = &self.angular_velocity;
        let wr = w.cross(r);
        (self.velocity + wr, self.acceleration + self.angular_acceleration.cross(r) + w.cross(&wr))
    }
}

/// Joint `i`'s turn, the world's up and the link's motion in `F_i`: what the torque paths need.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct BodyState<T: SimdRealField + Copy> {
    /// `sin` and `cos` of the joint angle plus its offset.
    pub(crate) turn: (T, T),
    /// The world's up direction in `F_i`.
    pub(crate) up: Vector3<T>,
    pub(crate) motion: BodyMotion<T>,
}

/// `Rz(q)ᵀ v` for `turn = (sin q, cos q)`.
#[inline(always)]
fn turn_back<T: SimdRealField + Copy>((sin, cos): (T, T), v: &Vector3<T>) -> Vector3<T> {
    Vector3::new(cos * v.x + sin * v.y, cos * v.y - sin * v.x, v.z)
}

/// `v` (in `F_{i-1}`) in `F_i` before joint `i` turns.
#[inline(always)]
fn before_turn<T: SimdRealField + Copy>(body: &Body<T>, v: &Vector3<T>) -> Vector3<T> {
    match &body.turn {
        Some(turn) => rotate_back(turn, v),
        None => *v,
    }
}

impl<T: SimdRealField + Copy> BodyState<T> {
    /// `v` (in `F_i`) in `F_{i-1}`.
    #[inline(always)]
    pub(crate) fn in_parent(&self, body: &Body<T>, v: &Vector3<T>) -> Vector3<T> {
        let (sin, cos) = self.turn;
        let v = Vector3::new(cos * v.x - sin * v.y, sin * v.x + cos * v.y, v.z);
        match &body.turn {
            Some(turn) => rotate(turn, &v),
            None => v,
        }
    }

    /// The moment about the parent joint's axis of a force and a moment (about this joint's
    /// origin, in `F_i`): their powers at the parent's unit rate. One row of the change of frame,
    /// where [`BodyState::in_parent`] needs three.
    #[inline(always)]
    pub(crate) fn moment_about_parent_axis(&self, body: &Body<T>, force: &Vector3<T>, moment: &Vector3<T>) -> T {
        // `a · Rz(q) v` as `Rz(q)ᵀ a · v`: the constant `a` is turned instead of `v`.
        let turned_dot = |a: &Vector3<T>, v: &Vector3<T>| dot(&turn_back(self.turn, a), v);
        let unit = &body.unit_turn;
        let about_axis = turned_dot(&unit.axis, moment);
        match &body.origin {
            Some(_) => about_axis + turned_dot(&unit.tangential, force),
            None => about_axis,
        }
    }

    /// The first joint: the world is at rest, so the link only turns about the joint axis.
    #[inline(always)]
    fn first(body: &Body<T>, turn: (T, T), qd: T, qdd: T) -> Self {
        let (zero, still) = (T::zero(), Vector3::zeros());
        let motion = BodyMotion {
            angular_velocity: Vector3::new(zero, zero, qd),
            angular_acceleration: Vector3::new(zero, zero, qdd),
            velocity: still,
            acceleration: still,
        };
        // A vertical first axis keeps up along it.
        let up = match &body.turn {
            Some(into_frame) => turn_back(turn, &rotate_back(into_frame, &Vector3::z())),
            None => Vector3::z(),
        };
        Self { turn, up, motion }
    }

    /// The second joint, whose parent turns about its fixed axis at rate `q̇₀` and acceleration
    /// `q̈₀`: the motion of its frame is the unit turn's, scaled.
    #[inline(always)]
    fn second(&self, body: &Body<T>, turn: (T, T), qd: T, qdd: T, vertical_first: bool) -> Self {
        let (rate, rate_change) = (self.motion.angular_velocity.z, self.motion.angular_acceleration.z);
        let unit = &body.unit_turn;
        let (velocity, acceleration) = match body.origin {
            Some(_) => (
                turn_back(turn, &(unit.tangential * rate)),
                turn_back(turn, &(unit.tangential * rate_change + unit.centripetal * (rate * rate))),
            ),
            None => (Vector3::zeros(), Vector3::zeros()),
        };
        let motion = BodyMotion {
            angular_velocity: turn_back(turn, &(unit.axis * rate)),
            angular_acceleration: turn_back(turn, &(unit.axis * rate_change)),
            velocity,
            acceleration,
        };
        // Up is the parent's axis if that is vertical.
        let up = turn_back(turn, &if vertical_first { unit.axis } else { before_turn(body, &self.up) });
        Self::with_joint_rates(turn, up, motion, qd, qdd)
    }

    /// Any later joint, by the general recursion from its parent.
    #[inline(always)]
    fn child(&self, body: &Body<T>, turn: (T, T), qd: T, qdd: T) -> Self {
        let m = &self.motion;
        let (velocity, acceleration) = match &body.origin {
            Some(origin) => m.point_motion(&origin.position),
            None => (m.velocity, m.acceleration),
        };
        let into_body = |v: &Vector3<T>| turn_back(turn, &before_turn(body, v));
        let motion = BodyMotion {
            angular_velocity: into_body(&m.angular_velocity),
            angular_acceleration: into_body(&m.angular_acceleration),
            velocity: into_body(&velocity),
            acceleration: into_body(&acceleration),
        };
        Self::with_joint_rates(turn, into_body(&self.up), motion, qd, qdd)
    }

    /// Adds the joint's own rates to the parent's motion (in `F_i`): `ω_i = ω + q̇ e_z` and
    /// `α_i = α + q̈ e_z + q̇ (ω × e_z)`, with `ω × e_z = (ω_y, −ω_x, 0)`.
    #[inline(always)]
    fn with_joint_rates(turn: (T, T), up: Vector3<T>, parent: BodyMotion<T>, qd: T, qdd: T) -> Self {
        let (w, alpha) = (parent.angular_velocity, parent.angular_acceleration);
        let motion = BodyMotion {
            angular_velocity: Vector3::new(w.x, w.y, w.z + qd),
            angular_acceleration: Vector3::new(alpha.x + qd * w.y, alpha.y - qd * w.x, alpha.z + qdd),
            ..parent
        };
        Self { turn, up, motion }
    }
}

/// Whether the first joint turns about world z (no turn into its frame): then buoyancy and
/// gravity have no moment about it, and up is its axis.
pub(crate) fn first_axis_vertical<T: SimdRealField + Copy>(bodies: &[Body<T>]) -> bool {
    bodies.first().is_some_and(|body| body.turn.is_none())
}

/// The body-frame state of every joint, by the forward recursion.
#[inline(always)]
pub(crate) fn body_states<T: SimdRealField + Copy, const N: usize>(
    chain: &Chain<T, N>,
    q: &SVector<T, N>,
    qd: &SVector<T, N>,
    qdd: &SVector<T, N>,
) -> [BodyState<T>; N] {
    // Arrays, not nalgebra's iterators, which cost more than the loop bodies here.
    let (q, qd, qdd): ([T; N], [T; N], [T; N]) = ((*q).into(), (*qd).into(), (*qdd).into());
    // All sines and cosines first: the calls are independent, and none has to keep the
    // recursion's registers.
    let mut turns = [(T::zero(), T::zero()); N];
    for ((turn, &q), body) in turns.iter_mut().zip(q.iter()).zip(chain.bodies().iter()) {
        *turn = body.offset(q.simd_sin_cos());
    }
    let still = BodyMotion {
        angular_velocity: Vector3::zeros(),
        angular_acceleration: Vector3::zeros(),
        velocity: Vector3::zeros(),
        acceleration: Vector3::zeros(),
    };
    let mut states = [BodyState { turn: (T::zero(), T::one()), up: Vector3::z(), motion: still }; N];
    let mut joints = states.iter_mut().zip(chain.bodies().iter()).zip(turns.into_iter().zip(qd.into_iter().zip(qdd)));
    // The first two joints are special cases; out of the loop, they leave chains of up to three
    // joints without a loop at all.
    let Some(((state, body), (turn, (qd, qdd)))) = joints.next() else { return states };
    *state = BodyState::first(body, turn, qd, qdd);
    let mut parent = *state;
    let Some(((state, body), (turn, (qd, qdd)))) = joints.next() else { return states };
    *state = parent.second(body, turn, qd, qdd, first_axis_vertical(chain.bodies()));
    parent = *state;
    for ((state, body), (turn, (qd, qdd))) in joints {
        *state = parent.child(body, turn, qd, qdd);
        parent = *state;
    }
    states
}

impl<T: SimdRealField + Copy> Body<T> {
    /// Every number mapped by `f` (see `Chain::map_scalars`); the structure (which optional
    /// parts are present, aligned or general segment frames) is kept.
    pub(crate) fn map_scalars<U: SimdRealField + Copy>(&self, f: impl Fn(T) -> U + Copy) -> Body<U> {
        let (sin, cos) = self.angle_offset;
        Body {
            turn: self.turn.map(|m| m.map(f)),
            angle_offset: (f(sin), f(cos)),
            origin: self.origin.map(|o| o.map_scalars(f)),
            unit_turn: self.unit_turn.map_scalars(f),
            volume_moment: self.volume_moment.map(f),
            mass_moment: self.mass_moment.map(f),
            segment: self.segment.map(|s| s.map_scalars(f)),
        }
    }
}

impl<T: SimdRealField + Copy> Origin<T> {
    /// Every number mapped by `f`.
    fn map_scalars<U: SimdRealField + Copy>(&self, f: impl Fn(T) -> U + Copy) -> Origin<U> {
        Origin {
            position: self.position.map(f),
            carried_volume_moment: self.carried_volume_moment.map(f),
            carried_mass_moment: self.carried_mass_moment.map(f),
        }
    }
}

impl<T: SimdRealField + Copy> UnitTurn<T> {
    /// Every number mapped by `f`.
    fn map_scalars<U: SimdRealField + Copy>(&self, f: impl Fn(T) -> U + Copy) -> UnitTurn<U> {
        UnitTurn { axis: self.axis.map(f), tangential: self.tangential.map(f), centripetal: self.centripetal.map(f) }
    }
}

impl<T: SimdRealField + Copy> BodySegment<T> {
    /// Every number mapped by `f`.
    fn map_scalars<U: SimdRealField + Copy>(&self, f: impl Fn(T) -> U + Copy) -> BodySegment<U> {
        BodySegment {
            start: self.start.map(|s| s.map(f)),
            frame: self.frame.map_scalars(f),
            sign: f(self.sign),
            length: f(self.length),
            widths: self.widths.map(f),
            area: f(self.area),
        }
    }
}

impl<T: SimdRealField + Copy> SegmentFrame<T> {
    /// Every number mapped by `f`.
    pub(crate) fn map_scalars<U: SimdRealField + Copy>(&self, f: impl Fn(T) -> U + Copy) -> SegmentFrame<U> {
        match self {
            Self::Aligned { swapped } => SegmentFrame::Aligned { swapped: *swapped },
            Self::General { axis, normals } => {
                SegmentFrame::General { axis: axis.map(f), normals: normals.map(|n| n.map(f)) }
            }
        }
    }
}
