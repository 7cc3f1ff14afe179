//! Physical limits of material and contact properties, checked before any simulation.
//!
//! The bounds are those of the contact model (DESIGN §2, seed 000 eqs. (3)–(7)):
//! - restitution e ∈ (0, 1]: β = ln e/√(ln²e + π²) needs e > 0, and e > 1 would create
//!   energy;
//! - friction coefficients μs, μr ≥ 0 (a Coulomb cap and a rolling torque that oppose motion);
//! - Poisson ratio ν ∈ (−1, 0.5): the bounds for an isotropic elastic solid, where
//!   G = E/(2(1+ν)) (seed 000 eq. (12)) stays positive and the bulk modulus finite. Seed 000
//!   Table 3 nevertheless screens ν from 0.186 to 0.586; a range may opt in to the wider
//!   contact-model bound (−1, 1) with `poisson_above_half = true`
//!   ([`Limits::PoissonContactModel`]);
//! - density, moduli, lengths, times and speeds > 0.

use std::fmt;

/// The admissible set of one quantity.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Limits {
    /// Coefficient of restitution: 0 < e ≤ 1.
    Restitution,
    /// Friction coefficient (static or rolling): μ ≥ 0.
    Friction,
    /// Poisson ratio: −1 < ν < 0.5.
    Poisson,
    /// Poisson ratio as far as the Hertz–Mindlin terms allow: −1 < ν < 1, where 1 − ν² and
    /// (2 − ν)(1 + ν) (DESIGN §2) stay positive. Only on explicit request
    /// (`poisson_above_half = true`), because seed 000 Table 3 screens ν up to 0.586.
    PoissonContactModel,
    /// A strictly positive quantity (density, modulus, length, speed, time).
    Positive,
    /// A quantity that may be zero but not negative (a count of centre points, a percentage).
    NonNegative,
    /// A fraction in [0, 1].
    Fraction,
    /// A fraction in [0, 1): the plastic fraction λ of the hysteretic contact, where λ = 1
    /// would leave no elastic unloading.
    FractionBelowOne,
    /// A probability strictly between 0 and 1 (a significance level).
    Probability,
}

impl Limits {
    /// The admissible value nearest an inadmissible `value` when the limit is a closed bound
    /// (μ ≥ 0 → 0, e ≤ 1 → 1, a fraction → 0 or 1); `None` when the admissible set is open
    /// on that side (e > 0, ν < 0.5, a positive quantity), where no nearest value exists.
    pub fn nearest_admissible(self, value: f64) -> Option<f64> {
        if !value.is_finite() {
            return None;
        }
        match self {
            Self::Friction | Self::NonNegative => Some(value.max(0.0)),
            Self::Restitution if value > 1.0 => Some(1.0),
            Self::Fraction => Some(value.clamp(0.0, 1.0)),
            Self::FractionBelowOne if value < 0.0 => Some(0.0),
            _ => None,
        }
    }

    /// The lower and upper ends of the admissible set (±∞ where it is unbounded), each with
    /// whether the end itself is admissible: e ∈ (0, 1] gives (0, open) and (1, closed).
    pub fn ends(self) -> (End, End) {
        let (lo, lo_closed, hi, hi_closed) = match self {
            Self::Restitution => (0.0, false, 1.0, true),
            Self::Friction | Self::NonNegative => (0.0, true, f64::INFINITY, false),
            Self::Poisson => (-1.0, false, 0.5, false),
            Self::PoissonContactModel => (-1.0, false, 1.0, false),
            Self::Positive => (0.0, false, f64::INFINITY, false),
            Self::Fraction => (0.0, true, 1.0, true),
            Self::FractionBelowOne => (0.0, true, 1.0, false),
            Self::Probability => (0.0, false, 1.0, false),
        };
        (
            End {
                value: lo,
                closed: lo_closed,
            },
            End {
                value: hi,
                closed: hi_closed,
            },
        )
    }

    /// `Ok` when `value` is finite and admissible, else the reason in words.
    pub fn check(self, value: f64) -> Result<(), String> {
        if !value.is_finite() {
            return Err(format!("{value} is not a finite number"));
        }
        let ok = match self {
            Self::Restitution => value > 0.0 && value <= 1.0,
            Self::Friction | Self::NonNegative => value >= 0.0,
            Self::Poisson => value > -1.0 && value < 0.5,
            Self::PoissonContactModel => value > -1.0 && value < 1.0,
            Self::Positive => value > 0.0,
            Self::Fraction => (0.0..=1.0).contains(&value),
            Self::FractionBelowOne => (0.0..1.0).contains(&value),
            Self::Probability => value > 0.0 && value < 1.0,
        };
        if ok {
            Ok(())
        } else {
            Err(format!("{value} is outside the physical limits: {self}"))
        }
    }
}

/// One end of an admissible set ([`Limits::ends`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct End {
    /// Where the set ends (±∞ when it does not).
    pub value: f64,
    /// Whether `value` itself is admissible.
    pub closed: bool,
}

impl fmt::Display for Limits {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::Restitution => "a restitution coefficient must lie in (0, 1]",
            Self::Friction => "a friction coefficient must be ≥ 0",
            Self::Poisson => "a Poisson ratio must lie in (−1, 0.5)",
            Self::PoissonContactModel => {
                "a Poisson ratio must lie in (−1, 1) for the Hertz–Mindlin terms to stay positive"
            }
            Self::Positive => "the value must be > 0",
            Self::NonNegative => "the value must be ≥ 0",
            Self::Fraction => "a fraction must lie in [0, 1]",
            Self::FractionBelowOne => "this fraction must lie in [0, 1)",
            Self::Probability => "a probability must lie in (0, 1)",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearest_admissible_stops_at_closed_bounds_only() {
        assert_eq!(Limits::Friction.nearest_admissible(-0.2), Some(0.0));
        assert_eq!(Limits::Restitution.nearest_admissible(1.3), Some(1.0));
        assert_eq!(Limits::Restitution.nearest_admissible(-0.1), None);
        assert_eq!(Limits::Poisson.nearest_admissible(0.7), None);
        assert_eq!(Limits::Fraction.nearest_admissible(1.5), Some(1.0));
        assert_eq!(Limits::Friction.nearest_admissible(f64::NAN), None);
    }
}
