//! Small vector and rotation helpers written out by components: nalgebra's generic products add
//! each sum to a zero first, which costs in the evaluation's inner loops.

use nalgebra::{Matrix3, SimdRealField, Vector3};

/// Rotation by the angle with sine `s` and cosine `c` about the unit `axis` (Rodrigues).
#[inline(always)]
pub(crate) fn axis_angle<T: SimdRealField + Copy>(axis: &Vector3<T>, (s, c): (T, T)) -> Matrix3<T> {
    let (x, y, z) = (axis.x, axis.y, axis.z);
    let t = T::one() - c;
    Matrix3::new(
        t * x * x + c,
        t * x * y - s * z,
        t * x * z + s * y,
        t * x * y + s * z,
        t * y * y + c,
        t * y * z - s * x,
        t * x * z - s * y,
        t * y * z + s * x,
        t * z * z + c,
    )
}

/// `a · b`, without the zero accumulator of nalgebra's generic dot.
#[inline(always)]
pub(crate) fn dot<T: SimdRealField + Copy>(a: &Vector3<T>, b: &Vector3<T>) -> T {
    a.x * b.x + a.y * b.y + a.z * b.z
}

/// `m · v`.
#[inline(always)]
pub(crate) fn rotate<T: SimdRealField + Copy>(m: &Matrix3<T>, v: &Vector3<T>) -> Vector3<T> {
    let (c0, c1, c2) = (m.column(0), m.column(1), m.column(2));
    Vector3::new(
        c0.x * v.x + c1.x * v.y + c2.x * v.z,
        c0.y * v.x + c1.y * v.y + c2.y * v.z,
        c0.z * v.x + c1.z * v.y + c2.z * v.z,
    )
}

/// `mᵀ · v`.
#[inline(always)]
pub(crate) fn rotate_back<T: SimdRealField + Copy>(m: &Matrix3<T>, v: &Vector3<T>) -> Vector3<T> {
    let (c0, c1, c2) = (m.column(0), m.column(1), m.column(2));
    Vector3::new(
        c0.x * v.x + c0.y * v.y + c0.z * v.z,
        c1.x * v.x + c1.y * v.y + c1.z * v.z,
        c2.x * v.x + c2.y * v.y + c2.z * v.z,
    )
}
