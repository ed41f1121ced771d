//! Drag and added-mass coefficients per segment and normal direction: a table to evaluate a
//! robot with other coefficients than its segments' own (docs/model.md section 10), checked once.

use nalgebra::{RealField, SimdRealField};

use crate::check::check_coefficient_table;
use crate::error::{ModelError, Problem};

/// Drag and added-mass coefficients per segment and normal direction (`[segment][k]`), to
/// evaluate a robot with other coefficients than its segments' own.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SegmentCoefficients<T: SimdRealField + Copy, const S: usize> {
    pub(crate) cd: [[T; 2]; S],
    pub(crate) cm: [[T; 2]; S],
}

impl<T: RealField + Copy, const S: usize> SegmentCoefficients<T, S> {
    /// One drag and one added-mass coefficient for every segment and direction.
    ///
    /// # Errors
    /// A coefficient that is negative or not finite.
    pub fn uniform(cd: T, cm: T) -> Result<Self, ModelError> {
        // One check of each value, not one per entry: the same errors (segment 0 named first).
        check_coefficient_table(&[[cd; 2]], &[[cm; 2]], ["segment.cd", "segment.cm"])?;
        Ok(Self { cd: [[cd; 2]; S], cm: [[cm; 2]; S] })
    }

    /// Coefficients per segment and normal direction, `[segment][k]` (a circular segment uses
    /// entry 0).
    ///
    /// # Errors
    /// A coefficient that is negative or not finite, naming the segment.
    pub fn per_segment(cd: [[T; 2]; S], cm: [[T; 2]; S]) -> Result<Self, ModelError> {
        check_coefficient_table(&cd, &cm, ["segment.cd", "segment.cm"])?;
        Ok(Self { cd, cm })
    }

    /// Segment `segment`'s coefficients, per normal direction.
    ///
    /// # Errors
    /// A coefficient that is negative, not finite or too large, or a segment beyond `S`, naming
    /// the segment; then nothing changes.
    pub fn set(&mut self, segment: usize, cd: [T; 2], cm: [T; 2]) -> Result<(), ModelError> {
        check_coefficient_table(&[cd], &[cm], ["segment.cd", "segment.cm"])
            .map_err(|error| ModelError { index: Some(segment), ..error })?;
        match (self.cd.get_mut(segment), self.cm.get_mut(segment)) {
            (Some(cd_slot), Some(cm_slot)) => {
                (*cd_slot, *cm_slot) = (cd, cm);
                Ok(())
            }
            _ => Err(ModelError::new("segment.cd", Some(segment), Problem::OutOfRange)),
        }
    }
}

impl<T: SimdRealField + Copy, const S: usize> SegmentCoefficients<T, S> {
    /// Drag coefficients `[segment][k]`.
    pub const fn cd(&self) -> &[[T; 2]; S] {
        &self.cd
    }

    /// Added-mass coefficients `[segment][k]`.
    pub const fn cm(&self) -> &[[T; 2]; S] {
        &self.cm
    }
}

impl<T: RealField + Copy, const S: usize> SegmentCoefficients<T, S> {
    /// The same coefficients over a SIMD type (see [`Robot::splat`]).
    #[must_use]
    pub fn splat<L: SimdRealField<Element = T> + Copy>(&self) -> SegmentCoefficients<L, S> {
        self.map_scalars(L::splat)
    }
}

impl<T: SimdRealField + Copy, const S: usize> SegmentCoefficients<T, S> {
    /// The same coefficients over another scalar type (see [`Robot::map_scalars`]).
    pub(crate) fn map_scalars<U: SimdRealField + Copy>(&self, f: impl Fn(T) -> U + Copy) -> SegmentCoefficients<U, S> {
        SegmentCoefficients { cd: self.cd.map(|c| c.map(f)), cm: self.cm.map(|c| c.map(f)) }
    }
}
