//! The kinematics of a robot for `uwml.Leg.jacobian` and `forward_kinematics`: every sample's
//! position and geometric Jacobian of a point on a link, by the core's free functions
//! (`uwml_core::forward_kinematics` and `point_jacobian`) over the model and a workspace.

use uwml_core::nalgebra::Vector3;
use uwml_core::{KinematicsData, forward_kinematics, point_jacobian};

use super::{MAX_ROBOT_JOINTS, Model};
use crate::NonFinite;

/// Positions `n_samples × 3` and Jacobians `n_samples × 6 × n` (row-major, `n` the robot's
/// joints) of `point`, given in link `link`'s frame (a link of the robot), at the joint positions
/// `q` (`n_samples × n`).
pub(super) fn jacobian_batch(
    robot: &Model,
    q: &[f64],
    link: usize,
    point: &Vector3<f64>,
) -> Result<(Vec<f64>, Vec<f64>), NonFinite> {
    let n = robot.joint_count().max(1);
    if let Some(index) = q.iter().position(|v| !v.is_finite()) {
        let value = q.get(index).copied().unwrap_or(f64::NAN);
        return Err(NonFinite { argument: "q", sample: index / n, joint: index % n, value });
    }
    let n_samples = q.len() / n;
    let (mut positions, mut jacobians) = (Vec::with_capacity(n_samples * 3), Vec::with_capacity(n_samples * 6 * n));
    let mut data = Box::new(KinematicsData::<f64, MAX_ROBOT_JOINTS>::new());
    let (mut angles, mut jacobian) = ([0.0; MAX_ROBOT_JOINTS], vec![0.0; 6 * n]);
    for row in q.chunks_exact(n) {
        for (slot, &angle) in angles.iter_mut().zip(row) {
            *slot = angle;
        }
        forward_kinematics(robot, &angles, &mut data);
        if let Some(position) = point_jacobian(robot, &data, link, point, &mut jacobian) {
            positions.extend(position.iter());
            jacobians.extend_from_slice(&jacobian);
        }
    }
    Ok((positions, jacobians))
}
