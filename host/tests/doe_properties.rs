//! Structural properties of the generated designs: balance and orthogonality of two-level
//! columns, defining relations of fractional factorials, run counts and estimability of the
//! quadratic model for Box–Behnken and central composite designs, rotatability, and bad input.

use arachis::doe::{
    box_behnken, central_composite, fractional_factorial, full_factorial, plackett_burman,
    steepest_ascent, Alpha, DesignError, Factor, PlackettBurmanRuns,
};
use nalgebra::DMatrix;
use proptest::prelude::*;

fn factors(k: usize) -> Vec<Factor> {
    (0..k)
        .map(|i| Factor::new(&format!("f{i}"), "-", 1.0, 2.0 + i as f64).unwrap())
        .collect()
}

fn column(rows: &[Vec<f64>], j: usize) -> Vec<f64> {
    rows.iter().map(|r| r[j]).collect()
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Every column sums to zero and every pair of columns is orthogonal, over the first `n` rows.
fn assert_balanced_orthogonal(rows: &[Vec<f64>]) {
    let cols = rows[0].len();
    for i in 0..cols {
        let ci = column(rows, i);
        assert_eq!(ci.iter().sum::<f64>(), 0.0, "column {i} unbalanced");
        assert_eq!(dot(&ci, &ci), rows.len() as f64);
        for j in i + 1..cols {
            assert_eq!(dot(&ci, &column(rows, j)), 0.0, "columns {i}, {j}");
        }
    }
}

#[test]
fn plackett_burman_columns_are_balanced_and_orthogonal() {
    for (runs, n) in [
        (PlackettBurmanRuns::Twelve, 12),
        (PlackettBurmanRuns::Twenty, 20),
    ] {
        let d = plackett_burman(runs, &factors(3), 4).unwrap();
        assert_eq!(d.runs(), n + 4);
        assert_eq!(d.dummy_columns.len(), n - 1 - 3);
        // X'X = N I over the N two-level runs (centre points add nothing).
        assert_balanced_orthogonal(&d.coded[..n]);
        assert!(d.coded[n..].iter().all(|r| r.iter().all(|&x| x == 0.0)));
    }
}

#[test]
fn plackett_burman_rejects_too_many_factors() {
    let err = plackett_burman(PlackettBurmanRuns::Twelve, &factors(12), 0).unwrap_err();
    assert!(
        matches!(err, DesignError::FactorCount { k: 12, .. }),
        "{err}"
    );
    assert!(plackett_burman(PlackettBurmanRuns::Twenty, &factors(19), 0).is_ok());
}

#[test]
fn full_factorial_is_yates_order_and_orthogonal() {
    let d = full_factorial(&factors(3), 2).unwrap();
    assert_eq!(d.runs(), 10);
    assert_eq!(d.coded[0], vec![-1.0, -1.0, -1.0]);
    assert_eq!(d.coded[1], vec![1.0, -1.0, -1.0]);
    assert_eq!(d.coded[2], vec![-1.0, 1.0, -1.0]);
    assert_eq!(d.coded[7], vec![1.0, 1.0, 1.0]);
    assert_balanced_orthogonal(&d.coded[..8]);
}

#[test]
fn fractional_factorial_follows_its_generators() {
    // 2^(6-2) with E = ABC, F = -BCD: resolution IV, 16 runs.
    let d = fractional_factorial(&factors(6), &["E=ABC", "F=-BCD"], 0).unwrap();
    assert_eq!(d.runs(), 16);
    for r in &d.coded {
        assert_eq!(r[4], r[0] * r[1] * r[2]);
        assert_eq!(r[5], -r[1] * r[2] * r[3]);
    }
    assert_balanced_orthogonal(&d.coded);
    // All 16 runs are distinct.
    let mut rows = d.coded.clone();
    rows.sort_by(|a, b| a.partial_cmp(b).unwrap());
    rows.dedup();
    assert_eq!(rows.len(), 16);
}

#[test]
fn fractional_factorial_letters_skip_i() {
    // Nine factors: A B C D E F G H J. J = ABCD generated from eight base factors.
    let d = fractional_factorial(&factors(9), &["J=ABCD"], 0).unwrap();
    assert_eq!(d.runs(), 256);
    assert!(d.coded.iter().all(|r| r[8] == r[0] * r[1] * r[2] * r[3]));
    assert!(fractional_factorial(&factors(9), &["I=ABCD"], 0).is_err());
}

#[test]
fn bad_generators_are_rejected_with_the_reason() {
    let f = factors(4);
    for (g, needle) in [
        ("D=AB=C", "base factors"),
        ("DABC", "form D=ABC"),
        ("C=AB", "only the last"),
        ("D=A", "at least two"),
        ("D=AAB", "twice"),
        ("D=ABX", "not one of the base factors"),
    ] {
        let err = fractional_factorial(&f, &[g], 0).unwrap_err().to_string();
        assert!(err.contains(needle), "{g}: {err}");
    }
    let err = fractional_factorial(&factors(6), &["E=ABC", "E=ABD"], 0).unwrap_err();
    assert!(err.to_string().contains("already generated"), "{err}");
}

/// One column of a model matrix as a function of a coded run.
type Term = Box<dyn Fn(&[f64]) -> f64>;

/// Rank of the full quadratic model matrix (1, xᵢ, xᵢxⱼ, xᵢ²) of `rows`.
fn quadratic_model_rank(rows: &[Vec<f64>]) -> (usize, usize) {
    let k = rows[0].len();
    let mut terms: Vec<Term> = vec![Box::new(|_| 1.0)];
    for i in 0..k {
        terms.push(Box::new(move |x| x[i]));
    }
    for i in 0..k {
        for j in i + 1..k {
            terms.push(Box::new(move |x| x[i] * x[j]));
        }
    }
    for i in 0..k {
        terms.push(Box::new(move |x| x[i] * x[i]));
    }
    let x = DMatrix::from_fn(rows.len(), terms.len(), |r, c| terms[c](&rows[r]));
    (x.rank(1e-9), terms.len())
}

#[test]
fn box_behnken_run_counts_and_quadratic_estimability_for_3_to_7_factors() {
    // Box & Behnken (1960): 12, 24, 40, 48, 56 runs before centre points.
    for (k, edge_runs) in [(3, 12), (4, 24), (5, 40), (6, 48), (7, 56)] {
        let d = box_behnken(&factors(k), 6).unwrap();
        assert_eq!(d.runs(), edge_runs + 6, "k = {k}");
        let (rank, p) = quadratic_model_rank(&d.coded);
        assert_eq!(rank, p, "k = {k}: quadratic model not estimable");
        for j in 0..k {
            let c = column(&d.coded, j);
            let plus = c.iter().filter(|&&x| x == 1.0).count();
            let minus = c.iter().filter(|&&x| x == -1.0).count();
            assert_eq!(plus, minus, "k = {k}, factor {j}");
            // Every factor is varied in the same number of blocks.
            assert_eq!(plus + minus, edge_runs * if k >= 6 { 3 } else { 2 } / k);
        }
        // First-order columns are orthogonal.
        for i in 0..k {
            for j in i + 1..k {
                assert_eq!(dot(&column(&d.coded, i), &column(&d.coded, j)), 0.0);
            }
        }
    }
}

#[test]
fn box_behnken_7_factor_blocks_meet_every_pair_once() {
    let blocks = arachis::doe::box_behnken::blocks(7).unwrap();
    for i in 0..7 {
        for j in i + 1..7 {
            let meets = blocks
                .iter()
                .filter(|b| b.contains(&i) && b.contains(&j))
                .count();
            assert_eq!(meets, 1, "pair ({i}, {j})");
        }
    }
}

#[test]
fn box_behnken_rejects_k_outside_3_to_7() {
    for k in [1, 2, 8] {
        let err = box_behnken(&factors(k), 3).unwrap_err();
        assert_eq!(
            err.to_string(),
            format!("Box-Behnken: {k} factors given, but it needs 3 to 7")
        );
    }
}

#[test]
fn central_composite_run_counts_and_alpha_for_2_to_7_factors() {
    for k in 2..=7 {
        for (alpha, expected) in [
            (Alpha::Rotatable, (2f64.powi(k as i32)).powf(0.25)),
            (Alpha::FaceCentred, 1.0),
            (Alpha::Spherical, (k as f64).sqrt()),
            (Alpha::Value(1.414), 1.414),
        ] {
            let d = central_composite(&factors(k), alpha, 5).unwrap();
            assert_eq!(d.runs(), (1 << k) + 2 * k + 5, "k = {k}");
            let max = d
                .coded
                .iter()
                .flatten()
                .fold(0.0_f64, |m, x| m.max(x.abs()));
            assert!((max - expected.max(1.0)).abs() < 1e-12, "k = {k}: {max}");
            let (rank, p) = quadratic_model_rank(&d.coded);
            assert_eq!(rank, p, "k = {k}, alpha {alpha:?}");
        }
    }
}

#[test]
fn rotatable_central_composite_has_rotatable_moments() {
    // Rotatability (Box & Hunter 1957): Σ xᵢ⁴ = 3 Σ xᵢ² xⱼ² over the design.
    for k in 2..=6 {
        let d = central_composite(&factors(k), Alpha::Rotatable, 3).unwrap();
        let c0 = column(&d.coded, 0);
        let c1 = column(&d.coded, 1);
        let pure: f64 = c0.iter().map(|x| x.powi(4)).sum();
        let mixed: f64 = c0.iter().zip(&c1).map(|(a, b)| a * a * b * b).sum();
        assert!(
            (pure - 3.0 * mixed).abs() < 1e-9,
            "k = {k}: {pure} vs 3 × {mixed}"
        );
    }
}

#[test]
fn factor_levels_are_checked() {
    assert!(Factor::new("x", "-", 1.0, 1.0).is_err());
    assert_eq!(
        Factor::new("x", "-", 2.0, 1.0).unwrap_err().to_string(),
        "factor 'x': low level 2 must be below high level 1"
    );
    assert!(Factor::new("", "-", 0.0, 1.0).is_err());
    assert!(Factor::new("x", "-", f64::NAN, 1.0).is_err());
    // Issue 23: ±1e308 levels once gave axial points of ±inf and NaN in the design file.
    assert!(Factor::parse("x:-1e308:1e308")
        .unwrap_err()
        .to_string()
        .contains("would leave double precision"));
    assert!(Factor::new("x", "-", -1e100, 1e100).is_ok());
    assert!(Factor::parse("x:0:1:mm").is_ok());
    assert!(Factor::parse("x:0").is_err());
    assert!(Factor::parse("x:a:1")
        .unwrap_err()
        .to_string()
        .contains("'a' is not a number"));
    let dup = vec![
        Factor::new("x", "-", 0.0, 1.0).unwrap(),
        Factor::new("x", "-", 0.0, 1.0).unwrap(),
    ];
    assert_eq!(
        box_behnken(&[dup.clone(), factors(1)].concat(), 0).unwrap_err(),
        DesignError::DuplicateName("x".into())
    );
}

#[test]
fn steepest_ascent_moves_the_largest_coefficient_by_the_base_step() {
    let d = steepest_ascent(&factors(3), &[2.0, -1.0, 0.5], &[0.0; 3], 0.5, 4).unwrap();
    assert_eq!(d.coded[1], vec![0.5, -0.25, 0.125]);
    assert_eq!(d.coded[3], vec![1.5, -0.75, 0.375]);
    assert!(steepest_ascent(&factors(2), &[0.0, 0.0], &[0.0; 2], 0.5, 4).is_err());
    assert!(steepest_ascent(&factors(2), &[1.0, 0.0], &[0.0; 2], -0.5, 4).is_err());
}

#[test]
fn run_order_must_be_a_permutation() {
    let d = box_behnken(&factors(3), 1).unwrap();
    assert!(d.clone().with_run_order(&[1; 13]).is_err());
    assert!(d.clone().with_run_order(&[1, 2]).is_err());
    let rev: Vec<usize> = (1..=13).rev().collect();
    let r = d.with_run_order(&rev).unwrap();
    assert_eq!(r.coded_in_run_order()[12], r.coded[0]);
}

proptest! {
    #[test]
    fn coding_round_trips(low in -1e6f64..1e6, width in 1e-6f64..1e6, x in -2.0f64..2.0) {
        let f = Factor::new("f", "-", low, low + width).unwrap();
        let back = f.to_coded(f.to_actual(x));
        prop_assert!((back - x).abs() < 1e-6 * (1.0 + low.abs() / width));
    }

    #[test]
    fn centre_points_are_appended(k in 3usize..=7, centre in 0usize..8) {
        let bbd = box_behnken(&factors(k), centre).unwrap();
        let ccd = central_composite(&factors(k), Alpha::FaceCentred, centre).unwrap();
        for d in [bbd, ccd] {
            let zero_rows = d.coded.iter().filter(|r| r.iter().all(|&x| x == 0.0)).count();
            prop_assert_eq!(zero_rows, centre);
        }
    }
}
