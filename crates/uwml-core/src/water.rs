//! The fluid a robot moves in: its density and gravity, checked once.

use nalgebra::{RealField, SimdRealField};

use crate::bounds::{MAX_DENSITY, MAX_GRAVITY};
use crate::check::{check_at_most, check_non_negative, check_positive, constant};
use crate::error::ModelError;

/// The fluid a robot moves in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Water<T: SimdRealField + Copy> {
    density: T,
    gravity: T,
}

impl<T: RealField + Copy> Water<T> {
    /// Water of the given density [kg/m³] under the given gravity [m/s²].
    ///
    /// # Errors
    /// Density not positive and finite, or gravity negative or not finite; either beyond
    /// [`MAX_DENSITY`], [`MAX_GRAVITY`].
    pub fn new(density: T, gravity: T) -> Result<Self, ModelError> {
        Ok(Self {
            density: check_at_most(
                check_positive(density, "water.density", None)?,
                MAX_DENSITY,
                "water.density",
                None,
            )?,
            gravity: check_at_most(
                check_non_negative(gravity, "water.gravity", None)?,
                MAX_GRAVITY,
                "water.gravity",
                None,
            )?,
        })
    }
}

impl<T: SimdRealField + Copy> Water<T> {
    /// Density [kg/m³].
    pub const fn density(&self) -> T {
        self.density
    }

    /// Gravitational acceleration [m/s²].
    pub const fn gravity(&self) -> T {
        self.gravity
    }
}

impl<T: RealField + Copy> Default for Water<T> {
    /// Fresh water as in the paper: 1000 kg/m³, g = 9.81 m/s².
    fn default() -> Self {
        Self { density: constant(1000.0), gravity: constant(9.81) }
    }
}

impl<T: RealField + Copy> Water<T> {
    /// The same water over another scalar type (which must keep values, as `Dual::constant` does).
    pub(crate) fn map_scalars<U: SimdRealField + Copy>(&self, f: impl Fn(T) -> U) -> Water<U> {
        Water { density: f(self.density), gravity: f(self.gravity) }
    }
}

impl<T: RealField + Copy> Water<T> {
    /// The same water over a SIMD type (see [`crate::Robot::splat`]).
    #[must_use]
    pub fn splat<L: SimdRealField<Element = T> + Copy>(&self) -> Water<L> {
        self.map_scalars(L::splat)
    }
}
