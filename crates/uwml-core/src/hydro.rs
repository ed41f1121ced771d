//! Drag, added-mass, buoyancy and gravity generalized forces of a chain in still water, and
//! their identification regressors (docs/model.md sections 3 and 4): a convenience for a serial
//! chain on a fixed base, which is the whole-robot evaluation ([`crate::tree::robot_hydro`]) of
//! the chain's robot ([`Chain::robot`]) with the chain's coefficients, in the chain's types.
//!
//! Sign: every torque is exerted by the environment on the joint, in the joint's positive
//! direction (`M q̈ + c + g = τ_motor + τ_env`).

use nalgebra::{SVector, SimdBool, SimdRealField};

use crate::conditions::Conditions;
use crate::model::{Chain, Coefficients, Water};
use crate::real::Real;
use crate::robot::Owner;
use crate::robot::SegmentCoefficients;
use crate::tree::{JointForces, RobotData, finite_lanes, hydro_in};
use crate::tree_regressors::{Column, regressor_columns};

/// The environment's generalized forces on every joint [N·m].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HydroTorques<T: SimdRealField + Copy, const N: usize> {
    /// Drag (Morison, quadratic in velocity); `q̇ · drag ≤ 0`.
    pub drag: SVector<T, N>,
    /// Added mass (reaction of the accelerated water).
    pub added_mass: SVector<T, N>,
    /// Buoyancy at the centres of buoyancy.
    pub buoyancy: SVector<T, N>,
    /// Gravity of the links at their centres of mass (not part of [`HydroTorques::total`]).
    pub gravity: SVector<T, N>,
}

impl<T: SimdRealField + Copy, const N: usize> HydroTorques<T, N> {
    /// `drag + added_mass + buoyancy`: the paper's `τ_w`.
    #[must_use]
    #[cfg_attr(uwml_no_panic, no_panic::no_panic)]
    pub fn total(&self) -> SVector<T, N> {
        self.drag + self.added_mass + self.buoyancy
    }

    /// Every torque vector mapped by `f`: one lane of SIMD torques, say, or a mask applied.
    #[must_use]
    #[inline(always)]
    pub fn map<U: SimdRealField + Copy>(&self, f: impl Fn(&SVector<T, N>) -> SVector<U, N>) -> HydroTorques<U, N> {
        HydroTorques {
            drag: f(&self.drag),
            added_mass: f(&self.added_mass),
            buoyancy: f(&self.buoyancy),
            gravity: f(&self.gravity),
        }
    }
}

/// The terms of `τ_hydro = buoyancy + Σ Cd[l][k]·drag[l][k] + Σ Cm[l][k]·added_mass[l][k]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HydroRegressors<T: SimdRealField + Copy, const N: usize> {
    /// Buoyancy torques.
    pub buoyancy: SVector<T, N>,
    /// Gravity torques (not part of `τ_hydro`).
    pub gravity: SVector<T, N>,
    /// `drag[l][k]`: torques on every joint from link `l`'s drag along its normal `k`, at Cd = 1.
    pub drag: [[SVector<T, N>; 2]; N],
    /// `added_mass[l][k]`: the same for added mass, at Cm = 1.
    pub added_mass: [[SVector<T, N>; 2]; N],
}

fn contract<T: SimdRealField + Copy, const N: usize>(
    columns: &[[SVector<T, N>; 2]; N],
    coefficients: &[[T; 2]; N],
) -> SVector<T, N> {
    let mut sum = SVector::<T, N>::zeros();
    for (link, c) in columns.iter().zip(coefficients.iter()) {
        for (column, &c) in link.iter().zip(c.iter()) {
            sum.axpy(c, column, T::one());
        }
    }
    sum
}

fn sum_columns<T: SimdRealField + Copy, const N: usize>(columns: &[[SVector<T, N>; 2]; N]) -> SVector<T, N> {
    columns.iter().flatten().fold(SVector::zeros(), |acc, column| acc + column)
}

impl<T: SimdRealField + Copy, const N: usize> HydroRegressors<T, N> {
    /// Every column mapped by `f` (see [`HydroTorques::map`]).
    #[must_use]
    #[inline(always)]
    pub fn map<U: SimdRealField + Copy>(&self, f: impl Fn(&SVector<T, N>) -> SVector<U, N>) -> HydroRegressors<U, N> {
        let columns = |c: &[[SVector<T, N>; 2]; N]| c.each_ref().map(|c| c.each_ref().map(&f));
        HydroRegressors {
            buoyancy: f(&self.buoyancy),
            gravity: f(&self.gravity),
            drag: columns(&self.drag),
            added_mass: columns(&self.added_mass),
        }
    }

    /// The torques for the given coefficients.
    #[must_use]
    #[cfg_attr(uwml_no_panic, no_panic::no_panic)]
    pub fn apply(&self, coefficients: &Coefficients<T, N>) -> HydroTorques<T, N> {
        HydroTorques {
            drag: contract(&self.drag, coefficients.cd()),
            added_mass: contract(&self.added_mass, coefficients.cm()),
            buoyancy: self.buoyancy,
            gravity: self.gravity,
        }
    }

    /// The paper's drag regressor `R_d = −α`: drag torques with Cd = 1 everywhere.
    #[must_use]
    #[cfg_attr(uwml_no_panic, no_panic::no_panic)]
    pub fn drag_uniform(&self) -> SVector<T, N> {
        sum_columns(&self.drag)
    }

    /// The paper's added-mass regressor `R_m = −β`: added-mass torques with Cm = 1 everywhere.
    #[must_use]
    #[cfg_attr(uwml_no_panic, no_panic::no_panic)]
    pub fn added_mass_uniform(&self) -> SVector<T, N> {
        sum_columns(&self.added_mass)
    }
}

/// The robot evaluation of the chain at `(q, q̇, q̈)` with the segments' coefficients `table`.
#[inline(always)]
fn evaluate<T: Real, const N: usize>(
    chain: &Chain<T, N>,
    water: &Water<T>,
    table: &SegmentCoefficients<T, N>,
    [q, qd, qdd]: [&SVector<T, N>; 3],
) -> RobotData<T, N> {
    let mut data = RobotData::new();
    let conditions = Conditions { coefficients: Some(table), ..Conditions::new(*water) };
    let state = |v: &SVector<T, N>| -> [T; N] { (*v).into() };
    hydro_in(chain.robot(), &conditions, [&state(q), &state(qd), &state(qdd)], &mut data);
    data
}

/// One component of every joint's forces, as a vector.
#[inline(always)]
fn each<T: SimdRealField + Copy, const N: usize>(
    data: &RobotData<T, N>,
    f: impl Fn(&JointForces<T>) -> T,
) -> SVector<T, N> {
    let mut column = [T::zero(); N];
    for (slot, forces) in column.iter_mut().zip(data.joint_forces()) {
        *slot = f(forces);
    }
    column.into()
}

/// Regressors of the hydrodynamic torques at joint state `(q, q̇, q̈)`, one column per link
/// and normal direction: the chain's robot's regressors ([`crate::tree::robot_hydro_regressors`]),
/// each segment's columns given to the link that carries it. For the torques at given
/// coefficients, [`hydro_torques`] is faster.
///
/// Never fails and never panics; non-finite states give NaN.
#[must_use]
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
pub fn hydro_regressors<T: Real, const N: usize>(
    chain: &Chain<T, N>,
    water: &Water<T>,
    q: &SVector<T, N>,
    qd: &SVector<T, N>,
    qdd: &SVector<T, N>,
) -> HydroRegressors<T, N> {
    let robot = chain.robot();
    let mut data = RobotData::new();
    let state = |v: &SVector<T, N>| -> [T; N] { (*v).into() };
    let zeros = SVector::<T, N>::zeros();
    let (mut drag, mut added_mass) = ([[zeros; 2]; N], [[zeros; 2]; N]);
    let conditions = Conditions::new(*water);
    // Non-finite lanes: NaN in every column, those of links without a segment too.
    let finite = finite_lanes(&[q.as_slice(), qd.as_slice(), qdd.as_slice()]);
    let nan = T::zero() / T::zero();
    if !finite.all() {
        for column in drag.iter_mut().chain(added_mass.iter_mut()).flatten() {
            *column = column.map(|x| x.select(finite, nan));
        }
    }
    regressor_columns(
        robot,
        &conditions,
        [&state(q), &state(qd), &state(qdd)],
        &mut data,
        |kind, row, column, value| {
            let (Some(joint), Some(segment)) = (row.checked_sub(6), robot.segments().get(column / 2)) else { return };
            let Owner::Link(link) = segment.owner else { return };
            let out = match kind {
                Column::Drag => &mut drag,
                Column::AddedMass => &mut added_mass,
            };
            if let Some(slot) = out.get_mut(link).and_then(|l| l.get_mut(column % 2)).and_then(|c| c.get_mut(joint)) {
                *slot = value;
            }
        },
    );
    HydroRegressors { buoyancy: each(&data, |f| f.buoyancy), gravity: each(&data, |f| f.gravity), drag, added_mass }
}

/// Drag, added-mass, buoyancy and gravity torques at joint state `(q, q̇, q̈)`: the chain's
/// robot evaluated with these coefficients.
///
/// Never fails and never panics; non-finite states give NaN.
#[must_use]
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
pub fn hydro_torques<T: Real, const N: usize>(
    chain: &Chain<T, N>,
    water: &Water<T>,
    coefficients: &Coefficients<T, N>,
    q: &SVector<T, N>,
    qd: &SVector<T, N>,
    qdd: &SVector<T, N>,
) -> HydroTorques<T, N> {
    let data = evaluate(chain, water, &chain.robot().link_coefficients(coefficients), [q, qd, qdd]);
    HydroTorques {
        drag: each(&data, |f| f.drag),
        added_mass: each(&data, |f| f.added_mass),
        buoyancy: each(&data, |f| f.buoyancy),
        gravity: each(&data, |f| f.gravity),
    }
}
