//! A response surface: a prediction ŷ at a point given in coded factor units.
//!
//! Any fitted model plugs into the optimiser through this trait; closures implement it.
//!
//! ```
//! use arachis::optimize::ResponseSurface;
//! let plane = |x: &[f64]| 1.0 + 2.0 * x[0];
//! assert_eq!(plane.predict(&[0.5]), 2.0);
//! ```

/// A model ŷ(x) over coded factors x (−1 … +1 inside the design box).
pub trait ResponseSurface: Sync {
    /// Predicted response at coded point `coded` (one value per factor), in the response's unit.
    fn predict(&self, coded: &[f64]) -> f64;
}

impl<F> ResponseSurface for F
where
    F: Fn(&[f64]) -> f64 + Sync,
{
    fn predict(&self, coded: &[f64]) -> f64 {
        self(coded)
    }
}
