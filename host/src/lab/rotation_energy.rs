//! Share of rebound kinetic energy in rotation, seed 001 eqs. (13)–(15), with the pod's
//! moments of inertia from an equivalent solid triaxial ellipsoid of semi-axes L/2, W/2,
//! H/2 (seed 001 §2.2.2).
//!
//! Axes follow seed 001 §2.1: X along the width W, Y along the thickness H, Z along the
//! length L. A solid ellipsoid of mass m has I_X = m(b_Y² + b_Z²)/5 and cyclically, where
//! b are its semi-axes. E_r = ½ Σ I_i ω_i², E_t = ½ m v², η_r = E_r/(E_t + E_r).
//!
//! ```
//! use arachis::lab::rotation_energy::{ellipsoid_inertia, rotational_share};
//! // A sphere of radius 0.01 m, mass 0.002 kg: I = (2/5) m r² = 8e-8 kg·m².
//! let i = ellipsoid_inertia(0.002, 0.02, 0.02, 0.02);
//! assert!(i.iter().all(|&v| (v - 8e-8).abs() < 1e-20));
//! assert_eq!(rotational_share(1.0, 3.0), 0.25);
//! ```

/// Moments of inertia (kg·m²) about the pod's X (width), Y (thickness) and Z (length) axes,
/// for mass `mass_kg` (kg) and length, width, thickness `l`, `w`, `h` (m).
pub fn ellipsoid_inertia(mass_kg: f64, l: f64, w: f64, h: f64) -> [f64; 3] {
    let (ax, ay, az) = (w / 2.0, h / 2.0, l / 2.0);
    let fifth = mass_kg / 5.0;
    [
        fifth * (ay * ay + az * az),
        fifth * (ax * ax + az * az),
        fifth * (ax * ax + ay * ay),
    ]
}

/// Rotational kinetic energy E_r = ½ Σ I_i ω_i² (J), inertia in kg·m², `omega` in rad/s
/// about the same axes. Seed 001 eq. (13).
pub fn rotational_energy(inertia: [f64; 3], omega: [f64; 3]) -> f64 {
    0.5 * inertia
        .iter()
        .zip(omega)
        .map(|(i, w)| i * w * w)
        .sum::<f64>()
}

/// Translational kinetic energy E_t = ½ m |v|² (J), mass in kg, velocity in m/s.
/// Seed 001 eq. (14).
pub fn translational_energy(mass_kg: f64, v: [f64; 3]) -> f64 {
    0.5 * mass_kg * v.iter().map(|c| c * c).sum::<f64>()
}

/// Rotational share η_r = E_r/(E_t + E_r) as a fraction (seed 001 eq. (15) prints it in %).
pub fn rotational_share(rotational_j: f64, translational_j: f64) -> f64 {
    rotational_j / (translational_j + rotational_j)
}
