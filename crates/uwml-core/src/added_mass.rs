//! The added-mass matrix of a whole robot (docs/model.md section 10, "What is computed") by the
//! composite-rigid-body algorithm: each body's added inertia, a 6×6 spatial inertia in its body
//! frame from its segments' strip integrals, summed over subtrees (as Featherstone's CRBA sums
//! rigid-body inertias), and projected on the joints' motions. The added-mass forces at zero
//! velocity are `−ρ Cm A (n·a) n` on every slice (the normal parts of its acceleration for a
//! circular section), linear in the body's spatial acceleration: so `M_A` is exactly
//! `Σ_b J_bᵀ I_b J_b`, symmetric and positive semi-definite by construction, at a cost of a few
//! hundred operations per joint instead of one evaluation per column.

use nalgebra::{Matrix3, SimdRealField, Vector3};

use crate::check::constant;
use crate::frames::SegmentGeometry;
use crate::hydro::{finite_lanes, used};
use crate::lumped::LumpedFrame;
use crate::model::Robot;
use crate::parts::{JointKind, Owner, RobotSegment, Section};
use crate::real::Real;
use crate::segment_coefficients::SegmentCoefficients;
use crate::water::Water;

/// A spatial inertia `[[A, B], [Bᵀ, C]]` (linear rows first) about a frame's origin, in its
/// components: the wrench `−I (a, α)` for the acceleration `a` of the origin and `α`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Inertia<T: SimdRealField + Copy> {
    a: Matrix3<T>,
    b: Matrix3<T>,
    c: Matrix3<T>,
}

/// `[v]×`, the cross product with `v` as a matrix.
#[inline(always)]
fn skew<T: SimdRealField + Copy>(v: &Vector3<T>) -> Matrix3<T> {
    let zero = T::zero();
    Matrix3::new(zero, -v.z, v.y, v.z, zero, -v.x, -v.y, v.x, zero)
}

impl<T: SimdRealField + Copy> Inertia<T> {
    fn zero() -> Self {
        Self { a: Matrix3::zeros(), b: Matrix3::zeros(), c: Matrix3::zeros() }
    }

    fn add(&mut self, other: &Self) {
        self.a += other.a;
        self.b += other.b;
        self.c += other.c;
    }

    /// A segment's added inertia about its body's origin (`geometry` in the body frame), at
    /// added-mass coefficients `[cm0, cm1]`, in water of `density`. With `P` the slice's
    /// added-mass tensor per length and `r(s) = p + s u`: `A = ∫ P`, `B = −∫ P [r]×`,
    /// `C = −∫ [r]× P [r]×`.
    fn of_segment(segment: &RobotSegment<T>, geometry: &SegmentGeometry<T>, [cm0, cm1]: [T; 2], density: T) -> Self {
        let scale = density * segment.area;
        let u = geometry.axis();
        let p = match segment.section {
            Section::Rectangular { .. } => {
                let [n0, n1] = geometry.normals();
                n0 * n0.transpose() * (scale * cm0) + n1 * n1.transpose() * (scale * cm1)
            }
            Section::Circular { .. } => (Matrix3::identity() - u * u.transpose()) * (scale * cm0),
        };
        let length = segment.length;
        let (l1, l2, l3) = (length, length * length * constant(0.5), length * length * length * constant(1.0 / 3.0));
        let (start, along) = (skew(&geometry.start), skew(&u));
        let first = geometry.start * l1 + u * l2;
        let q = (start * p * start) * l1 + (start * p * along + along * p * start) * l2 + (along * p * along) * l3;
        Self { a: p * l1, b: -(p * skew(&first)), c: -q }
    }

    /// A lumped model's added mass about its body frame's origin (its `M_A` about `P`, moved).
    fn of_lumped(model: &LumpedFrame<T>) -> Self {
        let m = &model.added_mass;
        let about_point = Self {
            a: m.fixed_view::<3, 3>(0, 0).into_owned(),
            b: m.fixed_view::<3, 3>(0, 3).into_owned(),
            c: m.fixed_view::<3, 3>(3, 3).into_owned(),
        };
        about_point.in_parent(&Matrix3::identity(), &model.point)
    }

    /// This inertia (of a child frame whose axes are `rotation` and whose origin is `offset` in
    /// the parent's frame) about the parent's origin in its components: `Xᵀ I X`.
    fn in_parent(&self, rotation: &Matrix3<T>, offset: &Vector3<T>) -> Self {
        let turn = |m: &Matrix3<T>| rotation * m * rotation.transpose();
        let (a, b, c) = (turn(&self.a), turn(&self.b), turn(&self.c));
        let o = skew(offset);
        let top_right = b - a * o;
        Self { a, b: top_right, c: c + o * top_right - b.transpose() * o }
    }

    /// The wrench `I s` for the unit motion `s` of a joint along or about the frame's z axis:
    /// `(force, moment)`.
    fn along_z(&self, kind: JointKind) -> (Vector3<T>, Vector3<T>) {
        match kind {
            // s = (0, e_z): the third columns of B and C.
            JointKind::Revolute => (self.b.column(2).into_owned(), self.c.column(2).into_owned()),
            // s = (e_z, 0): the third columns of A and Bᵀ.
            JointKind::Prismatic => (self.a.column(2).into_owned(), self.b.row(2).transpose()),
        }
    }
}

/// Every body's added inertia about its origin in its body frame, `[base, link 0, ...]` summed
/// over subtrees (the composite inertias), and each joint's rotation `F_parent ← F_i` and origin
/// in `F_parent` at `q`.
/// Returns the base's composite inertia.
fn composite_inertias<T: Real, const J: usize, const S: usize, const B: usize>(
    robot: &Robot<T, J, S, B>,
    water: &Water<T>,
    coefficients: Option<&SegmentCoefficients<T, S>>,
    q: &[T; J],
    inertias: &mut [Inertia<T>; J],
    placements: &mut [(Matrix3<T>, Vector3<T>); J],
) -> Inertia<T> {
    let n = robot.joint_count();
    let frames = robot.frames();
    let mut base = Inertia::zero();
    for slot in inertias.iter_mut().take(n) {
        *slot = Inertia::zero();
    }
    for (k, (segment, geometry)) in robot.segments().iter().zip(&frames.segments).enumerate() {
        let cm = coefficients.and_then(|c| c.cm().get(k).copied()).unwrap_or(segment.cm);
        let own = Inertia::of_segment(segment, geometry, cm, water.density());
        match segment.owner {
            Owner::Base => base.add(&own),
            Owner::Link(i) => {
                if let Some(slot) = inertias.get_mut(i) {
                    slot.add(&own);
                }
            }
        }
    }
    for (owner, model) in robot.lumped().iter() {
        let own = Inertia::of_lumped(model);
        match *owner {
            Owner::Base => base.add(&own),
            Owner::Link(i) => {
                if let Some(slot) = inertias.get_mut(i) {
                    slot.add(&own);
                }
            }
        }
    }
    // Children (later joints) into their parents.
    for i in (0..n).rev() {
        let (Some(joint), Some(geometry), Some(&q)) = (robot.joints().get(i), frames.joints.get(i), q.get(i)) else {
            continue;
        };
        let (turn, offset) = match joint.kind {
            JointKind::Revolute => {
                let (sin, cos) = q.sin_cos();
                let zero = T::zero();
                (Matrix3::new(cos, -sin, zero, sin, cos, zero, zero, zero, T::one()), geometry.origin)
            }
            JointKind::Prismatic => (Matrix3::identity(), geometry.origin + geometry.axis * q),
        };
        let rotation = match &geometry.turn {
            Some(t) => t * turn,
            None => turn,
        };
        if let Some(slot) = placements.get_mut(i) {
            *slot = (rotation, offset);
        }
        let Some(&own) = inertias.get(i) else { continue };
        let moved = own.in_parent(&rotation, &offset);
        match joint.parent.filter(|&p| p < i).and_then(|p| inertias.get_mut(p)) {
            Some(parent) => parent.add(&moved),
            None => base.add(&moved),
        }
    }
    base
}

/// The added-mass matrix over base and joints, `M_A = −∂(W_am, τ_am)/∂(ν̇, q̈)` (docs/model.md
/// section 10, "What is computed"), `(6 + n)²` entries row-major into `out`
/// (`n = robot.joint_count()`; base first: linear, then angular, then the joints), at joint
/// positions `q` (the first `n` entries).
///
/// By the composite-rigid-body algorithm on the bodies' added inertias (see the module): the
/// same numbers, to rounding, as minus the added-mass forces at unit accelerations with every
/// velocity and the current zero. Exactly symmetric and positive semi-definite; it does not
/// depend on the base's orientation or motion, nor on the added-mass form. An `out` shorter than `(6 + n)²` gets what fits; a non-finite `q` gives NaN. Never
/// fails, never panics.
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
pub fn robot_added_mass_matrix<T: Real, const J: usize, const S: usize, const B: usize>(
    robot: &Robot<T, J, S, B>,
    water: &Water<T>,
    coefficients: Option<&SegmentCoefficients<T, S>>,
    q: &[T; J],
    out: &mut [T],
) {
    added_mass_block(robot, water, coefficients, q, out, 0);
}

/// The joints' block of [`robot_added_mass_matrix`], `M_A[6.., 6..]`: the added mass the
/// joints of a robot on a fixed base feel, `n²` entries row-major into `out`. The same numbers
/// as the full matrix's block; never fails, never panics.
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
pub fn robot_joint_added_mass_matrix<T: Real, const J: usize, const S: usize, const B: usize>(
    robot: &Robot<T, J, S, B>,
    water: &Water<T>,
    coefficients: Option<&SegmentCoefficients<T, S>>,
    q: &[T; J],
    out: &mut [T],
) {
    added_mass_block(robot, water, coefficients, q, out, 6);
}

/// Rows and columns `first..6 + n` of the added-mass matrix (see [`robot_added_mass_matrix`]),
/// row-major, into `out`.
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
fn added_mass_block<T: Real, const J: usize, const S: usize, const B: usize>(
    robot: &Robot<T, J, S, B>,
    water: &Water<T>,
    coefficients: Option<&SegmentCoefficients<T, S>>,
    q: &[T; J],
    out: &mut [T],
    first: usize,
) {
    let n = robot.joint_count();
    let width = (6 + n).saturating_sub(first);
    let finite = finite_lanes(&[used(q, n)]);
    let nan = T::zero() / T::zero();
    // Joints on different branches do not move each other: zero, unless written below.
    for slot in out.iter_mut().take(width * width) {
        *slot = T::zero().select(finite, nan);
    }
    let mut put = |row: usize, column: usize, value: T| {
        let value = value.select(finite, nan);
        for (r, c) in [(row, column), (column, row)] {
            if let (Some(r), Some(c)) = (r.checked_sub(first), c.checked_sub(first))
                && let Some(slot) = out.get_mut(r * width + c)
            {
                *slot = value;
            }
        }
    };
    let mut inertias = [Inertia::zero(); J];
    let mut placements = [(Matrix3::identity(), Vector3::zeros()); J];
    let base = composite_inertias(robot, water, coefficients, q, &mut inertias, &mut placements);
    // The base block: the whole robot's composite inertia.
    if first == 0 {
        for r in 0..3 {
            for c in 0..3 {
                let entry = |m: &Matrix3<T>| m.get((r, c)).copied().unwrap_or_else(T::zero);
                put(r, c, entry(&base.a));
                put(r, 3 + c, entry(&base.b));
                put(3 + r, 3 + c, entry(&base.c));
            }
        }
    }
    // Each joint's column: its subtree's wrench at its unit motion, carried up to the base.
    for j in 0..n {
        let (Some(joint), Some(inertia)) = (robot.joints().get(j), inertias.get(j)) else { continue };
        let (mut force, mut moment) = inertia.along_z(joint.kind);
        let project = |kind: JointKind, force: &Vector3<T>, moment: &Vector3<T>| match kind {
            JointKind::Revolute => moment.z,
            JointKind::Prismatic => force.z,
        };
        put(6 + j, 6 + j, project(joint.kind, &force, &moment));
        let mut at = j;
        while let (Some(joint), Some((rotation, offset))) = (robot.joints().get(at), placements.get(at)) {
            force = rotation * force;
            moment = rotation * moment + offset.cross(&force);
            match joint.parent.filter(|&p| p < at) {
                Some(parent) => {
                    if let Some(kind) = robot.joints().get(parent).map(|p| p.kind) {
                        put(6 + parent, 6 + j, project(kind, &force, &moment));
                    }
                    at = parent;
                }
                None => {
                    for (row, value) in
                        [force.x, force.y, force.z, moment.x, moment.y, moment.z].into_iter().enumerate()
                    {
                        put(row, 6 + j, value);
                    }
                    break;
                }
            }
        }
    }
}
