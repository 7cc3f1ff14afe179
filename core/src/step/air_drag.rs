//! Air drag on moving bodies, a body-force stage: F = −½·ρ_air·Cd·A·|v|·v (quadratic drag,
//! e.g. Crowe et al., *Engineering Fluid Mechanics*, drag force definition), with A = π·r²
//! summed over a body's spheres (exact for a single sphere; an upper bound for a clump whose
//! spheres overlap or shadow each other). The body's translational velocity is used
//! (still air).
//!
//! Off value: Cd = 0 ([`AirDrag::on`] false), the default. The world's `set_air_drag` sets
//! it.

use crate::body::{Body, BodyForce, Sphere};
use crate::error::{Other, Stage, StepError};
use crate::num::{Scalar, Vec3};

/// mm² to m²: the projected area enters the SI formula in m².
const MM2_PER_M2: f64 = 1.0e6;

/// Air-drag constants of a world. Off value: `on = false`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AirDrag<S> {
    /// Whether drag is applied.
    pub on: bool,
    /// ½·ρ_air·Cd·π, kg/m³: F (N) = coef·r²(mm²)/10⁶·|v|·v (m/s).
    pub coef: S,
    /// Air density, kg/m³ (kept for reports).
    pub air_density_kg_m3: f64,
    /// Drag coefficient Cd (kept for reports).
    pub drag_coefficient: f64,
}

impl<S: Scalar> AirDrag<S> {
    /// Build from air density ρ_air (kg/m³) and drag coefficient Cd (dimensionless).
    pub fn new(air_density_kg_m3: f64, drag_coefficient: f64) -> Self {
        AirDrag {
            on: air_density_kg_m3 > 0.0 && drag_coefficient > 0.0,
            coef: S::from_f64(0.5 * air_density_kg_m3 * drag_coefficient * core::f64::consts::PI),
            air_density_kg_m3,
            drag_coefficient,
        }
    }
}

impl<S: Scalar> AirDrag<S> {
    /// Add the drag on each body (at its velocity at the start of the step) to its force sum
    /// in `forces`; `spheres` give the projected areas.
    pub(crate) fn apply(
        &self,
        bodies: &[Body<S>],
        spheres: &[Sphere<S>],
        forces: &mut [BodyForce<S>],
    ) -> Result<(), StepError> {
        let scale = S::from_f64(MM2_PER_M2);
        for (i, (b, acc)) in bodies.iter().zip(forces.iter_mut()).enumerate() {
            let first = b.first_sphere as usize;
            let mut r2 = S::ZERO;
            for s in &spheres[first..first + b.sphere_count as usize] {
                r2 += s.radius * s.radius;
            }
            let v = b.velocity;
            // coef·r² first (≈ 10), then /10⁶ after multiplying by the speed terms, so the
            // small SI area factor costs no fixed-point precision.
            let mag = self.coef * r2 * v.norm() / scale;
            let f: Vec3<S> = v.scale(mag);
            if !f.is_valid() {
                return Err(StepError::Overflow {
                    stage: Stage::BodyForces,
                    body: i as u32,
                    other: Other::None,
                });
            }
            acc.sub_force(f);
        }
        Ok(())
    }
}
