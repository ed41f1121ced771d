//! Drag, added mass, buoyancy (with Froude-Krylov) and gravity on a whole robot: the generalized
//! force on every joint and the wrench on the base (docs/model.md section 10).
//!
//! One forward pass over the joints (parents before children, `crate::kinematics`) gives every
//! link's motion relative to the water, in its own body frame (`crate::frames`: the joint axis is
//! z, the link's geometry constant). Each body's segments give their drag and added-mass wrenches about
//! its joint (exact strip integrals). One backward pass sums them over subtrees, as in recursive
//! Newton-Euler, with the buoyancy and gravity of a subtree carried as the first moments of its
//! volume and mass (its force is the total volume or mass times a uniform field). A joint's
//! generalized force is the z component of its subtree's moment (revolute) or force
//! (prismatic); the base wrench is the sum over all bodies, in the base frame. Evaluation never
//! fails and never panics; a non-finite joint state gives NaN.

use nalgebra::{Matrix3, SimdBool, SimdRealField, Vector3};

use crate::algebra::rotate;
use crate::conditions::Conditions;
use crate::kinematics::{Frame, forward};
use crate::losses::{JointLoss, LossState};
use crate::model::Robot;
use crate::parts::{JointKind, Owner};
use crate::real::Real;
use crate::segment_forces::{axial_drag, segment_wrenches};
use crate::wrench::{EnvironmentWrench, JointForces, Wrench};

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
        let frame = Frame::rest();
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
            *slot = joint_loss(loss, speed);
        }
    }
}

/// A joint's losses at output speed `speed` ([`LossState::evaluate`]), lane by lane: every lane
/// gets exactly the bits of the scalar evaluation of its own state (the loss model branches on
/// values, which lanes may not share).
#[inline(always)]
fn joint_loss<T: Real>(state: &LossState<T>, speed: T) -> JointLoss<T> {
    let lane = |l: usize| state.map_scalars(|x| x.extract(l)).evaluate(speed.extract(l));
    let first = lane(0);
    let mut loss =
        JointLoss { visc: T::splat(first.visc), seal: T::splat(first.seal), current: T::splat(first.current) };
    for l in 1..T::LANES {
        let other = lane(l);
        loss.visc.replace(l, other.visc);
        loss.seal.replace(l, other.seal);
        loss.current.replace(l, other.current);
    }
    loss
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
