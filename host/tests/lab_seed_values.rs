//! Bench-test analyses against the numbers the seeds print.
//!
//! Tolerance: half a unit in the last printed digit unless stated. The seeds print
//! summaries only (no replicates, no force–deformation pairs, no landing distances), so the
//! printed *results* we can reproduce from printed *inputs* are G from E and μ, the K(θ)
//! table, and the 0.338 constant; the rest of the analyses are checked against independent
//! hand calculations in `lab_analyses.rs`.

use std::f64::consts::PI;

use arachis::lab::bond::critical_normal_stress;
use arachis::lab::hertz_k::{k_elliptic, k_table, K_TABLE};
use arachis::lab::hertz_modulus::{seed001_radii, ASAE_CONSTANT};
use arachis::lab::shear_modulus::shear_modulus;

#[test]
fn seed000_shear_modulus_from_e_and_poisson() {
    // Seed 000 §3.1.3: E = 8.43 MPa, μ = 0.386 (§3.1.2) → G = 3.04 MPa (eq. (12)).
    let g_mpa = shear_modulus(8.43e6, 0.386) / 1e6;
    assert!((g_mpa - 3.04).abs() <= 0.005, "G = {g_mpa} MPa");
    // Seed 000 Table 3 uses 3.04 MPa, and the abstract quotes the same pair.
}

#[test]
fn hertz_k_from_elliptic_integrals_matches_seed000_table2() {
    // Seed 000 Table 2 prints K to three decimals: every entry within ±0.0005.
    for (theta_deg, printed) in K_TABLE {
        let k = k_elliptic(theta_deg.to_radians()).unwrap();
        assert!(
            (k - printed).abs() <= 0.0005,
            "θ = {theta_deg}°: elliptic K = {k:.5}, printed {printed}"
        );
    }
}

#[test]
fn hertz_k_table_reproduces_its_entries() {
    for (theta_deg, printed) in K_TABLE {
        assert_eq!(k_table(theta_deg), Some(printed));
    }
}

#[test]
fn asae_constant_is_hertz_constant_rounded() {
    // Eq. (9)'s 0.338 is 3/(2√2·π) = 0.337618 to three decimals; with it and K(90°) =
    // (π²/4)^(1/3) eq. (9) is Hertz's sphere–plate law (see hertz_k's derivation).
    let exact = 3.0 / (2.0 * 2f64.sqrt() * PI);
    assert!(
        (exact - ASAE_CONSTANT).abs() <= 0.0005,
        "3/(2√2π) = {exact}"
    );
}

#[test]
fn k_beyond_the_printed_table() {
    // Any θ is accepted: at 90° (a sphere) K = (π²/4)^(1/3) = 1.3513, continuing the table's
    // trend past 85° (1.349); at 30° K is below the table's 50° value.
    let k90 = k_elliptic(90f64.to_radians()).unwrap();
    assert!((k90 - 1.3513).abs() < 5e-5);
    let k30 = k_elliptic(30f64.to_radians()).unwrap();
    assert!(k30 < 1.198 && k30 > 0.0, "K(30°) = {k30}");
}

#[test]
fn seed001_radii_of_the_table1_pod() {
    // Seed 001 Table 1 pod: L = 34.27 mm, H = 15.76 mm. Eqs. (21)–(22) by hand:
    // R = 15.76/2 = 7.88 mm; R' = (15.76² + 17.135²)/(2·15.76) = 541.985825/31.52 = 17.19498 mm.
    let (r, r_prime) = seed001_radii(34.27, 15.76);
    assert!((r - 7.88).abs() < 1e-12);
    assert!((r_prime - 17.194982).abs() < 1e-6);
}

#[test]
fn seed001_table4_critical_stress_is_not_force_over_bond_area() {
    // Seed 001 §2.4.1 says Table 4 was calculated with eqs. (26)–(28) and prints
    // σc = 1×10^5 Pa: one significant digit, so half a unit is ±0.5×10^5 Pa. Eq. (27) with
    // Table 3's junction force 12.74 N on the 1.1 mm bond radius gives 3.35×10^6 Pa, 33 times
    // the printed value, so Table 4 is not that computation (DESIGN §3 lists Table 4 as the
    // calibration's start values). On the pod's contact radius R = H/2 = 7.88 mm (Table 1)
    // the same force gives 0.653×10^5 Pa, inside the printed digit's range: a possible
    // reading, not a reproduction.
    let on_bond = critical_normal_stress(12.74, 1.1e-3);
    assert!((on_bond / 1e6 - 3.35).abs() < 0.005, "{on_bond}");
    assert!((on_bond / 1e5 - 1.0).abs() > 0.5);
    let on_pod = critical_normal_stress(12.74, 7.88e-3);
    assert!((on_pod / 1e5 - 0.653).abs() < 0.0005, "{on_pod}");
    assert!((on_pod / 1e5 - 1.0).abs() <= 0.5);
}
