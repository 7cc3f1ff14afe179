//! Two-level full and fractional factorial designs.
//!
//! Factors are labelled by letters in column order, `A`, `B`, `C`, …, skipping `I` (which
//! denotes the identity in defining relations), as Design-Expert and Box, Hunter & Hunter do.
//! A 2^(k−p) fractional design takes the first k − p factors as a full factorial in standard
//! (Yates) order and computes each remaining factor from a generator word such as `D=ABC`
//! (D is the product of columns A, B and C) or `E=-ABD`.
//!
//! ```
//! use arachis::doe::{fractional_factorial, Factor};
//! let f: Vec<Factor> = ["A", "B", "C", "D"]
//!     .iter()
//!     .map(|n| Factor::new(n, "-", 0.0, 1.0).unwrap())
//!     .collect();
//! let d = fractional_factorial(&f, &["D=ABC"], 0).unwrap();
//! assert_eq!(d.runs(), 8);
//! for row in &d.coded {
//!     assert_eq!(row[3], row[0] * row[1] * row[2]);
//! }
//! ```

use super::design::{centre_rows, yates_corners, Design, PointType};
use super::factor::check_unique_names;
use super::{DesignError, Factor};

/// Largest number of factors accepted for a full factorial (2^15 = 32768 runs); larger
/// designs are not practical DEM campaigns.
pub const MAX_FULL_FACTORIAL_FACTORS: usize = 15;

/// Factor letters in column order: A–Z without I.
const LETTERS: &str = "ABCDEFGHJKLMNOPQRSTUVWXYZ";

/// The letter of column `index` (0-based), or `None` beyond the 25 available.
pub fn factor_letter(index: usize) -> Option<char> {
    LETTERS.chars().nth(index)
}

fn letter_index(c: char) -> Option<usize> {
    LETTERS.find(c.to_ascii_uppercase())
}

/// Full 2^k factorial in standard order, followed by `centre_points` centre runs.
pub fn full_factorial(factors: &[Factor], centre_points: usize) -> Result<Design, DesignError> {
    fractional_factorial(factors, &[], centre_points)
}

/// A generator parsed into its target column, the base columns it multiplies and its sign.
struct Generator {
    target: usize,
    word: Vec<usize>,
    sign: f64,
}

fn parse_generator(text: &str, base: usize, k: usize) -> Result<Generator, DesignError> {
    let bad = |reason: String| DesignError::BadGenerator {
        generator: text.to_owned(),
        reason,
    };
    let compact: String = text.chars().filter(|c| !c.is_whitespace()).collect();
    let (lhs, rhs) = compact
        .split_once('=')
        .ok_or_else(|| bad("expected the form D=ABC".into()))?;
    let mut lhs_chars = lhs.chars();
    let target = match (lhs_chars.next().and_then(letter_index), lhs_chars.next()) {
        (Some(t), None) => t,
        _ => return Err(bad(format!("'{lhs}' is not a single factor letter"))),
    };
    if target < base || target >= k {
        return Err(bad(format!(
            "only the last {} factor(s) ({}) can be generated; the first {base} form the base design",
            k - base,
            (base..k).filter_map(factor_letter).collect::<String>()
        )));
    }
    let (sign, letters) = match rhs.strip_prefix('-') {
        Some(rest) => (-1.0, rest),
        None => (1.0, rhs.strip_prefix('+').unwrap_or(rhs)),
    };
    let mut word = Vec::new();
    for c in letters.chars() {
        let i = letter_index(c)
            .filter(|&i| i < base)
            .ok_or_else(|| bad(format!("'{c}' is not one of the base factors")))?;
        if word.contains(&i) {
            return Err(bad(format!("'{c}' appears twice")));
        }
        word.push(i);
    }
    if word.len() < 2 {
        return Err(bad(
            "a generator needs at least two base factors, or main effects would be aliased".into(),
        ));
    }
    Ok(Generator { target, word, sign })
}

/// The 2^(k−p) fractional factorial with `generators` (p of them, one per generated factor,
/// e.g. `["D=ABC"]`), followed by `centre_points` centre runs. With no generators this is the
/// full factorial.
pub fn fractional_factorial(
    factors: &[Factor],
    generators: &[&str],
    centre_points: usize,
) -> Result<Design, DesignError> {
    let k = factors.len();
    let base = k.saturating_sub(generators.len());
    if k < 2 || !(2..=MAX_FULL_FACTORIAL_FACTORS).contains(&base) || k > LETTERS.len() {
        return Err(DesignError::FactorCount {
            design: "two-level factorial",
            k,
            allowed: format!(
                "2 to {} factors with at least 2 and at most {MAX_FULL_FACTORIAL_FACTORS} base factors",
                LETTERS.len()
            ),
        });
    }
    check_unique_names(factors)?;
    let parsed: Vec<Generator> = generators
        .iter()
        .map(|g| parse_generator(g, base, k))
        .collect::<Result<_, _>>()?;
    for (i, g) in parsed.iter().enumerate() {
        if parsed[..i].iter().any(|h| h.target == g.target) {
            return Err(DesignError::BadGenerator {
                generator: generators[i].to_owned(),
                reason: "this factor is already generated".into(),
            });
        }
    }
    let mut coded: Vec<Vec<f64>> = yates_corners(base)
        .into_iter()
        .map(|mut row| {
            row.resize(k, 0.0);
            for g in &parsed {
                row[g.target] = g.sign * g.word.iter().map(|&i| row[i]).product::<f64>();
            }
            row
        })
        .collect();
    let mut point_types = vec![PointType::Factorial; coded.len()];
    let (centre, centre_types) = centre_rows(centre_points, k);
    coded.extend(centre);
    point_types.extend(centre_types);
    let kind = if generators.is_empty() {
        format!("2^{k} full factorial")
    } else {
        format!("2^({k}-{}) fractional factorial", generators.len())
    };
    Ok(Design::new(
        &kind,
        factors.to_vec(),
        Vec::new(),
        coded,
        point_types,
    ))
}
