//! Derivatives of the environment torques for control: `∂τ_env/∂q`, `∂τ_env/∂q̇` and the
//! added-mass matrix `M_A(q)`, by forward-mode dual numbers ([`Dual`]) through the very same
//! [`environment_torques`] (no second implementation of the physics to keep in step).
//!
//! Sign: `τ_env` is the environment's torque on the joints, as everywhere in uwml
//! (`M(q) q̈ + c(q, q̇) + g(q) = τ_motor + τ_env`). Its added-mass part is linear in `q̈`,
//! `added_mass(q, q̇, q̈) = −M_A(q) q̈ + (terms in q̇)`, so a simulator adds `M_A(q)` to the
//! rigid-body inertia: `(M(q) + M_A(q)) q̈ = τ_motor + τ_env(q, q̇, 0) − c − g`. `M_A` is symmetric
//! and positive semi-definite (the kinetic energy of the entrained water).
//!
//! Cost: two dual passes of width `N` (one seeded in `q`, one in `q̇`; each costs a few real
//! evaluations, the derivative parts being `N` wide; the first's real parts are the value) and `N`
//! real evaluations (the columns of `M_A`). Stable Rust cannot size one dual number `2N` or `3N` wide from a
//! `const N` (no generic const expressions), and two passes of width `N` cost about as much as one
//! of width `2N`: the real part is computed twice, each of `2N` derivatives once.

use nalgebra::{RealField, SMatrix, SVector};

use crate::dual::Dual;
use crate::hydro::hydro_torques;
use crate::losses::{LossState, environment_torques};
use crate::model::{Chain, Coefficients, Water};
use crate::real::Real;

/// `τ_env` at a joint state and its derivatives.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EnvironmentJacobians<T: RealField + Copy, const N: usize> {
    /// `τ_env(q, q̇, q̈)` [N·m]: [`environment_torques`]`(..).total()`, bit for bit.
    pub value: SVector<T, N>,
    /// `∂τ_env/∂q` [N·m/rad]: entry `(i, j)` is `∂τ_i/∂q_j`.
    pub d_q: SMatrix<T, N, N>,
    /// `∂τ_env/∂q̇` [N·m·s/rad]: entry `(i, j)` is `∂τ_i/∂q̇_j`.
    pub d_qd: SMatrix<T, N, N>,
    /// `M_A(q)` [kg·m²], symmetric: `added_mass(q, 0, q̈) = −M_A(q) q̈`, and `∂τ_env/∂q̈ = −M_A(q)`.
    pub added_mass_matrix: SMatrix<T, N, N>,
}

/// `v` as constant dual numbers.
fn constants<T: RealField + Copy, const N: usize>(v: &SVector<T, N>) -> SVector<Dual<T, N>, N> {
    v.map(Dual::constant)
}

/// `v` as the `N` seeded inputs: entry `i` has derivative one in direction `i`.
fn seeded<T: RealField + Copy, const N: usize>(v: &SVector<T, N>) -> SVector<Dual<T, N>, N> {
    v.map_with_location(|i, _, x| Dual::variable(x, i))
}

/// The derivative parts of `tau` as a matrix: row `i` is `τ_i`'s.
fn jacobian<T: RealField + Copy, const N: usize>(tau: &SVector<Dual<T, N>, N>) -> SMatrix<T, N, N> {
    let mut m = SMatrix::<T, N, N>::zeros();
    for (mut row, t) in m.row_iter_mut().zip(tau.iter()) {
        for (slot, &e) in row.iter_mut().zip(t.eps.iter()) {
            *slot = e;
        }
    }
    m
}

/// `M_A(q)`, column `j` being `−added_mass(q, 0, e_j)` (exact: the added-mass torque is linear in
/// `q̈`, and at `q̇ = 0` it has no other terms), symmetrized (`½(M + Mᵀ)`: the two triangles
/// differ by rounding only).
fn added_mass_matrix<T: RealField + Real, const N: usize>(
    chain: &Chain<T, N>,
    water: &Water<T>,
    coefficients: &Coefficients<T, N>,
    q: &SVector<T, N>,
) -> SMatrix<T, N, N> {
    let still = SVector::<T, N>::zeros();
    let mut m = SMatrix::<T, N, N>::zeros();
    for (j, mut column) in m.column_iter_mut().enumerate() {
        let unit = SVector::<T, N>::from_fn(|i, _| if i == j { T::one() } else { T::zero() });
        column.copy_from(&-hydro_torques(chain, water, coefficients, q, &still, &unit).added_mass);
    }
    (m + m.transpose()) * nalgebra::convert::<f64, T>(0.5)
}

/// `τ_env = τ_hydro + τ_visc + τ_seal` at `(q, q̇, q̈)` with its derivatives `∂τ_env/∂q`,
/// `∂τ_env/∂q̇` and the added-mass matrix `M_A(q)`; arguments as for [`environment_torques`].
///
/// The derivatives are those of the branch the real evaluation takes, exact up to rounding. Where
/// the torques are not differentiable, they are one-sided: drag `v|v|` is differentiable
/// everywhere, but a joint loss at exactly zero speed with a hard sign (`ε = 0`) jumps, and there
/// `∂/∂q̇` is not meaningful (with `ε > 0` it is the smooth sign's finite slope). Non-finite states
/// give NaN, as for the torques. Never fails and never panics. Cost: see the [module](self).
#[must_use]
#[cfg_attr(uwml_no_panic, no_panic::no_panic)]
pub fn environment_jacobians<T: RealField + Real, const N: usize>(
    chain: &Chain<T, N>,
    water: &Water<T>,
    coefficients: &Coefficients<T, N>,
    losses: &[Option<LossState<T>>; N],
    q: &SVector<T, N>,
    qd: &SVector<T, N>,
    qdd: &SVector<T, N>,
) -> EnvironmentJacobians<T, N> {
    let constant = Dual::<T, N>::constant;
    let dual_chain = chain.map_scalars(constant);
    let dual_water = water.map_scalars(constant);
    let dual_coefficients = coefficients.map_scalars(constant);
    let dual_losses = losses.map(|state| state.map(|state| state.map_scalars(constant)));
    let qdd_constant = constants(qdd);
    let pass = |q: &SVector<Dual<T, N>, N>, qd: &SVector<Dual<T, N>, N>| {
        environment_torques(&dual_chain, &dual_water, &dual_coefficients, &dual_losses, q, qd, &qdd_constant).total()
    };
    let in_q = pass(&seeded(q), &constants(qd));
    EnvironmentJacobians {
        // A dual number's real part goes through the very operations of `T`: the value is the
        // real evaluation's, bit for bit, without a third pass.
        value: in_q.map(|t| t.re),
        d_q: jacobian(&in_q),
        d_qd: jacobian(&pass(&constants(q), &seeded(qd))),
        added_mass_matrix: added_mass_matrix(chain, water, coefficients, q),
    }
}

/// [`environment_jacobians`] of the hydrodynamic torques alone (`τ_hydro`, no joint losses).
#[must_use]
pub fn hydro_jacobians<T: RealField + Real, const N: usize>(
    chain: &Chain<T, N>,
    water: &Water<T>,
    coefficients: &Coefficients<T, N>,
    q: &SVector<T, N>,
    qd: &SVector<T, N>,
    qdd: &SVector<T, N>,
) -> EnvironmentJacobians<T, N> {
    environment_jacobians(chain, water, coefficients, &[None; N], q, qd, qdd)
}
