//! The results of a whole robot's evaluation: wrenches on bodies and generalized forces on
//! joints, per component (docs/model.md section 10, "What is computed").

use core::ops::{Add, AddAssign};

use nalgebra::{SimdRealField, Vector3};

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

    /// The same wrench about the origin, given about `point`.
    #[inline(always)]
    pub(crate) fn moved_from(self, point: &Vector3<T>) -> Self {
        Self { force: self.force, moment: self.moment + point.cross(&self.force) }
    }

    pub(crate) fn map(&self, f: impl Fn(T) -> T) -> Self {
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

    pub(crate) fn map(&self, f: impl Fn(&Wrench<T>) -> Wrench<T>) -> Self {
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
