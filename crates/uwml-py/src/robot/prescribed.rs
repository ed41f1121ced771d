//! Prescribed joint motion in the coupling's step (docs/model.md section 12.4): the motion's
//! piecewise cubics (a `uwml.sim.prescribed.Trajectory` made from samples: scipy's `PPoly`
//! coefficients of `q`, `q̇` and `q̈`), and the imposing torque, the generalized force on the
//! prescribed degrees of freedom `p` that makes their accelerations the motion's:
//! `τ = ((M⁻¹)_pp)⁻¹ (q̈* − q̈_p)`, after which `q̈ += M⁻¹[:, p] τ` and `q̈_p = q̈*` exactly
//! (`MujocoCoupling::impose`).

use pyo3::prelude::*;
use uwml_core::nalgebra::{DMatrix, DVector};

use super::view::View;

/// What [`PrescribedMotion::impose`] and [`PrescribedMotion::put_on_motion`] report.
pub(super) const DONE: u8 = 0;
/// The time is outside the motion's span.
pub(super) const OUTSIDE: u8 = 1;
/// `(M⁻¹)_pp` is singular, or a value not finite.
pub(super) const SINGULAR: u8 = 2;

/// A motion of `k` joints over `knots`: for each of `q`, `q̇`, `q̈`, the coefficients of its
/// cubic on each interval, `(4, intervals, k)`, highest degree first, in `t − knots[i]`.
pub(super) struct Pieces {
    knots: Vec<f64>,
    coefficients: [Vec<f64>; 3],
    k: usize,
    /// Times within this much past an end are that end (a simulation clock's rounding).
    slack: f64,
}

impl Pieces {
    /// The pieces, checked: at least two knots, increasing; each coefficient array of
    /// `4 · (knots − 1) · k` finite numbers.
    pub(super) fn new(knots: Vec<f64>, coefficients: [Vec<f64>; 3], k: usize, slack: f64) -> Result<Self, String> {
        let intervals = knots.len().saturating_sub(1);
        if intervals == 0 || knots.windows(2).any(|w| !matches!(w, [a, b] if a < b)) {
            return Err("a motion's knots must be at least 2 increasing times".into());
        }
        if !(knots.iter().all(|t| t.is_finite()) && slack.is_finite() && slack >= 0.0) {
            return Err("a motion's knots and slack must be finite".into());
        }
        for c in &coefficients {
            if c.len() != 4 * intervals * k || !c.iter().all(|x| x.is_finite()) {
                return Err(format!(
                    "each of a motion's coefficient arrays must hold 4 x {intervals} x {k} finite numbers"
                ));
            }
        }
        Ok(Self { knots, coefficients, k, slack })
    }

    /// The first and last knots.
    fn span(&self) -> (f64, f64) {
        (self.knots.first().copied().unwrap_or(0.0), self.knots.last().copied().unwrap_or(0.0))
    }

    /// `which` (0 `q`, 1 `q̇`, 2 `q̈`) at time `t` into `out` (`k` values); `false` where `t` is
    /// outside the span by more than the slack (a time within it is the end's).
    pub(super) fn at(&self, which: usize, t: f64, out: &mut [f64]) -> bool {
        let (start, end) = self.span();
        if !(t >= start - self.slack && t <= end + self.slack) {
            return false;
        }
        let t = t.clamp(start, end);
        let intervals = self.knots.len() - 1;
        let i = self.knots.partition_point(|&x| x <= t).saturating_sub(1).min(intervals - 1);
        let dt = t - self.knots.get(i).copied().unwrap_or(start);
        let Some(c) = self.coefficients.get(which) else { return false };
        let k = self.k;
        let at = |degree: usize, j: usize| c.get((degree * intervals + i) * k + j).copied().unwrap_or(f64::NAN);
        for (j, slot) in out.iter_mut().enumerate().take(k) {
            *slot = ((at(0, j) * dt + at(1, j)) * dt + at(2, j)) * dt + at(3, j);
        }
        true
    }
}

/// The prescribed joints of a coupling: their degrees of freedom and `qpos` entries, their
/// motion's pieces (None: the caller evaluates the motion and gives its values), and the
/// `(k, nv)` array into which the caller writes `M⁻¹[:, p]` (rows; MuJoCo's `mj_solveM`) each
/// step before [`PrescribedMotion::impose`].
pub(super) struct PrescribedMotion {
    dofs: Vec<usize>,
    qpos: Vec<usize>,
    pieces: Option<Pieces>,
    solved: View,
    /// The last imposing torque, one per prescribed joint.
    pub(super) torque: Vec<f64>,
    columns: Vec<f64>,
    values: Vec<f64>,
    other: Vec<f64>,
    state: Vec<f64>,
}

impl PrescribedMotion {
    /// The motion of the joints at `dofs` (`qpos` entries `qpos`) of `pieces`, `solved` the
    /// `(k, nv)` array of `M⁻¹`'s rows.
    pub(super) fn new(dofs: Vec<usize>, qpos: Vec<usize>, pieces: Option<Pieces>, solved: View) -> Self {
        let k = dofs.len();
        Self {
            dofs,
            qpos,
            pieces,
            solved,
            torque: vec![0.0; k],
            columns: Vec::new(),
            values: vec![0.0; k],
            other: vec![0.0; k],
            state: Vec::new(),
        }
    }

    /// The motion's `which` (0 `q`, 1 `q̇`, 2 `q̈`) at `time` into `self.values` (or `given`).
    fn evaluate(&mut self, which: usize, time: f64, given: Option<&[f64]>) -> bool {
        match (given, &self.pieces) {
            (Some(values), _) if values.len() == self.dofs.len() => {
                self.values.copy_from_slice(values);
                values.iter().all(|x| x.is_finite())
            }
            (None, Some(pieces)) => pieces.at(which, time, &mut self.values),
            _ => false,
        }
    }

    /// The imposing torque at `time` (the motion's `q̈`, or `target`): `data.qacc` made the
    /// motion's on the prescribed degrees of freedom and the rest's response, the torque added
    /// to `data.qfrc_applied`. [`DONE`], [`OUTSIDE`] or [`SINGULAR`] (nothing written).
    pub(super) fn impose(
        &mut self,
        py: Python<'_>,
        qacc: &View,
        applied: &View,
        time: f64,
        target: Option<&[f64]>,
    ) -> PyResult<u8> {
        if !self.evaluate(2, time, target) {
            return Ok(if target.is_some() { SINGULAR } else { OUTSIDE });
        }
        let k = self.dofs.len();
        self.solved.copy_into(py, &mut self.columns)?;
        qacc.copy_into(py, &mut self.state)?;
        let nv = self.state.len();
        let column = |a: usize, v: usize| self.columns.get(a * nv + v).copied().unwrap_or(f64::NAN);
        let block = DMatrix::from_fn(k, k, |a, b| column(a, self.dofs.get(b).copied().unwrap_or(usize::MAX)));
        let rhs = DVector::from_fn(k, |a, _| {
            let dof = self.dofs.get(a).copied().unwrap_or(usize::MAX);
            self.values.get(a).copied().unwrap_or(f64::NAN) - self.state.get(dof).copied().unwrap_or(f64::NAN)
        });
        let Some(torque) = block.lu().solve(&rhs).filter(|x| x.iter().all(|v| v.is_finite())) else {
            return Ok(SINGULAR);
        };
        for (v, slot) in self.state.iter_mut().enumerate() {
            *slot += (0..k).map(|a| column(a, v) * torque.get(a).copied().unwrap_or(0.0)).sum::<f64>();
        }
        for (&dof, &value) in self.dofs.iter().zip(&self.values) {
            if let Some(slot) = self.state.get_mut(dof) {
                *slot = value;
            }
        }
        qacc.write(py, &self.state)?;
        applied.copy_into(py, &mut self.state)?;
        for (&dof, &tau) in self.dofs.iter().zip(torque.iter()) {
            if let Some(slot) = self.state.get_mut(dof) {
                *slot += tau;
            }
        }
        applied.write(py, &self.state)?;
        self.torque.copy_from_slice(torque.as_slice());
        Ok(DONE)
    }

    /// The prescribed joints put on the motion at `time` (its `q`, `q̇`, or `given` ones) in
    /// `data.qpos` and `data.qvel`. [`DONE`] or [`OUTSIDE`] (nothing written).
    pub(super) fn put_on_motion(
        &mut self,
        py: Python<'_>,
        qpos: &View,
        qvel: &View,
        time: f64,
        given: Option<(&[f64], &[f64])>,
    ) -> PyResult<u8> {
        if !self.evaluate(1, time, given.map(|(_, qd)| qd)) {
            return Ok(OUTSIDE);
        }
        self.other.copy_from_slice(&self.values);
        if !self.evaluate(0, time, given.map(|(q, _)| q)) {
            return Ok(OUTSIDE);
        }
        for (view, entries, values) in [(qpos, &self.qpos, &self.values), (qvel, &self.dofs, &self.other)] {
            view.copy_into(py, &mut self.state)?;
            for (&at, &value) in entries.iter().zip(values) {
                if let Some(slot) = self.state.get_mut(at) {
                    *slot = value;
                }
            }
            view.write(py, &self.state)?;
        }
        Ok(DONE)
    }
}
