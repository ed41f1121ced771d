//! Kinematics: where every link is, and how it moves relative to the water.
//!
//! For a user: [`forward_kinematics`] gives every link's pose in the base frame, and
//! [`point_jacobian`] the geometric Jacobian of a point on a link, for any robot, as free functions
//! over the model and a workspace ([`KinematicsData`]).
//!
//! For the evaluation (`crate::hydro`): the forward pass over the joints (parents before
//! children) that gives every link's motion relative to the water in its own body frame
//! (`crate::frames`: the joint axis is z, the link's geometry constant).

use nalgebra::{Matrix3, SimdRealField, Vector3};

use crate::algebra::{axis_angle, rotate, rotate_back};
use crate::frames::JointFrame;
use crate::model::Robot;
use crate::motion::{BaseMotion, Current};
use crate::parts::{JointKind, TreeJoint};
use crate::real::Real;
use crate::water::Water;

/// The motion of a body frame (at its joint) relative to the water, in its own components, and
/// where it sits in its parent's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Frame<T: SimdRealField + Copy> {
    pub(crate) angular_velocity: Vector3<T>,
    pub(crate) angular_acceleration: Vector3<T>,
    /// Velocity of the frame origin less the water's.
    velocity: Vector3<T>,
    /// Classical acceleration of the frame origin less the water's.
    acceleration: Vector3<T>,
    /// Gravity's acceleration vector.
    pub(crate) gravity: Vector3<T>,
    /// The water's acceleration.
    pub(crate) water_acceleration: Vector3<T>,
    /// `(sin q, cos q)` of a revolute joint's angle; `(0, 1)` for a prismatic joint.
    turn: (T, T),
    /// The frame origin in the parent's body frame (a prismatic joint's slide included).
    pub(crate) offset: Vector3<T>,
    /// What is known of the motion from the robot's structure alone.
    shape: Shape,
}

/// What a frame's motion is, known from the robot's structure and whether the base is at rest:
/// the forward pass then skips the products with zeros.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Shape {
    /// At rest, in still water: the base of a fixed robot.
    Still,
    /// Turning about its own z axis through its fixed origin, in still water: `ω = ω_z e_z`,
    /// `α = α_z e_z`, and the origin at rest (a revolute joint's link on a base at rest).
    AboutAxis,
    /// Any motion.
    General,
}

/// `Rz(q)ᵀ v` for `turn = (sin q, cos q)`.
#[inline(always)]
fn turn_back<T: SimdRealField + Copy>((sin, cos): (T, T), v: &Vector3<T>) -> Vector3<T> {
    Vector3::new(cos * v.x + sin * v.y, cos * v.y - sin * v.x, v.z)
}

impl<T: SimdRealField + Copy> Frame<T> {
    /// At rest, in no field: a workspace's initial value.
    pub(crate) fn rest() -> Self {
        let zero = Vector3::zeros();
        Self {
            angular_velocity: zero,
            angular_acceleration: zero,
            velocity: zero,
            acceleration: zero,
            gravity: zero,
            water_acceleration: zero,
            turn: (T::zero(), T::one()),
            offset: zero,
            shape: Shape::General,
        }
    }

    /// A vector in this frame's components, in its parent's.
    #[inline(always)]
    pub(crate) fn in_parent(&self, kind: JointKind, joint: &JointFrame<T>, v: &Vector3<T>) -> Vector3<T> {
        let v = match kind {
            JointKind::Revolute => {
                let (sin, cos) = self.turn;
                Vector3::new(cos * v.x - sin * v.y, sin * v.x + cos * v.y, v.z)
            }
            JointKind::Prismatic => *v,
        };
        match &joint.turn {
            Some(turn) => rotate(turn, &v),
            None => v,
        }
    }

    /// The frame of a child moved by `joint` (whose body frame is `frame`) at `(q, q̇, q̈)`;
    /// `still_water`: whether the water's acceleration is zero.
    #[inline(always)]
    fn child(&self, joint: &TreeJoint<T>, frame: &JointFrame<T>, [q, qd, qdd]: [T; 3], still_water: bool) -> Self
    where
        T: Real,
    {
        let revolute = joint.kind == JointKind::Revolute;
        let (turn, offset) =
            if revolute { (q.sin_cos(), frame.origin) } else { ((T::zero(), T::one()), frame.origin + frame.axis * q) };
        let before_turn = |v: &Vector3<T>| match &frame.turn {
            Some(t) => rotate_back(t, v),
            None => *v,
        };
        let turned = |v: &Vector3<T>| if revolute { turn_back(turn, v) } else { *v };
        let into = |v: &Vector3<T>| turned(&before_turn(v));
        let zero = Vector3::zeros();
        let (w, alpha, mut velocity, mut acceleration) = match self.shape {
            Shape::Still => (zero, zero, zero, zero),
            // The parent turns about its z axis through its fixed origin: the joint's motion is
            // the unit turn's, scaled by the parent's rates.
            Shape::AboutAxis if revolute => {
                let (rate, rate_change) = (self.angular_velocity.z, self.angular_acceleration.z);
                let [axis, tangential, centripetal] = &frame.unit_turn;
                (
                    turned(&(axis * rate)),
                    turned(&(axis * rate_change)),
                    turned(&(tangential * rate)),
                    turned(&(tangential * rate_change + centripetal * (rate * rate))),
                )
            }
            Shape::AboutAxis | Shape::General => {
                let (velocity, acceleration) = self.point_motion(&offset);
                (into(&self.angular_velocity), into(&self.angular_acceleration), into(&velocity), into(&acceleration))
            }
        };
        // ω × e_z = (ω_y, −ω_x, 0).
        let (angular_velocity, angular_acceleration) = if revolute {
            (Vector3::new(w.x, w.y, w.z + qd), Vector3::new(alpha.x + qd * w.y, alpha.y - qd * w.x, alpha.z + qdd))
        } else {
            let twice = qd + qd;
            velocity.z += qd;
            acceleration += Vector3::new(twice * w.y, -twice * w.x, qdd);
            (w, alpha)
        };
        Self {
            angular_velocity,
            angular_acceleration,
            velocity,
            acceleration,
            gravity: into(&self.gravity),
            water_acceleration: if still_water { zero } else { into(&self.water_acceleration) },
            turn,
            offset,
            shape: if self.shape == Shape::Still && revolute { Shape::AboutAxis } else { Shape::General },
        }
    }

    /// The twist relative to the water `(v, ω)` of the material point at `r` and its components'
    /// derivative `(v̇, α)` (`v̇ = a − ω × v`, `a` the point's acceleration relative to the water).
    #[inline(always)]
    pub(crate) fn twist_at(&self, r: &Vector3<T>) -> [Vector3<T>; 4] {
        let (v, a) = self.point_motion(r);
        let w = self.angular_velocity;
        [v, w, a - w.cross(&v), self.angular_acceleration]
    }

    /// Velocity and acceleration (relative to the water) of the material point at `r`.
    #[inline(always)]
    pub(crate) fn point_motion(&self, r: &Vector3<T>) -> (Vector3<T>, Vector3<T>) {
        let w = &self.angular_velocity;
        let wr = w.cross(r);
        (self.velocity + wr, self.acceleration + self.angular_acceleration.cross(r) + w.cross(&wr))
    }
}

/// The forward pass: every link's frame into `frames` (parents first).
#[inline(always)]
pub(crate) fn forward<T: Real, const J: usize, const S: usize, const B: usize>(
    robot: &Robot<T, J, S, B>,
    base: &Frame<T>,
    [q, qd, qdd]: [&[T; J]; 3],
    frames: &mut [Frame<T>; J],
) {
    let n = robot.joint_count();
    let still_water = base.water_acceleration == Vector3::zeros();
    let per_joint = robot.joints().iter().zip(&robot.frames().joints).zip(q.iter().zip(qd).zip(qdd)).take(n);
    for (i, ((joint, geometry), ((&q, &qd), &qdd))) in per_joint.enumerate() {
        // Parents come first: the parent is read from the frames before `i`, the child written
        // in place.
        let Some((done, [slot, ..])) = frames.split_at_mut_checked(i) else { continue };
        let parent = match joint.parent {
            Some(p) => done.get(p).unwrap_or(base),
            None => base,
        };
        *slot = parent.child(joint, geometry, [q, qd, qdd], still_water);
    }
}

/// Where a link's frame is and how it is turned, in the base frame (the world's for a fixed,
/// upright base), and its joint's axis there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinkPose<T: SimdRealField + Copy> {
    /// Rotation from the link frame to the base frame.
    pub rotation: Matrix3<T>,
    /// The link frame's origin: the position of the joint that moves the link [m].
    pub origin: Vector3<T>,
    /// That joint's axis, in base components.
    pub axis: Vector3<T>,
}

impl<T: Real> Frame<T> {
    /// The base's own frame, relative to the water.
    #[inline(always)]
    pub(crate) fn base(motion: &BaseMotion<T>, water: &Water<T>, current: &Current<T>) -> Self {
        let rotation = motion.rotation();
        let (v, w) = motion.twist();
        let (v_dot, w_dot) = motion.twist_derivative();
        let zero = Vector3::zeros();
        let gravity = Vector3::new(rotation.m31, rotation.m32, rotation.m33) * -water.gravity();
        let still = Self {
            angular_velocity: zero,
            angular_acceleration: zero,
            velocity: zero,
            acceleration: zero,
            gravity,
            water_acceleration: zero,
            turn: (T::zero(), T::one()),
            offset: zero,
            shape: Shape::Still,
        };
        // Every part zero: a dual number's derivatives (a Jacobian's seed on the base's twist)
        // too, which `==` would not see.
        if [v, w, v_dot, w_dot, *current.velocity(), *current.acceleration()]
            .iter()
            .flat_map(|x| x.iter())
            .all(|c| c.is_all_zero())
        {
            return still;
        }
        let water_acceleration = rotate_back(rotation, current.acceleration());
        Self {
            angular_velocity: w,
            angular_acceleration: w_dot,
            velocity: v - rotate_back(rotation, current.velocity()),
            acceleration: v_dot + w.cross(&v) - water_acceleration,
            water_acceleration,
            shape: Shape::General,
            ..still
        }
    }
}

impl<T: SimdRealField + Copy> LinkPose<T> {
    /// The position of a point given in the link frame [m].
    #[inline]
    #[must_use]
    pub fn point(&self, local: &Vector3<T>) -> Vector3<T> {
        self.origin + rotate(&self.rotation, local)
    }
}

/// The workspace of [`forward_kinematics`] for robots of up to `J` joints: every link's pose of
/// the last evaluation, which [`point_jacobian`] reads.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KinematicsData<T: SimdRealField + Copy, const J: usize> {
    poses: [LinkPose<T>; J],
    joint_count: usize,
}

impl<T: SimdRealField + Copy, const J: usize> KinematicsData<T, J> {
    /// A workspace for robots of up to `J` joints.
    #[must_use]
    pub fn new() -> Self {
        let rest = LinkPose { rotation: Matrix3::identity(), origin: Vector3::zeros(), axis: Vector3::zeros() };
        Self { poses: [rest; J], joint_count: 0 }
    }

    /// Every link's pose in the last evaluation (link `i` is moved by joint `i`).
    pub fn poses(&self) -> &[LinkPose<T>] {
        self.poses.get(..self.joint_count).unwrap_or(&[])
    }
}

impl<T: SimdRealField + Copy, const J: usize> Default for KinematicsData<T, J> {
    fn default() -> Self {
        Self::new()
    }
}

/// Every link's pose at joint positions `q` (the first `robot.joint_count()` entries), into
/// `data` ([`KinematicsData::poses`]): parents first, each link turned about (revolute) or slid
/// along (prismatic) its joint's axis from where its parent puts the joint.
///
/// Never fails and never panics; a non-finite position gives non-finite poses below its joint.
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
pub fn forward_kinematics<T: Real, const J: usize, const S: usize, const B: usize>(
    robot: &Robot<T, J, S, B>,
    q: &[T; J],
    data: &mut KinematicsData<T, J>,
) {
    let n = robot.joint_count();
    data.joint_count = n;
    for (i, (joint, &q)) in robot.joints().iter().zip(q).enumerate() {
        // Parents come first: the parent is read from the poses before `i`, the child written
        // in place.
        let Some((done, [slot, ..])) = data.poses.split_at_mut_checked(i) else { continue };
        let (parent, origin) = match joint.parent.and_then(|p| done.get(p)) {
            Some(parent) => (parent.rotation, parent.origin),
            None => (Matrix3::identity(), Vector3::zeros()),
        };
        let axis = rotate(&parent, &joint.axis);
        let (offset, rotation) = match joint.kind {
            JointKind::Revolute => {
                let turned = axis_angle(&joint.axis, q.sin_cos());
                // (`rotate` column by column: nalgebra's product adds each sum to a zero first.)
                let columns = [0, 1, 2].map(|j| rotate(&parent, &turned.column(j).into_owned()));
                (joint.origin, Matrix3::from_columns(&columns))
            }
            JointKind::Prismatic => (joint.origin + joint.axis * q, parent),
        };
        *slot = LinkPose { rotation, origin: origin + rotate(&parent, &offset), axis };
    }
}

/// The position of `point` (given in link `link`'s frame) and the geometric Jacobian there, from
/// the poses of the last [`forward_kinematics`] into `data`, written row-major into `jacobian`
/// (`6 × n`, `n` the robot's joints; a shorter slice gets what fits). `None`, and nothing written,
/// if `link` is not a link of the robot.
///
/// Column `j` maps `q̇_j` to the point's velocity (rows 0-2) and the link's angular velocity
/// (rows 3-5): `(z_j × (p − o_j), z_j)` for a revolute joint, `(z_j, 0)` for a prismatic one, with
/// `z_j` and `o_j` joint `j`'s axis and origin; the columns of joints that do not carry the link
/// (not on its path to the base) are zero. Never fails and never panics.
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
pub fn point_jacobian<T: SimdRealField + Copy, const J: usize, const S: usize, const B: usize>(
    robot: &Robot<T, J, S, B>,
    data: &KinematicsData<T, J>,
    link: usize,
    point: &Vector3<T>,
    jacobian: &mut [T],
) -> Option<Vector3<T>> {
    let joints = robot.joints();
    let n = joints.len();
    let position = data.poses().get(link)?.point(point);
    for slot in jacobian.iter_mut().take(6 * n) {
        *slot = T::zero();
    }
    // From the link up to the base: every joint on the way moves the point.
    let mut at = Some(link);
    while let Some(j) = at {
        let (Some(joint), Some(pose)) = (joints.get(j), data.poses().get(j)) else { break };
        let axis = pose.axis;
        let (linear, angular) = match joint.kind {
            JointKind::Revolute => (axis.cross(&(position - pose.origin)), axis),
            JointKind::Prismatic => (axis, Vector3::zeros()),
        };
        for (row, value) in linear.iter().chain(angular.iter()).enumerate() {
            if let Some(slot) = jacobian.get_mut(row * n + j) {
                *slot = *value;
            }
        }
        at = joint.parent.filter(|&p| p < j);
    }
    Some(position)
}
