//! The regressors of a whole robot's drag and added-mass forces (docs/model.md sections 4, 10
//! and 12), by the evaluation of `crate::hydro`.

use crate::conditions::Conditions;
use crate::hydro::{RobotData, finite_lanes, hydro_in, used};
use crate::lumped::LUMPED_COLUMNS;
use crate::model::Robot;
use crate::parts::{JointKind, Owner};
use crate::real::Real;
use crate::segment_coefficients::SegmentCoefficients;
use crate::segment_forces::{axial_drag, segment_wrenches};
use crate::wrench::Wrench;

/// Regressors of the drag and added-mass forces (docs/model.md sections 4, 10 and 12): with
/// `c = robot.regressor_column_count()` and `n = robot.joint_count()`, entry `(row, column)` of
/// `drag` (row-major, `(6 + n) × c`) is the generalized force on row `row` (the base wrench's six
/// components first, then the joints) of one coefficient at unit value, the others zero; the
/// same for `added_mass`. The columns, for `s` segments:
/// - `2k + d` (`k < s`, `d < 2`): segment `k`'s drag (`cd`) and added mass (`cm`) along its
///   normal direction `d` (a circular segment has all of it in `d = 0`, and zeros in `d = 1`);
/// - `2s + k`: segment `k`'s axial drag (`cd_axial`, docs/model.md section 12.2; zero where its
///   `axial_area` is), in `drag` only;
/// - `3s + 63b + i` (`i < `[`LUMPED_COLUMNS`]): entry `i` of the robot's lumped model `b`, in
///   the order the models were added (section 12.1; the layout of [`LUMPED_COLUMNS`]), its added
///   mass in `added_mass`, its damping in `drag`.
///
/// So the drag forces at given coefficients are `Σ_column coefficient · drag[row, column]`, and
/// the hydrodynamic forces are those sums for drag and added mass plus the buoyancy of
/// [`RobotData::joint_forces`] and [`RobotData::base_wrench`], which this also evaluates into
/// `data`. Outputs shorter than `(6 + n) · c` get what fits. Never fails, never panics.
/// The regressors depend on the conditions' water, motion, current and added-mass form (both
/// forms' forces are linear in the coefficients); not on its coefficients or losses.
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
pub fn robot_hydro_regressors<T: Real, const J: usize, const S: usize, const B: usize>(
    robot: &Robot<T, J, S, B>,
    conditions: &Conditions<'_, T, J, S>,
    state: [&[T; J]; 3],
    data: &mut RobotData<T, J>,
    drag: &mut [T],
    added_mass: &mut [T],
) {
    let columns = robot.regressor_column_count();
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
/// for every row (the base wrench's six components, then the joints) of every column (the
/// layout of [`robot_hydro_regressors`]), NaN in a non-finite state's lanes. Evaluates `data` at
/// zero coefficients (buoyancy and gravity) first.
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
    let data = &*data;
    let rho = water.density();
    // One column's wrench on its body: every row, up the tree from the body to the base.
    let mut put_column = |kind: Column, column: usize, owner: Option<usize>, mut wrench: Wrench<T>| {
        let mut put = |row: usize, value: T| put_entry(kind, row, column, value.select(finite, nan));
        // Every joint: zero, unless it moves the body.
        for j in 0..n {
            put(6 + j, T::zero());
        }
        // Up the tree from the owner, in each joint's body frame, to the base's.
        let mut ancestor = owner;
        while let Some(j) = ancestor {
            let (Some(joint), Some(joint_frame), Some(geometry)) =
                (robot.joints().get(j), data.frames.get(j), robot.frames().joints.get(j))
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
    };
    let body = |owner: Owner| match owner {
        Owner::Base => Some((&base, None)),
        Owner::Link(i) => data.frames.get(i).map(|frame| (frame, Some(i))),
    };
    let (one, nothing) = (T::one(), T::zero());
    let segments = robot.segments();
    let s = segments.len();
    for (k, (segment, geometry)) in segments.iter().zip(&robot.frames().segments).enumerate() {
        let Some((frame, owner)) = body(segment.owner) else { continue };
        for (d, unit) in [[one, nothing], [nothing, one]].into_iter().enumerate() {
            let (drag, added_mass) = segment_wrenches(frame, segment, geometry, unit, unit, rho, form);
            put_column(Column::Drag, 2 * k + d, owner, drag);
            put_column(Column::AddedMass, 2 * k + d, owner, added_mass);
        }
        put_column(Column::Drag, 2 * s + k, owner, axial_drag(frame, segment, geometry, one, rho));
        put_column(Column::AddedMass, 2 * s + k, owner, Wrench::zero());
    }
    for (b, (model_owner, model)) in robot.lumped().iter().enumerate() {
        let Some((frame, owner)) = body(*model_owner) else { continue };
        let first = 3 * s + LUMPED_COLUMNS * b;
        model.unit_wrenches(frame.twist_at(&model.point), |i, is_added_mass, wrench| {
            let (this, other) =
                if is_added_mass { (Column::AddedMass, Column::Drag) } else { (Column::Drag, Column::AddedMass) };
            put_column(this, first + i, owner, wrench);
            put_column(other, first + i, owner, Wrench::zero());
        });
    }
}
