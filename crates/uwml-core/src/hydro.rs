//! Drag, added-mass, buoyancy and gravity generalized forces of a chain in still water, and
//! their identification regressors, in one pass (MODEL.md sections 3 and 4).
//!
//! Sign: every torque is exerted by the environment on the joint, in the joint's positive
//! direction (`M q̈ + c + g = τ_motor + τ_env`).

use nalgebra::{RealField, SVector, Vector3};

use crate::kinematics::{LinkMotion, link_motions};
use crate::model::{Chain, Coefficients, Link, Segment, Water, constant};
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

fn sum_columns<T: RealField + Copy, const N: usize>(columns: &[[SVector<T, N>; 2]; N]) -> SVector<T, N> {
    columns.iter().flatten().fold(SVector::zeros(), |acc, column| acc + column)
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

/// A link's straight segment at the current state, in world coordinates, with the exact strip
/// moments of each normal direction `k`: `drag[k] = (∫ v_k|v_k| ds, ∫ s v_k|v_k| ds)` and
/// `added_mass[k] = (∫ a_k ds, ∫ s a_k ds)`.
struct Strip<T: RealField + Copy> {
    start: Vector3<T>,
    normals: [Vector3<T>; 2],
    /// `axis × normals[k]`: the moment direction of a force along `normals[k]` at unit arm.
    moments: [Vector3<T>; 2],
    drag: [(T, T); 2],
    added_mass: [(T, T); 2],
}

impl<T: RealField + Copy> Strip<T> {
    fn new(segment: &Segment<T>, motion: &LinkMotion<T>) -> Self {
        let r = motion.rotation * segment.start;
        let axis = motion.rotation * segment.axis;
        let (v_start, a_start) = motion.point_motion(&r);
        let w = &motion.angular_velocity;
        let w_axial = w.dot(&axis);
        let [n1, n2] = segment.normals;
        let normals = [motion.rotation * n1, motion.rotation * n2];
        let moments = normals.map(|n| axis.cross(&n));
        let mut drag = [(T::zero(), T::zero()); 2];
        let mut added_mass = drag;
        for (((n, m), d), a) in normals.iter().zip(moments.iter()).zip(drag.iter_mut()).zip(added_mass.iter_mut()) {
            // Normal velocity and acceleration along the segment: v0 + v1 s, a0 + a1 s, with
            // v1 = n·(ω × u) = ω·m and a1 = n·(α × u + ω × (ω × u)) = α·m + (ω·n)(ω·u).
            *d = drag_moments(n.dot(&v_start), w.dot(m), segment.length);
            let a1 = motion.angular_acceleration.dot(m) + w.dot(n) * w_axial;
            *a = added_mass_moments(n.dot(&a_start), a1, segment.length);
        }
        Self { start: motion.origin + r, normals, moments, drag, added_mass }
    }
}

/// `(z × (point − origin)) · ẑ`: the moment arm of a vertical unit force about a joint axis.
#[inline]
fn vertical_arm<T: RealField + Copy>(joint: &LinkMotion<T>, point: &Vector3<T>) -> T {
    let r = point - joint.origin;
    joint.axis.x * r.y - joint.axis.y * r.x
}

/// Adds the buoyancy and gravity torques of `link` on the joints that move it.
fn add_static<'a, T: RealField + Copy + 'a>(
    link: &Link<T>,
    motion: &LinkMotion<T>,
    movers: impl Iterator<Item = &'a LinkMotion<T>>,
    water: &Water<T>,
    buoyancy: &mut [T],
    gravity: &mut [T],
) {
    let cob = motion.point(&link.cob);
    let com = motion.point(&link.com);
    let lift = water.density() * link.volume * water.gravity();
    let weight = link.mass * water.gravity();
    for ((b, w), joint) in buoyancy.iter_mut().zip(gravity.iter_mut()).zip(movers) {
        *b += lift * vertical_arm(joint, &cob);
        *w -= weight * vertical_arm(joint, &com);
    }
}

/// Regressors of the hydrodynamic torques at joint state `(q, q̇, q̈)`, one column per link
/// and normal direction. For the torques at given coefficients, [`hydro_torques`] is faster.
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
    let zeros = SVector::<T, N>::zeros();
    let mut out =
        HydroRegressors { buoyancy: zeros, gravity: zeros, drag: [[zeros; 2]; N], added_mass: [[zeros; 2]; N] };

    let columns = out.drag.iter_mut().zip(out.added_mass.iter_mut());
    for (i, ((link, motion), (drag, added_mass))) in chain.links().iter().zip(motions.iter()).zip(columns).enumerate() {
        // Joints 0..=i move link i; the later ones do not.
        let movers = motions.iter().take(i + 1);
        add_static(link, motion, movers.clone(), water, out.buoyancy.as_mut_slice(), out.gravity.as_mut_slice());
        let Some(segment) = &link.segment else { continue };
        let strip = Strip::new(segment, motion);
        let scales = segment.widths.map(|w| -constant::<T>(0.5) * rho * w);
        let directions =
            strip.normals.iter().zip(strip.moments.iter()).zip(strip.drag.iter().zip(strip.added_mass.iter()));
        for ((((n, m), (&(i0, i1), &(j0, j1))), &drag_scale), (drag, added_mass)) in
            directions.zip(scales.iter()).zip(drag.iter_mut().zip(added_mass.iter_mut()))
        {
            let added_mass_scale = -rho * segment.area;
            for ((d, a), joint) in drag.iter_mut().zip(added_mass.iter_mut()).zip(movers.clone()) {
                // Moment arm of a force along n at arc length s about joint j: g0 + g1·s.
                let g0 = joint.axis.dot(&(strip.start - joint.origin).cross(n));
                let g1 = joint.axis.dot(m);
                *d = drag_scale * (g0 * i0 + g1 * i1);
                *a = added_mass_scale * (g0 * j0 + g1 * j1);
            }
        }
    }
    out
}

/// Drag, added-mass, buoyancy and gravity torques at joint state `(q, q̇, q̈)`.
///
/// Each link's distributed forces are first summed into one force and one moment (per kind),
/// then projected on the joints that move the link.
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
    let motions = link_motions(chain, q, qd, qdd);
    let rho = water.density();
    let zeros = SVector::<T, N>::zeros();
    let mut out = HydroTorques { drag: zeros, added_mass: zeros, buoyancy: zeros, gravity: zeros };

    let coefficients = coefficients.cd().iter().zip(coefficients.cm().iter());
    for (i, ((link, motion), (cd, cm))) in chain.links().iter().zip(motions.iter()).zip(coefficients).enumerate() {
        let movers = motions.iter().take(i + 1);
        add_static(link, motion, movers.clone(), water, out.buoyancy.as_mut_slice(), out.gravity.as_mut_slice());
        let Some(segment) = &link.segment else { continue };
        let strip = Strip::new(segment, motion);
        // Resultant force and moment about the segment start, for drag and for added mass.
        let (mut drag_force, mut drag_moment) = (Vector3::zeros(), Vector3::zeros());
        let (mut am_force, mut am_moment) = (Vector3::zeros(), Vector3::zeros());
        let per_direction =
            strip.normals.iter().zip(strip.moments.iter()).zip(strip.drag.iter().zip(strip.added_mass.iter()));
        for ((((n, m), (&(i0, i1), &(j0, j1))), (&width, &cd)), &cm) in
            per_direction.zip(segment.widths.iter().zip(cd.iter())).zip(cm.iter())
        {
            let drag_scale = -constant::<T>(0.5) * rho * cd * width;
            let am_scale = -rho * cm * segment.area;
            drag_force.axpy(drag_scale * i0, n, T::one());
            drag_moment.axpy(drag_scale * i1, m, T::one());
            am_force.axpy(am_scale * j0, n, T::one());
            am_moment.axpy(am_scale * j1, m, T::one());
        }
        for ((d, a), joint) in out.drag.iter_mut().zip(out.added_mass.iter_mut()).zip(movers) {
            let arm = strip.start - joint.origin;
            *d += joint.axis.dot(&(drag_moment + arm.cross(&drag_force)));
            *a += joint.axis.dot(&(am_moment + arm.cross(&am_force)));
        }
    }
    out
}
