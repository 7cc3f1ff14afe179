//! Fuzz the contact law through the public set-up and step API: one free sphere against a
//! second sphere (coincident centres, any overlap up to full, any materials) or against a wall
//! (plane, cylinder, box), with extreme radii, moduli, densities, speeds and spins.
//!
//! Set-up errors are fine. Checked properties:
//! 1. nothing panics (the fuzz build has overflow checks on, so a wrapping integer operation
//!    in the core is a crash too);
//! 2. when `step` returns `Ok`, every state value is valid (no overflow poison / NaN): an
//!    overflow must surface as `StepError::Overflow`, never silently;
//! 3. the contact law is never attractive: over one step the normal relative velocity of two
//!    spheres (gravity cancels) does not decrease, and a sphere is not pulled into a plane,
//!    beyond rounding;
//! 4. for well-conditioned inputs, the fixed-point step agrees with the f64 step on the
//!    velocity change of each body (a silently wrapped value cannot).

#![no_main]

#[path = "common/mod.rs"]
mod common;

use arachis_core::prelude::*;
use arbitrary::Arbitrary;
use common::{assert_state_valid, outcome, strict, Arenas, MaterialIn, PairIn, Real, Real3};
use libfuzzer_sys::fuzz_target;

/// Where the second sphere sits relative to the first.
#[derive(Arbitrary, Debug, Clone, Copy)]
enum Offset {
    /// Along `dir` at `dist × (Ri + Rj)` (Near values span 1/16–16 × the contact distance).
    Along { dir: Real3, dist: Real },
    /// Same centre.
    Coincident,
    /// Any offset, m.
    Raw(Real3),
}

#[derive(Arbitrary, Debug, Clone, Copy)]
enum Partner {
    Sphere {
        radius: Real,
        other_material: bool,
        offset: Offset,
        velocity: Real3,
        spin: Real3,
    },
    /// Plane through the point `gap × Ri` below the centre along −normal.
    Plane {
        normal: Real3,
        gap: Real,
        velocity: Real3,
    },
    /// Cylinder around the sphere; axis through the centre shifted by `shift`, radius ~ 2Ri.
    Cylinder {
        axis: Real3,
        shift: Real3,
        radius: Real,
        finite: bool,
        velocity: Real3,
    },
    /// Box around the sphere with half-size ~ 2Ri, shifted.
    AaBox {
        half: Real3,
        shift: Real3,
        velocity: Real3,
    },
}

#[derive(Arbitrary, Debug, Clone, Copy)]
struct Input {
    mat_a: MaterialIn,
    mat_b: MaterialIn,
    pair_aa: PairIn,
    pair_ab: PairIn,
    pair_bb: PairIn,
    radius: Real,
    position: Real3,
    velocity: Real3,
    spin: Real3,
    gravity: Real3,
    partner: Partner,
    /// dt = max stable dt × (k + 1)/256.
    dt_fraction: u8,
    /// 1–8 steps.
    steps: u8,
}

/// Typical scales (SI): pod sphere radius, bed position, pour speed, spin, gravity.
const RADIUS_M: f64 = 0.004;
const POSITION_M: f64 = 0.02;
const SPEED_M_S: f64 = 0.2;
const SPIN_RAD_S: f64 = 10.0;
const GRAVITY_M_S2: f64 = 9.81;

/// The first step's record, compared between fixed point and f64.
#[derive(Debug, Clone, Copy)]
struct FirstStep {
    /// Velocity change of each body over step 1, m/s (= mm/ms).
    dv: [[f64; 3]; 2],
    /// Velocity before step 1, m/s.
    v0: [[f64; 3]; 2],
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Force resolution of Q32.32, N: the grid every contact force is rounded to.
const FORCE_QUANTUM_N: f64 = 1.0 / 4_294_967_296.0;
/// Force roundings a contact's normal component may carry (normal, tangential and damping
/// parts, each rounded once).
const FORCE_ROUNDINGS: f64 = 4.0;

/// Rounding slack for a velocity check, mm/ms: absolute floor plus relative part, plus, in
/// fixed point, what the force grid alone does to the bodies in one step: a force rounded by
/// one unit moves a body of mass m by 2^-32 N·dt/m (1 N/g = 1 mm/ms²), which is not small
/// for a light sphere and a long step (a 3.7e-5 g sphere at dt ≈ 1 ms: 6e-6 mm/ms; smoke
/// run of 2026-11-26). `inv_mass_sum` is Σ 1/m of the two bodies, 1/g; `dt_ms` the step.
fn slack<S: Scalar>(scale: f64, dist_mm: f64, inv_mass_sum: f64, dt_ms: f64) -> f64 {
    if S::NAME == "f64" {
        1e-12 * scale + 1e-300
    } else {
        // Q32.32: a few resolution units per product, and the normal's direction error
        // 2.3e-10/|d| turning tangential velocity into normal.
        let grid = FORCE_ROUNDINGS * FORCE_QUANTUM_N * dt_ms * inv_mass_sum;
        1e-8 + (1e-6 + 1e-8 / dist_mm.max(1e-300)) * scale + grid
    }
}

/// Build and run the scenario in `S`; returns the first step's record when it succeeded.
fn run<S: Scalar>(inp: &Input) -> Option<FirstStep> {
    let mut arenas = Arenas::<S>::new(2, 2);
    let mut w = arenas.world();
    let a = w.add_material(inp.mat_a.spec()).ok()?;
    let b = w.add_material(inp.mat_b.spec()).ok()?;
    w.set_pair(a, a, inp.pair_aa.spec()).ok()?;
    w.set_pair(a, b, inp.pair_ab.spec()).ok()?;
    w.set_pair(b, b, inp.pair_bb.spec()).ok()?;
    w.set_gravity_m_s2(inp.gravity.get(GRAVITY_M_S2)).ok()?;
    let r_i = inp.radius.get(RADIUS_M);
    let p_i = inp.position.get(POSITION_M);
    let mut s = SphereSpec::at_rest(a, r_i, p_i);
    s.velocity_m_s = inp.velocity.get(SPEED_M_S);
    s.angular_velocity_rad_s = inp.spin.get(SPIN_RAD_S);
    w.add_sphere(s).ok()?;
    let mut plane_normal = None;
    let (wall_speed, partner_radius_m) = match inp.partner {
        Partner::Sphere { radius, .. } => (0.0, radius.get(RADIUS_M)),
        Partner::Plane { velocity, .. }
        | Partner::Cylinder { velocity, .. }
        | Partner::AaBox { velocity, .. } => (norm(velocity.get(SPEED_M_S)), 0.0),
    };
    let max_radius_mm = r_i.abs().max(partner_radius_m.abs()) * 1e3;
    match inp.partner {
        Partner::Sphere {
            radius,
            other_material,
            offset,
            velocity,
            spin,
        } => {
            let r_j = radius.get(RADIUS_M);
            let off = match offset {
                Offset::Coincident => [0.0; 3],
                Offset::Along { dir, dist } => {
                    let d = dir.get(1.0);
                    let n = norm(d);
                    let k = dist.get(1.0) * (r_i + r_j) / n;
                    [d[0] * k, d[1] * k, d[2] * k]
                }
                Offset::Raw(v) => v.get(RADIUS_M),
            };
            let mut s = SphereSpec::at_rest(
                if other_material { b } else { a },
                r_j,
                [p_i[0] + off[0], p_i[1] + off[1], p_i[2] + off[2]],
            );
            s.velocity_m_s = velocity.get(SPEED_M_S);
            s.angular_velocity_rad_s = spin.get(SPIN_RAD_S);
            w.add_sphere(s).ok()?;
        }
        Partner::Plane {
            normal,
            gap,
            velocity,
        } => {
            let nv = normal.get(1.0);
            let n = norm(nv);
            let g = gap.get(r_i) / n;
            let point = [p_i[0] - nv[0] * g, p_i[1] - nv[1] * g, p_i[2] - nv[2] * g];
            let mut spec = WallSpec::fixed(
                WallGeometry::Plane {
                    point_m: point,
                    normal: nv,
                },
                b,
            );
            spec.velocity_m_s = velocity.get(SPEED_M_S);
            w.add_wall(spec).ok()?;
            plane_normal = Some([nv[0] / n, nv[1] / n, nv[2] / n]);
        }
        Partner::Cylinder {
            axis,
            shift,
            radius,
            finite,
            velocity,
        } => {
            let sh = shift.get(r_i);
            let base = [p_i[0] + sh[0], p_i[1] + sh[1], p_i[2] + sh[2] - 2.0 * r_i];
            let mut spec = WallSpec::fixed(
                WallGeometry::Cylinder {
                    base_m: base,
                    axis: axis.get(1.0),
                    radius_m: radius.get(2.0 * r_i),
                    length_m: finite.then_some(4.0 * r_i),
                },
                b,
            );
            spec.velocity_m_s = velocity.get(SPEED_M_S);
            w.add_wall(spec).ok()?;
        }
        Partner::AaBox {
            half,
            shift,
            velocity,
        } => {
            let h = half.get(2.0 * r_i);
            let sh = shift.get(r_i);
            let c = [p_i[0] + sh[0], p_i[1] + sh[1], p_i[2] + sh[2]];
            let mut spec = WallSpec::fixed(
                WallGeometry::AaBox {
                    min_m: [c[0] - h[0], c[1] - h[1], c[2] - h[2]],
                    max_m: [c[0] + h[0], c[1] + h[1], c[2] + h[2]],
                },
                b,
            );
            spec.velocity_m_s = velocity.get(SPEED_M_S);
            w.add_wall(spec).ok()?;
        }
    }
    let max_dt = w.max_timestep_s();
    let dt = if max_dt.is_finite() {
        max_dt * (f64::from(inp.dt_fraction) + 1.0) / 256.0
    } else {
        2e-5
    };
    w.set_timestep_s(dt).ok()?;
    outcome(&format!("{} setup ok", S::NAME));
    let g = w.gravity().to_f64();
    let dt_ms = dt * 1e3;
    let inv_mass_sum: f64 = w.bodies().iter().map(|b| b.inv_mass.to_f64()).sum();
    let mut first = None;
    for k in 0..u64::from(inp.steps % 8 + 1) {
        // The contact's own speed: a wall's velocity and the spheres' surface speed |ω|·R.
        // The normal part of the relative velocity is split off a vector of this size, so its
        // rounding (1e-16 of it in f64) leaks into the tangential force along the normal
        // (a plane at 6e8 m/s in an f64 run of 2026-11-26: 1.6e-8 mm/ms).
        let contact_speed = wall_speed
            + w.bodies()
                .iter()
                .map(|b| norm(b.angular_velocity.to_f64()) * max_radius_mm)
                .fold(0.0, f64::max);
        let pos0: Vec<[f64; 3]> = w.bodies().iter().map(|b| b.position.to_f64()).collect();
        let vel0: Vec<[f64; 3]> = w.bodies().iter().map(|b| b.velocity.to_f64()).collect();
        if let Err(e) = w.step() {
            // A typed error is an allowed outcome; the state is then unspecified.
            outcome(&format!(
                "{} step {} error {:?}",
                S::NAME,
                k + 1,
                discriminant(&e)
            ));
            break;
        }
        outcome(&format!("{} step ok", S::NAME));
        assert_state_valid(&w, k + 1);
        let vel1: Vec<[f64; 3]> = w.bodies().iter().map(|b| b.velocity.to_f64()).collect();
        let dv: Vec<[f64; 3]> = vel1.iter().zip(&vel0).map(|(a, b)| sub(*a, *b)).collect();
        let scale = vel0
            .iter()
            .chain(&vel1)
            .map(|v| norm(*v))
            .fold(norm(g) * dt_ms, f64::max)
            .max(contact_speed);
        if dv.len() == 2 {
            // Property 3, sphere–sphere: Δ(vj − vi)·n ≥ 0 (gravity cancels).
            let d = sub(pos0[1], pos0[0]);
            let dist = norm(d);
            if dist > 1e-6 {
                let n = [d[0] / dist, d[1] / dist, d[2] / dist];
                let dvn = dot(sub(dv[1], dv[0]), n);
                assert!(
                    dvn >= -slack::<S>(scale, dist, inv_mass_sum, dt_ms),
                    "{}: step {} pulled two spheres together: Δvn = {dvn:e} mm/ms (scale {scale:e})",
                    S::NAME,
                    k + 1
                );
            }
        } else if let Some(n) = plane_normal {
            // Property 3, sphere–plane: (Δv − g·dt)·n_plane ≥ 0.
            let dvn = dot(dv[0], n) - dot(g, n) * dt_ms;
            assert!(
                dvn >= -slack::<S>(scale, 1.0, inv_mass_sum, dt_ms),
                "{}: step {} pulled a sphere into a plane: Δvn = {dvn:e} mm/ms (scale {scale:e})",
                S::NAME,
                k + 1
            );
        }
        if k == 0 {
            let mut rec = FirstStep {
                dv: [[0.0; 3]; 2],
                v0: [[0.0; 3]; 2],
            };
            for (i, (d, v)) in dv.iter().zip(&vel0).enumerate() {
                rec.dv[i] = *d;
                rec.v0[i] = *v;
            }
            first = Some(rec);
        }
    }
    first
}

/// The error's variant name, for the outcome statistics.
fn discriminant(e: &StepError) -> &'static str {
    match e {
        StepError::Overflow { .. } => "Overflow",
        StepError::ContactCapacity { .. } => "ContactCapacity",
        StepError::UndefinedPair { .. } => "UndefinedPair",
        StepError::NoTimeStep => "NoTimeStep",
        StepError::TimeStepTooLarge { .. } => "TimeStepTooLarge",
        StepError::BondCapacity { .. } => "BondCapacity",
    }
}

/// Below this centre separation (m) fixed and f64 are not compared (finding F1).
const NEAR_COINCIDENT_M: f64 = 1e-7;
/// Within this distance (m) of touching, fixed and f64 are not compared: a gap of a few
/// Q32.32 units (2.3e-13 m each) is rounding, so one arithmetic may see the spheres touch and
/// the other not, and the law is not small there: the normal damping at overlap α grows as
/// α^(1/4)·vn, so one unit of overlap at 0.37 m/s already pushes a 3.5 g sphere by 1e-3 m/s
/// in a step (smoke run of 2026-11-26, an `Along` offset of exactly Ri + Rj). 1e-12 m is
/// four units: past it both arithmetics agree whether the spheres touch.
const NEAR_TOUCHING_M: f64 = 1e-12;

/// Inputs for which Q32.32 in mm-g-ms resolves every quantity to ≲1e-6 relative, so fixed
/// point and f64 must agree closely after one step.
fn well_conditioned(inp: &Input) -> bool {
    let inside = |x: f64, lo: f64, hi: f64| x.is_finite() && x.abs() >= lo && x.abs() <= hi;
    let inside_or_zero = |x: f64, hi: f64| x.is_finite() && x.abs() <= hi;
    let mats = [inp.mat_a.spec(), inp.mat_b.spec()];
    let mats_ok = mats
        .iter()
        .all(|m| inside(m.youngs_modulus_pa, 1e5, 1e12) && inside(m.density_kg_m3, 10.0, 1e5));
    let r_ok = inside(inp.radius.get(RADIUS_M), 1e-3, 0.1);
    let partner_ok = match inp.partner {
        Partner::Sphere {
            radius,
            velocity,
            spin,
            offset,
            ..
        } => {
            // Known finding F1 (reported, regressions/contact_law/
            // near_coincident_centres_normal_flip): for centres closer than ~1.5e-5 mm, |d|²
            // underflows Q32.32 and the core takes the coincident-centre normal +z although d
            // is resolvable, so fixed and f64 push in different directions. Excluded here so
            // fuzzing goes on past it (ARACHIS_FUZZ_STRICT=1 keeps it); drop this condition
            // once the core normalises d before squaring.
            let r_j = radius.get(RADIUS_M);
            let separation_m = match offset {
                Offset::Coincident => 1.0,
                Offset::Along { dist, .. } => {
                    dist.get(1.0).abs() * (inp.radius.get(RADIUS_M) + r_j)
                }
                Offset::Raw(v) => norm(v.get(RADIUS_M)),
            };
            let touching_m = inp.radius.get(RADIUS_M) + r_j;
            (strict() || separation_m >= NEAR_COINCIDENT_M)
                && (strict() || (separation_m - touching_m).abs() >= NEAR_TOUCHING_M)
                && inside(r_j, 1e-3, 0.1)
                && velocity
                    .get(SPEED_M_S)
                    .iter()
                    .all(|v| inside_or_zero(*v, 10.0))
                && spin.get(SPIN_RAD_S).iter().all(|v| inside_or_zero(*v, 1e3))
        }
        _ => false,
    };
    mats_ok
        && r_ok
        && partner_ok
        && inp
            .position
            .get(POSITION_M)
            .iter()
            .all(|v| inside_or_zero(*v, 1.0))
        && inp
            .velocity
            .get(SPEED_M_S)
            .iter()
            .all(|v| inside_or_zero(*v, 10.0))
        && inp
            .spin
            .get(SPIN_RAD_S)
            .iter()
            .all(|v| inside_or_zero(*v, 1e3))
        && inp
            .gravity
            .get(GRAVITY_M_S2)
            .iter()
            .all(|v| inside_or_zero(*v, 100.0))
}

fuzz_target!(|inp: Input| {
    let fx = run::<Fx>(&inp);
    let fl = run::<f64>(&inp);
    // Property 4: fixed point vs f64 over the first step.
    if let (Some(fx), Some(fl), true) = (fx, fl, well_conditioned(&inp)) {
        outcome("compared fixed vs f64");
        for i in 0..2 {
            let err = norm(sub(fx.dv[i], fl.dv[i]));
            let scale = norm(fl.dv[i]).max(norm(fl.v0[i]));
            assert!(
                err <= 1e-6 + 1e-3 * scale,
                "fixed vs f64 disagree on body {i}'s velocity change over step 1: \
                 fixed {:?}, f64 {:?} (mm/ms)",
                fx.dv[i],
                fl.dv[i]
            );
        }
    }
});
