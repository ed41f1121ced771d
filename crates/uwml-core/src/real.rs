//! The number types an evaluation of a whole robot runs on: `f32`, `f64`, dual numbers for
//! derivatives, and (with the `wide` feature) four `f64` side by side on SIMD lanes.

use nalgebra::SimdRealField;

use crate::dual::Dual;
use crate::losses::{JointLoss, LossState};

/// A number type of the evaluation. Everything but the joint angles' sines and cosines is
/// nalgebra's `SimdRealField` arithmetic; those are computed here, so that SIMD lanes take the
/// scalar functions lane by lane: every lane then has exactly the bits of a scalar evaluation
/// of its state, whatever its neighbours.
pub trait Real: SimdRealField + Copy {
    /// `(sin x, cos x)`.
    #[must_use]
    fn sin_cos(self) -> (Self, Self) {
        self.simd_sin_cos()
    }

    /// A joint's losses at output speed `speed` ([`LossState::evaluate`]; lane by lane).
    #[must_use]
    fn joint_loss(state: &LossState<Self>, speed: Self) -> JointLoss<Self>;
}

impl Real for f32 {
    fn joint_loss(state: &LossState<Self>, speed: Self) -> JointLoss<Self> {
        state.evaluate(speed)
    }
}

impl Real for f64 {
    fn joint_loss(state: &LossState<Self>, speed: Self) -> JointLoss<Self> {
        state.evaluate(speed)
    }
}

impl<T: nalgebra::RealField + Copy, const M: usize> Real for Dual<T, M> {
    fn joint_loss(state: &LossState<Self>, speed: Self) -> JointLoss<Self> {
        state.evaluate(speed)
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

            fn joint_loss(state: &LossState<Self>, speed: Self) -> JointLoss<Self> {
                use simba::simd::SimdValue;
                let lane = |l: usize| state.map_scalars(|x: Self| x.extract(l)).evaluate(speed.extract(l));
                let [a, b, c, d] = [lane(0), lane(1), lane(2), lane(3)];
                JointLoss {
                    visc: Self::from([a.visc, b.visc, c.visc, d.visc]),
                    seal: Self::from([a.seal, b.seal, c.seal, d.seal]),
                    current: Self::from([a.current, b.current, c.current, d.current]),
                }
            }
        }
    };
}

#[cfg(feature = "wide")]
four_lanes!(simba::simd::WideF64x4, f64);
#[cfg(feature = "wide")]
four_lanes!(simba::simd::WideF32x4, f32);
