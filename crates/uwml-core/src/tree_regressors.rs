//! The regressors of a whole robot's drag and added-mass forces (docs/model.md sections 4 and
//! 10), by the evaluation of `crate::tree`.

use crate::conditions::Conditions;
use crate::real::Real;
use crate::robot::{JointKind, Owner, Robot, SegmentCoefficients};
use crate::segment_forces::segment_wrenches;
use crate::tree::{RobotData, finite_lanes, hydro_in, used};

/// Regressors of the drag and added-mass forces (docs/model.md sections 4 and 10, for whole
/// robots): with `s = robot.segments().len()` and `n = robot.joint_count()`, entry `(row, 2k + d)` of `drag`
/// (row-major, `(6 + n) × 2s`) is the generalized force on row `row` (the base wrench's six
/// components first, then the joints) of segment `k`'s drag along its normal direction `d` at
/// unit coefficient (a circular segment has all of it in `d = 0`, and zeros in `d = 1`); the
/// same for `added_mass`. So the drag forces at coefficients `cd` are `Σ_{k,d} cd[k][d] ·
/// drag[row, 2k + d]`, and the hydrodynamic forces are those two sums plus the buoyancy of
/// [`RobotData::joint_forces`] and [`RobotData::base_wrench`], which this also evaluates into
/// `data`. Outputs shorter than `(6 + n) · 2s` get what fits. Never fails, never panics.
/// The regressors depend on the conditions' water, motion, current and added-mass form (both
/// forms' forces are linear in the coefficients); not on its coefficients or losses. A robot's
/// lumped models (docs/model.md section 12.1) and its segments' axial drag (12.2) have no columns
/// here: their forces are in `data`'s drag and added mass (evaluated at zero segment
/// coefficients), to be added to the sums.
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
pub fn robot_hydro_regressors<T: Real, const J: usize, const S: usize, const B: usize>(
    robot: &Robot<T, J, S, B>,
    conditions: &Conditions<'_, T, J, S>,
    state: [&[T; J]; 3],
    data: &mut RobotData<T, J>,
    drag: &mut [T],
    added_mass: &mut [T],
) {
    let columns = 2 * robot.segments().len();
    regressor_columns(robot, conditions, state, data, |kind, row, column, value| {
        let out = match kind {
            Column::Drag => &mut *drag,
            Column::AddedMass => &mut *added_mass,
        };
        if let Some(slot) = out.get_mut(row * columns + column) {
            *slot = value;
        }
    });
}

/// Which regressor an entry belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Column {
    Drag,
    AddedMass,
}

/// The regressors of [`robot_hydro_regressors`], entry by entry: `put(kind, row, column, value)`
/// for every row (the base wrench's six components, then the joints) of every column
/// (`2k + d`: segment `k`, normal direction `d`), NaN in a non-finite state's lanes. Evaluates
/// `data` at zero coefficients (buoyancy and gravity) first.
#[inline(always)]
pub(crate) fn regressor_columns<T: Real, const J: usize, const S: usize, const B: usize>(
    robot: &Robot<T, J, S, B>,
    conditions: &Conditions<'_, T, J, S>,
    state: [&[T; J]; 3],
    data: &mut RobotData<T, J>,
    mut put_entry: impl FnMut(Column, usize, usize, T),
) {
    let zero = [[T::zero(); 2]; S];
    let none = SegmentCoefficients { cd: zero, cm: zero };
    let (water, form) = (conditions.water, conditions.form);
    hydro_in(robot, &Conditions { coefficients: Some(&none), ..*conditions }, state, data);
    let [q, qd, qdd] = state;
    let n = robot.joint_count();
    let finite = finite_lanes(&[used(q, n), used(qd, n), used(qdd, n)]);
    let nan = T::zero() / T::zero();
    let base = data.base_frame;
    let frames = robot.frames();
    let (one, nothing) = (T::one(), T::zero());
    for (k, (segment, geometry)) in robot.segments().iter().zip(&frames.segments).enumerate() {
        let (frame, owner) = match segment.owner {
            Owner::Base => (&base, None),
            Owner::Link(i) => match data.frames.get(i) {
                Some(frame) => (frame, Some(i)),
                None => continue,
            },
        };
        for (d, unit) in [[one, nothing], [nothing, one]].into_iter().enumerate() {
            let wrenches = segment_wrenches(frame, segment, geometry, unit, unit, water.density(), form);
            let column = 2 * k + d;
            for (kind, mut wrench) in [(Column::Drag, wrenches.0), (Column::AddedMass, wrenches.1)] {
                let mut put = |row: usize, value: T| put_entry(kind, row, column, value.select(finite, nan));
                // Every joint: zero, unless it moves the segment's body.
                for j in 0..n {
                    put(6 + j, T::zero());
                }
                // Up the tree from the owner, in each joint's body frame, to the base's.
                let mut ancestor = owner;
                while let Some(j) = ancestor {
                    let (Some(joint), Some(joint_frame), Some(geometry)) =
                        (robot.joints().get(j), data.frames.get(j), frames.joints.get(j))
                    else {
                        break;
                    };
                    put(
                        6 + j,
                        match joint.kind {
                            JointKind::Revolute => wrench.moment.z,
                            JointKind::Prismatic => wrench.force.z,
                        },
                    );
                    let force = joint_frame.in_parent(joint.kind, geometry, &wrench.force);
                    let moment = joint_frame.in_parent(joint.kind, geometry, &wrench.moment);
                    wrench.force = force;
                    wrench.moment = moment + joint_frame.offset.cross(&force);
                    // Parents come before children: the walk ends.
                    ancestor = joint.parent.filter(|&p| p < j);
                }
                for (row, value) in wrench.to_array().into_iter().enumerate() {
                    put(row, value);
                }
            }
        }
    }
}
