//! Which experiment and condition would tell two candidate effects apart, or make them
//! identifiable at all.
//!
//! For a proposed extra measurement at condition x of an experiment K (with `replicates`
//! replicates and the experiment's noise SD), the augmented design has standardised
//! sensitivities J̃ (calibrated parameters), s̃_a and s̃_b. The part of effect a's signature that
//! neither the calibration nor effect b can mimic is ‖(I − P[J̃, s̃_b]) s̃_a‖; at the effect
//! size θ_a it is worth that many standard errors (and symmetrically for b). The separation
//! of a design is the smaller of the two; the proposal is the (K, x) that raises it most.
//! Linearised, like the ranking; θ_a, θ_b are the ranking's one-step estimates (or one
//! finite-difference step when the estimate is not positive).
//!
//! When no candidate is identifiable at all (the calibration absorbs every signature, as a
//! single stacking angle does), [`identify`] looks for the measurement that leaves the most
//! candidates identifiable: with the proposed row added, the share of s̃ outside the span of
//! J̃ reaches [`IDENTIFIABLE_FRACTION`], the ranking's own threshold.

use anyhow::Result;
use nalgebra::{DMatrix, DVector};

use super::model::{replicate_mean, Model};
use super::params::{value, ParamInfo};
use super::residuals::{Dataset, Experiment};
use super::scatter::lost_in_noise;
use super::score::{column_basis, IDENTIFIABLE_FRACTION};
use super::sensitivity::{standard_error, Difference, Linearisation};
use crate::calibration::{Condition, ParameterValues};

/// Candidate conditions per experiment (log-spaced over its rig's search range, the
/// practical conditions, narrower than what the simulation accepts).
const GRID_POINTS: usize = 8;

/// Where a new measurement may be taken.
pub struct Search<'s, 'm> {
    /// The experiments: the data's first, in order, then any rigs not yet measured
    /// ([`super::prospect`]).
    pub experiments: &'s [Experiment],
    /// Simulates `experiments`, in that order.
    pub model: &'s Model<'m>,
    /// The replicate SD of each experiment; `None` leaves it out of the search.
    pub noise_sd: &'s dyn Fn(usize) -> Option<f64>,
    /// Replicates a proposed measurement would have.
    pub replicates: usize,
}

/// A candidate measurement and the weighted row it would add to the sensitivities.
struct Row {
    /// Experiment index in [`Search::experiments`].
    experiment: usize,
    /// Condition value.
    condition: f64,
    /// The row of J̃ (calibrated parameters, in [`Linearisation::calibrated`] order).
    calibrated: Vec<f64>,
    /// The row of each effect asked for, in that order.
    effects: Vec<f64>,
    /// Whether each effect's finite difference lies within the placements' scatter
    /// ([`lost_in_noise`]; never for a rig simulated once).
    noisy: Vec<bool>,
}

/// A proposed measurement.
#[derive(Clone, Debug)]
pub struct Proposal {
    /// The experiment to measure (index in [`Search::experiments`]: a measured one again, or
    /// a rig not yet measured).
    pub experiment: usize,
    /// Condition.
    pub condition: f64,
    /// Separation (standard errors) with the proposal added.
    pub separation_after: f64,
    /// Separation of the current design.
    pub separation_now: f64,
    /// The two effects whose finite difference at the proposal lies within the placements'
    /// scatter: a proposal that rests on them rests on noise.
    pub noisy: Vec<&'static ParamInfo>,
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
        off_span(&column_basis(&m), s)
    };
    (unmimicked(sa, sb) * theta_a.abs()).min(unmimicked(sb, sa) * theta_b.abs())
}

/// The row every grid point of every searchable experiment would add (log-spaced over its
/// rig's search range), for the calibrated parameters and `effects`: per grid point the
/// prediction at `p`, then the finite differences of [`Difference::at`], as in the study's
/// own sensitivities, all simulated in one batch.
fn rows(
    search: &Search<'_, '_>,
    lin: &Linearisation,
    p: &ParameterValues,
    effects: &[&'static ParamInfo],
) -> Result<Vec<Row>> {
    let mut grid: Vec<(usize, f64, Condition, f64)> = Vec::new();
    for (ei, e) in search.experiments.iter().enumerate() {
        let range = crate::rigs::catalogue::find(&e.rig)
            .and_then(|k| k.condition(&e.condition.0))
            .and_then(|c| c.search);
        let (Some((lo, hi)), Some(sd)) = (range, (search.noise_sd)(ei)) else {
            continue;
        };
        let wx = (search.replicates as f64).sqrt() / sd;
        for g in 0..GRID_POINTS {
            let x = lo * (hi / lo).powf(g as f64 / (GRID_POINTS - 1) as f64);
            grid.push((ei, x, Condition::from([(e.condition.0.clone(), x)]), wx));
        }
    }
    let stepped: Vec<(&ParamInfo, Difference)> = lin
        .calibrated
        .iter()
        .chain(effects)
        .copied()
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
    // Each placement of every run, so that each effect's difference has its paired scatter.
    let y = search.model.simulate_replicates(&runs)?;
    let per_point = 1 + stepped.iter().map(|(_, d)| d.shifts().len()).sum::<usize>();
    Ok(grid
        .iter()
        .zip(y.chunks(per_point))
        .map(|((ei, x, _, wx), y)| {
            let means: Vec<f64> = y.iter().map(|v| replicate_mean(v)).collect();
            let placements = y[0].len();
            let mut row = Vec::with_capacity(stepped.len());
            let mut noisy = Vec::with_capacity(effects.len());
            let mut k = 1;
            for (j, (info, difference)) in stepped.iter().enumerate() {
                let m = difference.shifts().len();
                let value = difference.derivative(info.fd_step, &means[k..k + m], means[0]);
                row.push(value * wx);
                if j >= lin.calibrated.len() {
                    let paired: Vec<f64> = (0..placements)
                        .map(|r| {
                            let ys: Vec<f64> = y[k..k + m].iter().map(|v| v[r]).collect();
                            difference.derivative(info.fd_step, &ys, y[0][r])
                        })
                        .collect();
                    let se = standard_error(&paired);
                    noisy.push(lost_in_noise(value, se, placements as u32));
                }
                k += m;
            }
            let effects = row.split_off(lin.calibrated.len());
            Row {
                experiment: *ei,
                condition: *x,
                calibrated: row,
                effects,
                noisy,
            }
        })
        .collect())
}

/// `m` with `row` appended.
fn with_row(m: &DMatrix<f64>, row: &[f64]) -> DMatrix<f64> {
    let n = m.nrows();
    let mut x = m.clone().insert_row(n, 0.0);
    for (k, v) in row.iter().enumerate() {
        x[(n, k)] = *v;
    }
    x
}

/// Best extra measurement to separate effects `a` and `b` (both candidates of `lin`, with
/// their estimates), among new conditions of `search`'s experiments.
pub fn propose(
    data: &Dataset,
    search: &Search<'_, '_>,
    lin: &Linearisation,
    p: &ParameterValues,
    a: (&'static ParamInfo, f64),
    b: (&'static ParamInfo, f64),
) -> Result<Option<Proposal>> {
    let w: Vec<f64> = data.obs.iter().map(|o| 1.0 / o.se_mean).collect();
    let col = |info: &ParamInfo| lin.candidates.iter().position(|c| c.name == info.name);
    let (Some(ia), Some(ib)) = (col(a.0), col(b.0)) else {
        return Ok(None);
    };
    // The weighted sensitivities, with a row per bench prior (as in the score test).
    let jt = lin.weighted_calibrated(&w);
    let (sa, sb) = (
        lin.weighted_candidate(ia, &w),
        lin.weighted_candidate(ib, &w),
    );
    let theta_a = if a.1 > 0.0 { a.1 } else { a.0.fd_step };
    let theta_b = if b.1 > 0.0 { b.1 } else { b.0.fd_step };
    let now = separation(&jt, &sa, &sb, theta_a, theta_b);
    let mut best: Option<Proposal> = None;
    for row in rows(search, lin, p, &[a.0, b.0])? {
        let n = jt.nrows();
        let jx = with_row(&jt, &row.calibrated);
        let sax = sa.clone().insert_row(n, row.effects[0]);
        let sbx = sb.clone().insert_row(n, row.effects[1]);
        let s = separation(&jx, &sax, &sbx, theta_a, theta_b);
        if best.as_ref().is_none_or(|bp| s > bp.separation_after) {
            best = Some(Proposal {
                experiment: row.experiment,
                condition: row.condition,
                separation_after: s,
                separation_now: now,
                noisy: [a.0, b.0]
                    .into_iter()
                    .zip(&row.noisy)
                    .filter_map(|(info, noisy)| noisy.then_some(info))
                    .collect(),
            });
        }
    }
    Ok(best)
}

/// A measurement that would make candidate effects identifiable.
#[derive(Clone, Debug)]
pub struct Identification {
    /// The experiment (index in [`Search::experiments`]).
    pub experiment: usize,
    /// Condition.
    pub condition: f64,
    /// The candidates it would make identifiable, each with the share of its signature the
    /// calibration could no longer absorb.
    pub identifiable: Vec<(&'static ParamInfo, f64)>,
    /// Those of them whose finite difference there lies within the placements' scatter.
    pub noisy: Vec<&'static ParamInfo>,
}

/// The share of `s` outside the span of the orthonormal columns `basis` (0 for a zero `s`).
fn share_left(basis: &DMatrix<f64>, s: &DVector<f64>) -> f64 {
    let full = s.norm();
    if full == 0.0 {
        return 0.0;
    }
    off_span(basis, s) / full
}

/// ‖s − Q·Qᵀ·s‖: the length of what the orthonormal columns `q` cannot mimic of `s`.
fn off_span(q: &DMatrix<f64>, s: &DVector<f64>) -> f64 {
    (s - q * (q.transpose() * s)).norm()
}

/// Measurements that would make candidate effects of `lin` identifiable: first the new
/// condition of `search`'s experiments after which the most are (ties: the larger total
/// share left), then, for each candidate that one leaves unidentifiable, the condition that
/// leaves the largest share of its signature, where that reaches the threshold. Empty when no
/// measurement would make any candidate identifiable.
pub fn identify(
    data: &Dataset,
    search: &Search<'_, '_>,
    lin: &Linearisation,
    p: &ParameterValues,
) -> Result<Vec<Identification>> {
    let w: Vec<f64> = data.obs.iter().map(|o| 1.0 / o.se_mean).collect();
    let jt = lin.weighted_calibrated(&w);
    let n = jt.nrows();
    // Per grid point, the share left of each candidate's signature.
    let shares: Vec<(Row, Vec<f64>)> = rows(search, lin, p, &lin.candidates)?
        .into_iter()
        .map(|row| {
            // One basis per grid point, shared by every candidate.
            let basis = column_basis(&with_row(&jt, &row.calibrated));
            let each = (0..lin.candidates.len())
                .map(|k| {
                    let s = lin.weighted_candidate(k, &w).insert_row(n, row.effects[k]);
                    share_left(&basis, &s)
                })
                .collect();
            (row, each)
        })
        .collect();
    let at = |(row, each): &(Row, Vec<f64>), only: Option<usize>| {
        let chosen: Vec<usize> = (0..lin.candidates.len())
            .filter(|&k| each[k] >= IDENTIFIABLE_FRACTION && only.is_none_or(|o| o == k))
            .collect();
        Identification {
            experiment: row.experiment,
            condition: row.condition,
            identifiable: chosen
                .iter()
                .map(|&k| (lin.candidates[k], each[k]))
                .collect(),
            noisy: chosen
                .iter()
                .filter(|&&k| row.noisy[k])
                .map(|&k| lin.candidates[k])
                .collect(),
        }
    };
    let score = |each: &[f64]| {
        let ok: Vec<f64> = each
            .iter()
            .copied()
            .filter(|s| *s >= IDENTIFIABLE_FRACTION)
            .collect();
        (ok.len(), ok.iter().sum::<f64>())
    };
    let Some(best) = shares.iter().max_by(|a, b| {
        let (sa, sb) = (score(&a.1), score(&b.1));
        sa.0.cmp(&sb.0).then(sa.1.total_cmp(&sb.1))
    }) else {
        return Ok(Vec::new());
    };
    if score(&best.1).0 == 0 {
        return Ok(Vec::new());
    }
    let mut found = vec![at(best, None)];
    for k in 0..lin.candidates.len() {
        if best.1[k] >= IDENTIFIABLE_FRACTION {
            continue;
        }
        if let Some(own) = shares
            .iter()
            .filter(|(_, each)| each[k] >= IDENTIFIABLE_FRACTION)
            .max_by(|a, b| a.1[k].total_cmp(&b.1[k]))
        {
            found.push(at(own, Some(k)));
        }
    }
    Ok(found)
}
