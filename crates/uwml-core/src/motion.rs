//! The motion of a robot's base and of the water around it, per evaluation (docs/model.md section
//! 10, "Base motion and current").
//!
//! Base: orientation `R` (world from base) as a unit quaternion `(w, x, y, z)`, scalar first
//! (MuJoCo's order); the twist `ν = (v, ω)`, velocity of the base origin and angular velocity,
//! in base-frame components; `ν̇ = (v̇, ω̇)`, the time derivatives of those components (Fossen's
//! `ν̇`; Pinocchio's free-flyer acceleration in the LOCAL frame), so that the base origin's
//! classical acceleration is `v̇ + ω × v`. Current: a uniform water velocity and acceleration
//! in world components.

use nalgebra::{Matrix3, RealField, SMatrix, SimdRealField, Vector3};

use crate::bounds::AXIS_TOLERANCE;
use crate::check::{check_vector, constant};
use crate::error::{ModelError, Problem};

/// The base's orientation and motion at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BaseMotion<T: SimdRealField + Copy> {
    /// World from base.
    pub(crate) rotation: Matrix3<T>,
    pub(crate) velocity: Vector3<T>,
    pub(crate) angular_velocity: Vector3<T>,
    pub(crate) acceleration: Vector3<T>,
    pub(crate) angular_acceleration: Vector3<T>,
}

/// The water's uniform velocity and acceleration, world frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Current<T: SimdRealField + Copy> {
    pub(crate) velocity: Vector3<T>,
    pub(crate) acceleration: Vector3<T>,
}

/// The rotation of the unit quaternion `(w, x, y, z)`.
fn rotation_of<T: RealField + Copy>([w, x, y, z]: [T; 4]) -> Matrix3<T> {
    let two = constant::<T>(2.0);
    let one = T::one();
    Matrix3::new(
        one - two * (y * y + z * z),
        two * (x * y - w * z),
        two * (x * z + w * y),
        two * (x * y + w * z),
        one - two * (x * x + z * z),
        two * (y * z - w * x),
        two * (x * z - w * y),
        two * (y * z + w * x),
        one - two * (x * x + y * y),
    )
}

impl<T: RealField + Copy> BaseMotion<T> {
    /// The base at `orientation` (a unit quaternion `(w, x, y, z)`, normalized here), moving with
    /// `velocity` and `angular_velocity` (base components) and their component derivatives.
    ///
    /// # Errors
    /// A non-finite number (naming `base.orientation`, `base.velocity`, ...), or an orientation
    /// whose norm is not 1 within [`AXIS_TOLERANCE`](crate::AXIS_TOLERANCE).
    pub fn new(
        orientation: [T; 4],
        velocity: Vector3<T>,
        angular_velocity: Vector3<T>,
        acceleration: Vector3<T>,
        angular_acceleration: Vector3<T>,
    ) -> Result<Self, ModelError> {
        if !orientation.iter().all(|x| x.is_finite()) {
            return Err(ModelError::new("base.orientation", None, Problem::NonFinite));
        }
        let norm = orientation.iter().fold(T::zero(), |sum, &x| sum + x * x).sqrt();
        if (norm - T::one()).abs() > constant(AXIS_TOLERANCE) {
            return Err(ModelError::new("base.orientation", None, Problem::NotUnit));
        }
        Ok(Self {
            rotation: rotation_of(orientation.map(|x| x / norm)),
            velocity: check_vector(velocity, "base.velocity", None)?,
            angular_velocity: check_vector(angular_velocity, "base.angular_velocity", None)?,
            acceleration: check_vector(acceleration, "base.acceleration", None)?,
            angular_acceleration: check_vector(angular_acceleration, "base.angular_acceleration", None)?,
        })
    }
}

impl<T: SimdRealField + Copy> BaseMotion<T> {
    /// A fixed, upright base: the default of docs/model.md sections 2-9.
    #[must_use]
    pub fn fixed() -> Self {
        let zero = Vector3::zeros();
        Self {
            rotation: Matrix3::identity(),
            velocity: zero,
            angular_velocity: zero,
            acceleration: zero,
            angular_acceleration: zero,
        }
    }

    /// World from base.
    pub const fn rotation(&self) -> &Matrix3<T> {
        &self.rotation
    }

    /// `(v, ω)`, base components.
    pub const fn twist(&self) -> (Vector3<T>, Vector3<T>) {
        (self.velocity, self.angular_velocity)
    }

    /// `(v̇, ω̇)`, the derivatives of the base components.
    pub const fn twist_derivative(&self) -> (Vector3<T>, Vector3<T>) {
        (self.acceleration, self.angular_acceleration)
    }
}

impl<T: RealField + Copy> Default for BaseMotion<T> {
    fn default() -> Self {
        Self::fixed()
    }
}

impl<T: RealField + Copy> Current<T> {
    /// Water moving with `velocity` and `acceleration`, world components.
    ///
    /// # Errors
    /// A non-finite number, naming `current.velocity` or `current.acceleration`.
    pub fn new(velocity: Vector3<T>, acceleration: Vector3<T>) -> Result<Self, ModelError> {
        Ok(Self {
            velocity: check_vector(velocity, "current.velocity", None)?,
            acceleration: check_vector(acceleration, "current.acceleration", None)?,
        })
    }
}

impl<T: SimdRealField + Copy> Current<T> {
    /// Still water.
    #[must_use]
    pub fn still() -> Self {
        Self { velocity: Vector3::zeros(), acceleration: Vector3::zeros() }
    }

    /// Velocity, world components.
    pub const fn velocity(&self) -> &Vector3<T> {
        &self.velocity
    }

    /// Acceleration, world components.
    pub const fn acceleration(&self) -> &Vector3<T> {
        &self.acceleration
    }
}

impl<T: RealField + Copy> Default for Current<T> {
    fn default() -> Self {
        Self::still()
    }
}

impl<T: SimdRealField + Copy> BaseMotion<T> {
    /// The same motion over another scalar type (see `Robot::map_scalars`).
    pub(crate) fn map_scalars<U: SimdRealField + Copy>(&self, f: impl Fn(T) -> U + Copy) -> BaseMotion<U> {
        BaseMotion {
            rotation: self.rotation.map(f),
            velocity: self.velocity.map(f),
            angular_velocity: self.angular_velocity.map(f),
            acceleration: self.acceleration.map(f),
            angular_acceleration: self.angular_acceleration.map(f),
        }
    }
}

impl<T: SimdRealField + Copy> Current<T> {
    /// The same current over another scalar type.
    pub(crate) fn map_scalars<U: SimdRealField + Copy>(&self, f: impl Fn(T) -> U + Copy) -> Current<U> {
        Current { velocity: self.velocity.map(f), acceleration: self.acceleration.map(f) }
    }
}

/// One SIMD value from up to `L::LANES` scalars, lane `l` from `values[l]`; lanes beyond the
/// values take the first (zero where there are none).
fn gather<L: SimdRealField + Copy>(values: impl Iterator<Item = L::Element>) -> L
where
    L::Element: SimdRealField + Copy,
{
    let mut values = values.take(L::LANES);
    let mut out = L::splat(values.next().unwrap_or_else(nalgebra::zero));
    for (lane, value) in values.enumerate() {
        out.replace(lane + 1, value);
    }
    out
}

/// The matrix `field` of each of `items`, side by side on the lanes (see [`gather`]).
fn gather_each<L: SimdRealField + Copy, X, const R: usize, const C: usize>(
    items: &[X],
    field: impl Fn(&X) -> &SMatrix<L::Element, R, C>,
) -> SMatrix<L, R, C>
where
    L::Element: SimdRealField + Copy,
{
    SMatrix::from_fn(|row, column| {
        gather(items.iter().map(|x| field(x).get((row, column)).copied().unwrap_or_else(nalgebra::zero)))
    })
}

impl<L: SimdRealField + Copy> BaseMotion<L>
where
    L::Element: SimdRealField + Copy,
{
    /// The motions of up to `L::LANES` evaluations side by side, one per SIMD lane (`lanes[l]`
    /// in lane `l`; lanes beyond those given repeat the first).
    #[must_use]
    pub fn from_lanes(lanes: &[BaseMotion<L::Element>]) -> Self {
        Self {
            rotation: gather_each(lanes, |m| &m.rotation),
            velocity: gather_each(lanes, |m| &m.velocity),
            angular_velocity: gather_each(lanes, |m| &m.angular_velocity),
            acceleration: gather_each(lanes, |m| &m.acceleration),
            angular_acceleration: gather_each(lanes, |m| &m.angular_acceleration),
        }
    }
}

impl<L: SimdRealField + Copy> Current<L>
where
    L::Element: SimdRealField + Copy,
{
    /// The currents of up to `L::LANES` evaluations side by side (see
    /// [`BaseMotion::from_lanes`]).
    #[must_use]
    pub fn from_lanes(lanes: &[Current<L::Element>]) -> Self {
        Self { velocity: gather_each(lanes, |c| &c.velocity), acceleration: gather_each(lanes, |c| &c.acceleration) }
    }
}
