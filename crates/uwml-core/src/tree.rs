//! Drag, added mass, buoyancy (with Froude-Krylov) and gravity on a whole robot: the generalized
//! force on every joint and the wrench on the base (docs/model.md section 10).
//!
//! One forward pass over the joints (parents before children) gives every link's pose and motion
//! in base-frame components; each body's own wrench about the base origin follows from its
//! segments (exact strip integrals) and its centres of buoyancy and mass; one backward pass sums
//! them over subtrees, as in recursive Newton-Euler. A joint's generalized force is the moment of
//! its subtree's wrench about its axis (revolute) or the force along it (prismatic); the base
//! wrench is the sum over all bodies. Evaluation never fails and never panics; a non-finite joint
//! state gives NaN.

use core::ops::{Add, AddAssign};

use nalgebra::{Matrix3, SimdBool, SimdRealField, Vector3};

use crate::kinematics::{axis_angle, dot, rotate, rotate_back};
use crate::model::{Water, constant};
use crate::motion::{BaseMotion, Current};
use crate::robot::{JointKind, Owner, RigidBody, Robot, RobotSegment, Section, SegmentCoefficients};
use crate::strip::{added_mass_moments, circular_speed_moments, drag_moments};

/// A force and a moment (about a point named where it is used).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wrench<T: SimdRealField + Copy> {
    /// Force [N].
    pub force: Vector3<T>,
    /// Moment [N·m].
    pub moment: Vector3<T>,
}

impl<T: SimdRealField + Copy> Wrench<T> {
    /// No force, no moment.
    #[must_use]
    pub fn zero() -> Self {
        Self { force: Vector3::zeros(), moment: Vector3::zeros() }
    }

    /// `[force, moment]` as six numbers.
    #[must_use]
    pub fn to_array(&self) -> [T; 6] {
        let (f, m) = (&self.force, &self.moment);
        [f.x, f.y, f.z, m.x, m.y, m.z]
    }

    /// A force at `point` (moment about the origin of `point`'s coordinates).
    #[inline(always)]
    fn at(point: &Vector3<T>, force: Vector3<T>) -> Self {
        Self { force, moment: point.cross(&force) }
    }

    /// The same wrench about the origin, given about `point`.
    #[inline(always)]
    fn moved_from(self, point: &Vector3<T>) -> Self {
        Self { force: self.force, moment: self.moment + point.cross(&self.force) }
    }

    fn map(&self, f: impl Fn(T) -> T) -> Self {
        Self { force: self.force.map(&f), moment: self.moment.map(&f) }
    }
}

impl<T: SimdRealField + Copy> Add for Wrench<T> {
    type Output = Self;
    fn add(self, other: Self) -> Self {
        Self { force: self.force + other.force, moment: self.moment + other.moment }
    }
}

impl<T: SimdRealField + Copy> AddAssign for Wrench<T> {
    fn add_assign(&mut self, other: Self) {
        *self = *self + other;
    }
}

/// The environment's wrench, per component.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EnvironmentWrench<T: SimdRealField + Copy> {
    /// Drag on the segments (relative velocity).
    pub drag: Wrench<T>,
    /// Added mass on the segments (relative acceleration).
    pub added_mass: Wrench<T>,
    /// Buoyancy and Froude-Krylov, `ρV(ċ − g)` at the centres of buoyancy.
    pub buoyancy: Wrench<T>,
    /// Gravity at the centres of mass (not part of [`EnvironmentWrench::total`]).
    pub gravity: Wrench<T>,
}

impl<T: SimdRealField + Copy> EnvironmentWrench<T> {
    /// All components zero.
    #[must_use]
    pub fn zero() -> Self {
        Self { drag: Wrench::zero(), added_mass: Wrench::zero(), buoyancy: Wrench::zero(), gravity: Wrench::zero() }
    }

    /// `drag + added_mass + buoyancy`, the hydrodynamic part.
    #[must_use]
    pub fn total(&self) -> Wrench<T> {
        self.drag + self.added_mass + self.buoyancy
    }

    fn map(&self, f: impl Fn(&Wrench<T>) -> Wrench<T>) -> Self {
        Self {
            drag: f(&self.drag),
            added_mass: f(&self.added_mass),
            buoyancy: f(&self.buoyancy),
            gravity: f(&self.gravity),
        }
    }
}

impl<T: SimdRealField + Copy> Add for EnvironmentWrench<T> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
            drag: self.drag + o.drag,
            added_mass: self.added_mass + o.added_mass,
            buoyancy: self.buoyancy + o.buoyancy,
            gravity: self.gravity + o.gravity,
        }
    }
}

/// The environment's generalized force on one joint, per component [N·m, or N for prismatic].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointForces<T: SimdRealField + Copy> {
    /// Drag.
    pub drag: T,
    /// Added mass.
    pub added_mass: T,
    /// Buoyancy and Froude-Krylov.
    pub buoyancy: T,
    /// Gravity (not part of [`JointForces::total`]).
    pub gravity: T,
}

impl<T: SimdRealField + Copy> JointForces<T> {
    /// `drag + added_mass + buoyancy`.
    #[must_use]
    pub fn total(&self) -> T {
        self.drag + self.added_mass + self.buoyancy
    }
}

/// Pose and motion of a link frame (at its joint), in base-frame components.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Frame<T: SimdRealField + Copy> {
    /// Base from link.
    rotation: Matrix3<T>,
    /// Position of the frame origin relative to the base origin.
    position: Vector3<T>,
    /// The joint axis.
    axis: Vector3<T>,
    angular_velocity: Vector3<T>,
    angular_acceleration: Vector3<T>,
    /// Velocity of the frame origin.
    velocity: Vector3<T>,
    /// Classical acceleration of the frame origin.
    acceleration: Vector3<T>,
}

/// The workspace and results of an evaluation of a robot of up to `J` joints (Pinocchio's
/// `Data`): make one, evaluate into it as often as needed, read the results.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RobotData<T: SimdRealField + Copy, const J: usize> {
    frames: [Frame<T>; J],
    /// Each link's own wrench, then (after the backward pass) its subtree's; about the base
    /// origin, base components.
    subtree: [EnvironmentWrench<T>; J],
    /// Each link's own total wrench (all components, gravity included), as `subtree` before the
    /// backward pass.
    own: [Wrench<T>; J],
    base_own: Wrench<T>,
    joints: [JointForces<T>; J],
    base: EnvironmentWrench<T>,
    joint_count: usize,
    base_rotation: Matrix3<T>,
}

impl<T: SimdRealField + Copy, const J: usize> RobotData<T, J> {
    /// A workspace for robots of up to `J` joints.
    #[must_use]
    pub fn new() -> Self {
        let zero = Vector3::zeros();
        let frame = Frame {
            rotation: Matrix3::identity(),
            position: zero,
            axis: zero,
            angular_velocity: zero,
            angular_acceleration: zero,
            velocity: zero,
            acceleration: zero,
        };
        let nothing = T::zero();
        Self {
            frames: [frame; J],
            subtree: [EnvironmentWrench::zero(); J],
            own: [Wrench::zero(); J],
            base_own: Wrench::zero(),
            joints: [JointForces { drag: nothing, added_mass: nothing, buoyancy: nothing, gravity: nothing }; J],
            base: EnvironmentWrench::zero(),
            joint_count: 0,
            base_rotation: Matrix3::identity(),
        }
    }

    /// The generalized force on every joint of the last evaluation.
    pub fn joint_forces(&self) -> &[JointForces<T>] {
        self.joints.get(..self.joint_count).unwrap_or(&[])
    }

    /// The wrench on the base of the last evaluation: force and moment about the base origin, base
    /// components, of everything the environment exerts on the whole robot (docs/model.md section
    /// 10, "What is computed").
    pub const fn base_wrench(&self) -> &EnvironmentWrench<T> {
        &self.base
    }

    /// The environment's total wrench on one body (`None`: the base; `Some(i)`: link `i`) in the
    /// last evaluation, every component (gravity included), as force and moment about the
    /// body's centre of mass, in WORLD components: what a simulator applies to that body.
    /// `None` for a link that does not exist.
    pub fn body_wrench<const S: usize>(&self, robot: &Robot<T, J, S>, body: Option<usize>) -> Option<Wrench<T>> {
        let (own, com) = match body {
            None => (self.base_own, robot.base().com),
            Some(i) => {
                let (Some(own), Some(frame), Some(link)) = (self.own.get(i), self.frames.get(i), robot.links().get(i))
                else {
                    return None;
                };
                (*own, frame.position + rotate(&frame.rotation, &link.com))
            }
        };
        let about_com = own.moved_from(&-com);
        Some(Wrench {
            force: rotate(&self.base_rotation, &about_com.force),
            moment: rotate(&self.base_rotation, &about_com.moment),
        })
    }
}

impl<T: SimdRealField + Copy, const J: usize> Default for RobotData<T, J> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: SimdRealField + Copy> Frame<T> {
    /// The base's own frame.
    fn base(motion: &BaseMotion<T>) -> Self {
        let (v, w) = motion.twist();
        let (v_dot, w_dot) = motion.twist_derivative();
        Self {
            rotation: Matrix3::identity(),
            position: Vector3::zeros(),
            axis: Vector3::zeros(),
            angular_velocity: w,
            angular_acceleration: w_dot,
            velocity: v,
            acceleration: v_dot + w.cross(&v),
        }
    }

    /// A child's frame, moved by a joint of `kind` with `origin` and `axis` in this frame.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn child(&self, kind: JointKind, origin: &Vector3<T>, axis: &Vector3<T>, q: T, qd: T, qdd: T) -> Self {
        let z = rotate(&self.rotation, axis);
        let w = self.angular_velocity;
        let (rotation, offset, angular_velocity, angular_acceleration) = match kind {
            JointKind::Revolute => (
                self.rotation * axis_angle(axis, q.simd_sin_cos()),
                rotate(&self.rotation, origin),
                w + z * qd,
                self.angular_acceleration + z * qdd + w.cross(&z) * qd,
            ),
            JointKind::Prismatic => {
                (self.rotation, rotate(&self.rotation, &(origin + axis * q)), w, self.angular_acceleration)
            }
        };
        let wr = w.cross(&offset);
        let mut velocity = self.velocity + wr;
        let mut acceleration = self.acceleration + self.angular_acceleration.cross(&offset) + w.cross(&wr);
        if kind == JointKind::Prismatic {
            velocity += z * qd;
            let wz = w.cross(&z);
            acceleration += z * qdd + (wz + wz) * qd;
        }
        Self {
            rotation,
            position: self.position + offset,
            axis: z,
            angular_velocity,
            angular_acceleration,
            velocity,
            acceleration,
        }
    }

    /// Velocity and acceleration of the material point at `r` from the frame origin.
    #[inline(always)]
    fn point_motion(&self, r: &Vector3<T>) -> (Vector3<T>, Vector3<T>) {
        let w = &self.angular_velocity;
        let wr = w.cross(r);
        (self.velocity + wr, self.acceleration + self.angular_acceleration.cross(r) + w.cross(&wr))
    }
}

/// How the added-mass forces depend on the velocities (docs/simulation.md, "Energy-consistent added
/// mass"). Both share the added-mass matrix `M_A(q)`, the acceleration part; they differ in the
/// velocity terms.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum AddedMassForm {
    /// The paper's Morison form: each slice's added mass on the normal components of its
    /// acceleration relative to the water, `−ρ Cm_k A (n_k·a) n_k`. Not derived from the water's
    /// kinetic energy: with drag off it exchanges energy with the robot at the rate of
    /// docs/simulation.md, "Energy-consistent added mass".
    #[default]
    Morison,
    /// Kirchhoff's form, derived from the water's kinetic energy `T_A = ½ Σ ∫ ρ Cm_k A v_k² ds`:
    /// each slice, a body with the added-mass tensor `Σ_k ρ Cm_k A n_k n_kᵀ` and relative
    /// velocity `v`, feels the force `−dp/dt` (`p` its added momentum, `n_k` turning with the
    /// link) and the couple `−v × p` (Munk's). The generalized forces are then
    /// `−M_A q̈ − C_A q̇` with `Ṁ_A − 2 C_A` skew-symmetric: in still water, without drag, the
    /// energy `T_rigid + T_A + V` is conserved.
    Kirchhoff,
}

/// The water around the robot in base components, and its constants.
struct Surroundings<T: SimdRealField + Copy> {
    density: T,
    /// Gravity's acceleration vector.
    gravity: Vector3<T>,
    current: Vector3<T>,
    current_acceleration: Vector3<T>,
}

impl<T: SimdRealField + Copy> Surroundings<T> {
    /// The water and gravity of an evaluation, in the components of the base at `motion`.
    fn new(water: &Water<T>, motion: &BaseMotion<T>, current: &Current<T>) -> Self {
        let rotation = motion.rotation();
        Self {
            density: water.density(),
            gravity: rotate_back(rotation, &Vector3::z()) * -water.gravity(),
            current: rotate_back(rotation, current.velocity()),
            current_acceleration: rotate_back(rotation, current.acceleration()),
        }
    }
}

/// A segment's drag and added-mass wrenches about the base origin, at coefficients `cd`, `cm`.
#[inline(always)]
fn segment_wrenches<T: SimdRealField + Copy>(
    frame: &Frame<T>,
    segment: &RobotSegment<T>,
    [cd0, cd1]: [T; 2],
    [cm0, cm1]: [T; 2],
    water: &Surroundings<T>,
    form: AddedMassForm,
) -> (Wrench<T>, Wrench<T>) {
    let r = rotate(&frame.rotation, &segment.start);
    let u = rotate(&frame.rotation, &segment.axis);
    let start = frame.position + r;
    let (v, a) = frame.point_motion(&r);
    let w = &frame.angular_velocity;
    // Relative velocity and acceleration along the segment: affine in s.
    let (v0, v1) = (v - water.current, w.cross(&u));
    let (a0, a1) = (a - water.current_acceleration, frame.angular_acceleration.cross(&u) + w.cross(&v1));
    let length = segment.length;
    let rho = water.density;
    let half = constant::<T>(0.5);
    let added_mass_scale = -rho * segment.area;
    let (drag, added_mass) = match &segment.section {
        Section::Rectangular { normals, widths } => {
            let mut drag = Wrench::zero();
            let mut added_mass = Wrench::zero();
            for ((n, &width), (cd, cm)) in normals.iter().zip(widths.iter()).zip([(cd0, cm0), (cd1, cm1)]) {
                let n = rotate(&frame.rotation, n);
                let (d0, d1) = drag_moments(dot(&n, &v0), dot(&n, &v1), length);
                let (m0, m1) = added_mass_moments(dot(&n, &a0), dot(&n, &a1), length);
                let (drag_scale, mass_scale) = (-half * rho * cd * width, added_mass_scale * cm);
                let moment_direction = u.cross(&n);
                drag += Wrench { force: n * (drag_scale * d0), moment: moment_direction * (drag_scale * d1) };
                added_mass += Wrench { force: n * (mass_scale * m0), moment: moment_direction * (mass_scale * m1) };
                if form == AddedMassForm::Kirchhoff {
                    // ṅ = ω × n. Extra force density −m[(ṅ·v) n + (n·v) ṅ]; couple −v × p with
                    // p = m (n·v) n: ∫ (n·v)(v × n) times −m, v = v0 + s v1.
                    let n_dot = w.cross(&n);
                    let (e0, e1) = added_mass_moments(dot(&n_dot, &v0), dot(&n_dot, &v1), length);
                    let (c0, c1) = added_mass_moments(dot(&n, &v0), dot(&n, &v1), length);
                    added_mass += Wrench {
                        force: (n * e0 + n_dot * c0) * mass_scale,
                        moment: (moment_direction * e1 + u.cross(&n_dot) * c1 + v0.cross(&n) * c0 + v1.cross(&n) * c1)
                            * mass_scale,
                    };
                }
            }
            (drag, added_mass)
        }
        Section::Circular { diameter } => {
            // Normal parts: v1 = ω × u is normal already.
            let normal = |x: Vector3<T>| x - u * dot(&u, &x);
            let (p0, a0n, a1n) = (normal(v0), normal(a0), normal(a1));
            let [i0, i1, i2] = circular_speed_moments(&p0, &v1, length);
            let drag_scale = -half * rho * cd0 * *diameter;
            // ∫ s^k |v⊥| v⊥ = p0 I_k + v1 I_{k+1}.
            let drag =
                Wrench { force: (p0 * i0 + v1 * i1) * drag_scale, moment: u.cross(&(p0 * i1 + v1 * i2)) * drag_scale };
            let (m_force, m_moment) =
                (added_mass_moments(T::one(), T::zero(), length), added_mass_moments(T::zero(), T::one(), length));
            // ∫ a⊥ = a0 L + a1 L²/2, ∫ s a⊥ = a0 L²/2 + a1 L³/3.
            let mass_scale = added_mass_scale * cm0;
            let mut added_mass = Wrench {
                force: (a0n * m_force.0 + a1n * m_moment.0) * mass_scale,
                moment: u.cross(&(a0n * m_force.1 + a1n * m_moment.1)) * mass_scale,
            };
            if form == AddedMassForm::Kirchhoff {
                // p = m v⊥, v⊥ = p0 + s v1 (v1 = ω × u = u̇), c = u·v constant along the segment:
                // dv⊥/dt = a⊥ − v1 c − u (v1·v). Extra force density −m[−v1 c − u (v1·v)], whose
                // moment about the start is −m[−(u × v1) c s]; couple −v × p = −m c u × v⊥.
                let c = dot(&u, &v0);
                let (f0, _) = added_mass_moments(dot(&v1, &v0), dot(&v1, &v1), length);
                let (l, l2) = m_force;
                added_mass += Wrench {
                    force: (v1 * (c * l) + u * f0) * -mass_scale,
                    moment: (u.cross(&v1) * (c * l2) - u.cross(&(p0 * l + v1 * l2)) * c) * -mass_scale,
                };
            }
            (drag, added_mass)
        }
    };
    (drag.moved_from(&start), added_mass.moved_from(&start))
}

/// A body's buoyancy (with Froude-Krylov) and gravity wrenches about the base origin.
#[inline(always)]
fn static_wrenches<T: SimdRealField + Copy>(
    frame: &Frame<T>,
    body: &RigidBody<T>,
    water: &Surroundings<T>,
) -> (Wrench<T>, Wrench<T>) {
    let cob = frame.position + rotate(&frame.rotation, &body.cob);
    let com = frame.position + rotate(&frame.rotation, &body.com);
    let buoyancy = (water.current_acceleration - water.gravity) * (water.density * body.volume);
    (Wrench::at(&cob, buoyancy), Wrench::at(&com, water.gravity * body.mass))
}

/// The first `n` entries.
fn used<T, const J: usize>(x: &[T; J], n: usize) -> &[T] {
    x.get(..n).unwrap_or(&[])
}

/// Which lanes have every joint state finite.
fn finite_lanes<T: SimdRealField + Copy>(states: &[&[T]]) -> T::SimdBool {
    let sum = states.iter().flat_map(|s| s.iter()).fold(T::zero(), |sum, &x| sum + x * T::zero());
    sum.simd_eq(T::zero())
}

/// Drag, added-mass, buoyancy and gravity forces on every joint of `robot` and the wrench on its
/// base, at joint state `(q, q̇, q̈)` (the first `robot.joint_count()` entries), base motion
/// `motion` and `current`, into `data` (read [`RobotData::joint_forces`] and
/// [`RobotData::base_wrench`]). `coefficients`: `None` for the segments' own.
///
/// Never fails and never panics; a non-finite joint state gives NaN everywhere (in its lane).
/// The added mass is the paper's Morison form; [`robot_hydro_with`] takes the form.
#[allow(clippy::too_many_arguments)]
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
pub fn robot_hydro<T: SimdRealField + Copy, const J: usize, const S: usize>(
    robot: &Robot<T, J, S>,
    water: &Water<T>,
    coefficients: Option<&SegmentCoefficients<T, S>>,
    motion: &BaseMotion<T>,
    current: &Current<T>,
    q: &[T; J],
    qd: &[T; J],
    qdd: &[T; J],
    data: &mut RobotData<T, J>,
) {
    hydro_in(robot, water, coefficients, AddedMassForm::Morison, motion, current, [q, qd, qdd], data);
}

/// [`robot_hydro`] with the added mass in the given [`AddedMassForm`].
#[allow(clippy::too_many_arguments)]
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
pub fn robot_hydro_with<T: SimdRealField + Copy, const J: usize, const S: usize>(
    robot: &Robot<T, J, S>,
    water: &Water<T>,
    coefficients: Option<&SegmentCoefficients<T, S>>,
    form: AddedMassForm,
    motion: &BaseMotion<T>,
    current: &Current<T>,
    q: &[T; J],
    qd: &[T; J],
    qdd: &[T; J],
    data: &mut RobotData<T, J>,
) {
    hydro_in(robot, water, coefficients, form, motion, current, [q, qd, qdd], data);
}

#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn hydro_in<T: SimdRealField + Copy, const J: usize, const S: usize>(
    robot: &Robot<T, J, S>,
    water: &Water<T>,
    coefficients: Option<&SegmentCoefficients<T, S>>,
    form: AddedMassForm,
    motion: &BaseMotion<T>,
    current: &Current<T>,
    [q, qd, qdd]: [&[T; J]; 3],
    data: &mut RobotData<T, J>,
) {
    let n = robot.joint_count();
    let finite = finite_lanes(&[used(q, n), used(qd, n), used(qdd, n)]);
    let surroundings = Surroundings::new(water, motion, current);
    data.joint_count = n;
    data.base_rotation = *motion.rotation();
    // Forward: every link's frame, parents first; each body's own static wrenches.
    let base = Frame::base(motion);
    let per_joint = robot.joint_slots().iter().zip(robot.link_slots()).zip(q.iter().zip(qd).zip(qdd)).take(n);
    for (i, ((joint, link), ((&q, &qd), &qdd))) in per_joint.enumerate() {
        let parent = match joint.parent {
            Some(p) => data.frames.get(p).copied().unwrap_or(base),
            None => base,
        };
        let frame = parent.child(joint.kind, &joint.origin, &joint.axis, q, qd, qdd);
        let (buoyancy, gravity) = static_wrenches(&frame, link, &surroundings);
        if let (Some(slot), Some(subtree)) = (data.frames.get_mut(i), data.subtree.get_mut(i)) {
            *slot = frame;
            *subtree = EnvironmentWrench { buoyancy, gravity, ..EnvironmentWrench::zero() };
        }
    }
    let (buoyancy, gravity) = static_wrenches(&base, robot.base(), &surroundings);
    let mut total = EnvironmentWrench { buoyancy, gravity, ..EnvironmentWrench::zero() };
    // Each segment's drag and added mass, on its body.
    for (k, segment) in robot.segments().iter().enumerate() {
        let (cd, cm) = match coefficients {
            Some(c) => (c.cd.get(k).copied().unwrap_or(segment.cd), c.cm.get(k).copied().unwrap_or(segment.cm)),
            None => (segment.cd, segment.cm),
        };
        let (frame, body) = match segment.owner {
            Owner::Base => (&base, &mut total),
            Owner::Link(i) => match (data.frames.get(i), data.subtree.get_mut(i)) {
                (Some(frame), Some(body)) => (frame, body),
                _ => continue,
            },
        };
        let (drag, added_mass) = segment_wrenches(frame, segment, cd, cm, &surroundings, form);
        body.drag += drag;
        body.added_mass += added_mass;
    }
    let whole = |w: &EnvironmentWrench<T>| w.drag + w.added_mass + w.buoyancy + w.gravity;
    data.base_own = whole(&total);
    for (own, subtree) in data.own.iter_mut().zip(data.subtree.iter()).take(n) {
        *own = whole(subtree);
    }
    // Backward: subtrees summed into their parents; each joint's generalized force.
    for i in (0..n).rev() {
        let (Some(joint), Some(frame), Some(&subtree)) =
            (robot.joints().get(i), data.frames.get(i), data.subtree.get(i))
        else {
            continue;
        };
        let z = frame.axis;
        let project = |w: &Wrench<T>| match joint.kind {
            JointKind::Revolute => dot(&z, &(w.moment - frame.position.cross(&w.force))),
            JointKind::Prismatic => dot(&z, &w.force),
        };
        if let Some(forces) = data.joints.get_mut(i) {
            *forces = JointForces {
                drag: project(&subtree.drag),
                added_mass: project(&subtree.added_mass),
                buoyancy: project(&subtree.buoyancy),
                gravity: project(&subtree.gravity),
            };
        }
        match joint.parent.and_then(|p| data.subtree.get_mut(p)) {
            Some(parent) => *parent = *parent + subtree,
            None => total = total + subtree,
        }
    }
    data.base = total;
    if !finite.all() {
        let nan = T::zero() / T::zero();
        let mask = |x: T| x.select(finite, nan);
        data.base = data.base.map(|w| w.map(mask));
        data.base_own = data.base_own.map(mask);
        for (forces, own) in data.joints.iter_mut().zip(data.own.iter_mut()).take(n) {
            *forces = JointForces {
                drag: mask(forces.drag),
                added_mass: mask(forces.added_mass),
                buoyancy: mask(forces.buoyancy),
                gravity: mask(forces.gravity),
            };
            *own = own.map(mask);
        }
    }
}

/// The added-mass matrix over base and joints, `M_A = −∂(W_am, τ_am)/∂(ν̇, q̈)` (docs/model.md
/// section 10, "What is computed"), `(6 + n)²` entries row-major into `out`
/// (`n = robot.joint_count()`; base first: linear, then angular, then the joints), at joint
/// positions `q` (the first `n` entries).
///
/// Column `k` is minus the added-mass forces at unit acceleration `k` with every velocity and
/// the current zero: exact, as the added-mass forces are linear in the accelerations and have no
/// other terms there. The matrix is then symmetrized (`½(M + Mᵀ)`: the two triangles differ by
/// rounding only); it is positive semi-definite. It does not depend on the base's orientation
/// or motion. `data` is the workspace (overwritten). An `out` shorter than `(6 + n)²` gets what
/// fits; a non-finite `q` gives NaN. Never fails, never panics.
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
pub fn robot_added_mass_matrix<T: SimdRealField + Copy, const J: usize, const S: usize>(
    robot: &Robot<T, J, S>,
    water: &Water<T>,
    coefficients: Option<&SegmentCoefficients<T, S>>,
    q: &[T; J],
    data: &mut RobotData<T, J>,
    out: &mut [T],
) {
    added_mass_block(robot, water, coefficients, q, data, out, 0);
}

/// The joints' block of [`robot_added_mass_matrix`], `M_A[6.., 6..]`: the added mass the
/// joints of a robot on a fixed base feel, `n²` entries row-major into `out`, at a sixth and
/// less of the cost when the robot has few joints (the base's six columns are not evaluated).
/// The same numbers as the full matrix's block; never fails, never panics.
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
pub fn robot_joint_added_mass_matrix<T: SimdRealField + Copy, const J: usize, const S: usize>(
    robot: &Robot<T, J, S>,
    water: &Water<T>,
    coefficients: Option<&SegmentCoefficients<T, S>>,
    q: &[T; J],
    data: &mut RobotData<T, J>,
    out: &mut [T],
) {
    added_mass_block(robot, water, coefficients, q, data, out, 6);
}

/// Rows and columns `first..6 + n` of the added-mass matrix (see [`robot_added_mass_matrix`]),
/// row-major and symmetrized, into `out`.
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
fn added_mass_block<T: SimdRealField + Copy, const J: usize, const S: usize>(
    robot: &Robot<T, J, S>,
    water: &Water<T>,
    coefficients: Option<&SegmentCoefficients<T, S>>,
    q: &[T; J],
    data: &mut RobotData<T, J>,
    out: &mut [T],
    first: usize,
) {
    let n = robot.joint_count();
    let width = (6 + n).saturating_sub(first);
    let zero = Vector3::zeros();
    let still = Current { velocity: zero, acceleration: zero };
    let rest = [T::zero(); J];
    for k in 0..width {
        let unit = |i: usize| if i == first + k { T::one() } else { T::zero() };
        let motion = BaseMotion {
            rotation: Matrix3::identity(),
            velocity: zero,
            angular_velocity: zero,
            acceleration: Vector3::new(unit(0), unit(1), unit(2)),
            angular_acceleration: Vector3::new(unit(3), unit(4), unit(5)),
        };
        let qdd: [T; J] = core::array::from_fn(|j| unit(j + 6));
        robot_hydro(robot, water, coefficients, &motion, &still, q, &rest, &qdd, data);
        let base = data.base.added_mass.to_array();
        let column = base.iter().copied().chain(data.joint_forces().iter().map(|f| f.added_mass));
        for (row, value) in column.skip(first).enumerate() {
            if let Some(slot) = out.get_mut(row * width + k) {
                *slot = -value;
            }
        }
    }
    let half = constant::<T>(0.5);
    for row in 0..width {
        for column in row + 1..width {
            if let (Some(&a), Some(&b)) = (out.get(row * width + column), out.get(column * width + row)) {
                let mean = (a + b) * half;
                for index in [row * width + column, column * width + row] {
                    if let Some(slot) = out.get_mut(index) {
                        *slot = mean;
                    }
                }
            }
        }
    }
}

/// Regressors of the drag and added-mass forces (docs/model.md sections 4 and 10, for whole
/// robots): with `s = robot.segments().len()` and `n = robot.joint_count()`, entry `(row, 2k + d)` of `drag`
/// (row-major, `(6 + n) × 2s`) is the generalized force on row `row` (the base wrench's six
/// components first, then the joints) of segment `k`'s drag along its normal direction `d` at
/// unit coefficient (a circular segment has all of it in `d = 0`, and zeros in `d = 1`); the
/// same for `added_mass`. So the drag forces at coefficients `cd` are `Σ_{k,d} cd[k][d] ·
/// drag[row, 2k + d]`, and the hydrodynamic forces are those two sums plus the buoyancy of
/// [`RobotData::joint_forces`] and [`RobotData::base_wrench`], which this also evaluates into
/// `data`. Outputs shorter than `(6 + n) · 2s` get what fits. Never fails, never panics.
#[allow(clippy::too_many_arguments)]
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
pub fn robot_hydro_regressors<T: SimdRealField + Copy, const J: usize, const S: usize>(
    robot: &Robot<T, J, S>,
    water: &Water<T>,
    motion: &BaseMotion<T>,
    current: &Current<T>,
    q: &[T; J],
    qd: &[T; J],
    qdd: &[T; J],
    data: &mut RobotData<T, J>,
    drag: &mut [T],
    added_mass: &mut [T],
) {
    robot_hydro_regressors_with(
        robot,
        water,
        AddedMassForm::Morison,
        motion,
        current,
        q,
        qd,
        qdd,
        data,
        drag,
        added_mass,
    );
}

/// [`robot_hydro_regressors`] with the added mass in the given [`AddedMassForm`] (Kirchhoff's
/// forces are linear in the coefficients too).
#[allow(clippy::too_many_arguments)]
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
pub fn robot_hydro_regressors_with<T: SimdRealField + Copy, const J: usize, const S: usize>(
    robot: &Robot<T, J, S>,
    water: &Water<T>,
    form: AddedMassForm,
    motion: &BaseMotion<T>,
    current: &Current<T>,
    q: &[T; J],
    qd: &[T; J],
    qdd: &[T; J],
    data: &mut RobotData<T, J>,
    drag: &mut [T],
    added_mass: &mut [T],
) {
    let zero = [[T::zero(); 2]; S];
    let none = SegmentCoefficients { cd: zero, cm: zero };
    robot_hydro(robot, water, Some(&none), motion, current, q, qd, qdd, data);
    let n = robot.joint_count();
    let columns = 2 * robot.segments().len();
    let surroundings = Surroundings::new(water, motion, current);
    let finite = finite_lanes(&[used(q, n), used(qd, n), used(qdd, n)]);
    let nan = T::zero() / T::zero();
    let base = Frame::base(motion);
    let (one, nothing) = (T::one(), T::zero());
    for (k, segment) in robot.segments().iter().enumerate() {
        let (frame, owner) = match segment.owner {
            Owner::Base => (&base, None),
            Owner::Link(i) => match data.frames.get(i) {
                Some(frame) => (frame, Some(i)),
                None => continue,
            },
        };
        for (d, unit) in [[one, nothing], [nothing, one]].into_iter().enumerate() {
            let (drag_wrench, mass_wrench) = segment_wrenches(frame, segment, unit, unit, &surroundings, form);
            let column = 2 * k + d;
            for (out, wrench) in [(&mut *drag, &drag_wrench), (&mut *added_mass, &mass_wrench)] {
                for (row, value) in wrench.to_array().into_iter().enumerate() {
                    if let Some(slot) = out.get_mut(row * columns + column) {
                        *slot = value.select(finite, nan);
                    }
                }
                // Every joint: zero, unless it moves the segment's body.
                for j in 0..n {
                    if let Some(slot) = out.get_mut((6 + j) * columns + column) {
                        *slot = T::zero().select(finite, nan);
                    }
                }
                let mut ancestor = owner;
                while let Some(j) = ancestor {
                    let (Some(joint), Some(joint_frame)) = (robot.joints().get(j), data.frames.get(j)) else { break };
                    let value = match joint.kind {
                        JointKind::Revolute => {
                            dot(&joint_frame.axis, &(wrench.moment - joint_frame.position.cross(&wrench.force)))
                        }
                        JointKind::Prismatic => dot(&joint_frame.axis, &wrench.force),
                    };
                    if let Some(slot) = out.get_mut((6 + j) * columns + column) {
                        *slot = value.select(finite, nan);
                    }
                    // Parents come before children: the walk ends.
                    ancestor = joint.parent.filter(|&p| p < j);
                }
            }
        }
    }
}
