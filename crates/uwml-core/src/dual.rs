//! Forward-mode dual numbers: `re + Σ eps[k] ε_k` with `ε_j ε_k = 0`, so that any code generic
//! over `T: RealField + Copy` computes, run on `Dual<T, M>`, its value and its derivatives with
//! respect to `M` seeded inputs in one pass (no allocation, no panic).
//!
//! Every operation computes the real part exactly as `T` would (the same operation on the real
//! parts), and the derivative parts by the chain rule. Comparisons (`==`, `<`, `max`, ...) look at
//! the real parts only, so that branches follow the real-valued path and the derivatives are those
//! of the branch taken. Where a function is not differentiable (the kinks of `abs`, `max` and `min`
//! at ties, `floor`, `round`, ...), the derivative is that of the branch taken, or zero for the
//! piecewise-constant functions. Where a derivative is infinite (`sqrt`, `cbrt`, `ln`, a power
//! below one at zero, `asin`/`acos` at ±1, ...), the derivative parts are infinite or NaN only in
//! the directions that the argument actually depends on: a constant stays a constant.
//!
//! ```
//! use uwml_core::Dual;
//! use uwml_core::nalgebra::ComplexField;
//!
//! // d/dx (x sin x) at x = 2, and d/dy at y = 3 of x y.
//! let (x, y) = (Dual::<f64, 2>::variable(2.0, 0), Dual::<f64, 2>::variable(3.0, 1));
//! let f = x * x.sin() + x * y;
//! assert_eq!(f.re, 2.0 * 2.0f64.sin() + 6.0);
//! assert!((f.eps[0] - (2.0f64.sin() + 2.0 * 2.0f64.cos() + 3.0)).abs() < 1e-15);
//! assert_eq!(f.eps[1], 2.0);
//! ```

use core::cmp::Ordering;
use core::fmt;
use core::iter::{Product, Sum};
use core::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Rem, RemAssign, Sub, SubAssign};

use approx::{AbsDiffEq, RelativeEq, UlpsEq};
use nalgebra::{ComplexField, Field, RealField, SimdValue};
use num_traits::{FromPrimitive, Num, One, Signed, Zero};
use simba::scalar::{SubsetOf, SupersetOf};

/// A dual number: a real part `re` and its derivatives `eps[k]` with respect to `M` inputs.
#[derive(Clone, Copy, Debug)]
pub struct Dual<T, const M: usize> {
    /// The value.
    pub re: T,
    /// The derivatives of the value with respect to the `M` seeded inputs.
    pub eps: [T; M],
}

impl<T: RealField + Copy, const M: usize> Dual<T, M> {
    /// A constant: derivatives zero.
    #[inline]
    pub fn constant(re: T) -> Self {
        Self { re, eps: [T::zero(); M] }
    }

    /// The input number `index` (`0..M`) at value `re`: derivative one with respect to itself.
    /// An `index` out of range gives a constant.
    #[inline]
    pub fn variable(re: T, index: usize) -> Self {
        let mut x = Self::constant(re);
        if let Some(slot) = x.eps.get_mut(index) {
            *slot = T::one();
        }
        x
    }

    /// `f(self)` where `f(re) = value` and `f'(re) = derivative`.
    #[inline(always)]
    fn chain(self, value: T, derivative: T) -> Self {
        Self { re: value, eps: self.eps.map(|e| e * derivative) }
    }

    /// As [`Dual::chain`], but directions in which `self` is constant stay constant even where the
    /// derivative is infinite or NaN (at the singular points of `sqrt`, `ln`, ...).
    #[inline(always)]
    fn chain_singular(self, value: T, derivative: T) -> Self {
        Self { re: value, eps: self.eps.map(|e| if e == T::zero() { e } else { e * derivative }) }
    }

    /// Element-wise combination of two derivative arrays.
    #[inline(always)]
    fn zip_eps(a: [T; M], b: [T; M], f: impl Fn(T, T) -> T) -> [T; M] {
        let mut out = a;
        for (o, b) in out.iter_mut().zip(b) {
            *o = f(*o, b);
        }
        out
    }
}

// ---------------------------------------------------------------------------------------------
// Arithmetic.

impl<T: RealField + Copy, const M: usize> Add for Dual<T, M> {
    type Output = Self;
    #[inline(always)]
    fn add(self, other: Self) -> Self {
        Self { re: self.re + other.re, eps: Self::zip_eps(self.eps, other.eps, |a, b| a + b) }
    }
}

impl<T: RealField + Copy, const M: usize> Sub for Dual<T, M> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, other: Self) -> Self {
        Self { re: self.re - other.re, eps: Self::zip_eps(self.eps, other.eps, |a, b| a - b) }
    }
}

// The product rule needs `+` and `−`.
#[allow(clippy::suspicious_arithmetic_impl)]
impl<T: RealField + Copy, const M: usize> Mul for Dual<T, M> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, other: Self) -> Self {
        let (a, b) = (self.re, other.re);
        Self { re: a * b, eps: Self::zip_eps(self.eps, other.eps, |da, db| da * b + a * db) }
    }
}

// The quotient rule needs `−` and `·`.
#[allow(clippy::suspicious_arithmetic_impl)]
impl<T: RealField + Copy, const M: usize> Div for Dual<T, M> {
    type Output = Self;
    #[inline(always)]
    fn div(self, other: Self) -> Self {
        let (q, b) = (self.re / other.re, other.re);
        Self { re: q, eps: Self::zip_eps(self.eps, other.eps, |da, db| (da - q * db) / b) }
    }
}

#[allow(clippy::suspicious_arithmetic_impl)]
impl<T: RealField + Copy, const M: usize> Rem for Dual<T, M> {
    type Output = Self;
    /// `a − trunc(a/b)·b`: derivative `da − trunc(a/b)·db`.
    #[inline]
    fn rem(self, other: Self) -> Self {
        let n = (self.re / other.re).trunc();
        Self { re: self.re % other.re, eps: Self::zip_eps(self.eps, other.eps, |da, db| da - n * db) }
    }
}

impl<T: RealField + Copy, const M: usize> Neg for Dual<T, M> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Self { re: -self.re, eps: self.eps.map(|e| -e) }
    }
}

macro_rules! assign_ops {
    ($($trait:ident, $method:ident, $op:tt);*) => {$(
        impl<T: RealField + Copy, const M: usize> $trait for Dual<T, M> {
            #[inline(always)]
            fn $method(&mut self, other: Self) {
                *self = *self $op other;
            }
        }
    )*};
}
assign_ops!(AddAssign, add_assign, +; SubAssign, sub_assign, -; MulAssign, mul_assign, *;
            DivAssign, div_assign, /; RemAssign, rem_assign, %);

impl<T: RealField + Copy, const M: usize> Sum for Dual<T, M> {
    fn sum<I: Iterator<Item = Self>>(iter: I) -> Self {
        iter.fold(Self::zero(), |a, b| a + b)
    }
}

impl<T: RealField + Copy, const M: usize> Product for Dual<T, M> {
    fn product<I: Iterator<Item = Self>>(iter: I) -> Self {
        iter.fold(Self::one(), |a, b| a * b)
    }
}

// ---------------------------------------------------------------------------------------------
// Comparison (real parts only) and formatting.

impl<T: RealField + Copy, const M: usize> PartialEq for Dual<T, M> {
    #[inline(always)]
    fn eq(&self, other: &Self) -> bool {
        self.re == other.re
    }
}

impl<T: RealField + Copy, const M: usize> PartialOrd for Dual<T, M> {
    #[inline(always)]
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        self.re.partial_cmp(&other.re)
    }
}

impl<T: RealField + Copy, const M: usize> fmt::Display for Dual<T, M> {
    /// `re + [eps_0, eps_1, ...]ε`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(&self.re, f)?;
        f.write_str(" + [")?;
        for (k, e) in self.eps.iter().enumerate() {
            if k > 0 {
                f.write_str(", ")?;
            }
            fmt::Display::fmt(e, f)?;
        }
        f.write_str("]ε")
    }
}

impl<T: RealField + Copy, const M: usize> AbsDiffEq for Dual<T, M> {
    type Epsilon = Self;
    fn default_epsilon() -> Self {
        Self::constant(T::default_epsilon())
    }
    fn abs_diff_eq(&self, other: &Self, epsilon: Self) -> bool {
        self.re.abs_diff_eq(&other.re, epsilon.re)
    }
}

impl<T: RealField + Copy, const M: usize> RelativeEq for Dual<T, M> {
    fn default_max_relative() -> Self {
        Self::constant(T::default_max_relative())
    }
    fn relative_eq(&self, other: &Self, epsilon: Self, max_relative: Self) -> bool {
        self.re.relative_eq(&other.re, epsilon.re, max_relative.re)
    }
}

impl<T: RealField + Copy, const M: usize> UlpsEq for Dual<T, M> {
    fn default_max_ulps() -> u32 {
        T::default_max_ulps()
    }
    fn ulps_eq(&self, other: &Self, epsilon: Self, max_ulps: u32) -> bool {
        self.re.ulps_eq(&other.re, epsilon.re, max_ulps)
    }
}

// ---------------------------------------------------------------------------------------------
// num-traits.

impl<T: RealField + Copy, const M: usize> Zero for Dual<T, M> {
    #[inline(always)]
    fn zero() -> Self {
        Self::constant(T::zero())
    }
    /// Whether the real part is zero (as `==` compares real parts).
    #[inline(always)]
    fn is_zero(&self) -> bool {
        self.re.is_zero()
    }
}

impl<T: RealField + Copy, const M: usize> One for Dual<T, M> {
    #[inline(always)]
    fn one() -> Self {
        Self::constant(T::one())
    }
}

impl<T: RealField + Copy, const M: usize> Num for Dual<T, M> {
    type FromStrRadixErr = T::FromStrRadixErr;
    fn from_str_radix(s: &str, radix: u32) -> Result<Self, Self::FromStrRadixErr> {
        T::from_str_radix(s, radix).map(Self::constant)
    }
}

impl<T: RealField + Copy, const M: usize> Signed for Dual<T, M> {
    fn abs(&self) -> Self {
        ComplexField::abs(*self)
    }
    fn abs_sub(&self, other: &Self) -> Self {
        if *self <= *other { Self::zero() } else { *self - *other }
    }
    fn signum(&self) -> Self {
        ComplexField::signum(*self)
    }
    fn is_positive(&self) -> bool {
        self.re.is_positive()
    }
    fn is_negative(&self) -> bool {
        self.re.is_negative()
    }
}

macro_rules! from_primitive {
    ($($method:ident, $t:ty);*) => {$(
        fn $method(n: $t) -> Option<Self> {
            T::$method(n).map(Self::constant)
        }
    )*};
}

impl<T: RealField + Copy, const M: usize> FromPrimitive for Dual<T, M> {
    from_primitive!(from_isize, isize; from_i8, i8; from_i16, i16; from_i32, i32; from_i64, i64;
                    from_i128, i128; from_usize, usize; from_u8, u8; from_u16, u16; from_u32, u32;
                    from_u64, u64; from_u128, u128; from_f32, f32; from_f64, f64);
}

// ---------------------------------------------------------------------------------------------
// simba: one lane, inclusions of f32, f64 and itself.

impl<T: RealField + Copy, const M: usize> SimdValue for Dual<T, M> {
    const LANES: usize = 1;
    type Element = Self;
    type SimdBool = bool;

    #[inline(always)]
    fn splat(val: Self) -> Self {
        val
    }
    #[inline(always)]
    fn extract(&self, _: usize) -> Self {
        *self
    }
    // The trait declares these `unsafe`; the bodies are safe code (one lane, no index).
    #[allow(unsafe_code)]
    #[inline(always)]
    unsafe fn extract_unchecked(&self, _: usize) -> Self {
        *self
    }
    #[inline(always)]
    fn replace(&mut self, _: usize, val: Self) {
        *self = val;
    }
    #[allow(unsafe_code)]
    #[inline(always)]
    unsafe fn replace_unchecked(&mut self, _: usize, val: Self) {
        *self = val;
    }
    #[inline(always)]
    fn select(self, cond: bool, other: Self) -> Self {
        if cond { self } else { other }
    }
}

impl<T: RealField + Copy, const M: usize> Field for Dual<T, M> {}

impl<T: RealField + Copy, const M: usize> SubsetOf<Dual<T, M>> for Dual<T, M> {
    #[inline(always)]
    fn to_superset(&self) -> Self {
        *self
    }
    #[inline(always)]
    fn from_superset_unchecked(element: &Self) -> Self {
        *element
    }
    #[inline(always)]
    fn is_in_subset(_: &Self) -> bool {
        true
    }
}

macro_rules! subset_of_dual {
    ($($t:ty),*) => {$(
        /// A constant; a dual number is in the subset if its derivatives are zero.
        impl<T: RealField + Copy, const M: usize> SubsetOf<Dual<T, M>> for $t {
            #[inline(always)]
            fn to_superset(&self) -> Dual<T, M> {
                Dual::constant(T::from_subset(self))
            }
            #[inline(always)]
            fn from_superset_unchecked(element: &Dual<T, M>) -> Self {
                element.re.to_subset_unchecked()
            }
            #[inline(always)]
            fn is_in_subset(element: &Dual<T, M>) -> bool {
                element.eps.iter().all(|e| e.is_zero()) && <T as SupersetOf<$t>>::is_in_subset(&element.re)
            }
        }
    )*};
}
subset_of_dual!(f32, f64);

// ---------------------------------------------------------------------------------------------
// The field's functions, with their derivatives.

impl<T: RealField + Copy, const M: usize> ComplexField for Dual<T, M> {
    type RealField = Self;

    #[inline]
    fn from_real(re: Self) -> Self {
        re
    }
    #[inline]
    fn real(self) -> Self {
        self
    }
    #[inline]
    fn imaginary(self) -> Self {
        Self::zero()
    }
    #[inline]
    fn modulus(self) -> Self {
        ComplexField::abs(self)
    }
    #[inline]
    fn modulus_squared(self) -> Self {
        self * self
    }
    #[inline]
    fn argument(self) -> Self {
        if self.re >= T::zero() { Self::zero() } else { Self::constant(T::pi()) }
    }
    #[inline]
    fn norm1(self) -> Self {
        ComplexField::abs(self)
    }
    #[inline]
    fn scale(self, factor: Self) -> Self {
        self * factor
    }
    #[inline]
    fn unscale(self, factor: Self) -> Self {
        self / factor
    }
    #[inline]
    fn to_exp(self) -> (Self, Self) {
        if self.re >= T::zero() { (self, Self::one()) } else { (-self, -Self::one()) }
    }
    #[inline]
    fn signum(self) -> Self {
        Self::constant(ComplexField::signum(self.re))
    }
    #[inline]
    fn floor(self) -> Self {
        Self::constant(self.re.floor())
    }
    #[inline]
    fn ceil(self) -> Self {
        Self::constant(self.re.ceil())
    }
    #[inline]
    fn round(self) -> Self {
        Self::constant(self.re.round())
    }
    #[inline]
    fn trunc(self) -> Self {
        Self::constant(self.re.trunc())
    }
    /// `x − trunc(x)`: derivative one.
    #[inline]
    fn fract(self) -> Self {
        Self { re: self.re.fract(), eps: self.eps }
    }
    #[inline]
    fn mul_add(self, a: Self, b: Self) -> Self {
        let (x, y) = (self.re, a.re);
        let product = Self::zip_eps(self.eps, a.eps, |dx, dy| dx * y + x * dy);
        Self { re: x.mul_add(y, b.re), eps: Self::zip_eps(product, b.eps, |p, db| p + db) }
    }
    /// Derivative `signum(x)` (±1 at ±0: the side of the sign bit).
    #[inline]
    fn abs(self) -> Self {
        self.chain(ComplexField::abs(self.re), ComplexField::signum(self.re))
    }
    /// `sqrt(x² + y²)`; derivative zero at the origin.
    #[inline]
    fn hypot(self, other: Self) -> Self {
        let r = self.re.hypot(other.re);
        let (x, y) = (self.re, other.re);
        let eps = if r == T::zero() {
            [T::zero(); M]
        } else {
            Self::zip_eps(self.eps, other.eps, |dx, dy| (x * dx + y * dy) / r)
        };
        Self { re: r, eps }
    }
    #[inline]
    fn recip(self) -> Self {
        let r = self.re.recip();
        self.chain_singular(r, -(r * r))
    }
    #[inline]
    fn conjugate(self) -> Self {
        self
    }
    #[inline]
    fn sin(self) -> Self {
        let (s, c) = self.re.sin_cos();
        self.chain(s, c)
    }
    #[inline]
    fn cos(self) -> Self {
        let (s, c) = self.re.sin_cos();
        self.chain(c, -s)
    }
    #[inline]
    fn sin_cos(self) -> (Self, Self) {
        let (s, c) = self.re.sin_cos();
        (self.chain(s, c), self.chain(c, -s))
    }
    #[inline]
    fn sinh_cosh(self) -> (Self, Self) {
        let (s, c) = (self.re.sinh(), self.re.cosh());
        (self.chain(s, c), self.chain(c, s))
    }
    #[inline]
    fn tan(self) -> Self {
        let t = self.re.tan();
        self.chain(t, T::one() + t * t)
    }
    #[inline]
    fn asin(self) -> Self {
        let x = self.re;
        self.chain_singular(x.asin(), (T::one() - x * x).sqrt().recip())
    }
    #[inline]
    fn acos(self) -> Self {
        let x = self.re;
        self.chain_singular(x.acos(), -(T::one() - x * x).sqrt().recip())
    }
    #[inline]
    fn atan(self) -> Self {
        let x = self.re;
        self.chain(x.atan(), (T::one() + x * x).recip())
    }
    #[inline]
    fn sinh(self) -> Self {
        self.chain(self.re.sinh(), self.re.cosh())
    }
    #[inline]
    fn cosh(self) -> Self {
        self.chain(self.re.cosh(), self.re.sinh())
    }
    #[inline]
    fn tanh(self) -> Self {
        let t = self.re.tanh();
        self.chain(t, T::one() - t * t)
    }
    #[inline]
    fn asinh(self) -> Self {
        let x = self.re;
        self.chain(x.asinh(), (x * x + T::one()).sqrt().recip())
    }
    #[inline]
    fn acosh(self) -> Self {
        let x = self.re;
        self.chain_singular(x.acosh(), (x * x - T::one()).sqrt().recip())
    }
    #[inline]
    fn atanh(self) -> Self {
        let x = self.re;
        self.chain_singular(x.atanh(), (T::one() - x * x).recip())
    }
    /// `ln x / ln b`, differentiated in both.
    #[inline]
    fn log(self, base: Self) -> Self {
        let (x, b) = (self.re, base.re);
        let value = x.log(b);
        let ln_b = b.ln();
        let by_x = self.chain_singular(value, (x * ln_b).recip());
        let by_b = base.chain_singular(value, -value / (b * ln_b));
        Self { re: value, eps: Self::zip_eps(by_x.eps, by_b.eps, |a, b| a + b) }
    }
    #[inline]
    fn log2(self) -> Self {
        let x = self.re;
        self.chain_singular(x.log2(), (x * T::ln_2()).recip())
    }
    #[inline]
    fn log10(self) -> Self {
        let x = self.re;
        self.chain_singular(x.log10(), (x * T::ln_10()).recip())
    }
    #[inline]
    fn ln(self) -> Self {
        let x = self.re;
        self.chain_singular(x.ln(), x.recip())
    }
    #[inline]
    fn ln_1p(self) -> Self {
        let x = self.re;
        self.chain_singular(x.ln_1p(), (T::one() + x).recip())
    }
    /// Derivative `1 / (2 sqrt x)`: infinite at zero, in the directions the argument depends on.
    #[inline]
    fn sqrt(self) -> Self {
        let s = self.re.sqrt();
        self.chain_singular(s, (s + s).recip())
    }
    #[inline]
    fn exp(self) -> Self {
        let e = self.re.exp();
        self.chain(e, e)
    }
    #[inline]
    fn exp2(self) -> Self {
        let e = self.re.exp2();
        self.chain(e, e * T::ln_2())
    }
    #[inline]
    fn exp_m1(self) -> Self {
        let e = self.re.exp_m1();
        self.chain(e, e + T::one())
    }
    /// Derivative `n x^(n−1)`, finite at `x = 0` for `n ≥ 1`, zero for `n = 0`.
    #[inline]
    fn powi(self, n: i32) -> Self {
        let x = self.re;
        let value = x.powi(n);
        let derivative = match n.checked_sub(1) {
            _ if n == 0 => T::zero(),
            Some(m) => nalgebra::convert::<f64, T>(f64::from(n)) * x.powi(m),
            None => nalgebra::convert::<f64, T>(f64::from(n)) * value / x,
        };
        self.chain_singular(value, derivative)
    }
    /// `x^n` with `n` a dual number: `n x^(n−1) dx + x^n ln x dn`. The first term is computed as a
    /// power, not through `exp(n ln x)`, so that it is finite at `x = 0` for `n ≥ 1` (zero for
    /// `n > 1`); the second only enters where `n` has derivatives, so that a constant exponent
    /// needs no logarithm.
    #[inline]
    fn powf(self, n: Self) -> Self {
        let (x, p) = (self.re, n.re);
        let value = x.powf(p);
        // `n x^n / x` saves a second power where x ≠ 0; at x = 0, the power itself.
        let by_x = if p == T::zero() {
            T::zero()
        } else if x == T::zero() {
            p * x.powf(p - T::one())
        } else {
            p * value / x
        };
        let by_x = self.chain_singular(value, by_x);
        if n.eps.iter().all(|e| *e == T::zero()) {
            by_x
        } else {
            let by_n = n.chain_singular(value, value * x.ln());
            Self { re: value, eps: Self::zip_eps(by_x.eps, by_n.eps, |a, b| a + b) }
        }
    }
    #[inline]
    fn powc(self, n: Self) -> Self {
        self.powf(n)
    }
    #[inline]
    fn cbrt(self) -> Self {
        let c = self.re.cbrt();
        let three: T = nalgebra::convert(3.0);
        self.chain_singular(c, (three * c * c).recip())
    }
    /// The real part and every derivative finite.
    #[inline]
    fn is_finite(&self) -> bool {
        self.re.is_finite() && self.eps.iter().all(|e| e.is_finite())
    }
    #[inline]
    fn try_sqrt(self) -> Option<Self> {
        (self.re >= T::zero()).then(|| self.sqrt())
    }
}

impl<T: RealField + Copy, const M: usize> RealField for Dual<T, M> {
    #[inline]
    fn is_sign_positive(&self) -> bool {
        self.re.is_sign_positive()
    }
    #[inline]
    fn is_sign_negative(&self) -> bool {
        self.re.is_sign_negative()
    }
    #[inline]
    fn copysign(self, sign: Self) -> Self {
        if self.re.is_sign_negative() == sign.re.is_sign_negative() { self } else { -self }
    }
    /// The larger by real part, with its derivatives (`self` at a tie); NaN loses, as for floats.
    #[inline]
    fn max(self, other: Self) -> Self {
        if other.re > self.re || self.re.partial_cmp(&self.re).is_none() { other } else { self }
    }
    /// The smaller by real part, with its derivatives (`self` at a tie); NaN loses, as for floats.
    #[inline]
    fn min(self, other: Self) -> Self {
        if other.re < self.re || self.re.partial_cmp(&self.re).is_none() { other } else { self }
    }
    #[inline]
    fn clamp(self, min: Self, max: Self) -> Self {
        if self < min {
            min
        } else if self > max {
            max
        } else {
            self
        }
    }
    /// `atan2(y, x)` for `y = self`; derivative `(x dy − y dx) / (x² + y²)`, zero at the origin.
    #[inline]
    fn atan2(self, other: Self) -> Self {
        let (y, x) = (self.re, other.re);
        let r2 = x * x + y * y;
        let eps = if r2 == T::zero() {
            [T::zero(); M]
        } else {
            Self::zip_eps(self.eps, other.eps, |dy, dx| (x * dy - y * dx) / r2)
        };
        Self { re: y.atan2(x), eps }
    }
    #[inline]
    fn min_value() -> Option<Self> {
        T::min_value().map(Self::constant)
    }
    #[inline]
    fn max_value() -> Option<Self> {
        T::max_value().map(Self::constant)
    }
    #[inline]
    fn pi() -> Self {
        Self::constant(T::pi())
    }
    #[inline]
    fn two_pi() -> Self {
        Self::constant(T::two_pi())
    }
    #[inline]
    fn frac_pi_2() -> Self {
        Self::constant(T::frac_pi_2())
    }
    #[inline]
    fn frac_pi_3() -> Self {
        Self::constant(T::frac_pi_3())
    }
    #[inline]
    fn frac_pi_4() -> Self {
        Self::constant(T::frac_pi_4())
    }
    #[inline]
    fn frac_pi_6() -> Self {
        Self::constant(T::frac_pi_6())
    }
    #[inline]
    fn frac_pi_8() -> Self {
        Self::constant(T::frac_pi_8())
    }
    #[inline]
    fn frac_1_pi() -> Self {
        Self::constant(T::frac_1_pi())
    }
    #[inline]
    fn frac_2_pi() -> Self {
        Self::constant(T::frac_2_pi())
    }
    #[inline]
    fn frac_2_sqrt_pi() -> Self {
        Self::constant(T::frac_2_sqrt_pi())
    }
    #[inline]
    fn e() -> Self {
        Self::constant(T::e())
    }
    #[inline]
    fn log2_e() -> Self {
        Self::constant(T::log2_e())
    }
    #[inline]
    fn log10_e() -> Self {
        Self::constant(T::log10_e())
    }
    #[inline]
    fn ln_2() -> Self {
        Self::constant(T::ln_2())
    }
    #[inline]
    fn ln_10() -> Self {
        Self::constant(T::ln_10())
    }
}
