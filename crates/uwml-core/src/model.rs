//! The immutable, validated description of a serial chain, the water and the coefficients.
//!
//! Frames follow URDF without fixed rotations: every link frame is parallel to the world frame
//! when all joint angles are zero. Joint `i` sits at `origin` in the frame of link `i - 1` (the
//! world frame for the first joint) and turns link `i` about `axis` by `q[i]`. Link `i`'s
//! geometry is given in its own frame, whose origin is joint `i`. World z points up.

use nalgebra::{RealField, SimdRealField, Vector3};

use crate::error::{ModelError, Problem};
use crate::robot::Robot;

/// Tolerance on unit length and on orthogonality of axes and normals at construction.
pub const AXIS_TOLERANCE: f64 = 1e-6;

/// A revolute joint: origin and unit axis in the parent link's frame at `q = 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Joint<T: SimdRealField + Copy> {
    /// Position of the joint in the parent frame [m].
    pub origin: Vector3<T>,
    /// Unit rotation axis in the parent frame.
    pub axis: Vector3<T>,
}

/// The hydrodynamic geometry of a straight link (strip theory), in the link's frame.
///
/// A slice at arc length `s ∈ [0, length]` lies at `start + s·axis`. `normals[k]` are the two
/// principal cross-flow directions (orthonormal, perpendicular to `axis`); `widths[k]` is the
/// frontal width seen by flow along `normals[k]`; `area` is the section area for added mass.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment<T: SimdRealField + Copy> {
    /// Start point of the segment [m].
    pub start: Vector3<T>,
    /// Unit direction of the segment.
    pub axis: Vector3<T>,
    /// Length [m], positive.
    pub length: T,
    /// The two principal normal directions.
    pub normals: [Vector3<T>; 2],
    /// Frontal width for flow along each normal [m], positive.
    pub widths: [T; 2],
    /// Cross-section area for added mass [m²], positive.
    pub area: T,
}

/// A rigid link: mass and centre of mass, displaced volume and centre of buoyancy, and
/// optionally a straight segment that meets the water.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Link<T: SimdRealField + Copy> {
    /// Mass [kg], zero or positive.
    pub mass: T,
    /// Centre of mass in the link frame [m].
    pub com: Vector3<T>,
    /// Displaced volume [m³], zero or positive.
    pub volume: T,
    /// Centre of buoyancy in the link frame [m].
    pub cob: Vector3<T>,
    /// Hydrodynamic geometry; `None` for a link without drag or added mass.
    pub segment: Option<Segment<T>>,
}

/// A validated serial chain of `N` revolute joints, link `i` moved by joint `i`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Chain<T: SimdRealField + Copy, const N: usize> {
    joints: [Joint<T>; N],
    links: [Link<T>; N],
    /// The same chain as a robot (its joints in series on a fixed base, each link's segment in
    /// link order, at the default coefficients), derived once: the chain's functions are this
    /// robot's evaluation.
    robot: Robot<T, N, N>,
}

/// The fluid the chain moves in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Water<T: SimdRealField + Copy> {
    density: T,
    gravity: T,
}

/// Drag and added-mass coefficients per link and per normal direction (`[link][k]`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coefficients<T: SimdRealField + Copy, const N: usize> {
    cd: [[T; 2]; N],
    cm: [[T; 2]; N],
}

pub(crate) fn constant<T: SimdRealField + Copy>(x: f64) -> T {
    nalgebra::convert(x)
}

pub(crate) fn check_finite<T: RealField + Copy>(
    x: T,
    field: &'static str,
    index: Option<usize>,
) -> Result<T, ModelError> {
    if x.is_finite() { Ok(x) } else { Err(ModelError::new(field, index, Problem::NonFinite)) }
}

pub(crate) fn check_positive<T: RealField + Copy>(
    x: T,
    field: &'static str,
    index: Option<usize>,
) -> Result<T, ModelError> {
    let x = check_finite(x, field, index)?;
    if x > T::zero() { Ok(x) } else { Err(ModelError::new(field, index, Problem::NonPositive)) }
}

pub(crate) fn check_non_negative<T: RealField + Copy>(
    x: T,
    field: &'static str,
    index: Option<usize>,
) -> Result<T, ModelError> {
    let x = check_finite(x, field, index)?;
    if x >= T::zero() { Ok(x) } else { Err(ModelError::new(field, index, Problem::Negative)) }
}

/// `x` finite and at least `low`, else `problem`.
pub(crate) fn check_at_least<T: RealField + Copy>(
    x: T,
    low: T,
    field: &'static str,
    problem: Problem,
) -> Result<T, ModelError> {
    let x = check_finite(x, field, None)?;
    if x >= low { Ok(x) } else { Err(ModelError::new(field, None, problem)) }
}

/// Every drag and added-mass coefficient of a table (`[owner][k]`) finite and non-negative, or
/// an error naming `fields` and the owner's index.
pub(crate) fn check_coefficient_table<T: RealField + Copy>(
    cd: &[[T; 2]],
    cm: &[[T; 2]],
    [cd_field, cm_field]: [&'static str; 2],
) -> Result<(), ModelError> {
    for (index, (cd, cm)) in cd.iter().zip(cm.iter()).enumerate() {
        for (&d, &m) in cd.iter().zip(cm.iter()) {
            check_coefficient(d, cd_field, Some(index))?;
            check_coefficient(m, cm_field, Some(index))?;
        }
    }
    Ok(())
}

/// The largest length a model may hold [m]: every coordinate of a point (joint origins, centres
/// of mass and buoyancy, segment starts) and every length, width and diameter. A robot's
/// dimensions beyond 10 km are a unit mistake; the bounds keep every force of a finite state
/// finite (docs/domains.md), in f32 too.
pub const MAX_LENGTH: f64 = 1e4;
/// The largest mass of a body [kg] (the largest ships displace under 1e9 kg).
pub const MAX_MASS: f64 = 1e9;
/// The largest volume of a body [m³] (1e9 kg of water).
pub const MAX_VOLUME: f64 = 1e6;
/// The largest cross-section area of a segment [m²] (`MAX_LENGTH²`).
pub const MAX_AREA: f64 = 1e8;
/// The largest drag or added-mass coefficient (measured ones are of order 1).
pub const MAX_COEFFICIENT: f64 = 1e3;
/// The largest water density [kg/m³] (more than any liquid's).
pub const MAX_DENSITY: f64 = 1e5;
/// The largest gravity [m/s²].
pub const MAX_GRAVITY: f64 = 1e3;

/// `x` (already checked finite) at most `limit` in magnitude, else [`Problem::TooLarge`].
pub(crate) fn check_at_most<T: RealField + Copy>(
    x: T,
    limit: f64,
    field: &'static str,
    index: Option<usize>,
) -> Result<T, ModelError> {
    if x.abs() <= constant(limit) { Ok(x) } else { Err(ModelError::new(field, index, Problem::TooLarge)) }
}

/// A drag or added-mass coefficient: finite, not negative, at most [`MAX_COEFFICIENT`].
pub(crate) fn check_coefficient<T: RealField + Copy>(
    x: T,
    field: &'static str,
    index: Option<usize>,
) -> Result<T, ModelError> {
    check_at_most(check_non_negative(x, field, index)?, MAX_COEFFICIENT, field, index)
}

/// A point of the model: finite, each coordinate at most [`MAX_LENGTH`] in magnitude.
pub(crate) fn check_point<T: RealField + Copy>(
    v: Vector3<T>,
    field: &'static str,
    index: Option<usize>,
) -> Result<Vector3<T>, ModelError> {
    let v = check_vector(v, field, index)?;
    for &x in v.iter() {
        check_at_most(x, MAX_LENGTH, field, index)?;
    }
    Ok(v)
}

/// A length, width, diameter: finite, positive, at most [`MAX_LENGTH`].
pub(crate) fn check_length<T: RealField + Copy>(
    x: T,
    field: &'static str,
    index: Option<usize>,
) -> Result<T, ModelError> {
    check_at_most(check_positive(x, field, index)?, MAX_LENGTH, field, index)
}

pub(crate) fn check_vector<T: RealField + Copy>(
    v: Vector3<T>,
    field: &'static str,
    index: Option<usize>,
) -> Result<Vector3<T>, ModelError> {
    if v.iter().all(|x| x.is_finite()) { Ok(v) } else { Err(ModelError::new(field, index, Problem::NonFinite)) }
}

/// Checks that `v` is a unit vector within [`AXIS_TOLERANCE`] and returns it normalized exactly.
pub(crate) fn check_unit<T: RealField + Copy>(
    v: Vector3<T>,
    field: &'static str,
    index: Option<usize>,
) -> Result<Vector3<T>, ModelError> {
    let v = check_vector(v, field, index)?;
    let norm = v.norm();
    if (norm - T::one()).abs() <= constant(AXIS_TOLERANCE) {
        Ok(v / norm)
    } else {
        Err(ModelError::new(field, index, Problem::NotUnit))
    }
}

/// `v` made exactly perpendicular to the unit `axis` and normalized, if it was within
/// [`AXIS_TOLERANCE`] of perpendicular and of unit length.
pub(crate) fn check_normal<T: RealField + Copy>(
    v: Vector3<T>,
    axis: &Vector3<T>,
    field: &'static str,
    index: Option<usize>,
) -> Result<Vector3<T>, ModelError> {
    let v = check_unit(v, field, index)?;
    if v.dot(axis).abs() > constant(AXIS_TOLERANCE) {
        return Err(ModelError::new(field, index, Problem::NotPerpendicular));
    }
    Ok((v - axis * v.dot(axis)).normalize())
}

fn check_perpendicular<T: RealField + Copy>(
    a: &Vector3<T>,
    b: &Vector3<T>,
    field: &'static str,
    index: Option<usize>,
) -> Result<(), ModelError> {
    if a.dot(b).abs() <= constant(AXIS_TOLERANCE) {
        Ok(())
    } else {
        Err(ModelError::new(field, index, Problem::NotPerpendicular))
    }
}

impl<T: RealField + Copy> Joint<T> {
    fn validated(self, index: usize) -> Result<Self, ModelError> {
        let i = Some(index);
        Ok(Self { origin: check_point(self.origin, "joint.origin", i)?, axis: check_unit(self.axis, "joint.axis", i)? })
    }
}

impl<T: RealField + Copy> Segment<T> {
    fn validated(self, index: usize) -> Result<Self, ModelError> {
        let i = Some(index);
        let axis = check_unit(self.axis, "segment.axis", i)?;
        let [n1, n2] = self.normals;
        let n1 = check_normal(n1, &axis, "segment.normals[0]", i)?;
        let n2 = check_normal(n2, &axis, "segment.normals[1]", i)?;
        check_perpendicular(&n1, &n2, "segment.normals[1]", i)?;
        // An exact frame (the strip integrals' identities assume one): the second normal
        // exactly perpendicular to the axis and the first, on the side it was given.
        let n2 = axis.cross(&n1) * axis.cross(&n1).dot(&n2).signum();
        let [w1, w2] = self.widths;
        Ok(Self {
            start: check_point(self.start, "segment.start", i)?,
            axis,
            length: check_length(self.length, "segment.length", i)?,
            normals: [n1, n2],
            widths: [check_length(w1, "segment.widths[0]", i)?, check_length(w2, "segment.widths[1]", i)?],
            area: check_at_most(check_positive(self.area, "segment.area", i)?, MAX_AREA, "segment.area", i)?,
        })
    }
}

impl<T: RealField + Copy> Link<T> {
    fn validated(self, index: usize) -> Result<Self, ModelError> {
        let i = Some(index);
        Ok(Self {
            mass: check_at_most(check_non_negative(self.mass, "link.mass", i)?, MAX_MASS, "link.mass", i)?,
            com: check_point(self.com, "link.com", i)?,
            volume: check_at_most(check_non_negative(self.volume, "link.volume", i)?, MAX_VOLUME, "link.volume", i)?,
            cob: check_point(self.cob, "link.cob", i)?,
            segment: match self.segment {
                Some(segment) => Some(segment.validated(index)?),
                None => None,
            },
        })
    }
}

impl<T: RealField + Copy, const N: usize> Chain<T, N> {
    /// Validates and builds a chain. Axes are re-normalized exactly; each segment's normals are
    /// made an exact orthonormal frame with its axis (Gram-Schmidt, the second normal on the side
    /// it was given).
    ///
    /// # Errors
    /// The first non-finite, non-positive (lengths, widths, area), negative (mass, volume),
    /// non-unit or non-perpendicular parameter, naming the field and the joint or link.
    pub fn new(mut joints: [Joint<T>; N], mut links: [Link<T>; N]) -> Result<Self, ModelError> {
        for (index, (joint, link)) in joints.iter_mut().zip(links.iter_mut()).enumerate() {
            *joint = joint.validated(index)?;
            *link = link.validated(index)?;
        }
        Ok(Self::from_validated(joints, links))
    }

    /// A chain of valid joints and links (validated, or the paper's), with its robot.
    fn from_validated(joints: [Joint<T>; N], links: [Link<T>; N]) -> Self {
        Self { joints, links, robot: Robot::serial(&joints, &links, &Coefficients::default()) }
    }
}

impl<T: SimdRealField + Copy, const N: usize> Chain<T, N> {
    /// The joints, as validated.
    pub const fn joints(&self) -> &[Joint<T>; N] {
        &self.joints
    }

    /// The links, as validated.
    pub const fn links(&self) -> &[Link<T>; N] {
        &self.links
    }

    /// The chain as a robot of `N` joints and up to `N` segments (each link's, in link order), at
    /// the default coefficients: what the chain's functions evaluate.
    pub const fn robot(&self) -> &Robot<T, N, N> {
        &self.robot
    }
}

/// Table II of the paper, the UWML's parameters (SI units).
pub mod paper {
    /// Thigh length `L2` [m].
    pub const L2: f64 = 0.660;
    /// Calf length `L3` [m].
    pub const L3: f64 = 0.714;
    /// Thigh COM/COB distance from joint 2, `Lc2` [m].
    pub const LC2: f64 = 0.506;
    /// Calf COM/COB distance from joint 3, `Lc3` [m].
    pub const LC3: f64 = 0.560;
    /// Thigh frontal width for out-of-plane flow, `D21` [m].
    pub const D21: f64 = 0.131;
    /// Thigh frontal width for in-plane flow, `D22` [m].
    pub const D22: f64 = 0.238;
    /// Calf frontal width for out-of-plane flow, `D31` [m].
    pub const D31: f64 = 0.131;
    /// Calf frontal width for in-plane flow, `D32` [m].
    pub const D32: f64 = 0.279;
    /// Link masses `m1, m2, m3` [kg].
    pub const MASSES: [f64; 3] = [10.758, 19.261, 10.375];
    /// Equivalent link density `ρ_m` [kg/m³]; a link's displaced volume is `m / ρ_m`.
    pub const LINK_DENSITY: f64 = 2700.0;
}

impl<T: RealField + Copy> Chain<T, 3> {
    /// The paper's underwater mechanical leg (UWML, Table II): hip yaw about world z, hip roll
    /// and knee roll about `-e_t`; thigh along local +x, calf along local −z at `q = 0`.
    #[must_use]
    pub fn paper() -> Self {
        let c = constant::<T>;
        let v = |x: f64, y: f64, z: f64| Vector3::new(c(x), c(y), c(z));
        let roll_axis = v(0.0, -1.0, 0.0);
        let joints = [
            Joint { origin: Vector3::zeros(), axis: v(0.0, 0.0, 1.0) },
            Joint { origin: Vector3::zeros(), axis: roll_axis },
            Joint { origin: v(paper::L2, 0.0, 0.0), axis: roll_axis },
        ];
        let volume = |m: f64| c(m / paper::LINK_DENSITY);
        let [m1, m2, m3] = paper::MASSES;
        let out_of_plane = v(0.0, 1.0, 0.0);
        let links = [
            Link { mass: c(m1), com: Vector3::zeros(), volume: volume(m1), cob: Vector3::zeros(), segment: None },
            Link {
                mass: c(m2),
                com: v(paper::LC2, 0.0, 0.0),
                volume: volume(m2),
                cob: v(paper::LC2, 0.0, 0.0),
                segment: Some(Segment {
                    start: Vector3::zeros(),
                    axis: v(1.0, 0.0, 0.0),
                    length: c(paper::L2),
                    normals: [out_of_plane, v(0.0, 0.0, 1.0)],
                    widths: [c(paper::D21), c(paper::D22)],
                    area: c(paper::D21 * paper::D22),
                }),
            },
            Link {
                mass: c(m3),
                com: v(0.0, 0.0, -paper::LC3),
                volume: volume(m3),
                cob: v(0.0, 0.0, -paper::LC3),
                segment: Some(Segment {
                    start: Vector3::zeros(),
                    axis: v(0.0, 0.0, -1.0),
                    length: c(paper::L3),
                    normals: [out_of_plane, v(1.0, 0.0, 0.0)],
                    widths: [c(paper::D31), c(paper::D32)],
                    area: c(paper::D31 * paper::D32),
                }),
            },
        ];
        Self::from_validated(joints, links)
    }
}

impl<T: RealField + Copy> Water<T> {
    /// Water of the given density [kg/m³] under the given gravity [m/s²].
    ///
    /// # Errors
    /// Density not positive and finite, or gravity negative or not finite; either beyond
    /// [`MAX_DENSITY`], [`MAX_GRAVITY`].
    pub fn new(density: T, gravity: T) -> Result<Self, ModelError> {
        Ok(Self {
            density: check_at_most(
                check_positive(density, "water.density", None)?,
                MAX_DENSITY,
                "water.density",
                None,
            )?,
            gravity: check_at_most(
                check_non_negative(gravity, "water.gravity", None)?,
                MAX_GRAVITY,
                "water.gravity",
                None,
            )?,
        })
    }
}

impl<T: SimdRealField + Copy> Water<T> {
    /// Density [kg/m³].
    pub const fn density(&self) -> T {
        self.density
    }

    /// Gravitational acceleration [m/s²].
    pub const fn gravity(&self) -> T {
        self.gravity
    }
}

impl<T: RealField + Copy> Default for Water<T> {
    /// Fresh water as in the paper: 1000 kg/m³, g = 9.81 m/s².
    fn default() -> Self {
        Self { density: constant(1000.0), gravity: constant(9.81) }
    }
}

impl<T: RealField + Copy, const N: usize> Coefficients<T, N> {
    /// One drag and one added-mass coefficient for every link and direction (the paper's model).
    ///
    /// # Errors
    /// A coefficient that is negative or not finite.
    pub fn uniform(cd: T, cm: T) -> Result<Self, ModelError> {
        Self::per_direction([[cd; 2]; N], [[cm; 2]; N])
    }

    /// Coefficients per link and per normal direction, indexed `[link][k]`.
    ///
    /// # Errors
    /// A coefficient that is negative or not finite, naming the link.
    pub fn per_direction(cd: [[T; 2]; N], cm: [[T; 2]; N]) -> Result<Self, ModelError> {
        check_coefficient_table(&cd, &cm, ["cd", "cm"])?;
        Ok(Self { cd, cm })
    }
}

impl<T: SimdRealField + Copy, const N: usize> Coefficients<T, N> {
    /// Drag coefficients `[link][k]`.
    pub const fn cd(&self) -> &[[T; 2]; N] {
        &self.cd
    }

    /// Added-mass coefficients `[link][k]`.
    pub const fn cm(&self) -> &[[T; 2]; N] {
        &self.cm
    }
}

impl<T: RealField + Copy, const N: usize> Default for Coefficients<T, N> {
    /// The paper's fitted values rounded: `Cd = 2.2`, `Cm = 0.5` everywhere.
    fn default() -> Self {
        Self { cd: [[constant(2.2); 2]; N], cm: [[constant(0.5); 2]; N] }
    }
}

impl<T: RealField + Copy> Joint<T> {
    /// Every number mapped by `f` (see [`Chain::map_scalars`]).
    pub(crate) fn map_scalars<U: SimdRealField + Copy>(&self, f: impl Fn(T) -> U + Copy) -> Joint<U> {
        Joint { origin: self.origin.map(f), axis: self.axis.map(f) }
    }
}

impl<T: RealField + Copy> Segment<T> {
    /// Every number mapped by `f` (see [`Chain::map_scalars`]).
    pub(crate) fn map_scalars<U: SimdRealField + Copy>(&self, f: impl Fn(T) -> U + Copy) -> Segment<U> {
        Segment {
            start: self.start.map(f),
            axis: self.axis.map(f),
            length: f(self.length),
            normals: self.normals.map(|n| n.map(f)),
            widths: self.widths.map(f),
            area: f(self.area),
        }
    }
}

impl<T: RealField + Copy> Link<T> {
    /// Every number mapped by `f` (see [`Chain::map_scalars`]).
    pub(crate) fn map_scalars<U: SimdRealField + Copy>(&self, f: impl Fn(T) -> U + Copy) -> Link<U> {
        Link {
            mass: f(self.mass),
            com: self.com.map(f),
            volume: f(self.volume),
            cob: self.cob.map(f),
            segment: self.segment.map(|s| s.map_scalars(f)),
        }
    }
}

impl<T: RealField + Copy, const N: usize> Chain<T, N> {
    /// The same chain over another scalar type, every number (including the precomputed body
    /// frames) mapped by `f`, which must keep values (as `Dual::constant` does): nothing is
    /// validated or derived again, so the mapped chain takes the same branches as this one.
    pub(crate) fn map_scalars<U: SimdRealField + Copy>(&self, f: impl Fn(T) -> U + Copy) -> Chain<U, N> {
        Chain {
            joints: self.joints.map(|j| j.map_scalars(f)),
            links: self.links.map(|l| l.map_scalars(f)),
            robot: self.robot.map_scalars(f),
        }
    }
}

impl<T: RealField + Copy> Water<T> {
    /// The same water over another scalar type (see [`Chain::map_scalars`]).
    pub(crate) fn map_scalars<U: SimdRealField + Copy>(&self, f: impl Fn(T) -> U) -> Water<U> {
        Water { density: f(self.density), gravity: f(self.gravity) }
    }
}

impl<T: RealField + Copy, const N: usize> Coefficients<T, N> {
    /// The same coefficients over another scalar type (see [`Chain::map_scalars`]).
    pub(crate) fn map_scalars<U: SimdRealField + Copy>(&self, f: impl Fn(T) -> U + Copy) -> Coefficients<U, N> {
        Coefficients { cd: self.cd.map(|c| c.map(f)), cm: self.cm.map(|c| c.map(f)) }
    }
}

impl<T: RealField + Copy, const N: usize> Chain<T, N> {
    /// The same chain over a SIMD type `L` whose lanes are `T`s (such as simba's `WideF64x4`),
    /// every number splat across the lanes: the torque paths then evaluate one joint state per
    /// lane in one call, with the same operations as for `T`.
    #[must_use]
    pub fn splat<L: SimdRealField<Element = T> + Copy>(&self) -> Chain<L, N> {
        self.map_scalars(L::splat)
    }
}

impl<T: RealField + Copy> Water<T> {
    /// The same water over a SIMD type (see [`Chain::splat`]).
    #[must_use]
    pub fn splat<L: SimdRealField<Element = T> + Copy>(&self) -> Water<L> {
        self.map_scalars(L::splat)
    }
}

impl<T: RealField + Copy, const N: usize> Coefficients<T, N> {
    /// The same coefficients over a SIMD type (see [`Chain::splat`]).
    #[must_use]
    pub fn splat<L: SimdRealField<Element = T> + Copy>(&self) -> Coefficients<L, N> {
        self.map_scalars(L::splat)
    }
}
