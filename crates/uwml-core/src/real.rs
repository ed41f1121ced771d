//! The number types an evaluation of a whole robot runs on: `f32`, `f64`, dual numbers for
//! derivatives, and (with the `wide` feature) four `f64` side by side on SIMD lanes.

use nalgebra::{RealField, SimdRealField};

use crate::dual::Dual;

/// A number type of the evaluation. Everything but the joint angles' sines and cosines is
/// nalgebra's `SimdRealField` arithmetic; those are computed here, so that SIMD lanes take the
/// scalar functions lane by lane: every lane then has exactly the bits of a scalar evaluation
/// of its state, whatever its neighbours. A lane is itself a real number (`Element: RealField`),
/// so that what branches on values (the joint losses) can be evaluated lane by lane too.
pub trait Real: SimdRealField<Element: RealField + Copy> + Copy {
    /// `(sin x, cos x)`.
    #[must_use]
    fn sin_cos(self) -> (Self, Self) {
        self.simd_sin_cos()
    }

    /// Whether the number is zero in every part (every lane; a dual number's derivatives too):
    /// for a structural shortcut, unlike `==`, which compares a dual number's value only.
    #[must_use]
    fn is_all_zero(self) -> bool {
        self == Self::zero()
    }
}

impl Real for f32 {}

impl Real for f64 {}

impl<T: RealField + Copy, const M: usize> Real for Dual<T, M> {
    fn is_all_zero(self) -> bool {
        self.re == T::zero() && self.eps.iter().all(|e| *e == T::zero())
    }
}

/// `Real` for a simba SIMD type of four lanes of a scalar `Real`.
#[cfg(feature = "wide")]
macro_rules! four_lanes {
    ($lanes:ty, $scalar:ty) => {
        impl Real for $lanes {
            /// Lane by lane, by the scalar's own (`simba`'s vectorized sine differs in the last
            /// bits).
            fn sin_cos(self) -> (Self, Self) {
                let lanes: [$scalar; 4] = self.into();
                let [a, b, c, d] = lanes.map(<$scalar as Real>::sin_cos);
                (Self::from([a.0, b.0, c.0, d.0]), Self::from([a.1, b.1, c.1, d.1]))
            }
        }
    };
}

#[cfg(feature = "wide")]
four_lanes!(simba::simd::WideF64x4, f64);
#[cfg(feature = "wide")]
four_lanes!(simba::simd::WideF32x4, f32);
