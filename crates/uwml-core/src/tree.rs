//! Drag, added mass, buoyancy (with Froude-Krylov) and gravity on a whole robot: the generalized
//! force on every joint and the wrench on the base (docs/model.md section 10).
//!
//! One forward pass over the joints (parents before children) gives every link's motion
//! relative to the water, in its own body frame (`crate::frames`: the joint axis is z, the
//! link's geometry constant). Each body's segments give their drag and added-mass wrenches about
//! its joint (exact strip integrals). One backward pass sums them over subtrees, as in recursive
//! Newton-Euler, with the buoyancy and gravity of a subtree carried as the first moments of its
//! volume and mass (its force is the total volume or mass times a uniform field). A joint's
//! generalized force is the z component of its subtree's moment (revolute) or force
//! (prismatic); the base wrench is the sum over all bodies, in the base frame. Evaluation never
//! fails and never panics; a non-finite joint state gives NaN.

use nalgebra::{Matrix3, SimdBool, SimdRealField, Vector3};

pub use crate::added_mass::{robot_added_mass_matrix, robot_joint_added_mass_matrix};
use crate::conditions::Conditions;
use crate::frames::JointFrame;
use crate::kinematics::{rotate, rotate_back};
use crate::losses::JointLoss;
use crate::model::Water;
use crate::motion::{BaseMotion, Current};
use crate::real::Real;
use crate::robot::{JointKind, Owner, Robot, TreeJoint};
pub use crate::segment_forces::AddedMassForm;
use crate::segment_forces::{axial_drag, segment_wrenches};
pub use crate::tree_regressors::robot_hydro_regressors;
pub use crate::wrench::{EnvironmentWrench, JointForces, Wrench};

/// The motion of a body frame (at its joint) relative to the water, in its own components, and
/// where it sits in its parent's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Frame<T: SimdRealField + Copy> {
    pub(crate) angular_velocity: Vector3<T>,
    pub(crate) angular_acceleration: Vector3<T>,
    /// Velocity of the frame origin less the water's.
    velocity: Vector3<T>,
    /// Classical acceleration of the frame origin less the water's.
    acceleration: Vector3<T>,
    /// Gravity's acceleration vector.
    gravity: Vector3<T>,
    /// The water's acceleration.
    water_acceleration: Vector3<T>,
    /// `(sin q, cos q)` of a revolute joint's angle; `(0, 1)` for a prismatic joint.
    turn: (T, T),
    /// The frame origin in the parent's body frame (a prismatic joint's slide included).
    pub(crate) offset: Vector3<T>,
    /// What is known of the motion from the robot's structure alone.
    shape: Shape,
}

/// What a frame's motion is, known from the robot's structure and whether the base is at rest:
/// the forward pass then skips the products with zeros.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Shape {
    /// At rest, in still water: the base of a fixed robot.
    Still,
    /// Turning about its own z axis through its fixed origin, in still water: `ω = ω_z e_z`,
    /// `α = α_z e_z`, and the origin at rest (a revolute joint's link on a base at rest).
    AboutAxis,
    /// Any motion.
    General,
}

/// A subtree's drag and added-mass wrenches about its joint, and the first moments of its volume
/// and mass about it, in its body frame.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Subtree<T: SimdRealField + Copy> {
    drag: Wrench<T>,
    added_mass: Wrench<T>,
    volume_moment: Vector3<T>,
    mass_moment: Vector3<T>,
}

/// The workspace and results of an evaluation of a robot of up to `J` joints (Pinocchio's
/// `Data`): make one, evaluate into it as often as needed, read the results.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RobotData<T: SimdRealField + Copy, const J: usize> {
    pub(crate) frames: [Frame<T>; J],
    subtree: [Subtree<T>; J],
    /// Each link's own drag and added-mass wrench, about its joint, in its body frame.
    own: [Wrench<T>; J],
    /// The base's own, about its origin.
    base_own: Wrench<T>,
    pub(crate) base_frame: Frame<T>,
    joints: [JointForces<T>; J],
    losses: [JointLoss<T>; J],
    base: EnvironmentWrench<T>,
    joint_count: usize,
    base_rotation: Matrix3<T>,
    density: T,
}

impl<T: SimdRealField + Copy, const J: usize> RobotData<T, J> {
    /// A workspace for robots of up to `J` joints.
    #[must_use]
    pub fn new() -> Self {
        let zero = Vector3::zeros();
        let frame = Frame {
            angular_velocity: zero,
            angular_acceleration: zero,
            velocity: zero,
            acceleration: zero,
            gravity: zero,
            water_acceleration: zero,
            turn: (T::zero(), T::one()),
            offset: zero,
            shape: Shape::General,
        };
        let nothing = T::zero();
        Self {
            frames: [frame; J],
            subtree: [Subtree {
                drag: Wrench::zero(),
                added_mass: Wrench::zero(),
                volume_moment: zero,
                mass_moment: zero,
            }; J],
            own: [Wrench::zero(); J],
            base_own: Wrench::zero(),
            base_frame: frame,
            joints: [JointForces { drag: nothing, added_mass: nothing, buoyancy: nothing, gravity: nothing }; J],
            losses: [JointLoss { visc: nothing, seal: nothing, current: nothing }; J],
            base: EnvironmentWrench::zero(),
            joint_count: 0,
            base_rotation: Matrix3::identity(),
            density: nothing,
        }
    }

    /// The generalized force on every joint of the last evaluation.
    pub fn joint_forces(&self) -> &[JointForces<T>] {
        self.joints.get(..self.joint_count).unwrap_or(&[])
    }

    /// Each joint's oil and seal losses in the last evaluation (zero for a joint without, and for
    /// all when the conditions had none).
    pub fn joint_losses(&self) -> &[JointLoss<T>] {
        self.losses.get(..self.joint_count).unwrap_or(&[])
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
    pub fn body_wrench<const S: usize, const B: usize>(
        &self,
        robot: &Robot<T, J, S, B>,
        body: Option<usize>,
    ) -> Option<Wrench<T>> {
        let frames = robot.frames();
        let (own, frame, bulk) = match body {
            None => (self.base_own, &self.base_frame, &frames.base),
            Some(i) => match (self.own.get(i), self.frames.get(i), frames.joints.get(i)) {
                (Some(own), Some(frame), Some(joint)) if i < self.joint_count => (*own, frame, &joint.bulk),
                _ => return None,
            },
        };
        let b = (frame.water_acceleration - frame.gravity) * self.density;
        let whole = Wrench {
            force: own.force + b * bulk.volume + frame.gravity * bulk.mass,
            moment: own.moment + bulk.volume_moment.cross(&b) + bulk.mass_moment.cross(&frame.gravity),
        };
        let mut about_com = whole.moved_from(&-bulk.com);
        // Up the tree to the base's components, then the world's.
        let mut at = body;
        while let Some(i) = at {
            let (Some(joint), Some(frame), Some(geometry)) =
                (robot.joints().get(i), self.frames.get(i), frames.joints.get(i))
            else {
                break;
            };
            about_com = Wrench {
                force: frame.in_parent(joint.kind, geometry, &about_com.force),
                moment: frame.in_parent(joint.kind, geometry, &about_com.moment),
            };
            at = joint.parent.filter(|&p| p < i);
        }
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

/// `Rz(q)ᵀ v` for `turn = (sin q, cos q)`.
#[inline(always)]
fn turn_back<T: SimdRealField + Copy>((sin, cos): (T, T), v: &Vector3<T>) -> Vector3<T> {
    Vector3::new(cos * v.x + sin * v.y, cos * v.y - sin * v.x, v.z)
}

impl<T: SimdRealField + Copy> Frame<T> {
    /// The base's own frame, relative to the water.
    #[inline(always)]
    fn base(motion: &BaseMotion<T>, water: &Water<T>, current: &Current<T>) -> Self {
        let rotation = motion.rotation();
        let (v, w) = motion.twist();
        let (v_dot, w_dot) = motion.twist_derivative();
        let zero = Vector3::zeros();
        let gravity = Vector3::new(rotation.m31, rotation.m32, rotation.m33) * -water.gravity();
        let still = Self {
            angular_velocity: zero,
            angular_acceleration: zero,
            velocity: zero,
            acceleration: zero,
            gravity,
            water_acceleration: zero,
            turn: (T::zero(), T::one()),
            offset: zero,
            shape: Shape::Still,
        };
        if [v, w, v_dot, w_dot, *current.velocity(), *current.acceleration()].iter().all(|x| *x == zero) {
            return still;
        }
        let water_acceleration = rotate_back(rotation, current.acceleration());
        Self {
            angular_velocity: w,
            angular_acceleration: w_dot,
            velocity: v - rotate_back(rotation, current.velocity()),
            acceleration: v_dot + w.cross(&v) - water_acceleration,
            water_acceleration,
            shape: Shape::General,
            ..still
        }
    }

    /// A vector in this frame's components, in its parent's.
    #[inline(always)]
    pub(crate) fn in_parent(&self, kind: JointKind, joint: &JointFrame<T>, v: &Vector3<T>) -> Vector3<T> {
        let v = match kind {
            JointKind::Revolute => {
                let (sin, cos) = self.turn;
                Vector3::new(cos * v.x - sin * v.y, sin * v.x + cos * v.y, v.z)
            }
            JointKind::Prismatic => *v,
        };
        match &joint.turn {
            Some(turn) => rotate(turn, &v),
            None => v,
        }
    }

    /// The frame of a child moved by `joint` (whose body frame is `frame`) at `(q, q̇, q̈)`;
    /// `still_water`: whether the water's acceleration is zero.
    #[inline(always)]
    fn child(&self, joint: &TreeJoint<T>, frame: &JointFrame<T>, [q, qd, qdd]: [T; 3], still_water: bool) -> Self
    where
        T: Real,
    {
        let revolute = joint.kind == JointKind::Revolute;
        let (turn, offset) =
            if revolute { (q.sin_cos(), frame.origin) } else { ((T::zero(), T::one()), frame.origin + frame.axis * q) };
        let before_turn = |v: &Vector3<T>| match &frame.turn {
            Some(t) => rotate_back(t, v),
            None => *v,
        };
        let turned = |v: &Vector3<T>| if revolute { turn_back(turn, v) } else { *v };
        let into = |v: &Vector3<T>| turned(&before_turn(v));
        let zero = Vector3::zeros();
        let (w, alpha, mut velocity, mut acceleration) = match self.shape {
            Shape::Still => (zero, zero, zero, zero),
            // The parent turns about its z axis through its fixed origin: the joint's motion is
            // the unit turn's, scaled by the parent's rates.
            Shape::AboutAxis if revolute => {
                let (rate, rate_change) = (self.angular_velocity.z, self.angular_acceleration.z);
                let [axis, tangential, centripetal] = &frame.unit_turn;
                (
                    turned(&(axis * rate)),
                    turned(&(axis * rate_change)),
                    turned(&(tangential * rate)),
                    turned(&(tangential * rate_change + centripetal * (rate * rate))),
                )
            }
            Shape::AboutAxis | Shape::General => {
                let (velocity, acceleration) = self.point_motion(&offset);
                (into(&self.angular_velocity), into(&self.angular_acceleration), into(&velocity), into(&acceleration))
            }
        };
        // ω × e_z = (ω_y, −ω_x, 0).
        let (angular_velocity, angular_acceleration) = if revolute {
            (Vector3::new(w.x, w.y, w.z + qd), Vector3::new(alpha.x + qd * w.y, alpha.y - qd * w.x, alpha.z + qdd))
        } else {
            let twice = qd + qd;
            velocity.z += qd;
            acceleration += Vector3::new(twice * w.y, -twice * w.x, qdd);
            (w, alpha)
        };
        Self {
            angular_velocity,
            angular_acceleration,
            velocity,
            acceleration,
            gravity: into(&self.gravity),
            water_acceleration: if still_water { zero } else { into(&self.water_acceleration) },
            turn,
            offset,
            shape: if self.shape == Shape::Still && revolute { Shape::AboutAxis } else { Shape::General },
        }
    }

    /// The twist relative to the water `(v, ω)` of the material point at `r` and its components'
    /// derivative `(v̇, α)` (`v̇ = a − ω × v`, `a` the point's acceleration relative to the water).
    #[inline(always)]
    pub(crate) fn twist_at(&self, r: &Vector3<T>) -> [Vector3<T>; 4] {
        let (v, a) = self.point_motion(r);
        let w = self.angular_velocity;
        [v, w, a - w.cross(&v), self.angular_acceleration]
    }

    /// Velocity and acceleration (relative to the water) of the material point at `r`.
    #[inline(always)]
    pub(crate) fn point_motion(&self, r: &Vector3<T>) -> (Vector3<T>, Vector3<T>) {
        let w = &self.angular_velocity;
        let wr = w.cross(r);
        (self.velocity + wr, self.acceleration + self.angular_acceleration.cross(r) + w.cross(&wr))
    }
}

/// The first `n` entries.
pub(crate) fn used<T, const J: usize>(x: &[T; J], n: usize) -> &[T] {
    x.get(..n).unwrap_or(&[])
}

/// Which lanes have every joint state finite.
pub(crate) fn finite_lanes<T: SimdRealField + Copy>(states: &[&[T]]) -> T::SimdBool {
    let sum = states.iter().flat_map(|s| s.iter()).fold(T::zero(), |sum, &x| sum + x * T::zero());
    sum.simd_eq(T::zero())
}

/// Drag, added-mass, buoyancy and gravity forces on every joint of `robot` and the wrench on its
/// base, and each joint's oil and seal losses if `conditions` has them, at joint state
/// `[q, q̇, q̈]` (the first `robot.joint_count()` entries of each), into `data` (read
/// [`RobotData::joint_forces`], [`RobotData::joint_losses`] and [`RobotData::base_wrench`]).
///
/// Never fails and never panics; a non-finite joint state gives NaN everywhere (in its lane).
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
pub fn robot_hydro<T: Real, const J: usize, const S: usize, const B: usize>(
    robot: &Robot<T, J, S, B>,
    conditions: &Conditions<'_, T, J, S>,
    state: [&[T; J]; 3],
    data: &mut RobotData<T, J>,
) {
    hydro_in(robot, conditions, state, data);
    let Some(losses) = conditions.losses else { return };
    let [_, qd, _] = state;
    let n = robot.joint_count();
    for ((slot, loss), &speed) in data.losses.iter_mut().zip(losses).zip(qd).take(n) {
        if let Some(loss) = loss {
            *slot = T::joint_loss(loss, speed);
        }
    }
}

/// The forward pass: every link's frame into `data.frames` (parents first).
#[inline(always)]
fn forward<T: Real, const J: usize, const S: usize, const B: usize>(
    robot: &Robot<T, J, S, B>,
    base: &Frame<T>,
    [q, qd, qdd]: [&[T; J]; 3],
    frames: &mut [Frame<T>; J],
) {
    let n = robot.joint_count();
    let still_water = base.water_acceleration == Vector3::zeros();
    let per_joint = robot.joints().iter().zip(&robot.frames().joints).zip(q.iter().zip(qd).zip(qdd)).take(n);
    for (i, ((joint, geometry), ((&q, &qd), &qdd))) in per_joint.enumerate() {
        // Parents come first: the parent is read from the frames before `i`, the child written
        // in place.
        let Some((done, [slot, ..])) = frames.split_at_mut_checked(i) else { continue };
        let parent = match joint.parent {
            Some(p) => done.get(p).unwrap_or(base),
            None => base,
        };
        *slot = parent.child(joint, geometry, [q, qd, qdd], still_water);
    }
}

/// [`robot_hydro`] without the joint losses (whatever `conditions` holds): they are zero.
#[inline(always)]
pub(crate) fn hydro_in<T: Real, const J: usize, const S: usize, const B: usize>(
    robot: &Robot<T, J, S, B>,
    conditions: &Conditions<'_, T, J, S>,
    state: [&[T; J]; 3],
    data: &mut RobotData<T, J>,
) {
    let Conditions { water, motion, current, coefficients, form, .. } = conditions;
    let form = *form;
    let n = robot.joint_count();
    let [q, qd, qdd] = state;
    let finite = finite_lanes(&[used(q, n), used(qd, n), used(qdd, n)]);
    let rho = water.density();
    let frames = robot.frames();
    data.joint_count = n;
    for slot in data.losses.iter_mut().take(n) {
        slot.visc = T::zero();
        slot.seal = T::zero();
        slot.current = T::zero();
    }
    data.base_rotation = *motion.rotation();
    data.density = rho;
    let base = Frame::base(motion, water, current);
    data.base_frame = base;
    forward(robot, &base, state, &mut data.frames);
    // Field by field: a whole `Subtree` value would be built aside and copied in.
    for (subtree, geometry) in data.subtree.iter_mut().zip(&frames.joints).take(n) {
        subtree.drag = Wrench::zero();
        subtree.added_mass = Wrench::zero();
        subtree.volume_moment = geometry.bulk.volume_moment;
        subtree.mass_moment = geometry.bulk.mass_moment;
    }
    let mut total = Subtree {
        drag: Wrench::zero(),
        added_mass: Wrench::zero(),
        volume_moment: frames.base.volume_moment,
        mass_moment: frames.base.mass_moment,
    };
    // Each segment's drag and added mass, on its body, in its body frame.
    for (k, (segment, geometry)) in robot.segments().iter().zip(&frames.segments).enumerate() {
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
        let (drag, added_mass) = segment_wrenches(frame, segment, geometry, cd, cm, rho, form);
        body.drag += drag;
        body.added_mass += added_mass;
        if geometry.axial {
            body.drag += axial_drag(frame, segment, geometry, segment.cd_axial, rho);
        }
    }
    // Each lumped model's damping and added mass, on its body (docs/model.md section 12.1).
    for (owner, model) in robot.lumped().iter() {
        let (frame, body) = match *owner {
            Owner::Base => (&base, &mut total),
            Owner::Link(i) => match (data.frames.get(i), data.subtree.get_mut(i)) {
                (Some(frame), Some(body)) => (frame, body),
                _ => continue,
            },
        };
        let (drag, added_mass) = model.wrenches(frame.twist_at(&model.point));
        body.drag += drag;
        body.added_mass += added_mass;
    }
    data.base_own = total.drag + total.added_mass;
    for (own, subtree) in data.own.iter_mut().zip(data.subtree.iter()).take(n) {
        *own = subtree.drag + subtree.added_mass;
    }
    // Backward: subtrees summed into their parents; each joint's generalized force.
    for i in (0..n).rev() {
        // The subtree is read in place and its parent (before it) written.
        let (Some(joint), Some(frame), Some(geometry), Some((before, [subtree, ..]))) =
            (robot.joints().get(i), data.frames.get(i), frames.joints.get(i), data.subtree.split_at_mut_checked(i))
        else {
            continue;
        };
        let g = frame.gravity;
        let b = (frame.water_acceleration - g) * rho;
        let z_cross = |a: &Vector3<T>, b: &Vector3<T>| a.x * b.y - a.y * b.x;
        let forces = match joint.kind {
            JointKind::Revolute => JointForces {
                drag: subtree.drag.moment.z,
                added_mass: subtree.added_mass.moment.z,
                buoyancy: z_cross(&subtree.volume_moment, &b),
                gravity: z_cross(&subtree.mass_moment, &g),
            },
            JointKind::Prismatic => JointForces {
                drag: subtree.drag.force.z,
                added_mass: subtree.added_mass.force.z,
                buoyancy: b.z * geometry.subtree_volume,
                gravity: g.z * geometry.subtree_mass,
            },
        };
        if let Some(slot) = data.joints.get_mut(i) {
            *slot = forces;
        }
        let up = |v: &Vector3<T>| frame.in_parent(joint.kind, geometry, v);
        let moved = |w: &Wrench<T>| {
            let force = up(&w.force);
            Wrench { force, moment: up(&w.moment) + frame.offset.cross(&force) }
        };
        let parent = match joint.parent.and_then(|p| before.get_mut(p)) {
            Some(parent) => parent,
            None => &mut total,
        };
        parent.drag += moved(&subtree.drag);
        parent.added_mass += moved(&subtree.added_mass);
        parent.volume_moment += up(&subtree.volume_moment) + frame.offset * geometry.subtree_volume;
        parent.mass_moment += up(&subtree.mass_moment) + frame.offset * geometry.subtree_mass;
    }
    let g = base.gravity;
    let b = (base.water_acceleration - g) * rho;
    data.base = EnvironmentWrench {
        drag: total.drag,
        added_mass: total.added_mass,
        buoyancy: Wrench { force: b * frames.total_volume, moment: total.volume_moment.cross(&b) },
        gravity: Wrench { force: g * frames.total_mass, moment: total.mass_moment.cross(&g) },
    };
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
