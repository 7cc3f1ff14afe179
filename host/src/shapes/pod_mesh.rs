//! A triangle mesh of an analytic pod surface, to export a pod as STL (e.g. for EDEM) or
//! to test the STL path against the exact shape.
//!
//! Each lobe is sampled by its polar angle φ: a ring at z = ±(d + c·cos φ) with section
//! scale sin φ, from the tip (φ = 0, one vertex) to the waist (cos φ = −d/c, the ring both
//! lobes share). Uniform steps in φ put more rings near the tips, where the surface turns
//! fastest. Triangles are wound outward.
//!
//! ```
//! use arachis::shapes::{pod_triangles, PodKind, PodShape, TriangleMesh};
//! let pod = PodShape::seed001_mean(PodKind::Normal);
//! let tris = pod_triangles(&pod, 24, 48);
//! let mesh = TriangleMesh::from_triangles(std::path::Path::new("pod"), &tris).unwrap();
//! let rel = mesh.enclosed_volume_mm3() / pod.analytic_volume_mm3() - 1.0;
//! assert!(rel < 0.0 && rel > -0.01); // inscribed polyhedron, slightly smaller
//! ```

use std::f64::consts::PI;

use super::pod_shape::PodShape;

/// Triangles (vertex coordinates, mm) of `pod`'s surface with `rings_per_lobe` steps in φ
/// per lobe (≥ 2) and `sectors` vertices around each ring (≥ 3).
pub fn pod_triangles(pod: &PodShape, rings_per_lobe: usize, sectors: usize) -> Vec<[[f64; 3]; 3]> {
    let rings_per_lobe = rings_per_lobe.max(2);
    let sectors = sectors.max(3);
    let ([a, b, c], d) = pod.lobes_mm();
    let phi_waist = (-d / c).clamp(-1.0, 1.0).acos();
    // Rings from the −z tip to the +z tip: (z, section scale); the waist ring once.
    let mut rings: Vec<(f64, f64)> = Vec::new();
    for n in 0..=rings_per_lobe {
        let phi = phi_waist * n as f64 / rings_per_lobe as f64;
        rings.push((-(d + c * phi.cos()), phi.sin()));
    }
    for n in (0..rings_per_lobe).rev() {
        let phi = phi_waist * n as f64 / rings_per_lobe as f64;
        rings.push((d + c * phi.cos(), phi.sin()));
    }
    let point = |ring: usize, sector: usize| {
        let (z, rho) = rings[ring];
        if ring == 0 || ring == rings.len() - 1 {
            return [0.0, 0.0, z]; // a tip: one vertex
        }
        let theta = 2.0 * PI * (sector % sectors) as f64 / sectors as f64;
        [a * rho * theta.cos(), b * rho * theta.sin(), z]
    };
    let mut tris = Vec::new();
    for ring in 0..rings.len() - 1 {
        for s in 0..sectors {
            let (p00, p01) = (point(ring, s), point(ring, s + 1));
            let (p10, p11) = (point(ring + 1, s), point(ring + 1, s + 1));
            // z grows with the ring and θ counter-clockwise about +z: (p00, p01, p11) faces
            // outward. Skip the degenerate half at a tip.
            if ring != 0 {
                tris.push([p00, p01, p11]);
            }
            if ring + 1 != rings.len() - 1 {
                tris.push([p00, p11, p10]);
            }
        }
    }
    tris
}
