//! Derringer–Suich desirability (Derringer & Suich 1980), as Design-Expert's numerical
//! optimisation uses it.
//!
//! Each response y gets an individual desirability d ∈ [0, 1] from its goal and limits
//! L < U (weights s, t > 0 shape the ramps):
//! - maximise: d = 0 for y ≤ L, ((y − L)/(U − L))^s between, 1 for y ≥ U;
//! - minimise: d = 1 for y ≤ L, ((U − y)/(U − L))^s between, 0 for y ≥ U;
//! - target T (L ≤ T ≤ U): ((y − L)/(T − L))^s for L ≤ y ≤ T, ((U − y)/(U − T))^t for
//!   T ≤ y ≤ U, 0 outside;
//! - in range: 1 for L ≤ y ≤ U, 0 outside.
//!
//! The overall desirability weighs each dᵢ by its importance rᵢ (DESIGN §9):
//! D = (Π dᵢ^rᵢ)^(1/Σrᵢ).
//!
//! ```
//! use arachis::optimize::{Goal, GoalKind};
//! let g = Goal::new(GoalKind::Target(31.06), 28.0, 32.0).unwrap();
//! assert_eq!(g.desirability(31.06), 1.0);
//! assert!((g.desirability(29.53) - 0.5).abs() < 1e-12);
//! assert_eq!(g.desirability(33.0), 0.0);
//! ```

use super::OptimizeError;

/// What a response should do.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GoalKind {
    /// As large as possible (d = 1 at and above the upper limit).
    Maximise,
    /// As small as possible (d = 1 at and below the lower limit).
    Minimise,
    /// Equal to this value (in the response's unit).
    Target(f64),
    /// Anywhere between the limits.
    InRange,
}

/// A goal for one response: kind, limits (in the response's unit), weights and importance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Goal {
    /// What the response should do.
    pub kind: GoalKind,
    /// Lower limit L.
    pub low: f64,
    /// Upper limit U.
    pub high: f64,
    /// Weight s of the lower (rising) ramp; 1 is linear.
    pub weight_low: f64,
    /// Weight t of the upper (falling) ramp of a target; 1 is linear.
    pub weight_high: f64,
    /// Importance rᵢ in D = (Π dᵢ^rᵢ)^(1/Σrᵢ); Design-Expert offers 1 to 5.
    pub importance: f64,
}

impl Goal {
    /// A goal with linear ramps and importance 1. Requires finite L < U and, for a target,
    /// L ≤ T ≤ U.
    pub fn new(kind: GoalKind, low: f64, high: f64) -> Result<Self, OptimizeError> {
        Self {
            kind,
            low,
            high,
            weight_low: 1.0,
            weight_high: 1.0,
            importance: 1.0,
        }
        .checked()
    }

    /// The same goal with importance `r` (> 0).
    pub fn with_importance(mut self, r: f64) -> Result<Self, OptimizeError> {
        self.importance = r;
        self.checked()
    }

    /// The same goal with ramp weights `s` (lower) and `t` (upper), both > 0.
    pub fn with_weights(mut self, s: f64, t: f64) -> Result<Self, OptimizeError> {
        self.weight_low = s;
        self.weight_high = t;
        self.checked()
    }

    /// The goal in words, for messages: "target 31.06 within 26.5 … 33.6".
    pub fn describe(&self) -> String {
        let kind = match self.kind {
            GoalKind::Maximise => "maximise".to_string(),
            GoalKind::Minimise => "minimise".to_string(),
            GoalKind::Target(t) => format!("target {}", readable(t)),
            GoalKind::InRange => "in range".to_string(),
        };
        format!(
            "{kind} within {} … {}",
            readable(self.low),
            readable(self.high)
        )
    }

    fn checked(self) -> Result<Self, OptimizeError> {
        let bad = |reason: String| OptimizeError::BadGoal {
            goal: self.describe(),
            reason,
        };
        if !(self.low.is_finite() && self.high.is_finite() && self.low < self.high) {
            return Err(bad(format!(
                "limits {} and {} must be finite with lower < upper",
                readable(self.low),
                readable(self.high)
            )));
        }
        if let GoalKind::Target(t) = self.kind {
            if !(t.is_finite() && self.low <= t && t <= self.high) {
                return Err(bad(format!(
                    "target {} lies outside the limits {} … {}",
                    readable(t),
                    readable(self.low),
                    readable(self.high)
                )));
            }
        }
        for (what, v) in [
            ("lower weight", self.weight_low),
            ("upper weight", self.weight_high),
            ("importance", self.importance),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(bad(format!("{what} {v} must be a positive number")));
            }
        }
        Ok(self)
    }

    /// Individual desirability d(y) ∈ [0, 1] (Derringer & Suich 1980).
    pub fn desirability(&self, y: f64) -> f64 {
        let (l, u) = (self.low, self.high);
        match self.kind {
            GoalKind::Maximise => {
                if y <= l {
                    0.0
                } else if y >= u {
                    1.0
                } else {
                    ((y - l) / (u - l)).powf(self.weight_low)
                }
            }
            GoalKind::Minimise => {
                if y >= u {
                    0.0
                } else if y <= l {
                    1.0
                } else {
                    ((u - y) / (u - l)).powf(self.weight_low)
                }
            }
            GoalKind::Target(t) => {
                if y < l || y > u {
                    0.0
                } else if y == t {
                    1.0
                } else if y < t {
                    ((y - l) / (t - l)).powf(self.weight_low)
                } else {
                    ((u - y) / (u - t)).powf(self.weight_high)
                }
            }
            GoalKind::InRange => {
                if (l..=u).contains(&y) {
                    1.0
                } else {
                    0.0
                }
            }
        }
    }

    /// How far y lies outside the region where d > 0, in units of U − L (0 inside). Used to
    /// steer the search where D = 0 is flat.
    pub fn shortfall(&self, y: f64) -> f64 {
        let (l, u) = (self.low, self.high);
        let below = (l - y).max(0.0);
        let above = (y - u).max(0.0);
        let gap = match self.kind {
            GoalKind::Maximise => below,
            GoalKind::Minimise => above,
            GoalKind::Target(_) | GoalKind::InRange => below + above,
        };
        gap / (u - l)
    }
}

/// Overall desirability D = (Π dᵢ^rᵢ)^(1/Σrᵢ) of responses `ys` under `goals` (DESIGN §9).
/// Zero as soon as one dᵢ is zero.
pub fn overall_desirability(goals: &[Goal], ys: &[f64]) -> f64 {
    let total: f64 = goals.iter().map(|g| g.importance).sum();
    let mut log_sum = 0.0;
    for (g, &y) in goals.iter().zip(ys) {
        let d = g.desirability(y);
        if d <= 0.0 {
            return 0.0;
        }
        log_sum += g.importance * d.ln();
    }
    (log_sum / total).exp()
}

/// `x` as a message shows it: plain between 1e-4 and 1e6, else in exponent form (a target
/// of 1e300 was once printed with 300 zeros).
fn readable(x: f64) -> String {
    if x == 0.0 || (1e-4..1e6).contains(&x.abs()) || !x.is_finite() {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}
