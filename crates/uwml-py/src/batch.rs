//! The batch kernels of the chain (`uwml.Leg`) bindings: the samples of a batch (`States`),
//! four of them at a time on SIMD lanes, and the loops that evaluate hydrodynamics, environment
//! torques, derivatives, regressors and design matrices over them, writing rows of the output
//! arrays. Called by the `Chain` methods (`crate::PyChain`) and the one-state paths
//! (`crate::single`), with the GIL released.

use std::ops::Range;

use numpy::PyArray;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use uwml_core::nalgebra::{SVector, SimdValue, Vector3};
use uwml_core::{
    Chain, Coefficients, HydroRegressors, HydroTorques, JointLosses, LossState, ModelError, Water,
    environment_jacobians, hydro_regressors, hydro_torques, loss_torques, point_jacobian,
};

use crate::NonFinite;

/// `values` (exactly N of them) as a vector.
#[inline]
pub(crate) fn vector<const N: usize>(values: &[f64]) -> Option<SVector<f64, N>> {
    <[f64; N]>::try_from(values).ok().map(SVector::from)
}

/// One sample's `(q, q̇, q̈)`.
pub(crate) type State<const N: usize> = (SVector<f64, N>, SVector<f64, N>, SVector<f64, N>);

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

    /// The samples `range` (of `n` joints each).
    pub(crate) fn range(&self, range: &Range<usize>, n: usize) -> Self {
        let rows = |values: &'a [f64]| values.get(range.start * n..range.end * n).unwrap_or(&[]);
        States { q: rows(self.q), qd: rows(self.qd), qdd: rows(self.qdd) }
    }

    /// Every sample's `(q, q̇, q̈)`, after [`States::check_finite`].
    pub(crate) fn each<const N: usize>(&self) -> impl Iterator<Item = State<N>> + '_ {
        let rows = self.q.chunks_exact(N).zip(self.qd.chunks_exact(N)).zip(self.qdd.chunks_exact(N));
        rows.filter_map(|((q, qd), qdd)| Some((vector(q)?, vector(qd)?, vector(qdd)?)))
    }
}

/// Writes `values` into an output row (a plain loop: N is small, no call to memcpy).
#[inline]
pub(crate) fn write_row<const N: usize>(row: &mut [f64], values: &SVector<f64, N>) {
    for (slot, value) in row.iter_mut().zip(values.iter()) {
        *slot = *value;
    }
}

pub(crate) fn coefficients<const N: usize>(cd: &[f64], cm: &[f64]) -> Result<Coefficients<f64, N>, ModelError> {
    let mut cd_array = [[0.0; 2]; N];
    let mut cm_array = [[0.0; 2]; N];
    for (slot, pair) in cd_array.iter_mut().zip(cd.chunks_exact(2)) {
        slot.copy_from_slice(pair);
    }
    for (slot, pair) in cm_array.iter_mut().zip(cm.chunks_exact(2)) {
        slot.copy_from_slice(pair);
    }
    Coefficients::per_direction(cd_array, cm_array)
}

/// Torque arrays of a batch, each `n_samples × N`, row-major.
pub(crate) struct TorqueBatch {
    pub(crate) drag: Vec<f64>,
    pub(crate) added_mass: Vec<f64>,
    pub(crate) buoyancy: Vec<f64>,
    pub(crate) gravity: Vec<f64>,
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

/// Drag, added-mass, buoyancy and gravity torques of a batch into `out` (each `n_samples × N`),
/// four samples per evaluation.
pub(crate) fn hydro_into<const N: usize>(
    chain: &Chain<f64, N>,
    water: &Water<f64>,
    coefficients: &Coefficients<f64, N>,
    states: &States<'_>,
    out: [&mut [f64]; 4],
) -> Result<(), NonFinite> {
    states.check_finite::<N>()?;
    hydro_rows(chain, water, coefficients, states, out);
    Ok(())
}

/// [`hydro_into`] after [`States::check_finite`].
pub(crate) fn hydro_rows<const N: usize>(
    chain: &Chain<f64, N>,
    water: &Water<f64>,
    coefficients: &Coefficients<f64, N>,
    states: &States<'_>,
    out: [&mut [f64]; 4],
) {
    hydro_lane_rows(&chain.splat(), water, coefficients, states, out);
}

/// [`hydro_rows`] with the chain already over lanes (`Chain::splat`).
pub(crate) fn hydro_lane_rows<const N: usize>(
    chain: &Chain<Lanes, N>,
    water: &Water<f64>,
    coefficients: &Coefficients<f64, N>,
    states: &States<'_>,
    [drag, added_mass, buoyancy, gravity]: [&mut [f64]; 4],
) {
    let (water, coefficients) = (water.splat(), coefficients.splat());
    let torques = states
        .each_in_lanes::<N, _>(|q, qd, qdd| unpack_torques(&hydro_torques(chain, &water, &coefficients, q, qd, qdd)));
    let rows = drag
        .chunks_exact_mut(N)
        .zip(added_mass.chunks_exact_mut(N))
        .zip(buoyancy.chunks_exact_mut(N).zip(gravity.chunks_exact_mut(N)));
    for (tau, ((drag, added_mass), (buoyancy, gravity))) in torques.zip(rows) {
        write_row(drag, &tau.drag);
        write_row(added_mass, &tau.added_mass);
        write_row(buoyancy, &tau.buoyancy);
        write_row(gravity, &tau.gravity);
    }
}

/// Hydrodynamic and loss torques of a batch: drag, added mass, buoyancy, gravity, visc, seal,
/// current, each `n_samples × N` (`chain` over lanes: `Chain::splat`).
pub(crate) fn environment_into<const N: usize>(
    chain: &Chain<Lanes, N>,
    water: &Water<f64>,
    coefficients: &Coefficients<f64, N>,
    losses: &[Option<JointLosses<f64>>],
    states: &States<'_>,
    conditions: (&[f64], &[f64]),
    [drag, added_mass, buoyancy, gravity, visc, seal, current]: [&mut [f64]; 7],
) -> Result<(), NonFinite> {
    // Every input checked first (the states, then pressure and temperature sample by sample);
    // then the hydrodynamics exactly as `Leg.hydro` has them (four samples per evaluation), and
    // the losses of each loaded joint at its speed, as `environment_torques` adds them.
    states.check_finite::<N>()?;
    for (sample, (&p, &t)) in conditions.0.iter().zip(conditions.1).enumerate() {
        for (argument, value) in [("pressure", p), ("temperature", t)] {
            if !value.is_finite() {
                return Err(NonFinite { argument, sample, joint: 0, value });
            }
        }
    }
    hydro_lane_rows(chain, water, coefficients, states, [drag, added_mass, buoyancy, gravity]);
    let mut joint_losses = [None; N];
    for (slot, l) in joint_losses.iter_mut().zip(losses) {
        *slot = *l;
    }
    let mut current_conditions = (f64::NAN, f64::NAN);
    let mut loss_states: [Option<LossState<f64>>; N] = [None; N];
    let rows = visc.chunks_exact_mut(N).zip(seal.chunks_exact_mut(N)).zip(current.chunks_exact_mut(N));
    let per_sample = states.qd.chunks_exact(N).filter_map(vector).zip(conditions.0.iter().zip(conditions.1));
    for ((qd, (&p, &t)), ((visc, seal), current)) in per_sample.zip(rows) {
        if current_conditions != (p, t) {
            current_conditions = (p, t);
            loss_states = joint_losses.map(|l| l.and_then(|l| l.at(p, t).ok()));
        }
        let (v, s, c) = loss_torques(&loss_states, &qd);
        for (row, values) in [(visc, v), (seal, s), (current, c)] {
            write_row(row, &values);
        }
    }
    Ok(())
}

/// Environment torques and their derivatives over a batch: `value` (`n_samples × N`), and
/// `d_q`, `d_qd` and the added-mass matrix (each `n_samples × N × N`, row-major: `[sample][i][j]`).
/// Pressure and temperature as for [`environment_batch`].
pub(crate) fn environment_jacobian_batch<const N: usize>(
    chain: &Chain<f64, N>,
    water: &Water<f64>,
    coefficients: &Coefficients<f64, N>,
    losses: &[Option<JointLosses<f64>>],
    states: &States<'_>,
    conditions: (&[f64], &[f64]),
) -> Result<[Vec<f64>; 4], NonFinite> {
    let n_samples = conditions.0.len();
    let mut out = [
        Vec::with_capacity(n_samples * N),
        Vec::with_capacity(n_samples * N * N),
        Vec::with_capacity(n_samples * N * N),
        Vec::with_capacity(n_samples * N * N),
    ];
    let mut joint_losses = [None; N];
    for (slot, l) in joint_losses.iter_mut().zip(losses) {
        *slot = *l;
    }
    let mut current_conditions = (f64::NAN, f64::NAN);
    let mut loss_states: [Option<LossState<f64>>; N] = [None; N];
    states.check_finite::<N>()?;
    for (sample, ((q, qd, qdd), (&p, &t))) in states.each::<N>().zip(conditions.0.iter().zip(conditions.1)).enumerate()
    {
        for (argument, value) in [("pressure", p), ("temperature", t)] {
            if !value.is_finite() {
                return Err(NonFinite { argument, sample, joint: 0, value });
            }
        }
        if current_conditions != (p, t) {
            current_conditions = (p, t);
            loss_states = joint_losses.map(|l| l.and_then(|l| l.at(p, t).ok()));
        }
        let j = environment_jacobians(chain, water, coefficients, &loss_states, &q, &qd, &qdd);
        let [value, d_q, d_qd, added_mass_matrix] = &mut out;
        value.extend(j.value.iter());
        // The transposes' column-major order is the matrices' row-major order.
        for (column, matrix) in [(d_q, j.d_q), (d_qd, j.d_qd), (added_mass_matrix, j.added_mass_matrix)] {
            column.extend(matrix.transpose().iter());
        }
    }
    Ok(out)
}

/// Regressor arrays of a batch: buoyancy and gravity `n × N`; drag and added mass either
/// `n × N` (summed over links and directions) or `n × N × N × 2` (`[sample][joint][link][k]`).
pub(crate) fn regressor_batch<const N: usize>(
    chain: &Chain<f64, N>,
    water: &Water<f64>,
    states: &States<'_>,
    n_samples: usize,
    per_direction: bool,
) -> Result<TorqueBatch, NonFinite> {
    let columns = if per_direction { N * N * 2 } else { N };
    let mut out = TorqueBatch {
        drag: Vec::with_capacity(n_samples * columns),
        added_mass: Vec::with_capacity(n_samples * columns),
        buoyancy: Vec::with_capacity(n_samples * N),
        gravity: Vec::with_capacity(n_samples * N),
    };
    states.check_finite::<N>()?;
    let (chain, water) = (chain.splat::<Lanes>(), water.splat());
    for r in states.each_in_lanes::<N, _>(|q, qd, qdd| unpack_regressors(&hydro_regressors(&chain, &water, q, qd, qdd)))
    {
        out.buoyancy.extend(r.buoyancy.iter());
        out.gravity.extend(r.gravity.iter());
        if per_direction {
            for joint in 0..N {
                out.drag.extend(joint_row(&r.drag, joint));
                out.added_mass.extend(joint_row(&r.added_mass, joint));
            }
        } else {
            out.drag.extend(r.drag_uniform().iter());
            out.added_mass.extend(r.added_mass_uniform().iter());
        }
    }
    Ok(out)
}

/// Joint `joint`'s entries of per-link, per-direction regressor columns, in `[link][k]` order.
pub(crate) fn joint_row<const N: usize>(
    columns: &[[SVector<f64, N>; 2]; N],
    joint: usize,
) -> impl Iterator<Item = f64> + '_ {
    columns.iter().flatten().map(move |c| c.get(joint).copied().unwrap_or(f64::NAN))
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
