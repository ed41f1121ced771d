//! The water's forces on one straight segment of a body (docs/model.md sections 3, 10 and 12.2):
//! its drag and added-mass wrenches by the exact strip integrals (the added mass in the paper's
//! Morison form or Kirchhoff's, `crate::conditions::AddedMassForm`), and its optional axial drag,
//! each about its body's origin in its body frame, for the whole-robot evaluation
//! (`crate::hydro`) and its regressors.

use nalgebra::{SimdRealField, Vector3};

use crate::algebra::dot;
use crate::check::constant;
use crate::conditions::AddedMassForm;
use crate::frames::SegmentGeometry;
use crate::kinematics::Frame;
use crate::parts::{RobotSegment, Section};
use crate::strip::{added_mass_moments, circular_speed_moments, drag_moments_2};
use crate::wrench::Wrench;

/// A segment's drag and added-mass wrenches about its body's origin, in its body frame (where
/// `geometry` gives its directions), at coefficients `cd`, `cm`, in water of `density`.
#[inline(always)]
pub(crate) fn segment_wrenches<T: SimdRealField + Copy>(
    frame: &Frame<T>,
    segment: &RobotSegment<T>,
    geometry: &SegmentGeometry<T>,
    [cd0, cd1]: [T; 2],
    [cm0, cm1]: [T; 2],
    density: T,
    form: AddedMassForm,
) -> (Wrench<T>, Wrench<T>) {
    let start = geometry.start;
    let u = geometry.axis();
    let (v0, a0) = frame.point_motion(&start);
    let w = &frame.angular_velocity;
    // Relative velocity and acceleration along the segment: affine in s.
    let v1 = || w.cross(&u);
    let a1 = |v1: &Vector3<T>| frame.angular_acceleration.cross(&u) + w.cross(v1);
    let length = segment.length;
    let rho = density;
    let half = constant::<T>(0.5);
    let added_mass_scale = -rho * segment.area;
    let (drag, added_mass) = match &segment.section {
        Section::Rectangular { widths: [width0, width1], .. } => {
            // Projections on the normals (components where the segment is aligned). With the
            // moment directions m_k = u × n_k (σ n1 and −σ n0): the normal speed along the
            // segment is v0_k + s ω·m_k, the normal acceleration a0_k + s (α·m_k + (ω·n_k)(ω·u)).
            let (directions, sign) = (&geometry.frame, geometry.sign);
            let [w0, w1] = directions.normal_components(w);
            let [alpha0, alpha1] = directions.normal_components(&frame.angular_acceleration);
            let [speed0, speed1] = directions.normal_components(&v0);
            let [accel0, accel1] = directions.normal_components(&a0);
            let w_axial = directions.axial_component(w);
            let [(d00, d01), (d10, d11)] = drag_moments_2([speed0, speed1], [sign * w1, -sign * w0], length);
            let (m00, m01) = added_mass_moments(accel0, sign * alpha1 + w0 * w_axial, length);
            let (m10, m11) = added_mass_moments(accel1, -sign * alpha0 + w1 * w_axial, length);
            let (drag0, drag1) = (-half * rho * cd0 * *width0, -half * rho * cd1 * *width1);
            let (mass0, mass1) = (added_mass_scale * cm0, added_mass_scale * cm1);
            // Forces along the normals; moments about the start Σ_k m_k ∫ s f_k.
            let along = |f0: T, f1: T, g0: T, g1: T| Wrench {
                force: directions.along_normals([f0, f1]),
                moment: directions.along_normals([-sign * g1, sign * g0]),
            };
            let drag = along(drag0 * d00, drag1 * d10, drag0 * d01, drag1 * d11);
            let mut added_mass = along(mass0 * m00, mass1 * m10, mass0 * m01, mass1 * m11);
            if form == AddedMassForm::Kirchhoff {
                let v1 = v1();
                for (n, mass_scale) in geometry.normals().iter().zip([mass0, mass1]) {
                    // ṅ = ω × n. Extra force density −m[(ṅ·v) n + (n·v) ṅ]; couple −v × p with
                    // p = m (n·v) n: ∫ (n·v)(v × n) times −m, v = v0 + s v1.
                    let moment_direction = u.cross(n);
                    let n_dot = w.cross(n);
                    let (e0, e1) = added_mass_moments(dot(&n_dot, &v0), dot(&n_dot, &v1), length);
                    let (c0, c1) = added_mass_moments(dot(n, &v0), dot(n, &v1), length);
                    added_mass += Wrench {
                        force: (n * e0 + n_dot * c0) * mass_scale,
                        moment: (moment_direction * e1 + u.cross(&n_dot) * c1 + v0.cross(n) * c0 + v1.cross(n) * c1)
                            * mass_scale,
                    };
                }
            }
            (drag, added_mass)
        }
        Section::Circular { diameter } => {
            let v1 = v1();
            let a1 = a1(&v1);
            // Normal parts: v1 = ω × u is normal already.
            let normal = |x: Vector3<T>| x - u * dot(&u, &x);
            let (p0, a0n, a1n) = (normal(v0), normal(a0), normal(a1));
            let [i0, i1, i2] = circular_speed_moments(&p0, &v1, length);
            let drag_scale = -half * rho * cd0 * *diameter;
            // ∫ s^k |v⊥| v⊥ = p0 I_k + v1 I_{k+1}.
            let drag =
                Wrench { force: (p0 * i0 + v1 * i1) * drag_scale, moment: u.cross(&(p0 * i1 + v1 * i2)) * drag_scale };
            let (m_force, m_moment) =
                (added_mass_moments(T::one(), T::zero(), length), added_mass_moments(T::zero(), T::one(), length));
            // ∫ a⊥ = a0 L + a1 L²/2, ∫ s a⊥ = a0 L²/2 + a1 L³/3.
            let mass_scale = added_mass_scale * cm0;
            let mut added_mass = Wrench {
                force: (a0n * m_force.0 + a1n * m_moment.0) * mass_scale,
                moment: u.cross(&(a0n * m_force.1 + a1n * m_moment.1)) * mass_scale,
            };
            if form == AddedMassForm::Kirchhoff {
                // p = m v⊥, v⊥ = p0 + s v1 (v1 = ω × u = u̇), c = u·v constant along the segment:
                // dv⊥/dt = a⊥ − v1 c − u (v1·v). Extra force density −m[−v1 c − u (v1·v)], whose
                // moment about the start is −m[−(u × v1) c s]; couple −v × p = −m c u × v⊥.
                let c = dot(&u, &v0);
                let (f0, _) = added_mass_moments(dot(&v1, &v0), dot(&v1, &v1), length);
                let (l, l2) = m_force;
                added_mass += Wrench {
                    force: (v1 * (c * l) + u * f0) * -mass_scale,
                    moment: (u.cross(&v1) * (c * l2) - u.cross(&(p0 * l + v1 * l2)) * c) * -mass_scale,
                };
            }
            (drag, added_mass)
        }
    };
    (drag.moved_from(&start), added_mass.moved_from(&start))
}

/// A segment's axial drag (docs/model.md section 12.2) at coefficient `cd_axial` about its body's origin, in its body frame:
/// `−½ ρ cd_axial A_axial |u·v| (u·v) u` at its midpoint, `u·v` the same at every slice of a
/// straight segment (`u·(ω × u) = 0`), so along the axis through the start, with no moment about
/// it.
#[inline(always)]
pub(crate) fn axial_drag<T: SimdRealField + Copy>(
    frame: &Frame<T>,
    segment: &RobotSegment<T>,
    geometry: &SegmentGeometry<T>,
    cd_axial: T,
    density: T,
) -> Wrench<T> {
    let (velocity, _) = frame.point_motion(&geometry.start);
    let speed = geometry.frame.axial_component(&velocity);
    let scale = -constant::<T>(0.5) * density * cd_axial * segment.axial_area;
    let force = geometry.axis() * (scale * speed.simd_abs() * speed);
    Wrench { force, moment: Vector3::zeros() }.moved_from(&geometry.start)
}
