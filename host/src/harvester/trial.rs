//! The field trial in simulation (issue 20, item 4; seed 001 §3.3): one harvest pass per
//! replicate field, each laid out from its own seed, the loss rate of every replicate, and the
//! comparison with the field's losses as seed 001 Table 12 makes it: a relative error per
//! replicate (the simulation as reference) and a pooled two-sample t-test of equal means at
//! α = 0.05 ([`crate::stats::pooled_t_test`]).
//!
//! ```
//! use arachis::harvester::trial::summarise;
//! // Seed 001 Table 12: simulated against field loss, %.
//! let s = summarise(&[3.75, 4.02, 4.27, 3.18], &[4.01, 3.83, 4.04, 3.42], 12.5);
//! assert_eq!(s.significant_difference, Some(false));
//! assert!(s.p_value.unwrap() > 0.05);
//! ```

use serde::Serialize;

use crate::stats::{pooled_t_test, relative_error_percent};

/// Significance level of the t-test (seed 001 §3.3: the difference is significant when
/// p < 0.05).
pub const ALPHA: f64 = 0.05;

/// The trial's comparison with the field.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TrialSummary {
    /// Loss rate of each replicate, %, in replicate order.
    pub loss_rate_pct: Vec<f64>,
    /// The field's loss rates, %, in trial order.
    pub field_loss_rate_pct: Vec<f64>,
    /// |field − simulated| / simulated × 100 for replicate i against field trial i (seed
    /// 001 Table 12); `None` where the simulated loss is zero or there is no trial i.
    pub relative_error_pct: Vec<Option<f64>>,
    /// Mean simulated loss, %.
    pub mean_simulated_pct: f64,
    /// Mean field loss, %.
    pub mean_field_pct: f64,
    /// Pooled t statistic; `None` when the test cannot be made (fewer than two values on a
    /// side, or no spread on either).
    pub t: Option<f64>,
    /// Degrees of freedom n₁ + n₂ − 2.
    pub df: Option<usize>,
    /// Two-sided p-value.
    pub p_value: Option<f64>,
    /// Significance level, [`ALPHA`].
    pub alpha: f64,
    /// `p < alpha`: the simulation's mean loss differs from the field's.
    pub significant_difference: Option<bool>,
    /// Why the t-test was not made, when it was not.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub no_test: Option<String>,
    /// Pods per plant, mean over the replicates.
    pub pods_per_plant: f64,
}

/// Compare the replicates' loss rates `simulated` (%) with the field's `field` (%).
pub fn summarise(simulated: &[f64], field: &[f64], pods_per_plant: f64) -> TrialSummary {
    let mean = |s: &[f64]| s.iter().sum::<f64>() / s.len().max(1) as f64;
    let relative_error_pct = simulated
        .iter()
        .enumerate()
        .map(|(i, &s)| {
            let f = field.get(i)?;
            (s != 0.0).then(|| relative_error_percent(*f, s))
        })
        .collect();
    let test = pooled_t_test(simulated, field);
    let (t, df, p_value, no_test) = match &test {
        Ok(t) => (Some(t.t), Some(t.df), Some(t.p), None),
        Err(e) => (None, None, None, Some(e.to_string())),
    };
    TrialSummary {
        loss_rate_pct: simulated.to_vec(),
        field_loss_rate_pct: field.to_vec(),
        relative_error_pct,
        mean_simulated_pct: mean(simulated),
        mean_field_pct: mean(field),
        t,
        df,
        p_value,
        alpha: ALPHA,
        significant_difference: p_value.map(|p| p < ALPHA),
        no_test,
        pods_per_plant,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seed_001_table_12_is_not_significant_and_its_errors_match_the_table() {
        // Seed 001 Table 12: simulated 3.75, 4.02, 4.27, 3.18 %; field 4.01, 3.83, 4.04,
        // 3.42 %; relative errors 6.93, 4.73, 5.39, 7.55 %.
        let s = summarise(&[3.75, 4.02, 4.27, 3.18], &[4.01, 3.83, 4.04, 3.42], 10.0);
        let rel: Vec<f64> = s.relative_error_pct.iter().map(|r| r.unwrap()).collect();
        for (got, table) in rel.iter().zip([6.93, 4.73, 5.39, 7.55]) {
            assert!((got - table).abs() < 0.01, "{got} against {table}");
        }
        assert_eq!(s.df, Some(6));
        assert_eq!(s.significant_difference, Some(false));
        assert!(s.no_test.is_none());
    }

    #[test]
    fn a_zero_loss_has_no_relative_error_and_a_far_mean_is_significant() {
        let s = summarise(&[0.0, 0.0, 0.0, 0.0], &[4.01, 3.83, 4.04, 3.42], 10.0);
        assert_eq!(s.relative_error_pct, vec![None; 4]);
        assert_eq!(s.significant_difference, Some(true));
        assert!(s.p_value.unwrap() < 1e-4);
    }

    #[test]
    fn one_replicate_gives_no_test_and_says_why() {
        let s = summarise(&[3.0], &[4.01, 3.83, 4.04, 3.42], 10.0);
        assert!(s.p_value.is_none() && s.significant_difference.is_none());
        assert!(s.no_test.unwrap().contains("two values"));
    }
}
