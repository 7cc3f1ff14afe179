//! The Hertz contact coefficient K(θ) of ASAE S368.4 (seed 000 Table 2, eq. (10)), both
//! interpolated from the printed table and computed from Hertz's elliptic-integral solution.
//!
//! A convex body with principal radii of curvature R and R′ touching a flat plate makes an
//! elliptical contact whose shape is set by the auxiliary angle θ,
//!
//! ```text
//! cos θ = |1/R − 1/R′| / (1/R + 1/R′)          (seed 000 eq. (10), seed 001 eq. (20))
//! ```
//!
//! With m = e² the squared eccentricity of the contact ellipse and 𝐊(m), 𝐄(m) the complete
//! elliptic integrals of the first and second kind, Hertz's solution (Johnson, *Contact
//! Mechanics*, §4.2: A, B ∝ 𝐊 − 𝐄 and (a²/b²)𝐄 − 𝐊; approach δ = p₀ b 𝐊/E*) gives
//!
//! ```text
//! cos θ = [(2 − m) 𝐄(m) − 2(1 − m) 𝐊(m)] / (m 𝐄(m))
//! δ     = (3F/(2πE*))^(2/3) · ((1/R + 1/R′)/2)^(1/3) · K(θ),   K(θ) = [(1 − m) 𝐊³/𝐄]^(1/3)
//! ```
//!
//! Summing δ over the two plate contacts and solving for E gives ASAE S368.4's eq. (9) with
//! the constant 3/(2√2·π) = 0.33762, printed as 0.338. K(90°) (a sphere, m = 0) is
//! (π²/4)^(1/3) = 1.3513, and the computed K matches every entry of the printed table to its
//! three decimals (see the tests), so any θ in (0°, 90°] is accepted.
//!
//! ```
//! use arachis::lab::hertz_k::{k_elliptic, k_table};
//! let k = k_elliptic(70f64.to_radians()).unwrap();
//! assert!((k - 1.314).abs() < 5e-4);
//! assert_eq!(k_table(70.0), Some(1.314));
//! ```

use std::f64::consts::FRAC_PI_2;

/// Seed 000 Table 2 (Kozma and Cunningham 1962, ASAE S368.4): (θ in degrees, K).
pub const K_TABLE: [(f64, f64); 8] = [
    (50.0, 1.198),
    (55.0, 1.235),
    (60.0, 1.267),
    (65.0, 1.293),
    (70.0, 1.314),
    (75.0, 1.331),
    (80.0, 1.342),
    (85.0, 1.349),
];

/// Halvings of the eccentricity bracket [0, 1): 2⁻⁶⁰ is below f64 resolution of m.
const BISECTION_STEPS: u32 = 60;

/// cos θ = |1/R − 1/R′|/(1/R + 1/R′) for one convex contact on a flat plate, from its two
/// principal radii of curvature `r1`, `r2` (any one length unit, either order).
/// Seed 001 eq. (20); ASAE S368.4 with the plate's curvatures zero.
///
/// Seed 000 eq. (10) as printed puts the lower contact's curvatures in the denominator too,
/// which for the identical upper and lower contacts of eq. (11) halves cos θ. In ASAE
/// S368.4 the two "bodies" of that formula are the pod and the plate, whose curvatures are
/// zero; see [`cos_theta_seed000_as_printed`] to reproduce the printed form.
pub fn cos_theta(r1: f64, r2: f64) -> f64 {
    let (c1, c2) = (1.0 / r1, 1.0 / r2);
    (c1 - c2).abs() / (c1 + c2)
}

/// Seed 000 eq. (10) exactly as printed: (1/R_U − 1/R′_U)/(1/R_U + 1/R′_U + 1/R_L + 1/R′_L),
/// kept for comparison only (its magnitude is taken, as the seed lists R_U as the larger
/// radius, which would make it negative).
pub fn cos_theta_seed000_as_printed(ru: f64, ru_prime: f64, rl: f64, rl_prime: f64) -> f64 {
    (1.0 / ru - 1.0 / ru_prime).abs() / (1.0 / ru + 1.0 / ru_prime + 1.0 / rl + 1.0 / rl_prime)
}

/// Complete elliptic integrals (𝐊(m), 𝐄(m)) for 0 ≤ m < 1, from the `ellip` crate.
fn complete_integrals(m: f64) -> (f64, f64) {
    // m is in [0, 1) here, the crate's domain, so this never fails.
    ellip::ellipke(m).expect("0 <= m < 1 is inside ellipke's domain")
}

/// cos θ of a Hertz contact ellipse with squared eccentricity `m` in (0, 1).
pub fn cos_theta_of_eccentricity(m: f64) -> f64 {
    let (k, e) = complete_integrals(m);
    ((2.0 - m) * e - 2.0 * (1.0 - m) * k) / (m * e)
}

/// The squared eccentricity m in [0, 1) of the contact ellipse with the given cos θ in
/// [0, 1).
///
/// Exception to "no hand-rolled solvers": a plain bisection, because cos θ(m) is strictly
/// increasing from 0 (m = 0, a circle) to 1 (m → 1) and no crate in our tree offers a
/// bracketed scalar root finder; 60 halvings pin m to f64 resolution.
pub fn eccentricity_from_cos_theta(cos_theta: f64) -> f64 {
    if cos_theta <= 0.0 {
        return 0.0;
    }
    let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
    for _ in 0..BISECTION_STEPS {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            // Adjacent floats: stop before m rounds to 1, where 𝐊 is infinite.
            break;
        }
        if cos_theta_of_eccentricity(mid) < cos_theta {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

/// K(θ) from Hertz's elliptic-integral solution, for θ (rad) in (0, π/2]; `None` outside.
pub fn k_elliptic(theta_rad: f64) -> Option<f64> {
    if !(theta_rad > 0.0 && theta_rad <= FRAC_PI_2) {
        return None;
    }
    let m = eccentricity_from_cos_theta(theta_rad.cos().max(0.0));
    let (k, e) = complete_integrals(m);
    Some(((1.0 - m) * k.powi(3) / e).cbrt())
}

/// K(θ) linearly interpolated in seed 000 Table 2, for θ (degrees) in [50°, 85°]; `None`
/// outside the printed range.
pub fn k_table(theta_deg: f64) -> Option<f64> {
    let (first, last) = (K_TABLE[0], K_TABLE[K_TABLE.len() - 1]);
    if !(first.0..=last.0).contains(&theta_deg) {
        return None;
    }
    K_TABLE.windows(2).find_map(|w| {
        let ((t0, k0), (t1, k1)) = (w[0], w[1]);
        (theta_deg <= t1).then(|| k0 + (k1 - k0) * (theta_deg - t0) / (t1 - t0))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sphere_limit_is_cube_root_of_pi_squared_over_four() {
        let k = k_elliptic(FRAC_PI_2).unwrap();
        assert!((k - (std::f64::consts::PI.powi(2) / 4.0).cbrt()).abs() < 1e-12);
    }

    #[test]
    fn eccentricity_round_trips() {
        for m in [0.05, 0.3, 0.6, 0.9, 0.99] {
            let c = cos_theta_of_eccentricity(m);
            assert!((eccentricity_from_cos_theta(c) - m).abs() < 1e-9, "m = {m}");
        }
    }

    #[test]
    fn table_interpolates_between_entries() {
        // Halfway between 60° (1.267) and 65° (1.293).
        assert!((k_table(62.5).unwrap() - 1.280).abs() < 1e-12);
        assert_eq!(k_table(49.9), None);
        assert_eq!(k_table(85.1), None);
    }

    #[test]
    fn seed000_eq10_as_printed_halves_cos_theta_for_equal_contacts() {
        let (r, rp) = (7.88, 17.19);
        let printed = cos_theta_seed000_as_printed(r, rp, r, rp);
        assert!((printed - cos_theta(r, rp) / 2.0).abs() < 1e-15);
    }

    #[test]
    fn cos_theta_of_equal_radii_is_zero() {
        assert_eq!(cos_theta(7.0, 7.0), 0.0);
        assert!((cos_theta(1.0, 3.0) - 0.5).abs() < 1e-15);
    }
}
