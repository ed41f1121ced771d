//! The batch kernels of the chain bindings (`uwml.Leg`'s kinematics and its fit's design): the
//! samples of a batch (`States`), four of them at a time on SIMD lanes, and the loops that
//! evaluate point Jacobians and design matrices over them, writing rows of the output arrays.
//! Called by the `Chain` methods (`crate::PyChain`), with the GIL released.

use numpy::PyArray;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use uwml_core::nalgebra::{SVector, SimdValue, Vector3};
use uwml_core::{
    Chain, Coefficients, HydroRegressors, HydroTorques, Water, hydro_regressors, hydro_torques, point_jacobian,
};

use crate::NonFinite;

/// `values` (exactly N of them) as a vector.
#[inline]
pub(crate) fn vector<const N: usize>(values: &[f64]) -> Option<SVector<f64, N>> {
    <[f64; N]>::try_from(values).ok().map(SVector::from)
}

/// A 2-D float64 numpy array.
pub(crate) type Array2<'py> = Bound<'py, PyArray<f64, numpy::Ix2>>;

pub(crate) struct States<'a> {
    pub(crate) q: &'a [f64],
    pub(crate) qd: &'a [f64],
    pub(crate) qdd: &'a [f64],
}

impl<'a> States<'a> {
    /// The first non-finite value of the batch, naming the array, sample and joint. One tight
    /// scan per array, so that the evaluation loop has nothing to check.
    pub(crate) fn check_finite<const N: usize>(&self) -> Result<(), NonFinite> {
        for (argument, values) in [("q", self.q), ("qd", self.qd), ("qdd", self.qdd)] {
            if let Some(index) = values.iter().position(|v| !v.is_finite()) {
                let value = values.get(index).copied().unwrap_or(f64::NAN);
                return Err(NonFinite { argument, sample: index / N, joint: index % N, value });
            }
        }
        Ok(())
    }
}

/// Four float64 samples side by side, one per SIMD lane (two SSE2 registers on baseline x86-64).
pub(crate) type Lanes = simba::simd::WideF64x4;

/// Up to four samples of one array (rows of N values) as one vector of lanes, the missing
/// samples of a last group zero.
#[inline(always)]
pub(crate) fn lanes<const N: usize>(rows: &[f64]) -> SVector<Lanes, N> {
    SVector::from_fn(|j, _| Lanes::from([0, 1, 2, 3].map(|l| rows.get(l * N + j).copied().unwrap_or(0.0))))
}

/// Joint angles larger than this [rad] in magnitude are reduced to `[−π, π]` before they reach
/// the SIMD lanes: the lanes' sine and cosine (simba's `WideF64x4`) reduce the argument in double
/// precision only, so they are exact to rounding up to about 1e8 rad but lose accuracy beyond
/// (4e-7 relative at 1e10 rad, 0.02 at 1e15), while the scalar ones (libm's, with exact argument
/// reduction) do not. Well below that limit, so that no angle a robot reaches in practice pays
/// for the reduction.
pub(crate) const LARGE_ANGLE: f64 = 1e6;

/// `q` itself, or for `|q| > LARGE_ANGLE` the angle in `[−π, π]` with the same sine and cosine
/// (to one rounding: `atan2(sin q, cos q)` with libm's exactly reduced sine and cosine).
#[inline(always)]
pub(crate) fn reduced_angle(q: f64) -> f64 {
    if q.abs() <= LARGE_ANGLE { q } else { q.sin().atan2(q.cos()) }
}

/// [`lanes`] of joint angles, each reduced by [`reduced_angle`].
#[inline(always)]
pub(crate) fn angle_lanes<const N: usize>(rows: &[f64]) -> SVector<Lanes, N> {
    SVector::from_fn(|j, _| {
        Lanes::from([0, 1, 2, 3].map(|l| reduced_angle(rows.get(l * N + j).copied().unwrap_or(0.0))))
    })
}

/// The four samples' torques.
#[inline(always)]
pub(crate) fn unpack_torques<const N: usize>(t: &HydroTorques<Lanes, N>) -> [HydroTorques<f64, N>; 4] {
    core::array::from_fn(|l| t.map(|v| v.map(|x| x.extract(l))))
}

/// The four samples' regressors.
#[inline(always)]
pub(crate) fn unpack_regressors<const N: usize>(r: &HydroRegressors<Lanes, N>) -> [HydroRegressors<f64, N>; 4] {
    core::array::from_fn(|l| r.map(|v| v.map(|x| x.extract(l))))
}

impl<'a> States<'a> {
    /// `evaluate` on the samples four at a time, one per SIMD lane (a last group of fewer than
    /// four padded with zero states, whose results are dropped): every sample's result, in order.
    pub(crate) fn each_in_lanes<'s, const N: usize, R: 's>(
        &'s self,
        evaluate: impl Fn(&SVector<Lanes, N>, &SVector<Lanes, N>, &SVector<Lanes, N>) -> [R; 4] + 's,
    ) -> impl Iterator<Item = R> + 's {
        let group = 4 * N;
        let groups = self.q.chunks(group).zip(self.qd.chunks(group)).zip(self.qdd.chunks(group));
        groups.flat_map(move |((q, qd), qdd)| {
            evaluate(&angle_lanes(q), &lanes(qd), &lanes(qdd)).into_iter().take(q.len() / N)
        })
    }
}

/// Positions `n × 3` and Jacobians `n × 6 × N` (row-major) of a point on link `link` (< N).
pub(crate) fn jacobian_batch<const N: usize>(
    chain: &Chain<f64, N>,
    q: &[f64],
    link: usize,
    point: &Vector3<f64>,
) -> Result<(Vec<f64>, Vec<f64>), NonFinite> {
    if let Some(index) = q.iter().position(|v| !v.is_finite()) {
        let value = q.get(index).copied().unwrap_or(f64::NAN);
        return Err(NonFinite { argument: "q", sample: index / N, joint: index % N, value });
    }
    let n_samples = q.len() / N;
    let (mut positions, mut jacobians) = (Vec::with_capacity(n_samples * 3), Vec::with_capacity(n_samples * 6 * N));
    for q in q.chunks_exact(N).filter_map(vector::<N>) {
        if let Some((p, j)) = point_jacobian(chain, &q, link, point) {
            positions.extend(p.iter());
            // The transpose's column-major order is the Jacobian's row-major order.
            jacobians.extend(j.transpose().iter());
        }
    }
    Ok((positions, jacobians))
}

/// How the identification design groups the coefficients (`uwml.fit.hydro_coefficients`'s `per`).
#[derive(Clone, Copy, PartialEq)]
pub(crate) enum Per {
    Leg,
    Link,
    Direction,
}

impl Per {
    pub(crate) fn parse(per: &str) -> PyResult<Self> {
        match per {
            "leg" => Ok(Self::Leg),
            "link" => Ok(Self::Link),
            "direction" => Ok(Self::Direction),
            _ => Err(PyValueError::new_err(format!("per must be 'leg', 'link' or 'direction', got {per:?}"))),
        }
    }

    /// Columns of the design of an N-joint chain: Cd then Cm, one each, per link, or per link
    /// and direction.
    pub(crate) const fn columns(self, n: usize) -> usize {
        match self {
            Self::Leg => 2,
            Self::Link => 2 * n,
            Self::Direction => 4 * n,
        }
    }
}

/// The identification problem of the selected joints, assembled in one pass over the batch:
/// `J × n × (P + 1)`, joint-major so that each joint's block is contiguous; a row holds the
/// regressors of the torque on joint `joints[j]` (Cd columns then Cm columns, grouped as `per`
/// says) and, last, the target `y = −Δτ − τ_buoy` (docs/model.md section 4), where `delta` is the
/// measured `τ_water − τ_land`, `n × N`.
pub(crate) fn design_batch<const N: usize>(
    chain: &Chain<f64, N>,
    water: &Water<f64>,
    states: &States<'_>,
    delta: &[f64],
    joints: &[usize],
    per: Per,
) -> Result<Vec<f64>, NonFinite> {
    let n_samples = delta.len() / N;
    let width = per.columns(N) + 1;
    let mut design = vec![0.0; joints.len() * n_samples * width];
    states.check_finite::<N>()?;
    if let Some(index) = delta.iter().position(|v| !v.is_finite()) {
        let value = delta.get(index).copied().unwrap_or(f64::NAN);
        return Err(NonFinite { argument: "delta", sample: index / N, joint: index % N, value });
    }
    // Per selected joint: its rows, consumed sample by sample.
    let mut blocks: Vec<_> = design
        .chunks_exact_mut(n_samples * width)
        .zip(joints)
        .map(|(rows, &joint)| (rows.chunks_exact_mut(width), joint))
        .collect();
    // One Cd and one Cm: the torques at unit coefficients are the two columns, at a third of
    // the cost of the regressors of every link and direction.
    // Four samples per evaluation.
    let (chain, water) = (chain.splat::<Lanes>(), water.splat());
    if let (Per::Leg, Ok(unit)) = (per, Coefficients::uniform(1.0, 1.0)) {
        let unit = unit.splat();
        let torques = states
            .each_in_lanes::<N, _>(|q, qd, qdd| unpack_torques(&hydro_torques(&chain, &water, &unit, q, qd, qdd)));
        for (tau, delta) in torques.zip(delta.chunks_exact(N)) {
            for (rows, joint) in &mut blocks {
                let on_joint = |column: &SVector<f64, N>| column.get(*joint).copied().unwrap_or(f64::NAN);
                if let Some([drag, added_mass, target]) =
                    rows.next().and_then(|row| <&mut [f64; 3]>::try_from(row).ok())
                {
                    (*drag, *added_mass) = (on_joint(&tau.drag), on_joint(&tau.added_mass));
                    *target = -delta.get(*joint).copied().unwrap_or(f64::NAN) - on_joint(&tau.buoyancy);
                }
            }
        }
        return Ok(design);
    }
    let regressors =
        states.each_in_lanes::<N, _>(|q, qd, qdd| unpack_regressors(&hydro_regressors(&chain, &water, q, qd, qdd)));
    for (r, delta) in regressors.zip(delta.chunks_exact(N)) {
        for (rows, joint) in &mut blocks {
            let on_joint = |column: &SVector<f64, N>| column.get(*joint).copied().unwrap_or(f64::NAN);
            let Some((target, row)) = rows.next().and_then(|row| row.split_last_mut()) else { continue };
            *target = -delta.get(*joint).copied().unwrap_or(f64::NAN) - on_joint(&r.buoyancy);
            let (cd, cm) = row.split_at_mut(row.len() / 2);
            for (half, table) in [(cd, &r.drag), (cm, &r.added_mass)] {
                match per {
                    Per::Leg => {
                        for value in half.iter_mut() {
                            *value = table.iter().flatten().map(on_joint).sum();
                        }
                    }
                    Per::Link => {
                        for (value, [n0, n1]) in half.iter_mut().zip(table.iter()) {
                            *value = on_joint(n0) + on_joint(n1);
                        }
                    }
                    Per::Direction => {
                        for (value, column) in half.iter_mut().zip(table.iter().flatten()) {
                            *value = on_joint(column);
                        }
                    }
                }
            }
        }
    }
    Ok(design)
}
