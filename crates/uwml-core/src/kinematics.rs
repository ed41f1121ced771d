//! Forward kinematics of the chain in world coordinates, and the small vector helpers shared
//! with the body-frame recursion of the whole-robot evaluation (`crate::frames`).

use nalgebra::{Matrix3, RealField, SVector, SimdRealField, Vector3};

use crate::model::{Chain, Joint};
use crate::real::Real;
use crate::robot::{JointKind, Robot};

/// `for $pattern in $items $body`, with the first two items taken out of the loop. LLVM does not
/// fully unroll loops with bodies as big as a link's, so this gives chains of up to three joints
/// (the paper's leg) straight-line code: no loop and no state through memory. A macro rather
/// than a function taking a closure, which LLVM would not inline three times.
macro_rules! for_each_peeled {
    ($pattern:pat in $items:expr => $body:block) => {{
        let mut items = $items;
        if let Some($pattern) = items.next() $body
        if let Some($pattern) = items.next() $body
        for $pattern in items $body
    }};
}

/// Pose and motion of one link frame (at its joint), in world coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinkMotion<T: RealField + Copy> {
    /// Rotation from the link frame to the world frame.
    pub rotation: Matrix3<T>,
    /// World position of the joint that moves this link (the frame origin) [m].
    pub origin: Vector3<T>,
    /// World direction of that joint's axis.
    pub axis: Vector3<T>,
    /// Angular velocity of the link [rad/s].
    pub angular_velocity: Vector3<T>,
    /// Angular acceleration of the link [rad/s²].
    pub angular_acceleration: Vector3<T>,
    /// Velocity of the frame origin [m/s].
    pub velocity: Vector3<T>,
    /// Acceleration of the frame origin [m/s²].
    pub acceleration: Vector3<T>,
}

impl<T: RealField + Copy> LinkMotion<T> {
    /// World position of a point given in the link frame.
    #[inline]
    #[cfg_attr(uwml_no_panic, no_panic::no_panic)]
    pub fn point(&self, local: &Vector3<T>) -> Vector3<T> {
        self.origin + self.rotation * local
    }

    /// Velocity and acceleration of the material point at world offset `r` from the origin.
    #[inline]
    #[cfg_attr(uwml_no_panic, no_panic::no_panic)]
    pub fn point_motion(&self, r: &Vector3<T>) -> (Vector3<T>, Vector3<T>) {
        let w = &self.angular_velocity;
        let velocity = self.velocity + w.cross(r);
        let acceleration = self.acceleration + self.angular_acceleration.cross(r) + w.cross(&w.cross(r));
        (velocity, acceleration)
    }
}

/// Rotation by the angle with sine `s` and cosine `c` about the unit `axis` (Rodrigues).
#[inline(always)]
pub(crate) fn axis_angle<T: SimdRealField + Copy>(axis: &Vector3<T>, (s, c): (T, T)) -> Matrix3<T> {
    let (x, y, z) = (axis.x, axis.y, axis.z);
    let t = T::one() - c;
    Matrix3::new(
        t * x * x + c,
        t * x * y - s * z,
        t * x * z + s * y,
        t * x * y + s * z,
        t * y * y + c,
        t * y * z - s * x,
        t * x * z - s * y,
        t * y * z + s * x,
        t * z * z + c,
    )
}

impl<T: RealField + Copy> LinkMotion<T> {
    /// The first link: the world is at rest.
    #[inline(always)]
    fn first(joint: &Joint<T>, turn: (T, T), qd: T, qdd: T) -> Self {
        let still = Vector3::zeros();
        Self {
            rotation: axis_angle(&joint.axis, turn),
            origin: joint.origin,
            axis: joint.axis,
            angular_velocity: joint.axis * qd,
            angular_acceleration: joint.axis * qdd,
            velocity: still,
            acceleration: still,
        }
    }

    /// A later link, moved by `joint` relative to this one.
    #[inline(always)]
    fn child(&self, joint: &Joint<T>, turn: (T, T), qd: T, qdd: T) -> Self {
        let axis = rotate(&self.rotation, &joint.axis);
        let offset = rotate(&self.rotation, &joint.origin);
        let (velocity, acceleration) = self.point_motion(&offset);
        let w = self.angular_velocity;
        // (`rotate` column by column: nalgebra's product adds each sum to a zero first.)
        let turned = axis_angle(&joint.axis, turn);
        Self {
            rotation: Matrix3::from_columns(&[0, 1, 2].map(|j| rotate(&self.rotation, &turned.column(j).into_owned()))),
            origin: self.origin + offset,
            axis,
            angular_velocity: w + axis * qd,
            angular_acceleration: self.angular_acceleration + axis * qdd + w.cross(&axis) * qd,
            velocity,
            acceleration,
        }
    }
}

/// World pose, velocity and acceleration of every link, by the usual forward recursion.
///
/// Joints with non-finite states give non-finite motions; nothing fails.
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
pub fn link_motions<T: RealField + Copy, const N: usize>(
    chain: &Chain<T, N>,
    q: &SVector<T, N>,
    qd: &SVector<T, N>,
    qdd: &SVector<T, N>,
) -> [LinkMotion<T>; N] {
    // Arrays, not nalgebra's iterators, which cost more than the loop bodies here; all sines and
    // cosines first, as the calls are independent.
    let (q, qd, qdd): ([T; N], [T; N], [T; N]) = ((*q).into(), (*qd).into(), (*qdd).into());
    let turns = q.map(|q| q.sin_cos());
    let zero = Vector3::zeros();
    let rest = LinkMotion {
        rotation: Matrix3::identity(),
        origin: zero,
        axis: zero,
        angular_velocity: zero,
        angular_acceleration: zero,
        velocity: zero,
        acceleration: zero,
    };
    let mut motions = [rest; N];
    let mut links = motions.iter_mut().zip(chain.joints().iter()).zip(turns.into_iter().zip(qd.into_iter().zip(qdd)));
    // The first link on its own: its parent, the world, is at rest (no products with zeros).
    let Some(((motion, joint), (turn, (qd, qdd)))) = links.next() else { return motions };
    *motion = LinkMotion::first(joint, turn, qd, qdd);
    let mut parent = *motion;
    for_each_peeled!(((motion, joint), (turn, (qd, qdd))) in links => {
        *motion = parent.child(joint, turn, qd, qdd);
        parent = *motion;
    });
    motions
}

/// `a · b`, without the zero accumulator of nalgebra's generic dot.
#[inline(always)]
pub(crate) fn dot<T: SimdRealField + Copy>(a: &Vector3<T>, b: &Vector3<T>) -> T {
    a.x * b.x + a.y * b.y + a.z * b.z
}

/// `m · v`.
#[inline(always)]
pub(crate) fn rotate<T: SimdRealField + Copy>(m: &Matrix3<T>, v: &Vector3<T>) -> Vector3<T> {
    let (c0, c1, c2) = (m.column(0), m.column(1), m.column(2));
    Vector3::new(
        c0.x * v.x + c1.x * v.y + c2.x * v.z,
        c0.y * v.x + c1.y * v.y + c2.y * v.z,
        c0.z * v.x + c1.z * v.y + c2.z * v.z,
    )
}

/// `mᵀ · v`.
#[inline(always)]
pub(crate) fn rotate_back<T: SimdRealField + Copy>(m: &Matrix3<T>, v: &Vector3<T>) -> Vector3<T> {
    let (c0, c1, c2) = (m.column(0), m.column(1), m.column(2));
    Vector3::new(
        c0.x * v.x + c0.y * v.y + c0.z * v.z,
        c1.x * v.x + c1.y * v.y + c1.z * v.z,
        c2.x * v.x + c2.y * v.y + c2.z * v.z,
    )
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
