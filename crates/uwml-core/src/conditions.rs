//! What an evaluation of a whole robot takes besides the robot and its joint state, in one
//! value (docs/model.md sections 7 and 10): the water, the base's motion, the current, other
//! coefficients than the segments' own, the added-mass form, and the joints' losses at their
//! depth and temperature.

use nalgebra::SimdRealField;

use crate::losses::LossState;
use crate::model::Water;
use crate::motion::{BaseMotion, Current};
use crate::robot::SegmentCoefficients;
use crate::tree::AddedMassForm;

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
