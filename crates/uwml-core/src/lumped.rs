//! Fossen's lumped hydrodynamic model of a bluff body: a vehicle's hull, a battery can, a gripper
//! (docs/model.md section 12.1). Strip theory (section 3) is for slender segments and has no force
//! along a segment's axis; a body that is not slender carries an added-mass matrix, a linear
//! damping matrix and quadratic damping about a reference point instead (or beside its strips).
//!
//! With `ν_r = (v_P − Rᵀc, ω)` the body's twist relative to the water at `P`, in the body's
//! components, the body feels at `P`
//! `W = −M_A ν̇_r − C_A(ν_r) ν_r − D_L ν_r − D_Q(ν_r) ν_r`, where `ν̇_r` is the time derivative
//! of `ν_r`'s components and `C_A(ν) ν = (ω × p, v × p + ω × h)` with `(p, h) = M_A ν` (Fossen's
//! added-mass Coriolis-centripetal term): the added-mass part conserves `½ ν_rᵀ M_A ν_r` in still
//! water. The damping is reported with the drag, the rest with the added mass.

use nalgebra::{Matrix3, Matrix6, RealField, SimdRealField, Vector3, Vector6};

use crate::bounds::{
    AXIS_TOLERANCE, LUMPED_ABSOLUTE_TOLERANCE, LUMPED_EIGENVALUE_TOLERANCE, LUMPED_SYMMETRY_TOLERANCE, MAX_LUMPED,
};
use crate::check::{check_at_most, check_finite, check_non_negative, check_point, check_unit, constant};
use crate::error::{ModelError, Problem};
use crate::parts::Owner;
use crate::wrench::Wrench;

/// Fossen's lumped model of one body (docs/model.md section 12.1), about the reference point
/// `point` of the body's frame, in the axes `axes` (the identity: the body's own). Every matrix is
/// ordered `(x, y, z, roll, pitch, yaw)`, linear first.
///
/// The entries are magnitudes as they act: the added mass `M_A` is positive on its diagonal
/// (SNAME's `X_u̇` is `−M_A[0][0]`), and so are the damping's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LumpedBody<T: SimdRealField + Copy> {
    /// The body it belongs to.
    pub owner: Owner,
    /// The reference point `P`, in the body's frame [m].
    pub point: Vector3<T>,
    /// The model's axes (columns) in the body's frame, a rotation: its matrices and quadratic
    /// damping are in these axes (a description's body frame turned from uwml's link frame; a
    /// hull's principal axes).
    pub axes: Matrix3<T>,
    /// `M_A` about `P`: symmetric, positive semi-definite [kg, kg·m, kg·m²].
    pub added_mass: Matrix6<T>,
    /// `D_L` about `P`, whose symmetric part is positive semi-definite [N·s/m, N·s, N·m·s].
    pub linear_damping: Matrix6<T>,
    /// `d_i ≥ 0` of the quadratic damping `−d_i |ν_i| ν_i`, per component [kg/m, kg·m²].
    pub quadratic_damping: [T; 6],
}

impl<T: RealField + Copy> LumpedBody<T> {
    /// No added mass, no damping, at the body's origin.
    #[must_use]
    pub fn none(owner: Owner) -> Self {
        Self {
            owner,
            point: Vector3::zeros(),
            axes: Matrix3::identity(),
            added_mass: Matrix6::zeros(),
            linear_damping: Matrix6::zeros(),
            quadratic_damping: [T::zero(); 6],
        }
    }

    /// Validated (lumped model `index` of a robot of `joint_count` joints), `M_A` made exactly
    /// symmetric (the mean of it and its transpose).
    pub(crate) fn validated(self, index: usize, joint_count: usize) -> Result<Self, ModelError> {
        let i = Some(index);
        if let Owner::Link(link) = self.owner
            && link >= joint_count
        {
            return Err(ModelError::new("lumped.owner", i, Problem::OutOfRange));
        }
        let point = check_point(self.point, "lumped.point", i)?;
        let axes = check_rotation(&self.axes, "lumped.axes", i)?;
        let added_mass = check_matrix(&self.added_mass, "lumped.added_mass", i)?;
        let linear_damping = check_matrix(&self.linear_damping, "lumped.linear_damping", i)?;
        // Judged in f64 on the exact values (an f32 converts exactly), so that a model is taken
        // or refused alike in either precision: f32 arithmetic would round a singular
        // semi-definite matrix's zero eigenvalues far below the tolerance.
        let (given_mass, given_damping) = (in_f64(&added_mass), in_f64(&linear_damping));
        if !nearly_symmetric(&given_mass) {
            return Err(ModelError::new("lumped.added_mass", i, Problem::NotSymmetric));
        }
        if !positive_semidefinite(&((given_mass + given_mass.transpose()) * 0.5)) {
            return Err(ModelError::new("lumped.added_mass", i, Problem::NotPositiveSemidefinite));
        }
        if !positive_semidefinite(&((given_damping + given_damping.transpose()) * 0.5)) {
            return Err(ModelError::new("lumped.linear_damping", i, Problem::NotPositiveSemidefinite));
        }
        let added_mass = (added_mass + added_mass.transpose()) * constant::<T>(0.5);
        let mut quadratic_damping = self.quadratic_damping;
        for d in &mut quadratic_damping {
            *d = check_at_most(
                check_non_negative(*d, "lumped.quadratic_damping", i)?,
                MAX_LUMPED,
                "lumped.quadratic_damping",
                i,
            )?;
        }
        Ok(Self { owner: self.owner, point, axes, added_mass, linear_damping, quadratic_damping })
    }
}

/// A rotation within [`AXIS_TOLERANCE`] (unit, perpendicular columns, right-handed), made exact
/// (Gram-Schmidt on its first two columns, the third their cross product).
fn check_rotation<T: RealField + Copy>(
    m: &Matrix3<T>,
    field: &'static str,
    index: Option<usize>,
) -> Result<Matrix3<T>, ModelError> {
    let [x, y, z] = [0, 1, 2].map(|c| m.column(c).into_owned());
    let (x, y, z) = (check_unit(x, field, index)?, check_unit(y, field, index)?, check_unit(z, field, index)?);
    let tolerance = constant::<T>(AXIS_TOLERANCE);
    if x.dot(&y).abs() > tolerance || x.dot(&z).abs() > tolerance || y.dot(&z).abs() > tolerance {
        return Err(ModelError::new(field, index, Problem::NotPerpendicular));
    }
    if (x.cross(&y) - z).amax() > tolerance {
        // Orthonormal but left-handed: a reflection, not a rotation.
        return Err(ModelError::new(field, index, Problem::OutOfRange));
    }
    let y = (y - x * x.dot(&y)).normalize();
    Ok(Matrix3::from_columns(&[x, y, x.cross(&y)]))
}

/// Every entry finite and at most [`MAX_LUMPED`] in magnitude.
fn check_matrix<T: RealField + Copy>(
    m: &Matrix6<T>,
    field: &'static str,
    index: Option<usize>,
) -> Result<Matrix6<T>, ModelError> {
    for &x in m.iter() {
        check_at_most(check_finite(x, field, index)?, MAX_LUMPED, field, index)?;
    }
    Ok(*m)
}

/// `m`'s entries in f64 (exact for f32 and f64; NaN, which no check takes, for a number that
/// has none).
fn in_f64<T: RealField + Copy>(m: &Matrix6<T>) -> Matrix6<f64> {
    m.map(|x| nalgebra::try_convert_ref::<T, f64>(&x).unwrap_or(f64::NAN))
}

/// The tolerance of docs/model.md section 12.1: `relative` times `scale`, but never more than
/// [`LUMPED_ABSOLUTE_TOLERANCE`].
fn tolerance(relative: f64, scale: f64) -> f64 {
    (relative * scale).min(LUMPED_ABSOLUTE_TOLERANCE)
}

/// Symmetric to rounding: `|m_ij − m_ji| ≤ min(LUMPED_SYMMETRY_TOLERANCE · max |m|,
/// LUMPED_ABSOLUTE_TOLERANCE)`.
fn nearly_symmetric(m: &Matrix6<f64>) -> bool {
    let allowed = tolerance(LUMPED_SYMMETRY_TOLERANCE, m.iter().fold(0.0_f64, |s, x| s.max(x.abs())));
    (m - m.transpose()).iter().all(|x| x.abs() <= allowed)
}

/// Whether the symmetric `m` is positive semi-definite, to rounding: its smallest eigenvalue (by
/// Jacobi's method, robust for the singular matrices a semi-definite one may be) at least
/// `−min(LUMPED_EIGENVALUE_TOLERANCE · s, LUMPED_ABSOLUTE_TOLERANCE)`, `s` its largest diagonal
/// entry in magnitude.
fn positive_semidefinite(m: &Matrix6<f64>) -> bool {
    let scale = m.diagonal().iter().fold(0.0_f64, |s, x| s.max(x.abs()));
    smallest_eigenvalue(m) >= -tolerance(LUMPED_EIGENVALUE_TOLERANCE, scale)
}

/// The smallest eigenvalue of the symmetric `m`: cyclic Jacobi rotations until the off-diagonal
/// part is negligible (at most 30 sweeps; six by six needs a handful).
fn smallest_eigenvalue<T: RealField + Copy>(m: &Matrix6<T>) -> T {
    let mut a = *m;
    let at = |a: &Matrix6<T>, i: usize, j: usize| a.get((i, j)).copied().unwrap_or_else(T::zero);
    let set = |a: &mut Matrix6<T>, i: usize, j: usize, x: T| {
        if let Some(slot) = a.get_mut((i, j)) {
            *slot = x;
        }
    };
    let scale = m.iter().fold(T::zero(), |s, x| s.max(x.abs()));
    for _ in 0..30 {
        let off =
            (0..6).flat_map(|i| (0..6).map(move |j| (i, j))).filter(|(i, j)| i != j).fold(T::zero(), |s, (i, j)| {
                let x = at(&a, i, j);
                s + x * x
            });
        if off.sqrt() <= scale * constant(1e-15) {
            break;
        }
        for p in 0..5 {
            for q in p + 1..6 {
                let apq = at(&a, p, q);
                if apq == T::zero() {
                    continue;
                }
                let theta = (at(&a, q, q) - at(&a, p, p)) / (apq + apq);
                // The smaller root of t² + 2θt − 1 = 0, without overflow for a large θ.
                let t = if theta.abs() > constant(1e100) {
                    (theta + theta).recip()
                } else {
                    let root = (theta * theta + T::one()).sqrt();
                    if theta >= T::zero() { (theta + root).recip() } else { -(root - theta).recip() }
                };
                let c = (t * t + T::one()).sqrt().recip();
                let sn = t * c;
                for k in 0..6 {
                    let (akp, akq) = (at(&a, k, p), at(&a, k, q));
                    set(&mut a, k, p, c * akp - sn * akq);
                    set(&mut a, k, q, sn * akp + c * akq);
                }
                for k in 0..6 {
                    let (apk, aqk) = (at(&a, p, k), at(&a, q, k));
                    set(&mut a, p, k, c * apk - sn * aqk);
                    set(&mut a, q, k, sn * apk + c * aqk);
                }
            }
        }
    }
    (0..6).fold(at(&a, 0, 0), |s, i| s.min(at(&a, i, i)))
}

/// The lumped models of a robot's bodies (up to `B`), each in its body's frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Lumped<T: SimdRealField + Copy, const B: usize> {
    models: [(Owner, LumpedFrame<T>); B],
    /// How many are used (small, so that a robot without room for any grows by nothing).
    count: u16,
}

impl<T: SimdRealField + Copy, const B: usize> Lumped<T, B> {
    /// None.
    pub(crate) fn none() -> Self {
        let zero = LumpedFrame {
            point: Vector3::zeros(),
            rotation: None,
            added_mass: Matrix6::zeros(),
            linear_damping: Matrix6::zeros(),
            quadratic_damping: [T::zero(); 6],
        };
        Self { models: [(Owner::Base, zero); B], count: 0 }
    }

    /// Each model and its body.
    pub(crate) fn iter(&self) -> impl Iterator<Item = &(Owner, LumpedFrame<T>)> {
        self.models.iter().take(usize::from(self.count))
    }

    /// Whether `owner` has one.
    pub(crate) fn len(&self) -> usize {
        usize::from(self.count)
    }

    pub(crate) fn has(&self, owner: Owner) -> bool {
        self.iter().any(|(o, _)| *o == owner)
    }

    /// `model` on `owner`; `false` when full.
    pub(crate) fn push(&mut self, owner: Owner, model: LumpedFrame<T>) -> bool {
        match (self.models.get_mut(usize::from(self.count)), self.count.checked_add(1)) {
            (Some(slot), Some(count)) => {
                *slot = (owner, model);
                self.count = count;
                true
            }
            _ => false,
        }
    }

    /// Every number mapped by `f`.
    pub(crate) fn map_scalars<U: SimdRealField + Copy>(&self, f: impl Fn(T) -> U + Copy) -> Lumped<U, B> {
        Lumped { models: self.models.map(|(owner, model)| (owner, model.map_scalars(f))), count: self.count }
    }
}

/// A lumped model in its body's body frame `F` (`crate::frames`), for the evaluation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct LumpedFrame<T: SimdRealField + Copy> {
    /// `P` in `F` [m].
    pub(crate) point: Vector3<T>,
    /// `F ← model` (the model's axes into `F`'s), where it is not the identity.
    rotation: Option<Matrix3<T>>,
    /// `M_A` and `D_L` in `F`'s components, about `P`.
    pub(crate) added_mass: Matrix6<T>,
    linear_damping: Matrix6<T>,
    /// In the model's own axes (a diagonal there is not one in `F`).
    quadratic_damping: [T; 6],
}

/// `[[R, 0], [0, R]] m [[R, 0], [0, R]]ᵀ`.
fn turned<T: RealField + Copy>(m: &Matrix6<T>, rotation: &Matrix3<T>) -> Matrix6<T> {
    let mut t = Matrix6::zeros();
    t.fixed_view_mut::<3, 3>(0, 0).copy_from(rotation);
    t.fixed_view_mut::<3, 3>(3, 3).copy_from(rotation);
    t * m * t.transpose()
}

impl<T: RealField + Copy> LumpedFrame<T> {
    /// `body` (validated) in the body frame whose axes (columns) in the body's coordinates are
    /// `axes`.
    pub(crate) fn new(body: &LumpedBody<T>, axes: &Matrix3<T>) -> Self {
        // F ← body, then F ← the model's axes.
        let into_frame = axes.transpose();
        let rotation = into_frame * body.axes;
        let identity = rotation == Matrix3::identity();
        Self {
            point: into_frame * body.point,
            rotation: (!identity).then_some(rotation),
            added_mass: if identity { body.added_mass } else { turned(&body.added_mass, &rotation) },
            linear_damping: if identity { body.linear_damping } else { turned(&body.linear_damping, &rotation) },
            quadratic_damping: body.quadratic_damping,
        }
    }
}

impl<T: SimdRealField + Copy> LumpedFrame<T> {
    /// Every number mapped by `f`.
    pub(crate) fn map_scalars<U: SimdRealField + Copy>(&self, f: impl Fn(T) -> U + Copy) -> LumpedFrame<U> {
        LumpedFrame {
            point: self.point.map(f),
            rotation: self.rotation.map(|r| r.map(f)),
            added_mass: self.added_mass.map(f),
            linear_damping: self.linear_damping.map(f),
            quadratic_damping: self.quadratic_damping.map(f),
        }
    }

    /// The damping and added-mass wrenches about `F`'s origin, in its components, for the twist
    /// `(v, ω)` of `P` relative to the water and its components' derivative `(v̇, α)`.
    #[inline(always)]
    pub(crate) fn wrenches(&self, [v, w, v_dot, alpha]: [Vector3<T>; 4]) -> (Wrench<T>, Wrench<T>) {
        let six = |a: &Vector3<T>, b: &Vector3<T>| Vector6::new(a.x, a.y, a.z, b.x, b.y, b.z);
        let halves = |x: &Vector6<T>| (Vector3::new(x[0], x[1], x[2]), Vector3::new(x[3], x[4], x[5]));
        let nu = six(&v, &w);
        let momentum = self.added_mass * nu;
        let (p, h) = halves(&momentum);
        let inertial = self.added_mass * six(&v_dot, &alpha);
        let (f_inertial, m_inertial) = halves(&inertial);
        let added_mass =
            Wrench { force: -(f_inertial + w.cross(&p)), moment: -(m_inertial + v.cross(&p) + w.cross(&h)) };
        let (f_linear, m_linear) = halves(&(self.linear_damping * nu));
        // The quadratic damping in the model's own axes.
        let (v_own, w_own) = match &self.rotation {
            Some(r) => (r.transpose() * v, r.transpose() * w),
            None => (v, w),
        };
        let [d0, d1, d2, d3, d4, d5] = self.quadratic_damping;
        let quadratic = |d: T, x: T| d * x.simd_abs() * x;
        let f_own = Vector3::new(quadratic(d0, v_own.x), quadratic(d1, v_own.y), quadratic(d2, v_own.z));
        let m_own = Vector3::new(quadratic(d3, w_own.x), quadratic(d4, w_own.y), quadratic(d5, w_own.z));
        let (f_quadratic, m_quadratic) = match &self.rotation {
            Some(r) => (r * f_own, r * m_own),
            None => (f_own, m_own),
        };
        let damping = Wrench { force: -(f_linear + f_quadratic), moment: -(m_linear + m_quadratic) };
        (damping.moved_from(&self.point), added_mass.moved_from(&self.point))
    }
}

/// Regressor columns per lumped model (docs/model.md section 12.1: the model is linear in each
/// of its entries): the added mass's 21 independent entries (upper triangle, row by row: `(0,0),
/// (0,1), …, (0,5), (1,1), …, (5,5)`; an off-diagonal column is the unit entry at `(i, j)` and
/// `(j, i)` both), the linear damping's 36 (row by row), the quadratic damping's 6; every entry
/// in the model's own axes.
pub const LUMPED_COLUMNS: usize = 63;

impl<T: SimdRealField + Copy> LumpedFrame<T> {
    /// The wrench of each of the [`LUMPED_COLUMNS`] unit coefficients, as [`Self::wrenches`]
    /// gives them (about `F`'s origin, in its components): `put(column, added_mass, wrench)`,
    /// `added_mass` true for the added-mass columns (the others are damping, reported as drag).
    #[inline(always)]
    pub(crate) fn unit_wrenches(
        &self,
        [v, w, v_dot, alpha]: [Vector3<T>; 4],
        mut put: impl FnMut(usize, bool, Wrench<T>),
    ) {
        // The twist in the model's own axes, where its coefficients are given.
        let own = |x: Vector3<T>| match &self.rotation {
            Some(r) => r.transpose() * x,
            None => x,
        };
        let (v, w, v_dot, alpha) = (own(v), own(w), own(v_dot), own(alpha));
        let nu = [v.x, v.y, v.z, w.x, w.y, w.z];
        let nu_dot = [v_dot.x, v_dot.y, v_dot.z, alpha.x, alpha.y, alpha.z];
        let at = |x: &[T; 6], i: usize| x.get(i).copied().unwrap_or_else(T::zero);
        // `x` at entry `i` of a 6-vector, as its linear and angular halves.
        let unit = |i: usize, x: T| {
            let mut a = [T::zero(); 6];
            if let Some(slot) = a.get_mut(i) {
                *slot = x;
            }
            (Vector3::new(a[0], a[1], a[2]), Vector3::new(a[3], a[4], a[5]))
        };
        let back = |force: Vector3<T>, moment: Vector3<T>| {
            let wrench = match &self.rotation {
                Some(r) => Wrench { force: r * force, moment: r * moment },
                None => Wrench { force, moment },
            };
            wrench.moved_from(&self.point)
        };
        let mut column = 0;
        for i in 0..6 {
            for j in i..6 {
                // (p, h) = E ν and E ν̇ for the symmetric unit E at (i, j) and (j, i).
                let (mut p, mut h) = unit(i, at(&nu, j));
                let (mut f, mut m) = unit(i, at(&nu_dot, j));
                if i != j {
                    let (p2, h2) = unit(j, at(&nu, i));
                    let (f2, m2) = unit(j, at(&nu_dot, i));
                    (p, h, f, m) = (p + p2, h + h2, f + f2, m + m2);
                }
                put(column, true, back(-(f + w.cross(&p)), -(m + v.cross(&p) + w.cross(&h))));
                column += 1;
            }
        }
        for i in 0..6 {
            for j in 0..6 {
                let (f, m) = unit(i, at(&nu, j));
                put(column, false, back(-f, -m));
                column += 1;
            }
        }
        for i in 0..6 {
            let x = at(&nu, i);
            let (f, m) = unit(i, x.simd_abs() * x);
            put(column, false, back(-f, -m));
            column += 1;
        }
    }
}
