//! Forward kinematics of a point on a link, and the chain's geometric Jacobian at that point.

use nalgebra::{RealField, SMatrix, SVector, Vector3};

use crate::kinematics::link_motions;
use crate::model::Chain;

/// World position of `point` (given in the frame of link `link`) and the geometric Jacobian
/// there, or `None` if `link >= N`.
///
/// Column `j` of the Jacobian maps `q̇_j` to the point's velocity: rows 0-2 are the linear part
/// `z_j × (p − o_j)`, rows 3-5 the angular part `z_j` (the link's angular velocity is the sum of
/// the angular parts), with `z_j` and `o_j` joint `j`'s world axis and origin. Joints after
/// `link` do not move the point: their columns are zero. Non-finite angles give non-finite
/// results; nothing fails.
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
pub fn point_jacobian<T: RealField + Copy, const N: usize>(
    chain: &Chain<T, N>,
    q: &SVector<T, N>,
    link: usize,
    point: &Vector3<T>,
) -> Option<(Vector3<T>, SMatrix<T, 6, N>)> {
    let still = SVector::zeros();
    let motions = link_motions(chain, q, &still, &still);
    let position = motions.get(link)?.point(point);
    let mut jacobian = SMatrix::<T, 6, N>::zeros();
    for (mut column, motion) in jacobian.column_iter_mut().zip(motions.iter()).take(link + 1) {
        let axis = motion.axis;
        column.fixed_rows_mut::<3>(0).copy_from(&axis.cross(&(position - motion.origin)));
        column.fixed_rows_mut::<3>(3).copy_from(&axis);
    }
    Some((position, jacobian))
}
