//! Pure error from replicated runs, and the lack-of-fit test built on it (DESIGN §9).
//!
//! Runs at identical coded settings measure the same expected response, so their scatter
//! about their own mean is error no model can remove:
//! SS_PE = Σ_groups Σ_i (yᵢ − ȳ_group)², df_PE = Σ_groups (n_group − 1).
//! Lack of fit is what remains of the residual: SS_LOF = SS_res − SS_PE,
//! df_LOF = df_res − df_PE, tested by F = MS_LOF / MS_PE.

use std::collections::BTreeMap;

use super::curvature::LEVEL_TOLERANCE;

/// Pure-error sum of squares and its degrees of freedom.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PureError {
    /// SS_PE (response units squared).
    pub ss: f64,
    /// df_PE.
    pub df: usize,
}

/// Pure error of `y` over groups of runs with equal coded settings (within
/// [`LEVEL_TOLERANCE`]); `None` when no setting is replicated.
pub fn pure_error(coded: &[Vec<f64>], y: &[f64]) -> Option<PureError> {
    let mut groups: BTreeMap<Vec<i64>, Vec<f64>> = BTreeMap::new();
    for (run, value) in coded.iter().zip(y) {
        // Settings snapped to a grid finer than any design spacing identify replicates.
        let key = run
            .iter()
            .map(|v| (v / LEVEL_TOLERANCE).round() as i64)
            .collect();
        groups.entry(key).or_default().push(*value);
    }
    let mut ss = 0.0;
    let mut df = 0;
    for values in groups.values().filter(|g| g.len() > 1) {
        let mean = values.iter().sum::<f64>() / values.len() as f64;
        ss += values.iter().map(|v| (v - mean).powi(2)).sum::<f64>();
        df += values.len() - 1;
    }
    (df > 0).then_some(PureError { ss, df })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn replicates_are_grouped_by_setting() {
        let coded = vec![
            vec![0.0],
            vec![1.0],
            vec![0.0],
            vec![1.0 + 1e-12],
            vec![-1.0],
        ];
        let y = [1.0, 5.0, 3.0, 6.0, 2.0];
        // Groups {1, 3} and {5, 6}: SS = 2 + 0.5, df = 2.
        assert_eq!(pure_error(&coded, &y), Some(PureError { ss: 2.5, df: 2 }));
        assert_eq!(pure_error(&coded[..2], &y[..2]), None);
    }
}
