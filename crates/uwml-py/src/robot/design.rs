//! The identification design of a leg's hydrodynamic coefficients (docs/model.md section 4;
//! `uwml.fit`'s `hydro_coefficients`), by the robot's evaluation four samples per call on SIMD
//! lanes: for every sample and selected joint, the regressors of the joint's force grouped as the
//! fit asks (one Cd and one Cm; per link; per link and normal direction, each segment's columns
//! given to the link that carries it), then the target `y = −Δτ − τ_buoy`.

use std::ops::Range;

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use simba::simd::SimdValue;
use uwml_core::{Conditions, Owner, SegmentCoefficients, Water, robot_hydro, robot_hydro_regressors};

use super::evaluate::{Row, States};
use super::{LaneData, LaneModel, MAX_SEGMENTS};
use crate::arrays::Lanes;

/// How the identification design groups the coefficients (`uwml.fit.hydro_coefficients`'s `per`).
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Per {
    Leg,
    Link,
    Direction,
}

impl Per {
    pub(super) fn parse(per: &str) -> PyResult<Self> {
        match per {
            "leg" => Ok(Self::Leg),
            "link" => Ok(Self::Link),
            "direction" => Ok(Self::Direction),
            _ => Err(PyValueError::new_err(format!("per must be 'leg', 'link' or 'direction', got {per:?}"))),
        }
    }

    /// Columns of the design of `n` links: Cd then Cm, one each, per link, or per link and
    /// direction.
    pub(super) const fn columns(self, n: usize) -> usize {
        match self {
            Self::Leg => 2,
            Self::Link => 2 * n,
            Self::Direction => 4 * n,
        }
    }
}

/// The identification problem of the selected joints over the samples `states` (each
/// `n_samples × n`, finite), in one pass: `J × n_samples × (P + 1)`, joint-major so that each
/// joint's block is contiguous; a row holds the regressors of the force on joint `joints[j]` (Cd
/// columns then Cm columns, grouped as `per` says) and, last, the target `−delta − buoyancy`, where
/// `delta` (`n_samples × n`) is the measured `τ_water − τ_land`.
pub(super) fn design(
    robot: &LaneModel,
    water: &Water<f64>,
    states: &States<'_>,
    delta: &[f64],
    joints: &[usize],
    per: Per,
) -> Vec<f64> {
    let n = robot.joint_count();
    let n_samples = delta.len() / n.max(1);
    let width = per.columns(n) + 1;
    let mut design = vec![0.0; joints.len() * n_samples * width];
    let water = water.splat::<Lanes>();
    let unit = SegmentCoefficients::<f64, MAX_SEGMENTS>::uniform(1.0, 1.0).ok().map(|c| c.splat::<Lanes>());
    // The Leg grouping: the forces at unit coefficients are the two columns, at a third of the cost
    // of the regressors of every segment and direction.
    let conditions = match per {
        Per::Leg => Conditions { coefficients: unit.as_ref(), ..Conditions::new(water) },
        Per::Link | Per::Direction => Conditions::new(water),
    };
    let columns = robot.regressor_column_count();
    let (mut drag, mut added_mass) =
        (vec![Lanes::splat(0.0); (6 + n) * columns], vec![Lanes::splat(0.0); (6 + n) * columns]);
    // The link of each segment's columns (none for the base's).
    let owners: Vec<Option<usize>> = robot
        .segments()
        .iter()
        .map(|s| match s.owner {
            Owner::Link(i) => Some(i),
            Owner::Base => None,
        })
        .collect();
    let mut data = Box::new(LaneData::new());
    let mut lanes = Row::<Lanes>::new();
    for first in (0..n_samples).step_by(4) {
        let samples: Range<usize> = first..(first + 4).min(n_samples);
        lanes.load(states, &samples);
        let state = [&lanes.q, &lanes.qd, &lanes.qdd];
        if per == Per::Leg {
            robot_hydro(robot, &conditions, state, &mut data);
        } else {
            robot_hydro_regressors(robot, &conditions, state, &mut data, &mut drag, &mut added_mass);
        }
        for (lane, sample) in samples.enumerate() {
            for (block, &joint) in design.chunks_exact_mut(n_samples * width).zip(joints) {
                let Some(row) = block.get_mut(sample * width..(sample + 1) * width) else { continue };
                let Some(forces) = data.joint_forces().get(joint) else { continue };
                let Some((target, values)) = row.split_last_mut() else { continue };
                let measured = delta.get(sample * n + joint).copied().unwrap_or(f64::NAN);
                *target = -measured - forces.buoyancy.extract(lane);
                let (cd, cm) = values.split_at_mut(values.len() / 2);
                if per == Per::Leg {
                    if let (Some(d), Some(m)) = (cd.first_mut(), cm.first_mut()) {
                        (*d, *m) = (forces.drag.extract(lane), forces.added_mass.extract(lane));
                    }
                    continue;
                }
                // Joint `joint`'s row of the regressors: each segment's two directions, to its link.
                let at = |table: &[Lanes], column: usize| {
                    table.get((6 + joint) * columns + column).map_or(0.0, |x| x.extract(lane))
                };
                for (half, table) in [(&mut *cd, &drag), (&mut *cm, &added_mass)] {
                    half.fill(0.0);
                    for (k, owner) in owners.iter().enumerate() {
                        let Some(link) = *owner else { continue };
                        for d in 0..2 {
                            let slot = if per == Per::Link { link } else { 2 * link + d };
                            if let Some(value) = half.get_mut(slot) {
                                *value += at(table, 2 * k + d);
                            }
                        }
                    }
                }
            }
        }
    }
    design
}
