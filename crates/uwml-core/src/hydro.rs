//! Drag, added-mass, buoyancy and gravity generalized forces of a chain in still water, and
//! their identification regressors, in one pass (docs/model.md sections 3 and 4).
//!
//! Sign: every torque is exerted by the environment on the joint, in the joint's positive
//! direction (`M q̈ + c + g = τ_motor + τ_env`).

use nalgebra::{SVector, SimdBool, SimdRealField, Vector3};

use crate::body::{Body, BodyMotion, BodySegment, BodyState, body_states, first_axis_vertical};
use crate::kinematics::for_each_peeled;
use crate::model::{Chain, Coefficients, Water, constant};
use crate::strip::{added_mass_moments, drag_moments_2};

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

/// The exact strip moments of a segment along each normal direction `k` (docs/model.md section 3):
/// drag `(∫ v_k|v_k| ds, ∫ s v_k|v_k| ds)` and added mass `(∫ a_k ds, ∫ s a_k ds)`.
#[derive(Clone, Copy)]
struct StripMoments<T: SimdRealField + Copy> {
    drag: [(T, T); 2],
    added_mass: [(T, T); 2],
}

impl<T: SimdRealField + Copy> StripMoments<T> {
    #[inline(always)]
    fn new(segment: &BodySegment<T>, motion: &BodyMotion<T>) -> Self {
        let (v_start, a_start) = match &segment.start {
            Some(start) => motion.point_motion(start),
            None => (motion.velocity, motion.acceleration),
        };
        let (frame, sign) = (&segment.frame, segment.sign);
        let [w_n0, w_n1] = frame.normal_components(&motion.angular_velocity);
        let [alpha_n0, alpha_n1] = frame.normal_components(&motion.angular_acceleration);
        let [v_n0, v_n1] = frame.normal_components(&v_start);
        let [a_n0, a_n1] = frame.normal_components(&a_start);
        let w_axial = frame.axial_component(&motion.angular_velocity);
        // Normal velocity and acceleration along the segment: v0 + v1 s, a0 + a1 s, with
        // v1 = n·(ω × u) = ω·m and a1 = n·(α × u + ω × (ω × u)) = α·m + (ω·n)(ω·u), where the
        // moment directions m = u × n are σ n1 (for n0) and −σ n0 (for n1).
        let length = segment.length;
        let drag = drag_moments_2([v_n0, v_n1], [sign * w_n1, -sign * w_n0], length);
        let added_mass = [
            added_mass_moments(a_n0, sign * alpha_n1 + w_n0 * w_axial, length),
            added_mass_moments(a_n1, -sign * alpha_n0 + w_n1 * w_axial, length),
        ];
        Self { drag, added_mass }
    }
}

/// A force and its moment about a joint origin, in that joint's body frame.
#[derive(Clone, Copy)]
struct Wrench<T: SimdRealField + Copy> {
    force: Vector3<T>,
    moment: Vector3<T>,
}

impl<T: SimdRealField + Copy> Wrench<T> {
    /// The resultant about the body origin of strip forces `scales[k]·f_k(s)` along the normals,
    /// whose integrals over the segment are `integrals[k] = (∫ f_k ds, ∫ s f_k ds)`.
    #[inline(always)]
    fn of_strip(segment: &BodySegment<T>, [s0, s1]: [T; 2], &[(f0, g0), (f1, g1)]: &[(T, T); 2]) -> Self {
        let force = segment.frame.along_normals([s0 * f0, s1 * f1]);
        // A force f·n at arc length s has the moment s·f·(axis × n) about the segment start;
        // Σ_k c_k (axis × n_k) = σ (c_0 n_1 − c_1 n_0).
        let sign = segment.sign;
        let moment = segment.frame.along_normals([-sign * s1 * g1, sign * s0 * g0]);
        match &segment.start {
            Some(start) => Self { force, moment: moment + start.cross(&force) },
            None => Self { force, moment },
        }
    }

    /// The same wrench in the parent joint's frame, about the parent joint's origin.
    #[inline(always)]
    fn in_parent(&self, body: &Body<T>, state: &BodyState<T>) -> Self {
        let force = state.in_parent(body, &self.force);
        let moment = state.in_parent(body, &self.moment);
        match &body.origin {
            Some(origin) => Self { force, moment: moment + origin.position.cross(&force) },
            None => Self { force, moment },
        }
    }
}

/// The drag and the added-mass wrench, carried down the chain together.
#[derive(Clone, Copy)]
struct Wrenches<T: SimdRealField + Copy> {
    drag: Wrench<T>,
    added_mass: Wrench<T>,
}

impl<T: SimdRealField + Copy> Wrenches<T> {
    fn zero() -> Self {
        let zero = Wrench { force: Vector3::zeros(), moment: Vector3::zeros() };
        Self { drag: zero, added_mass: zero }
    }

    /// A segment's wrenches for drag scales `−½ρ Cd_k w_k` and added-mass scales `−ρ Cm_k A`.
    #[inline(always)]
    fn of_strip(segment: &BodySegment<T>, strip: &StripMoments<T>, drag: [T; 2], added_mass: [T; 2]) -> Self {
        Self {
            drag: Wrench::of_strip(segment, drag, &strip.drag),
            added_mass: Wrench::of_strip(segment, added_mass, &strip.added_mass),
        }
    }

    #[inline(always)]
    fn add(&self, other: &Self) -> Self {
        let sum = |a: &Wrench<T>, b: &Wrench<T>| Wrench { force: a.force + b.force, moment: a.moment + b.moment };
        Self { drag: sum(&self.drag, &other.drag), added_mass: sum(&self.added_mass, &other.added_mass) }
    }

    /// The generalized forces on the joint: the moments about its axis, `e_z`.
    #[inline(always)]
    fn torques(&self) -> (T, T) {
        (self.drag.moment.z, self.added_mass.moment.z)
    }

    #[inline(always)]
    fn in_parent(&self, body: &Body<T>, state: &BodyState<T>) -> Self {
        Self { drag: self.drag.in_parent(body, state), added_mass: self.added_mass.in_parent(body, state) }
    }

    /// The generalized forces on the parent joint, without the full change of frame.
    #[inline(always)]
    fn torques_on_parent(&self, body: &Body<T>, state: &BodyState<T>) -> (T, T) {
        let on_parent = |w: &Wrench<T>| state.moment_about_parent_axis(body, &w.force, &w.moment);
        (on_parent(&self.drag), on_parent(&self.added_mass))
    }
}

/// The drag and added-mass generalized forces on every joint of wrenches applied to the links
/// (`applied(j)`: link j's, in `F_j` about joint j), carried down the chain from the last link to
/// the first as in recursive Newton-Euler.
#[inline(always)]
fn carry_down<T: SimdRealField + Copy, const N: usize>(
    chain: &Chain<T, N>,
    states: &[BodyState<T>; N],
    applied: impl Fn(usize) -> Option<Wrenches<T>>,
) -> ([T; N], [T; N]) {
    let (mut drag, mut added_mass) = ([T::zero(); N], [T::zero(); N]);
    let per_joint = chain.bodies().iter().zip(states.iter()).zip(drag.iter_mut().zip(added_mass.iter_mut()));
    let mut joints = per_joint.enumerate().rev();
    // The wrenches on the links from joint j on, in F_j about joint j.
    let mut carried = Wrenches::zero();
    // Adds link j's own wrenches to those of the links after it; the torques on joint j.
    let add_own = |j: usize, carried: &mut Wrenches<T>| {
        if let Some(own) = applied(j) {
            *carried = carried.add(&own);
        }
        carried.torques()
    };
    // The last joints down to the third. The first two are special cases, out of the loop, so
    // that chains of up to three joints have no loop at all.
    for (j, ((body, state), (d, a))) in joints.by_ref().take(N.saturating_sub(2)) {
        (*d, *a) = add_own(j, &mut carried);
        carried = carried.in_parent(body, state);
    }
    // The first joint needs only the moments about its axis, not the full change of frame.
    let mut on_first = (T::zero(), T::zero());
    if N > 1
        && let Some((j, ((body, state), (d, a)))) = joints.next()
    {
        (*d, *a) = add_own(j, &mut carried);
        on_first = carried.torques_on_parent(body, state);
    }
    if let Some((j, (_, (d, a)))) = joints.next() {
        let (own_drag, own_added_mass) = applied(j).map_or((T::zero(), T::zero()), |own| own.torques());
        (*d, *a) = (own_drag + on_first.0, own_added_mass + on_first.1);
    }
    (drag, added_mass)
}

/// Buoyancy and gravity torques on every joint. Both are vertical, so the torque on a joint is
/// fixed by the first moments `Σ V_i c_i` and `Σ m_i c_i` of the links it carries.
#[inline(always)]
fn static_torques<T: SimdRealField + Copy, const N: usize>(
    chain: &Chain<T, N>,
    water: &Water<T>,
    states: &[BodyState<T>; N],
) -> (SVector<T, N>, SVector<T, N>) {
    let (g, zero) = (water.gravity(), Vector3::zeros());
    let lift = water.density() * g;
    let (mut buoyancy, mut gravity) = ([T::zero(); N], [T::zero(); N]);
    // e_z · (S × up): the moment about the joint axis of vertical unit forces with first moment S.
    let about_axis = |s: &Vector3<T>, up: &Vector3<T>| s.x * up.y - s.y * up.x;
    // Σ V_i c_i and Σ m_i c_i of the links from joint j on, in F_j about joint j.
    let (mut volume_moment, mut mass_moment) = (zero, zero);
    // About a vertical first axis they have no moment at all.
    let vertical_first = first_axis_vertical(chain.bodies());
    let per_joint = chain.bodies().iter().zip(states.iter()).zip(buoyancy.iter_mut().zip(gravity.iter_mut()));
    for (j, ((body, state), (b, w))) in per_joint.enumerate().rev() {
        volume_moment += body.volume_moment;
        mass_moment += body.mass_moment;
        (*b, *w) = (lift * about_axis(&volume_moment, &state.up), -g * about_axis(&mass_moment, &state.up));
        // On to the parent joint, unless there is none or it is the first and vertical.
        (volume_moment, mass_moment) = if j > 1 || (j == 1 && !vertical_first) {
            let (volume, mass) = (state.in_parent(body, &volume_moment), state.in_parent(body, &mass_moment));
            match &body.origin {
                Some(origin) => (volume + origin.carried_volume_moment, mass + origin.carried_mass_moment),
                None => (volume, mass),
            }
        } else {
            (zero, zero)
        };
    }
    (buoyancy.into(), gravity.into())
}

/// Which lanes have every joint state finite (for a scalar `T`, whether it has). Where one has
/// not, the torques are NaN, rather than whatever the non-finite input reaches: in body frames,
/// for instance, no torque depends on the first joint angle but through buoyancy and gravity,
/// and those not at all where the first axis is vertical.
#[inline(always)]
fn finite_lanes<T: SimdRealField + Copy, const N: usize>(
    q: &SVector<T, N>,
    qd: &SVector<T, N>,
    qdd: &SVector<T, N>,
) -> T::SimdBool {
    // 0·x is 0 for finite x and NaN otherwise: one comparison instead of 3N.
    let states = q.as_slice().iter().chain(qd.as_slice()).chain(qdd.as_slice());
    states.fold(T::zero(), |sum, &x| sum + x * T::zero()).simd_eq(T::zero())
}

/// NaN in the lanes that are not `finite`.
#[inline(always)]
fn nan_unless<T: SimdRealField + Copy, const N: usize>(finite: T::SimdBool, v: &SVector<T, N>) -> SVector<T, N> {
    v.map(|x| x.select(finite, T::zero() / T::zero()))
}

/// `−½ρ w_k` and `−ρ A`: the drag and added-mass scales of a segment at unit coefficients.
#[inline(always)]
fn unit_scales<T: SimdRealField + Copy>(segment: &BodySegment<T>, water: &Water<T>) -> ([T; 2], T) {
    let rho = water.density();
    (segment.widths.map(|w| -constant::<T>(0.5) * rho * w), -rho * segment.area)
}

/// Regressors of the hydrodynamic torques at joint state `(q, q̇, q̈)`, one column per link
/// and normal direction. For the torques at given coefficients, [`hydro_torques`] is faster.
///
/// Never fails and never panics; non-finite states give NaN.
#[must_use]
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
pub fn hydro_regressors<T: SimdRealField + Copy, const N: usize>(
    chain: &Chain<T, N>,
    water: &Water<T>,
    q: &SVector<T, N>,
    qd: &SVector<T, N>,
    qdd: &SVector<T, N>,
) -> HydroRegressors<T, N> {
    let finite = finite_lanes(q, qd, qdd);
    if finite.none() {
        let nan = SVector::repeat(T::zero() / T::zero());
        return HydroRegressors { buoyancy: nan, gravity: nan, drag: [[nan; 2]; N], added_mass: [[nan; 2]; N] };
    }
    let states = body_states(chain, q, qd, qdd);
    let (buoyancy, gravity) = static_torques(chain, water, &states);
    let zeros = SVector::<T, N>::zeros();
    let (mut drag, mut added_mass) = ([[zeros; 2]; N], [[zeros; 2]; N]);
    let columns = drag.iter_mut().zip(added_mass.iter_mut());
    for (link, ((body, state), (drag, added_mass))) in chain.bodies().iter().zip(states.iter()).zip(columns).enumerate()
    {
        let Some(segment) = &body.segment else { continue };
        let strip = StripMoments::new(segment, &state.motion);
        let ([w0, w1], area) = unit_scales(segment, water);
        let zero = T::zero();
        let directions = [([w0, zero], [area, zero]), ([zero, w1], [zero, area])];
        for ((drag, added_mass), (drag_scales, added_mass_scales)) in
            drag.iter_mut().zip(added_mass.iter_mut()).zip(directions)
        {
            // This direction alone, at unit coefficients, applied to this link only.
            let column = Wrenches::of_strip(segment, &strip, drag_scales, added_mass_scales);
            let (d, a) = carry_down(chain, &states, |j| (j == link).then_some(column));
            (*drag, *added_mass) = (d.into(), a.into());
        }
    }
    let regressors = HydroRegressors { buoyancy, gravity, drag, added_mass };
    if finite.all() { regressors } else { regressors.map(|v| nan_unless(finite, v)) }
}

/// Drag, added-mass, buoyancy and gravity torques at joint state `(q, q̇, q̈)`.
///
/// Each link's distributed forces are summed into one wrench per kind, and the wrenches are
/// carried down the chain from the last link to the first, as in recursive Newton-Euler.
/// Never fails and never panics; non-finite states give NaN.
#[must_use]
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
pub fn hydro_torques<T: SimdRealField + Copy, const N: usize>(
    chain: &Chain<T, N>,
    water: &Water<T>,
    coefficients: &Coefficients<T, N>,
    q: &SVector<T, N>,
    qd: &SVector<T, N>,
    qdd: &SVector<T, N>,
) -> HydroTorques<T, N> {
    let finite = finite_lanes(q, qd, qdd);
    if finite.none() {
        let nan = SVector::repeat(T::zero() / T::zero());
        return HydroTorques { drag: nan, added_mass: nan, buoyancy: nan, gravity: nan };
    }
    let states = body_states(chain, q, qd, qdd);
    let (buoyancy, gravity) = static_torques(chain, water, &states);
    let mut applied = [None; N];
    let per_link = chain.bodies().iter().zip(states.iter()).zip(coefficients.cd().iter().zip(coefficients.cm().iter()));
    for_each_peeled!((own, ((body, state), (&[cd0, cd1], &[cm0, cm1]))) in applied.iter_mut().zip(per_link) => {
        if let Some(segment) = &body.segment {
            let ([w0, w1], area) = unit_scales(segment, water);
            let strip = StripMoments::new(segment, &state.motion);
            *own = Some(Wrenches::of_strip(segment, &strip, [cd0 * w0, cd1 * w1], [cm0 * area, cm1 * area]));
        }
    });
    let (drag, added_mass) = carry_down(chain, &states, |j| applied.get(j).copied().flatten());
    let torques = HydroTorques { drag: drag.into(), added_mass: added_mass.into(), buoyancy, gravity };
    if finite.all() { torques } else { torques.map(|v| nan_unless(finite, v)) }
}
