//! A segment's directions in its body frame (`crate::frames`): where the segment runs along the
//! frame's axes, as most links' do, its projections are plain components.

use nalgebra::{Matrix3, RealField, SimdRealField, Vector3};

use crate::algebra::dot;

/// The directions of a segment in its body frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum SegmentFrame<T: SimdRealField + Copy> {
    /// Along the body axes, as for most links: the segment along x, one normal along the joint
    /// axis z and the other along y (`normals[0]` along z where `swapped`). A normal's sign does
    /// not matter: flipping it flips the normal speed, acceleration and moment direction, and the
    /// force stays the same.
    Aligned { swapped: bool },
    /// Any directions.
    General { axis: Vector3<T>, normals: [Vector3<T>; 2] },
}

impl<T: SimdRealField + Copy> SegmentFrame<T> {
    /// `(v · normals[0], v · normals[1])`.
    #[inline(always)]
    pub(crate) fn normal_components(&self, v: &Vector3<T>) -> [T; 2] {
        match self {
            Self::Aligned { swapped: false } => [v.y, v.z],
            Self::Aligned { swapped: true } => [v.z, v.y],
            Self::General { normals: [n0, n1], .. } => [dot(n0, v), dot(n1, v)],
        }
    }

    /// `v · axis`.
    #[inline(always)]
    pub(crate) fn axial_component(&self, v: &Vector3<T>) -> T {
        match self {
            Self::Aligned { .. } => v.x,
            Self::General { axis, .. } => dot(axis, v),
        }
    }

    /// `c[0] normals[0] + c[1] normals[1]`.
    #[inline(always)]
    pub(crate) fn along_normals(&self, [c0, c1]: [T; 2]) -> Vector3<T> {
        match self {
            Self::Aligned { swapped: false } => Vector3::new(T::zero(), c0, c1),
            Self::Aligned { swapped: true } => Vector3::new(T::zero(), c1, c0),
            Self::General { normals: [n0, n1], .. } => n0 * c0 + n1 * c1,
        }
    }
}

/// An orthonormal frame (columns) whose z column is the unit `axis` and whose x column is the
/// column of `previous` most perpendicular to it, made perpendicular (exact for axis-aligned axes).
pub(crate) fn frame_about<T: RealField + Copy>(axis: &Vector3<T>, previous: &Matrix3<T>) -> Matrix3<T> {
    let mut x = previous.column(0).into_owned();
    for c in [previous.column(1).into_owned(), previous.column(2).into_owned()] {
        if c.dot(axis).abs() < x.dot(axis).abs() {
            x = c;
        }
    }
    let x = (x - axis * x.dot(axis)).normalize();
    Matrix3::from_columns(&[x, axis.cross(&x), *axis])
}

impl<T: SimdRealField + Copy> SegmentFrame<T> {
    /// Every number mapped by `f`.
    pub(crate) fn map_scalars<U: SimdRealField + Copy>(&self, f: impl Fn(T) -> U + Copy) -> SegmentFrame<U> {
        match self {
            Self::Aligned { swapped } => SegmentFrame::Aligned { swapped: *swapped },
            Self::General { axis, normals } => {
                SegmentFrame::General { axis: axis.map(f), normals: normals.map(|n| n.map(f)) }
            }
        }
    }
}
