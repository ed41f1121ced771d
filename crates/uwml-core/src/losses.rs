//! Joint losses inside an oil-filled, pressure-compensated joint (docs/losses.md, "The models"): the
//! oil's viscous (churning) drag on the motor side, the output-shaft seal's friction, and the
//! drive that turns them into a loss current and a loss torque at the joint output.
//!
//! Units: SI (pressures in Pa, speeds in rad/s) except temperatures, in °C. Pressure and
//! temperature change slowly, so their effect is computed once per change with
//! [`JointLosses::at`] (one `exp` for the oil, none for the seal); the per-call work of
//! [`LossState::evaluate`] is then one square root (the smooth sign), one power
//! `|ω_m|ⁿ` (none if n is exactly 1 or 2) and one `exp` (the Stribeck term).
//!
//! Sign: as everywhere in uwml, the returned torques are exerted by the environment on the
//! joint, so they oppose motion: `ω · τ ≤ 0`.

use nalgebra::{RealField, SVector, SimdRealField};

use crate::check::{check_at_least, check_finite, check_positive, constant};
use crate::error::{ModelError, Problem};

/// `sgn_ε(x) = x / sqrt(x² + ε²)`: a smooth sign; `ε = 0` gives the hard sign with `sgn(0) = 0`.
///
/// Evaluated as `(x/m) / sqrt((x/m)² + (ε/m)²)` with `m = max(|x|, ε)`, so that neither square
/// overflows or underflows whatever the magnitudes.
#[inline]
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
pub fn smooth_sign<T: RealField + Copy>(x: T, epsilon: T) -> T {
    let m = x.abs().max(epsilon);
    // m == 0 only for x = 0 with ε = 0; NaN falls through to x and propagates.
    if m > T::zero() {
        let (a, b) = (x / m, epsilon / m);
        a / (a * a + b * b).sqrt()
    } else {
        x
    }
}

/// Viscous (churning) loss of the compensation oil, as torque at the motor shaft:
/// `T_oil = k · exp(a_p (p − p_ref)) · exp(−a_T (θ − θ_ref)) · |ω_m|ⁿ · sgn_ε(ω_m)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OilDrag<T: RealField + Copy> {
    k_oil: T,
    exponent: T,
    pressure_sensitivity: T,
    temperature_sensitivity: T,
    reference_pressure: T,
    reference_temperature: T,
}

impl<T: RealField + Copy> OilDrag<T> {
    /// `k_oil` [N·m·(rad/s)⁻ⁿ] ≥ 0; `exponent` n in [1, 2]; `pressure_sensitivity` a_p [1/Pa] ≥ 0;
    /// `temperature_sensitivity` a_T [1/K] ≥ 0; `reference_pressure` [Pa] ≥ 0;
    /// `reference_temperature` [°C] above absolute zero.
    ///
    /// # Errors
    /// A parameter out of its range or not finite.
    pub fn new(
        k_oil: T,
        exponent: T,
        pressure_sensitivity: T,
        temperature_sensitivity: T,
        reference_pressure: T,
        reference_temperature: T,
    ) -> Result<Self, ModelError> {
        let zero = T::zero();
        const EXPONENT: &str = "oil.exponent (1 to 2)";
        let exponent = check_at_least(exponent, T::one(), EXPONENT, Problem::OutOfRange)?;
        if exponent > constant(2.0) {
            return Err(ModelError::new(EXPONENT, None, Problem::OutOfRange));
        }
        const TEMPERATURE: &str = "oil.reference_temperature (above -273.15 °C)";
        let reference_temperature = check_finite(reference_temperature, TEMPERATURE, None)?;
        if reference_temperature <= constant(-273.15) {
            return Err(ModelError::new(TEMPERATURE, None, Problem::OutOfRange));
        }
        Ok(Self {
            k_oil: check_at_least(k_oil, zero, "oil.k_oil", Problem::Negative)?,
            exponent,
            pressure_sensitivity: check_at_least(
                pressure_sensitivity,
                zero,
                "oil.pressure_sensitivity",
                Problem::Negative,
            )?,
            temperature_sensitivity: check_at_least(
                temperature_sensitivity,
                zero,
                "oil.temperature_sensitivity",
                Problem::Negative,
            )?,
            reference_pressure: check_at_least(reference_pressure, zero, "oil.reference_pressure", Problem::Negative)?,
            reference_temperature,
        })
    }

    /// `k · exp(a_p (p − p_ref) − a_T (θ − θ_ref))`: the torque at `|ω_m| = 1 rad/s` at pressure
    /// `p` [Pa] and temperature `θ` [°C].
    #[must_use]
    #[cfg_attr(uwml_no_panic, no_panic::no_panic)]
    pub fn scale(&self, pressure: T, temperature: T) -> T {
        let exponent = self.pressure_sensitivity * (pressure - self.reference_pressure)
            - self.temperature_sensitivity * (temperature - self.reference_temperature);
        self.k_oil * exponent.exp()
    }

    /// The speed exponent n.
    pub const fn exponent(&self) -> T {
        self.exponent
    }

    /// `k_oil` [N·m·(rad/s)⁻ⁿ].
    pub const fn k_oil(&self) -> T {
        self.k_oil
    }

    /// `a_p` [1/Pa].
    pub const fn pressure_sensitivity(&self) -> T {
        self.pressure_sensitivity
    }

    /// `a_T` [1/K].
    pub const fn temperature_sensitivity(&self) -> T {
        self.temperature_sensitivity
    }

    /// `p_ref` [Pa].
    pub const fn reference_pressure(&self) -> T {
        self.reference_pressure
    }

    /// `θ_ref` [°C].
    pub const fn reference_temperature(&self) -> T {
        self.reference_temperature
    }
}

/// Friction of the output-shaft dynamic seal, as torque at the joint output:
/// `T_seal = sgn_ε(ω) [C(p) + (S(p) − C(p)) exp(−(|ω|/ω_s)²)] + D(p) ω`,
/// `C = c0 + c1 p`, `S = s0 + s1 p`, `D = d0 + d1 p`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Seal<T: RealField + Copy> {
    c: [T; 2],
    s: [T; 2],
    d: [T; 2],
    stribeck_speed: T,
}

impl<T: RealField + Copy> Seal<T> {
    /// Running level `c0 + c1 p` [N·m, N·m/Pa], breakaway level `s0 + s1 p`, viscous slope
    /// `d0 + d1 p` [N·m·s/rad, N·m·s/(rad·Pa)] and Stribeck speed ω_s [rad/s] > 0. For every
    /// pressure ≥ 0, `S ≥ C ≥ 0` and `D ≥ 0`: `s0 ≥ c0 ≥ 0`, `s1 ≥ c1 ≥ 0`, `d0, d1 ≥ 0`.
    ///
    /// # Errors
    /// A parameter out of its range, out of order, or not finite.
    pub fn new(c: [T; 2], s: [T; 2], d: [T; 2], stribeck_speed: T) -> Result<Self, ModelError> {
        let zero = T::zero();
        let [c0, c1] = c;
        let [s0, s1] = s;
        let [d0, d1] = d;
        let c0 = check_at_least(c0, zero, "seal.c0", Problem::Negative)?;
        let c1 = check_at_least(c1, zero, "seal.c1", Problem::Negative)?;
        Ok(Self {
            c: [c0, c1],
            s: [
                check_at_least(s0, c0, "seal.s0", Problem::OutOfOrder)?,
                check_at_least(s1, c1, "seal.s1", Problem::OutOfOrder)?,
            ],
            d: [
                check_at_least(d0, zero, "seal.d0", Problem::Negative)?,
                check_at_least(d1, zero, "seal.d1", Problem::Negative)?,
            ],
            stribeck_speed: check_positive(stribeck_speed, "seal.stribeck_speed", None)?,
        })
    }

    /// `(C(p), S(p), D(p))` at pressure `p` [Pa].
    #[must_use]
    #[cfg_attr(uwml_no_panic, no_panic::no_panic)]
    pub fn levels(&self, pressure: T) -> (T, T, T) {
        let line = |[a, b]: [T; 2]| a + b * pressure;
        (line(self.c), line(self.s), line(self.d))
    }

    /// `[c0, c1]` of the running level `C(p) = c0 + c1 p`.
    pub const fn running(&self) -> [T; 2] {
        self.c
    }

    /// `[s0, s1]` of the breakaway level `S(p)`.
    pub const fn breakaway(&self) -> [T; 2] {
        self.s
    }

    /// `[d0, d1]` of the viscous slope `D(p)`.
    pub const fn viscous(&self) -> [T; 2] {
        self.d
    }

    /// The Stribeck speed ω_s [rad/s].
    pub const fn stribeck_speed(&self) -> T {
        self.stribeck_speed
    }
}

/// Motor and reducer of a joint.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Drive<T: RealField + Copy> {
    torque_constant: T,
    ratio: T,
    efficiency: T,
    rated_current: T,
}

impl<T: RealField + Copy> Drive<T> {
    /// Torque constant K_t [N·m/A] > 0, gear ratio N > 0, gear efficiency η in (0, 1] (motoring),
    /// rated current [A] > 0. With K_t = 1, torques read as currents.
    ///
    /// # Errors
    /// A parameter out of its range or not finite.
    pub fn new(torque_constant: T, ratio: T, efficiency: T, rated_current: T) -> Result<Self, ModelError> {
        let efficiency = check_positive(efficiency, "drive.efficiency", None)?;
        if efficiency > T::one() {
            return Err(ModelError::new("drive.efficiency (0 to 1)", None, Problem::OutOfRange));
        }
        Ok(Self {
            torque_constant: check_positive(torque_constant, "drive.torque_constant", None)?,
            ratio: check_positive(ratio, "drive.ratio", None)?,
            efficiency,
            rated_current: check_positive(rated_current, "drive.rated_current", None)?,
        })
    }

    /// Gear ratio N.
    pub const fn ratio(&self) -> T {
        self.ratio
    }

    /// Rated current [A].
    pub const fn rated_current(&self) -> T {
        self.rated_current
    }

    /// Torque constant K_t [N·m/A].
    pub const fn torque_constant(&self) -> T {
        self.torque_constant
    }

    /// Gear efficiency η.
    pub const fn efficiency(&self) -> T {
        self.efficiency
    }
}

/// The losses of one joint: its drive, and optionally oil drag and a dynamic seal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointLosses<T: RealField + Copy> {
    /// The drive.
    pub drive: Drive<T>,
    /// Oil drag on the motor side, if the joint is oil-filled.
    pub oil: Option<OilDrag<T>>,
    /// Output-shaft seal, if any.
    pub seal: Option<Seal<T>>,
    epsilon: T,
}

/// The loss of one joint at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointLoss<T: SimdRealField + Copy> {
    /// Oil drag reflected to the output, `−N η T_oil` [N·m] (environment sign).
    pub visc: T,
    /// Seal friction, `−T_seal` [N·m] (environment sign).
    pub seal: T,
    /// Loss current `T_oil/K_t + T_seal/(N η K_t)` [A], signed like the motion.
    pub current: T,
}

/// A joint's losses at a given pressure and temperature: everything that does not depend on
/// speed, computed once per change of the conditions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LossState<T: SimdRealField + Copy> {
    oil_scale: T,
    exponent: T,
    seal_running: T,
    seal_breakaway_excess: T,
    seal_viscous: T,
    inverse_stribeck_speed: T,
    ratio: T,
    output_per_motor_torque: T,
    inverse_torque_constant: T,
    epsilon: T,
}

impl<T: RealField + Copy> JointLosses<T> {
    /// A joint's losses; `epsilon` [rad/s, output speed] ≥ 0 is the smooth sign's width (a few
    /// times the velocity noise; 0 for the hard sign).
    ///
    /// # Errors
    /// `epsilon` negative or not finite.
    pub fn new(
        drive: Drive<T>,
        oil: Option<OilDrag<T>>,
        seal: Option<Seal<T>>,
        epsilon: T,
    ) -> Result<Self, ModelError> {
        let epsilon = check_at_least(epsilon, T::zero(), "losses.epsilon", Problem::Negative)?;
        Ok(Self { drive, oil, seal, epsilon })
    }

    /// The smooth sign's width [rad/s].
    pub const fn epsilon(&self) -> T {
        self.epsilon
    }

    /// Fixes the ambient pressure `p` [Pa] and oil temperature `θ` [°C].
    ///
    /// # Errors
    /// Outside the physics' domain: a pressure that is not finite, negative (it is the gauge
    /// pressure of the water around the joint) or above [`MAX_PRESSURE`] (the deepest ocean's,
    /// with margin: `pressure`); a temperature that is not finite or not above absolute zero,
    /// [`ABSOLUTE_ZERO_C`] (`temperature`). The oil model is meant for the sea's temperatures,
    /// [`OIL_TEMPERATURE_RANGE_C`] (Python warns outside); beyond them it extrapolates, which is
    /// allowed.
    #[cfg_attr(uwml_no_panic, no_panic::no_panic)]
    pub fn at(&self, pressure: T, temperature: T) -> Result<LossState<T>, ModelError> {
        check_conditions(pressure, temperature)?;
        Ok(self.at_unchecked(pressure, temperature))
    }

    #[cfg_attr(uwml_no_panic, no_panic::no_panic)]
    fn at_unchecked(&self, pressure: T, temperature: T) -> LossState<T> {
        let zero = T::zero();
        let (oil_scale, exponent) = match &self.oil {
            Some(oil) => (oil.scale(pressure, temperature), oil.exponent),
            None => (zero, T::one()),
        };
        let (seal_running, seal_breakaway_excess, seal_viscous, inverse_stribeck_speed) = match &self.seal {
            Some(seal) => {
                let (c, s, d) = seal.levels(pressure);
                (c, s - c, d, T::one() / seal.stribeck_speed)
            }
            None => (zero, zero, zero, zero),
        };
        let drive = &self.drive;
        LossState {
            oil_scale,
            exponent,
            seal_running,
            seal_breakaway_excess,
            seal_viscous,
            inverse_stribeck_speed,
            ratio: drive.ratio,
            output_per_motor_torque: drive.ratio * drive.efficiency,
            inverse_torque_constant: T::one() / drive.torque_constant,
            epsilon: self.epsilon,
        }
    }
}

impl<T: RealField + Copy> LossState<T> {
    /// `|ω_m|ⁿ` at motor speed `motor_speed` = `|ω_m|` ≥ 0.
    #[inline]
    #[cfg_attr(uwml_no_panic, no_panic::no_panic)]
    fn oil_power(&self, motor_speed: T) -> T {
        // The flow regimes' exponents (laminar 1, Taylor vortices 1.5) and 2 need no power
        // function: one square root at most.
        if self.exponent == T::one() {
            motor_speed
        } else if self.exponent == constant(1.5) {
            // At rest exactly 0 (and so is its slope, which the square root's would not give).
            if motor_speed > T::zero() { motor_speed * motor_speed.sqrt() } else { T::zero() }
        } else if self.exponent == constant(2.0) {
            motor_speed * motor_speed
        } else {
            motor_speed.powf(self.exponent)
        }
    }

    /// Oil and seal losses at output speed `speed` [rad/s].
    #[must_use]
    #[inline]
    #[cfg_attr(uwml_no_panic, no_panic::no_panic)]
    pub fn evaluate(&self, speed: T) -> JointLoss<T> {
        // sgn_ε(ω_m) with ε_m = N ε equals sgn_ε(ω): one square root serves both.
        let sign = smooth_sign(speed, self.epsilon);
        let magnitude = speed.abs();
        let oil = self.oil_scale * self.oil_power(self.ratio * magnitude) * sign;
        let x = magnitude * self.inverse_stribeck_speed;
        let seal =
            sign * (self.seal_running + self.seal_breakaway_excess * (-(x * x)).exp()) + self.seal_viscous * speed;
        JointLoss {
            visc: -self.output_per_motor_torque * oil,
            seal: -seal,
            current: (oil + seal / self.output_per_motor_torque) * self.inverse_torque_constant,
        }
    }
}

/// A joint's losses as a simulator with dry friction as a constraint applies them
/// ([`LossState::dry_friction_split`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DryFrictionSplit<T: RealField + Copy> {
    /// The seal's dry-friction level `C(p) + (S(p) − C(p)) exp(−(|ω|/ω_s)²)` [N·m], ≥ 0: the
    /// most a friction constraint may apply (MuJoCo's `frictionloss`), against the motion, or
    /// holding the joint at rest.
    pub friction: T,
    /// The secant damping of the smooth rest [N·m·s/rad], ≥ 0: the oil drag and the seal's
    /// viscous term are `−damping · ω` at this speed.
    pub damping: T,
}

impl<T: RealField + Copy> LossState<T> {
    /// The losses at output speed `speed` [rad/s] split for a simulator that solves dry friction
    /// as a constraint (docs/simulation.md): the seal's Coulomb and breakaway part, whose slope
    /// `S/ε` at rest makes it stiff as an explicit force, becomes a friction level; the oil drag
    /// and the seal's viscous term a damping, which a simulator may integrate implicitly. With
    /// the hard sign (ε = 0) and `speed` ≠ 0, `−(friction · sgn ω + damping · ω)` is
    /// `visc + seal` of [`LossState::evaluate`]; with ε > 0 they differ only in the smooth sign.
    /// At rest the damping is its limit: `N η k N` for laminar oil (n = 1) with the hard sign,
    /// else 0.
    #[must_use]
    #[inline]
    #[cfg_attr(uwml_no_panic, no_panic::no_panic)]
    pub fn dry_friction_split(&self, speed: T) -> DryFrictionSplit<T> {
        let magnitude = speed.abs();
        let x = magnitude * self.inverse_stribeck_speed;
        let friction = self.seal_running + self.seal_breakaway_excess * (-(x * x)).exp();
        let oil = if magnitude > T::zero() {
            // −visc / ω = N η T_oil / ω ≥ 0.
            let sign = smooth_sign(speed, self.epsilon);
            self.output_per_motor_torque * self.oil_scale * self.oil_power(self.ratio * magnitude) * sign / speed
        } else if self.exponent == T::one() && self.epsilon == T::zero() {
            self.output_per_motor_torque * self.oil_scale * self.ratio
        } else {
            T::zero()
        };
        DryFrictionSplit { friction, damping: oil.max(T::zero()) + self.seal_viscous }
    }
}

/// One megapascal in pascals.
const MPA: f64 = 1e6;

impl<T: RealField + Copy> Default for OilDrag<T> {
    /// Illustrative (the paper publishes laws, not parameters): k = 3.3234e-3 N·m·s/rad, n = 1
    /// (laminar Couette flow in the gap, which holds for this motor class in nearly all cases:
    /// docs/losses.md, "The defaults are illustrative"), a_p = 0.02 /MPa, a_T = 0.06 /K, at 0 MPa
    /// and 20 °C. With the default seal and drive: 2.85 A of loss current at 10 r/min and 10 MPa
    /// (27.4 % of 10.4 A).
    fn default() -> Self {
        let c = constant::<T>;
        Self {
            k_oil: c(3.3234e-3),
            exponent: T::one(),
            pressure_sensitivity: c(0.02 / MPA),
            temperature_sensitivity: c(0.06),
            reference_pressure: T::zero(),
            reference_temperature: c(20.0),
        }
    }
}

impl<T: RealField + Copy> Default for Seal<T> {
    /// Illustrative: C = 16 + 3.7 p, S = 21 + 6.7 p [N·m, p in MPa], D = 2.2 + 0.34 p
    /// [N·m·s/rad], ω_s = 0.05 rad/s.
    fn default() -> Self {
        let c = constant::<T>;
        Self {
            c: [c(16.0), c(3.7 / MPA)],
            s: [c(21.0), c(6.7 / MPA)],
            d: [c(2.2), c(0.34 / MPA)],
            stribeck_speed: c(0.05),
        }
    }
}

impl<T: RealField + Copy> Default for Drive<T> {
    /// The paper's hip-roll joint: ratio 160, rated current 10.4 A; K_t = 0.40 N·m/A and
    /// η = 0.80 are illustrative.
    fn default() -> Self {
        let c = constant::<T>;
        Self { torque_constant: c(0.40), ratio: c(160.0), efficiency: c(0.80), rated_current: c(10.4) }
    }
}

impl<T: RealField + Copy> Default for JointLosses<T> {
    /// Default drive, oil and seal; ε = 1e-3 rad/s.
    fn default() -> Self {
        Self {
            drive: Drive::default(),
            oil: Some(OilDrag::default()),
            seal: Some(Seal::default()),
            epsilon: constant(1e-3),
        }
    }
}

/// The deepest ocean [m]: depths are taken from 0 to this (the Challenger Deep is about
/// 10,935 m).
pub const MAX_DEPTH: f64 = 11_000.0;

/// The largest ambient (gauge) pressure taken [Pa]: the deepest ocean's, about 110 MPa, with
/// margin for denser water.
pub const MAX_PRESSURE: f64 = 1.2e8;

/// Absolute zero [°C]: temperatures must be above it.
pub const ABSOLUTE_ZERO_C: f64 = -273.15;

/// The oil temperatures [°C] the oil model is meant for: the sea's, from where sea water freezes
/// (about −2 °C) to the 40 °C of the oil's viscosity grade. Outside, [`JointLosses::at`] still
/// evaluates (the exponential temperature law extrapolates); the Python package warns.
pub const OIL_TEMPERATURE_RANGE_C: [f64; 2] = [-2.0, 40.0];

/// `pressure` [Pa] finite and within `0..=MAX_PRESSURE`.
fn check_pressure<T: RealField + Copy>(pressure: T) -> Result<T, ModelError> {
    let pressure = check_at_least(pressure, T::zero(), "pressure", Problem::Negative)?;
    if pressure <= constant(MAX_PRESSURE) {
        Ok(pressure)
    } else {
        Err(ModelError::new("pressure", None, Problem::BeyondDeepestOcean))
    }
}

/// `temperature` [°C] finite and above absolute zero.
fn check_temperature<T: RealField + Copy>(temperature: T) -> Result<T, ModelError> {
    let temperature = check_finite(temperature, "temperature", None)?;
    if temperature > constant(ABSOLUTE_ZERO_C) {
        Ok(temperature)
    } else {
        Err(ModelError::new("temperature", None, Problem::BelowAbsoluteZero))
    }
}

/// The domain of the loss conditions, as [`JointLosses::at`] checks it: `pressure` [Pa] finite
/// and from 0 to [`MAX_PRESSURE`], `temperature` [°C] finite and above [`ABSOLUTE_ZERO_C`].
///
/// # Errors
/// The first condition outside its domain, as a `ModelError` with field `pressure` or
/// `temperature`.
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
pub fn check_conditions<T: RealField + Copy>(pressure: T, temperature: T) -> Result<(), ModelError> {
    check_pressure(pressure)?;
    check_temperature(temperature)?;
    Ok(())
}

/// Gauge pressure [Pa] at `depth` [m] below the surface: `ρ g z` (no compressibility; within
/// the bound documented in docs/losses.md of TEOS-10).
///
/// # Errors
/// A `depth` that is not finite, negative or beyond [`MAX_DEPTH`]; a `sea_density` or `gravity`
/// that is not finite and positive; a pressure beyond [`MAX_PRESSURE`] (a density or gravity far
/// from the sea's, field `pressure`).
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
pub fn pressure_at_depth<T: RealField + Copy>(depth: T, sea_density: T, gravity: T) -> Result<T, ModelError> {
    let depth = check_at_least(depth, T::zero(), "depth", Problem::Negative)?;
    if depth > constant(MAX_DEPTH) {
        return Err(ModelError::new("depth", None, Problem::BeyondDeepestOcean));
    }
    let sea_density = check_positive(sea_density, "sea_density", None)?;
    let gravity = check_positive(gravity, "gravity", None)?;
    let pressure = sea_density * gravity * depth;
    if !pressure.is_finite() {
        // Finite, positive factors whose product overflows: a water far from the sea's.
        return Err(ModelError::new("pressure", None, Problem::BeyondDeepestOcean));
    }
    check_pressure(pressure)
}

/// Default sea-water density for [`pressure_at_depth`] [kg/m³].
pub const SEA_WATER_DENSITY: f64 = 1025.0;

/// The joint losses of `N` joints: `(visc, seal, current)` of every joint at its speed `q̇[i]`,
/// zero where `losses[i]` is `None` (what `robot_hydro` gives with the conditions'
/// losses, as vectors).
///
/// Never fails and never panics.
#[must_use]
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
pub fn loss_torques<T: RealField + Copy, const N: usize>(
    losses: &[Option<LossState<T>>; N],
    qd: &SVector<T, N>,
) -> (SVector<T, N>, SVector<T, N>, SVector<T, N>) {
    let zeros = SVector::<T, N>::zeros();
    let (mut visc, mut seal, mut current) = (zeros, zeros, zeros);
    let slots = visc.iter_mut().zip(seal.iter_mut()).zip(current.iter_mut());
    for (((visc, seal), current), (state, &speed)) in slots.zip(losses.iter().zip(qd.iter())) {
        if let Some(state) = state {
            let loss = state.evaluate(speed);
            (*visc, *seal, *current) = (loss.visc, loss.seal, loss.current);
        }
    }
    (visc, seal, current)
}

impl<T: RealField + Copy> LossState<T> {
    /// The same state over a SIMD type, every number splat across the lanes (see
    /// `Robot::splat`).
    #[must_use]
    pub fn splat<L: SimdRealField<Element = T> + Copy>(&self) -> LossState<L> {
        self.map_scalars(L::splat)
    }
}

impl<T: SimdRealField + Copy> LossState<T> {
    /// The same state over another scalar type, every number mapped by `f`, which must keep
    /// values (as `Dual::constant` does).
    pub(crate) fn map_scalars<U: SimdRealField + Copy>(&self, f: impl Fn(T) -> U) -> LossState<U> {
        LossState {
            oil_scale: f(self.oil_scale),
            exponent: f(self.exponent),
            seal_running: f(self.seal_running),
            seal_breakaway_excess: f(self.seal_breakaway_excess),
            seal_viscous: f(self.seal_viscous),
            inverse_stribeck_speed: f(self.inverse_stribeck_speed),
            ratio: f(self.ratio),
            output_per_motor_torque: f(self.output_per_motor_torque),
            inverse_torque_constant: f(self.inverse_torque_constant),
            epsilon: f(self.epsilon),
        }
    }
}
