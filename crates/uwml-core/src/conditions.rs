//! What an evaluation of a whole robot takes besides the robot and its joint state, in one
//! value (docs/model.md sections 7 and 10): the water, the base's motion, the current, other
//! coefficients than the segments' own, the added-mass form ([`AddedMassForm`]), and the joints'
//! losses at their depth and temperature.

use nalgebra::SimdRealField;

use crate::losses::LossState;
use crate::motion::{BaseMotion, Current};
use crate::segment_coefficients::SegmentCoefficients;
use crate::water::Water;

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

/// The conditions of an evaluation of a robot of up to `J` joints and `S` segments. Start from
/// [`Conditions::new`] (a fixed, upright base in still water) and set what differs:
///
/// ```
/// # use uwml_core::{BaseMotion, Conditions, Current, Water};
/// # use uwml_core::nalgebra::Vector3;
/// let current = Current::new(Vector3::new(0.3, 0.0, 0.0), Vector3::zeros()).unwrap();
/// let conditions = Conditions::<f64, 7, 15> { current, ..Conditions::new(Water::default()) };
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Conditions<'a, T: SimdRealField + Copy, const J: usize, const S: usize> {
    /// The water's density and gravity.
    pub water: Water<T>,
    /// The base's orientation and motion.
    pub motion: BaseMotion<T>,
    /// The water's uniform velocity and acceleration.
    pub current: Current<T>,
    /// Drag and added-mass coefficients to use instead of the segments' own; `None`: their own.
    pub coefficients: Option<&'a SegmentCoefficients<T, S>>,
    /// How the added-mass forces depend on the velocities.
    pub form: AddedMassForm,
    /// Each joint's oil and seal losses at its pressure and temperature ([`LossState`], made
    /// once per change of depth or temperature), or `None` for a joint without; `None` for none
    /// at all.
    pub losses: Option<&'a [Option<LossState<T>>; J]>,
}

impl<T: SimdRealField + Copy, const J: usize, const S: usize> Conditions<'_, T, J, S> {
    /// In `water`: a fixed, upright base in still water, the segments' own coefficients, the
    /// paper's Morison added mass, and no joint losses.
    #[must_use]
    pub fn new(water: Water<T>) -> Self {
        Self {
            water,
            motion: BaseMotion::fixed(),
            current: Current::still(),
            coefficients: None,
            form: AddedMassForm::Morison,
            losses: None,
        }
    }
}
