//! Which experiment and condition would tell two candidate effects apart.
//!
//! For a proposed extra measurement at condition x of an experiment K (with `replicates`
//! replicates and the experiment's noise SD), the augmented design has standardised
//! sensitivities J̃ (calibrated parameters), s̃_a and s̃_b. The part of effect a's signature that
//! neither the calibration nor effect b can mimic is ‖(I − P[J̃, s̃_b]) s̃_a‖; at the effect
//! size θ_a it is worth that many standard errors (and symmetrically for b). The separation
//! of a design is the smaller of the two; the proposal is the (K, x) that raises it most.
//! Linearised, like the ranking; θ_a, θ_b are the ranking's one-step estimates (or one
//! finite-difference step when the estimate is not positive).

use anyhow::Result;
use nalgebra::{DMatrix, DVector};

use super::model::Model;
use super::params::{value, ParamInfo};
use super::residuals::{Dataset, Experiment};
use super::score::column_basis;
use super::sensitivity::{Difference, Linearisation};
use crate::calibration::{Condition, ParameterValues};

/// Candidate conditions per experiment (log-spaced over its rig's search range, the
/// practical conditions, narrower than what the simulation accepts).
const GRID_POINTS: usize = 8;

/// A proposed measurement.
#[derive(Clone, Debug)]
pub struct Proposal {
    /// The experiment (index in the data) to measure again.
    pub experiment: usize,
    /// Condition.
    pub condition: f64,
    /// Separation (standard errors) with the proposal added.
    pub separation_after: f64,
    /// Separation of the current design.
    pub separation_now: f64,
}

fn separation(
    jt: &DMatrix<f64>,
    sa: &DVector<f64>,
    sb: &DVector<f64>,
    theta_a: f64,
    theta_b: f64,
) -> f64 {
    let unmimicked = |s: &DVector<f64>, other: &DVector<f64>| {
        let mut m = jt.clone().insert_column(jt.ncols(), 0.0);
        m.set_column(jt.ncols(), other);
        let q = column_basis(&m);
        (s - &q * (q.transpose() * s)).norm()
    };
    (unmimicked(sa, sb) * theta_a.abs()).min(unmimicked(sb, sa) * theta_b.abs())
}

/// Best extra measurement to separate effects `a` and `b` (both candidates of `lin`), among
/// new conditions of `experiments`: the data's experiments first, in order, then any rigs
/// not yet measured ([`super::prospect`]); `model` simulates them in that order.
/// `noise_sd(experiment)` gives the replicate SD of an experiment, `None` to skip it.
#[allow(clippy::too_many_arguments)]
pub fn propose(
    data: &Dataset,
    experiments: &[Experiment],
    model: &Model<'_>,
    lin: &Linearisation,
    p: &ParameterValues,
    a: (&'static ParamInfo, f64),
    b: (&'static ParamInfo, f64),
    noise_sd: impl Fn(usize) -> Option<f64>,
    replicates: usize,
) -> Result<Option<Proposal>> {
    let w: Vec<f64> = data.obs.iter().map(|o| 1.0 / o.se_mean).collect();
    let col = |k: usize| -> usize {
        lin.candidates
            .iter()
            .position(|c| c.name == [a.0.name, b.0.name][k])
            .unwrap_or(usize::MAX)
    };
    let (ia, ib) = (col(0), col(1));
    if ia == usize::MAX || ib == usize::MAX {
        return Ok(None);
    }
    // The weighted sensitivities, with a row per bench prior (as in the score test).
    let jt = lin.weighted_calibrated(&w);
    let rows = jt.nrows();
    let (sa, sb) = (
        lin.weighted_candidate(ia, &w),
        lin.weighted_candidate(ib, &w),
    );
    let theta_a = if a.1 > 0.0 { a.1 } else { a.0.fd_step };
    let theta_b = if b.1 > 0.0 { b.1 } else { b.0.fd_step };
    let now = separation(&jt, &sa, &sb, theta_a, theta_b);
    // The candidate measurements: every grid point of every experiment that has a search
    // range and a noise SD, with its weight.
    let mut grid: Vec<(usize, f64, Condition, f64)> = Vec::new();
    for (ei, e) in experiments.iter().enumerate() {
        let search = crate::rigs::catalogue::find(&e.rig)
            .and_then(|k| k.condition(&e.condition.0))
            .and_then(|c| c.search);
        let (Some((lo, hi)), Some(sd)) = (search, noise_sd(ei)) else {
            continue;
        };
        let wx = (replicates as f64).sqrt() / sd;
        for g in 0..GRID_POINTS {
            let x = lo * (hi / lo).powf(g as f64 / (GRID_POINTS - 1) as f64);
            grid.push((ei, x, Condition::from([(e.condition.0.clone(), x)]), wx));
        }
    }
    // Every simulation of every candidate, asked for in one batch: per candidate the
    // prediction at p, then the steps of each calibrated parameter and of a and b (the
    // finite differences of [`Difference::at`], as in the study's own sensitivities).
    let stepped: Vec<(&ParamInfo, Difference)> = lin
        .calibrated
        .iter()
        .copied()
        .chain([a.0, b.0])
        .map(|info| Ok((info, Difference::at(info, value(info, p))?)))
        .collect::<Result<_>>()?;
    let mut runs = Vec::new();
    for (ei, _, at, _) in &grid {
        runs.push((*ei, at, p.clone()));
        for (info, difference) in &stepped {
            runs.extend(
                difference
                    .stepped(info, p)
                    .into_iter()
                    .map(|q| (*ei, at, q)),
            );
        }
    }
    let y = model.simulate_all(&runs)?;
    let per_candidate = 1 + stepped.iter().map(|(_, d)| d.shifts().len()).sum::<usize>();
    let mut best: Option<Proposal> = None;
    for ((ei, x, _, wx), y) in grid.iter().zip(y.chunks(per_candidate)) {
        // This candidate measurement's row of each sensitivity, weighted.
        let mut extra = Vec::with_capacity(stepped.len());
        let mut k = 1;
        for (info, difference) in &stepped {
            let m = difference.shifts().len();
            extra.push(difference.derivative(info.fd_step, &y[k..k + m], y[0]) * wx);
            k += m;
        }
        let c = lin.calibrated.len();
        let mut jx = jt.clone().insert_row(rows, 0.0);
        for (k, row) in extra[..c].iter().enumerate() {
            jx[(rows, k)] = *row;
        }
        let sax = sa.clone().insert_row(rows, extra[c]);
        let sbx = sb.clone().insert_row(rows, extra[c + 1]);
        let s = separation(&jx, &sax, &sbx, theta_a, theta_b);
        if best.as_ref().is_none_or(|bp| s > bp.separation_after) {
            best = Some(Proposal {
                experiment: *ei,
                condition: *x,
                separation_after: s,
                separation_now: now,
            });
        }
    }
    Ok(best)
}
