//! Forward kinematics of the chain: world pose, velocity and acceleration of every link frame.

use nalgebra::{Matrix3, RealField, SVector, Vector3};

use crate::model::Chain;

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
    const fn at_rest(rotation: Matrix3<T>, origin: Vector3<T>, axis: Vector3<T>, zero: Vector3<T>) -> Self {
        Self {
            rotation,
            origin,
            axis,
            angular_velocity: zero,
            angular_acceleration: zero,
            velocity: zero,
            acceleration: zero,
        }
    }

    /// World position of a point given in the link frame.
    #[inline]
    pub fn point(&self, local: &Vector3<T>) -> Vector3<T> {
        self.origin + self.rotation * local
    }

    /// Velocity and acceleration of the material point at world offset `r` from the origin.
    #[inline]
    pub fn point_motion(&self, r: &Vector3<T>) -> (Vector3<T>, Vector3<T>) {
        let w = &self.angular_velocity;
        let velocity = self.velocity + w.cross(r);
        let acceleration = self.acceleration + self.angular_acceleration.cross(r) + w.cross(&w.cross(r));
        (velocity, acceleration)
    }
}

/// Rotation by `angle` about the unit `axis` (Rodrigues).
#[inline]
fn axis_angle<T: RealField + Copy>(axis: &Vector3<T>, angle: T) -> Matrix3<T> {
    let (s, c) = angle.sin_cos();
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

/// World pose, velocity and acceleration of every link, by the usual forward recursion.
///
/// Joints with non-finite states give non-finite motions; nothing fails.
pub fn link_motions<T: RealField + Copy, const N: usize>(
    chain: &Chain<T, N>,
    q: &SVector<T, N>,
    qd: &SVector<T, N>,
    qdd: &SVector<T, N>,
) -> [LinkMotion<T>; N] {
    let zero = Vector3::zeros();
    let mut parent = LinkMotion::at_rest(Matrix3::identity(), zero, zero, zero);
    let mut motions = [parent; N];
    let states = q.iter().zip(qd.iter()).zip(qdd.iter());
    for ((motion, joint), ((&q, &qd), &qdd)) in motions.iter_mut().zip(chain.joints().iter()).zip(states) {
        let axis = parent.rotation * joint.axis;
        let origin = parent.point(&joint.origin);
        let (velocity, acceleration) = parent.point_motion(&(origin - parent.origin));
        let w = parent.angular_velocity;
        *motion = LinkMotion {
            rotation: parent.rotation * axis_angle(&joint.axis, q),
            origin,
            axis,
            angular_velocity: w + axis * qd,
            angular_acceleration: parent.angular_acceleration + axis * qdd + w.cross(&axis) * qd,
            velocity,
            acceleration,
        };
        parent = *motion;
    }
    motions
}
