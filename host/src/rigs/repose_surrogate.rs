//! A cheap, deterministic stand-in for the repose rig, built only from numbers seed 000
//! prints, so the calibration workflow can be tested end to end in milliseconds. It is
//! **not** a DEM simulation and the report says so. Its runs are specified exactly as the
//! DEM repose rig's ([`PodBenchRig::run_spec`]), so a run has the same hash either way.
//!
//! The stacking angle (degrees) is ζ = L(x) + Q(x) + ε:
//! - L, the global first-order trend over the eight factors of seed 000 Table 3: the
//!   least-squares first-order fit to seed 000 Table 4 (the Plackett–Burman runs). In a
//!   Plackett–Burman design the columns are orthogonal, so b₀ = Σy/12 and bⱼ = Σ xᵢⱼ yᵢ/12
//!   with xᵢⱼ the Table 3 coding of run i (the unit test below re-derives these from
//!   `testdata/seed-tables/seed000_table4_plackett_burman.csv` with `stats::analyze`). This
//!   trend alone predicts Table 6's steepest-ascent angles within 2.2° (24.8, 29.3, 33.7,
//!   36.5, 39.3 against 23.89, 29.36, 31.48, 35.01, 38.22).
//! - Q, the curvature of seed 000 eq. (22) (its interaction and square terms) in the coding
//!   of seed 000 Table 7, where the seed measured it. Outside the Table 7 box each coded
//!   variable is clamped to ±1: eq. (22) was fitted on a box a quarter as wide as Table 3,
//!   and extrapolating its squares to the Table 3 corners would swamp the Table 4 trend.
//! - ε, run-to-run scatter: N(0, σ²) with σ = 0.312° by default, the sample SD of the five
//!   replicated centre runs of seed 000 Table 8 (30.42, 30.02, 30.35, 30.61, 30.86), drawn
//!   deterministically from the run's spec hash (so replicates with different random seeds
//!   differ, and a replayed run gives the same bits).

use std::time::Duration;

use statrs::distribution::{ContinuousCDF, Normal};

use super::pod_bench::{parameter_values, PodBenchRig};
use crate::calibration::{Responses, Rig, RigError, RunRequest};

/// Seed 000 Table 3 levels (low, high) of x1…x8, in registry order and SI units
/// (x2 in Pa: 1.020–5.060 MPa).
pub const TABLE3_LEVELS: [(&str, f64, f64); 8] = [
    ("pod.poisson", 0.186, 0.586),
    ("pod.shear_modulus_pa", 1.020e6, 5.060e6),
    ("pod-pod.restitution", 0.314, 0.366),
    ("pod-pod.static_friction", 0.837, 0.878),
    ("pod-pod.rolling_friction", 0.314, 0.356),
    ("pod-steel.restitution", 0.282, 0.396),
    ("pod-steel.static_friction", 0.578, 0.601),
    ("pod-steel.rolling_friction", 0.145, 0.172),
];

/// Runs of seed 000 Table 4.
const TABLE4_RUNS: f64 = 12.0;
/// Σy over seed 000 Table 4, degrees.
const TABLE4_SUM_DEG: f64 = 384.47;
/// Σ xᵢⱼ yᵢ over seed 000 Table 4 for x1…x8 (Table 3 coding), degrees.
const TABLE4_CONTRASTS_DEG: [f64; 8] = [-4.21, -8.29, 15.13, 45.79, 25.67, 2.41, 13.53, -10.25];

/// Seed 000 Table 7 coding of x3, x4, x5: (registry name, centre, half-range). The x3
/// centre is the true midpoint (0.327 + 0.340)/2 = 0.3335 (Table 7 prints 0.334).
const TABLE7_CODING: [(&str, f64, f64); 3] = [
    ("pod-pod.restitution", 0.3335, 0.0065),
    ("pod-pod.static_friction", 0.853, 0.005),
    ("pod-pod.rolling_friction", 0.341, 0.009),
];

/// Seed 000 eq. (22) second-order coefficients, degrees: x3x4, x3x5, x4x5, x3², x4², x5².
const EQ22_X3X4: f64 = 0.21;
const EQ22_X3X5: f64 = 0.078;
const EQ22_X4X5: f64 = -0.08;
const EQ22_X3SQ: f64 = -0.25;
const EQ22_X4SQ: f64 = -0.26;
const EQ22_X5SQ: f64 = -0.009;

/// SD of seed 000 Table 8's five centre replicates, degrees.
pub const TABLE8_REPLICATE_SD_DEG: f64 = 0.312;

/// Seed 000's response as a closed-form test function (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Seed000Surrogate {
    /// SD of the run-to-run scatter, degrees (0 for none).
    pub noise_sd_deg: f64,
}

impl Default for Seed000Surrogate {
    fn default() -> Self {
        Self {
            noise_sd_deg: TABLE8_REPLICATE_SD_DEG,
        }
    }
}

/// The surrogate as the repose rig of a study: the DEM rig's specifications, the
/// surrogate's angles.
pub struct SurrogateRig<'a> {
    /// Specifies the runs.
    pub pod: PodBenchRig<'a>,
    /// The response function.
    pub surrogate: Seed000Surrogate,
    /// Test hook: time each run sleeps, so tests can interrupt a calibration part-way.
    pub delay: Duration,
}

impl Seed000Surrogate {
    /// The noise-free angle ζ = L + Q (degrees) at parameter values `value(name)`.
    pub fn mean_angle_deg(&self, value: impl Fn(&str) -> Option<f64>) -> Result<f64, String> {
        let get = |name: &str| value(name).ok_or_else(|| format!("the run sets no {name}"));
        let mut angle = TABLE4_SUM_DEG / TABLE4_RUNS;
        for ((name, low, high), contrast) in TABLE3_LEVELS.iter().zip(TABLE4_CONTRASTS_DEG) {
            let coded = (get(name)? - 0.5 * (low + high)) / (0.5 * (high - low));
            angle += contrast / TABLE4_RUNS * coded;
        }
        let mut c = [0.0; 3];
        for (slot, (name, centre, half)) in c.iter_mut().zip(TABLE7_CODING) {
            *slot = ((get(name)? - centre) / half).clamp(-1.0, 1.0);
        }
        let [c3, c4, c5] = c;
        angle += EQ22_X3X4 * c3 * c4 + EQ22_X3X5 * c3 * c5 + EQ22_X4X5 * c4 * c5;
        angle += EQ22_X3SQ * c3 * c3 + EQ22_X4SQ * c4 * c4 + EQ22_X5SQ * c5 * c5;
        Ok(angle)
    }
}

/// SplitMix64's output function (Steele, Lea & Flood 2014): spreads the bits of a spec hash
/// evenly before they become a uniform number. A named exception to "no hand-rolled
/// random numbers": three shifts and two multiplies, used only by this test surrogate.
fn mix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Mantissa bits of an f64: a uniform number in (0, 1) takes the top 53 bits.
const MANTISSA_BITS: u32 = 53;

/// A standard-normal number fixed by `key`: Φ⁻¹(u) with u = (top 53 bits + ½)/2⁵³ ∈ (0, 1).
pub fn standard_normal_from(key: u64) -> f64 {
    let top = mix64(key) >> (u64::BITS - MANTISSA_BITS);
    let u = (top as f64 + 0.5) / (1u64 << MANTISSA_BITS) as f64;
    Normal::standard().inverse_cdf(u)
}

impl Rig for SurrogateRig<'_> {
    fn id(&self) -> String {
        format!(
            "seed000-surrogate-1(noise_sd_deg={})",
            self.surrogate.noise_sd_deg
        )
    }

    fn description(&self) -> String {
        format!(
            "seed 000 surrogate (NOT a DEM simulation): the first-order fit to seed 000 \
             Table 4 plus the curvature of eq. (22) inside the Table 7 box, with \
             deterministic N(0, {}²) scatter keyed by the spec hash",
            self.surrogate.noise_sd_deg
        )
    }

    fn specification(&self, request: &RunRequest<'_>) -> Result<serde_json::Value, RigError> {
        self.pod.specification(request)
    }

    fn run(&self, request: &RunRequest<'_>) -> Result<Responses, RigError> {
        std::thread::sleep(self.delay);
        let spec = self.pod.run_spec(request)?;
        let values = parameter_values(&spec);
        let mean = self
            .surrogate
            .mean_angle_deg(|n| values.get(n).copied())
            .map_err(RigError)?;
        let noise = self.surrogate.noise_sd_deg * standard_normal_from(spec.spec_hash().0);
        Ok(Responses::from([(REPOSE_ANGLE.to_owned(), mean + noise)]))
    }
}

/// The response the surrogate answers.
pub const REPOSE_ANGLE: &str = "repose_angle";

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stats::{analyze, CodedDesign, ModelOrder};

    /// The Table 4 constants are the first-order least-squares fit to Table 4.
    #[test]
    fn trend_is_the_table4_fit() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../testdata/seed-tables/seed000_table4_plackett_burman.csv"
        );
        let text = std::fs::read_to_string(path).unwrap();
        let mut runs = Vec::new();
        let mut y = Vec::new();
        for line in text
            .lines()
            .filter(|l| l.starts_with(|c: char| c.is_ascii_digit()))
        {
            let v: Vec<f64> = line.split(',').map(|s| s.parse().unwrap()).collect();
            let coded = TABLE3_LEVELS
                .iter()
                .enumerate()
                .map(|(j, (_, lo, hi))| {
                    // Table 4 prints x2 in MPa.
                    let x = if j == 1 { v[j + 1] * 1e6 } else { v[j + 1] };
                    (x - 0.5 * (lo + hi)) / (0.5 * (hi - lo))
                })
                .collect();
            runs.push(coded);
            y.push(v[9]);
        }
        let names = (1..=8).map(|i| format!("x{i}")).collect();
        let fit = analyze(
            &CodedDesign::new(names, runs, y).unwrap(),
            ModelOrder::Linear,
        )
        .unwrap();
        assert!((fit.coefficients[0].estimate - TABLE4_SUM_DEG / TABLE4_RUNS).abs() < 1e-9);
        for (c, contrast) in fit.coefficients[1..].iter().zip(TABLE4_CONTRASTS_DEG) {
            assert!(
                (c.estimate - contrast / TABLE4_RUNS).abs() < 1e-9,
                "{}",
                c.term
            );
        }
    }

    #[test]
    fn noise_sd_is_the_table8_replicate_sd() {
        let centre = [30.42, 30.02, 30.35, 30.61, 30.86];
        let mean = centre.iter().sum::<f64>() / 5.0;
        let var = centre.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / 4.0;
        assert!((var.sqrt() - TABLE8_REPLICATE_SD_DEG).abs() < 5e-4);
    }

    #[test]
    fn normal_draws_look_standard() {
        let n = 20_000;
        let draws: Vec<f64> = (0..n).map(standard_normal_from).collect();
        let mean = draws.iter().sum::<f64>() / n as f64;
        let var = draws.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
        // Standard errors: 1/√n = 0.007 for the mean, √(2/n) = 0.01 for the variance.
        assert!(mean.abs() < 0.03, "{mean}");
        assert!((var - 1.0).abs() < 0.04, "{var}");
    }
}
