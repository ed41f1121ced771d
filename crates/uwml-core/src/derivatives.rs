//! Derivatives of a whole robot's environment forces for control (docs/model.md sections 9 and 10;
//! the losses of docs/losses.md, "The models"): the generalized forces on the base (its wrench) and
//! on the joints, their derivatives with respect to the joint positions and to the velocities (base
//! twist and joint rates), and the added-mass matrix, by forward-mode dual numbers ([`Dual`])
//! through the very same [`robot_hydro`] (its joint losses included).
//!
//! Rows are `(W, τ)`: the base wrench's six components (force, moment about the base origin,
//! base frame) then the joints. Columns of `d_velocity` are `(ν, q̇)`: the base twist (`v`, `ω`,
//! base components) then the joint rates. The dual numbers are [`DUAL_WIDTH`] wide; the `2n + 6`
//! directions are taken in passes of that many, so the cost grows with the robot, not with the
//! capacity.

use nalgebra::{RealField, SimdRealField};

use crate::added_mass::robot_added_mass_matrix;
use crate::conditions::Conditions;
use crate::dual::Dual;
use crate::hydro::{RobotData, robot_hydro};
use crate::model::Robot;
use crate::real::Real;

/// Derivative directions per dual pass.
pub const DUAL_WIDTH: usize = 8;

type D<T> = Dual<T, DUAL_WIDTH>;

/// The workspace of [`robot_jacobians`]: the robot over dual numbers (made once, by
/// [`RobotJacobianData::new`]) and the evaluations' data. Large for a large capacity (the
/// robot's every number `DUAL_WIDTH + 1` times): keep one, on the heap where stacks are small.
#[derive(Clone, Debug)]
pub struct RobotJacobianData<T: RealField + Copy, const J: usize, const S: usize, const B: usize = 0> {
    robot: Robot<D<T>, J, S, B>,
    dual: RobotData<D<T>, J>,
    /// The value's own evaluation (see [`robot_jacobians`]).
    plain: RobotData<T, J>,
}

impl<T: RealField + Copy, const J: usize, const S: usize, const B: usize> RobotJacobianData<T, J, S, B> {
    /// The workspace for `robot` (and only for it).
    #[must_use]
    pub fn new(robot: &Robot<T, J, S, B>) -> Self {
        Self { robot: robot.map_scalars(Dual::constant), dual: RobotData::new(), plain: RobotData::new() }
    }
}

/// Where [`robot_jacobians`] writes, each row-major with `m = 6 + n` rows (`n` joints).
pub struct RobotJacobians<'a, T> {
    /// `(W, τ)` at the state, hydrodynamics plus joint losses (`m`).
    pub value: &'a mut [T],
    /// `∂(W, τ)/∂q` (`m × n`).
    pub d_q: &'a mut [T],
    /// `∂(W, τ)/∂(ν, q̇)` (`m × m`).
    pub d_velocity: &'a mut [T],
    /// The added-mass matrix `M_A = −∂(W, τ)/∂(ν̇, q̈)` (`m × m`), as [`robot_added_mass_matrix`].
    pub added_mass_matrix: &'a mut [T],
}

/// The environment's forces on base and joints, `(W, τ) = hydro (+ joint losses on τ)`, and
/// their derivatives, into `out` (see [`RobotJacobians`]); arguments as for [`robot_hydro`] (the
/// losses those of `conditions`). The added-mass matrix is the same for both added-mass forms.
///
/// The derivatives are exact (up to rounding) for the branch the evaluation takes; at a joint
/// speed of exactly zero with a hard-sign loss model they are one-sided. Outputs shorter than
/// their sizes get what fits. Never fails, never panics.
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
pub fn robot_jacobians<T: RealField + Real, const J: usize, const S: usize, const B: usize>(
    robot: &Robot<T, J, S, B>,
    conditions: &Conditions<'_, T, J, S>,
    [q, qd, qdd]: [&[T; J]; 3],
    work: &mut RobotJacobianData<T, J, S, B>,
    out: RobotJacobians<'_, T>,
) {
    let Conditions { water, motion, current, coefficients, form, losses } = *conditions;
    let n = robot.joint_count();
    let m = 6 + n;
    let constant = D::<T>::constant;
    let water_d = water.map_scalars(constant);
    let coefficients_d = coefficients.map(|c| c.map_scalars(constant));
    let no_losses = [None; J];
    let losses_d = losses.unwrap_or(&no_losses).map(|state| state.map(|state| state.map_scalars(constant)));
    let current_d = current.map_scalars(constant);
    let motion_d = motion.map_scalars(constant);
    let qdd_d = qdd.map(constant);
    // Direction `k`: q_k for k < n, then ν_{k − n} (6), then q̇_{k − n − 6}.
    let directions = n + m;
    let mut start = 0;
    while start < directions {
        let seed = |k: usize, x: T| match k.checked_sub(start) {
            Some(slot) if slot < DUAL_WIDTH => Dual::variable(x, slot),
            _ => constant(x),
        };
        let q_d: [D<T>; J] = core::array::from_fn(|j| seed(j, q.get(j).copied().unwrap_or(T::zero())));
        let qd_d: [D<T>; J] = core::array::from_fn(|j| seed(n + 6 + j, qd.get(j).copied().unwrap_or(T::zero())));
        let mut motion_seeded = motion_d;
        for (i, slot) in motion_seeded.velocity.iter_mut().chain(motion_seeded.angular_velocity.iter_mut()).enumerate()
        {
            *slot = seed(n + i, slot.re);
        }
        let dual_conditions = Conditions {
            water: water_d,
            motion: motion_seeded,
            current: current_d,
            coefficients: coefficients_d.as_ref(),
            form,
            losses: Some(&losses_d),
        };
        robot_hydro(&work.robot, &dual_conditions, [&q_d, &qd_d, &qdd_d], &mut work.dual);
        for (row, value) in generalized_forces(&work.dual).enumerate() {
            for (slot, derivative) in value.eps.iter().enumerate() {
                let k = start + slot;
                let target = if k < n {
                    out.d_q.get_mut(row * n + k)
                } else if k < directions {
                    out.d_velocity.get_mut(row * m + k - n)
                } else {
                    None
                };
                if let Some(target) = target {
                    *target = *derivative;
                }
            }
        }
        start += DUAL_WIDTH;
    }
    // The value by the plain evaluation, bit for bit `robot_hydro`'s: the dual passes seed the
    // base's twist, so they never take the shortcut of a base at rest in still water, whose
    // value can differ in the last bits.
    robot_hydro(robot, conditions, [q, qd, qdd], &mut work.plain);
    for (slot, value) in out.value.iter_mut().zip(generalized_forces(&work.plain)) {
        *slot = value;
    }
    robot_added_mass_matrix(robot, &water, coefficients, q, out.added_mass_matrix);
}

/// `(W, τ)` of an evaluation: the base wrench's hydrodynamic total (six components), then each
/// joint's, its losses' oil drag and seal friction added.
fn generalized_forces<U: SimdRealField + Copy, const J: usize>(data: &RobotData<U, J>) -> impl Iterator<Item = U> + '_ {
    let base = data.base_wrench().total().to_array();
    let joints = data.joint_forces().iter().zip(data.joint_losses()).map(|(f, l)| f.total() + l.visc + l.seal);
    base.into_iter().chain(joints)
}
