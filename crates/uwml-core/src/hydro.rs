//! Drag, added-mass, buoyancy and gravity generalized forces of a chain in still water, and
//! their identification regressors, in one pass (MODEL.md sections 3 and 4).
//!
//! Sign: every torque is exerted by the environment on the joint, in the joint's positive
//! direction (`M q̈ + c + g = τ_motor + τ_env`).

use nalgebra::{RealField, SVector};

use crate::kinematics::link_motions;
use crate::model::{Chain, Coefficients, Water, constant};
use crate::strip::{added_mass_moments, drag_moments};

/// The environment's generalized forces on every joint [N·m].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HydroTorques<T: RealField + Copy, const N: usize> {
    /// Drag (Morison, quadratic in velocity); `q̇ · drag ≤ 0`.
    pub drag: SVector<T, N>,
    /// Added mass (reaction of the accelerated water).
    pub added_mass: SVector<T, N>,
    /// Buoyancy at the centres of buoyancy.
    pub buoyancy: SVector<T, N>,
    /// Gravity of the links at their centres of mass (not part of [`HydroTorques::total`]).
    pub gravity: SVector<T, N>,
}

impl<T: RealField + Copy, const N: usize> HydroTorques<T, N> {
    /// `drag + added_mass + buoyancy`: the paper's `τ_w`.
    #[must_use]
    pub fn total(&self) -> SVector<T, N> {
        self.drag + self.added_mass + self.buoyancy
    }
}

/// The terms of `τ_hydro = buoyancy + Σ Cd[l][k]·drag[l][k] + Σ Cm[l][k]·added_mass[l][k]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HydroRegressors<T: RealField + Copy, const N: usize> {
    /// Buoyancy torques.
    pub buoyancy: SVector<T, N>,
    /// Gravity torques (not part of `τ_hydro`).
    pub gravity: SVector<T, N>,
    /// `drag[l][k]`: torques on every joint from link `l`'s drag along its normal `k`, at Cd = 1.
    pub drag: [[SVector<T, N>; 2]; N],
    /// `added_mass[l][k]`: the same for added mass, at Cm = 1.
    pub added_mass: [[SVector<T, N>; 2]; N],
}

fn contract<T: RealField + Copy, const N: usize>(
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

fn sum_columns<T: RealField + Copy, const N: usize>(
    columns: &[[SVector<T, N>; 2]; N],
) -> SVector<T, N> {
    columns
        .iter()
        .flatten()
        .fold(SVector::zeros(), |acc, column| acc + column)
}

impl<T: RealField + Copy, const N: usize> HydroRegressors<T, N> {
    /// The torques for the given coefficients.
    #[must_use]
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
    pub fn drag_uniform(&self) -> SVector<T, N> {
        sum_columns(&self.drag)
    }

    /// The paper's added-mass regressor `R_m = −β`: added-mass torques with Cm = 1 everywhere.
    #[must_use]
    pub fn added_mass_uniform(&self) -> SVector<T, N> {
        sum_columns(&self.added_mass)
    }
}

/// Regressors of the hydrodynamic torques at joint state `(q, q̇, q̈)`, in one pass over the chain.
///
/// Never fails and never panics; non-finite states give non-finite torques.
#[must_use]
pub fn hydro_regressors<T: RealField + Copy, const N: usize>(
    chain: &Chain<T, N>,
    water: &Water<T>,
    q: &SVector<T, N>,
    qd: &SVector<T, N>,
    qdd: &SVector<T, N>,
) -> HydroRegressors<T, N> {
    let motions = link_motions(chain, q, qd, qdd);
    let rho = water.density();
    let g = water.gravity();
    let half = constant::<T>(0.5);
    let zeros = SVector::<T, N>::zeros();
    let mut out = HydroRegressors {
        buoyancy: zeros,
        gravity: zeros,
        drag: [[zeros; 2]; N],
        added_mass: [[zeros; 2]; N],
    };

    let columns = out.drag.iter_mut().zip(out.added_mass.iter_mut());
    for (i, ((link, motion), (drag, added_mass))) in chain
        .links()
        .iter()
        .zip(motions.iter())
        .zip(columns)
        .enumerate()
    {
        // Joints 0..=i move link i; the later ones do not.
        let movers = motions.iter().take(i + 1);

        let cob = motion.point(&link.cob);
        let com = motion.point(&link.com);
        let lift = rho * link.volume * g;
        let weight = link.mass * g;
        for ((b, w), joint) in out
            .buoyancy
            .iter_mut()
            .zip(out.gravity.iter_mut())
            .zip(movers.clone())
        {
            *b += lift * joint.axis.cross(&(cob - joint.origin)).z;
            *w -= weight * joint.axis.cross(&(com - joint.origin)).z;
        }

        let Some(segment) = &link.segment else {
            continue;
        };
        let start = motion.point(&segment.start);
        let axis = motion.rotation * segment.axis;
        let (v_start, a_start) = motion.point_motion(&(start - motion.origin));
        let v_slope = motion.angular_velocity.cross(&axis);
        let a_slope =
            motion.angular_acceleration.cross(&axis) + motion.angular_velocity.cross(&v_slope);

        let directions = segment.normals.iter().zip(segment.widths.iter());
        for ((normal, &width), (drag, added_mass)) in
            directions.zip(drag.iter_mut().zip(added_mass.iter_mut()))
        {
            let n = motion.rotation * normal;
            let (i0, i1) = drag_moments(n.dot(&v_start), n.dot(&v_slope), segment.length);
            let (j0, j1) = added_mass_moments(n.dot(&a_start), n.dot(&a_slope), segment.length);
            let drag_scale = -half * rho * width;
            let added_mass_scale = -rho * segment.area;
            for ((d, a), joint) in drag
                .iter_mut()
                .zip(added_mass.iter_mut())
                .zip(movers.clone())
            {
                // Moment arm of the force along n about joint j: g0 + g1·s.
                let g0 = n.dot(&joint.axis.cross(&(start - joint.origin)));
                let g1 = n.dot(&joint.axis.cross(&axis));
                *d = drag_scale * (g0 * i0 + g1 * i1);
                *a = added_mass_scale * (g0 * j0 + g1 * j1);
            }
        }
    }
    out
}

/// Drag, added-mass, buoyancy and gravity torques at joint state `(q, q̇, q̈)`.
///
/// Never fails and never panics; non-finite states give non-finite torques.
#[must_use]
pub fn hydro_torques<T: RealField + Copy, const N: usize>(
    chain: &Chain<T, N>,
    water: &Water<T>,
    coefficients: &Coefficients<T, N>,
    q: &SVector<T, N>,
    qd: &SVector<T, N>,
    qdd: &SVector<T, N>,
) -> HydroTorques<T, N> {
    hydro_regressors(chain, water, q, qd, qdd).apply(coefficients)
}
