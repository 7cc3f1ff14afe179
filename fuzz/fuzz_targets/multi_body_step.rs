//! Fuzz a short multi-body run: up to 8 bodies (free spheres and clumps of 2–4 spheres) on a
//! small lattice so that they touch, up to 4 walls (planes, cylinders, boxes, moving or not),
//! up to 16 steps, with arbitrary materials, pair switches, speeds and storage sizes (so
//! capacity errors are reached too).
//!
//! Checked properties:
//! 1. nothing panics (overflow checks are on in the fuzz build);
//! 2. when `step` returns `Ok`, every state value is valid (overflow is never silent);
//! 3. determinism: the same input run twice in fixed point gives the same step results and
//!    the same digest after every step (DESIGN §5);
//! 4. the f64 reference path also never panics.

#![no_main]

#[path = "common/mod.rs"]
mod common;

use arachis_core::prelude::*;
use arbitrary::Arbitrary;
use common::{assert_state_valid, outcome, Arenas, MaterialIn, PairIn, Real, Real3};
use libfuzzer_sys::fuzz_target;

/// Typical scales (SI).
const RADIUS_M: f64 = 0.004;
const SPEED_M_S: f64 = 0.2;
const SPIN_RAD_S: f64 = 10.0;
const GRAVITY_M_S2: f64 = 9.81;
/// Lattice spacing: bodies on neighbouring sites touch or overlap.
const SITE_M: f64 = 0.007;
const MAX_BODIES: usize = 8;
const MAX_WALLS: usize = 4;

#[derive(Arbitrary, Debug, Clone, Copy)]
struct ClumpSphereIn {
    offset: Real3,
    radius: Real,
}

#[derive(Arbitrary, Debug, Clone)]
enum Shape {
    Sphere {
        radius: Real,
    },
    Clump {
        spheres: [ClumpSphereIn; 4],
        /// 2–4 spheres used.
        count: u8,
        /// Integrate mass properties on the core's grid (slow) instead of caller-given ones.
        integrate_mass: bool,
        inertia: Real3,
        axes: [Real; 4],
    },
}

#[derive(Arbitrary, Debug, Clone)]
struct BodyIn {
    shape: Shape,
    /// Lattice site: 3 bits each for x, y, z (a 8 × 8 × 4 block).
    site: u16,
    jitter: Real3,
    velocity: Real3,
    spin: Real3,
    second_material: bool,
}

#[derive(Arbitrary, Debug, Clone, Copy)]
enum WallIn {
    Plane {
        normal: Real3,
        offset: Real,
    },
    Cylinder {
        axis: Real3,
        radius: Real,
        length: Option<Real>,
    },
    AaBox {
        lo: Real3,
        hi: Real3,
    },
    OrificePlate {
        normal: Real3,
        offset: Real,
        hole: Real,
    },
}

#[derive(Arbitrary, Debug, Clone)]
struct Input {
    materials: [MaterialIn; 2],
    pairs: [PairIn; 3],
    gravity: Real3,
    /// Fixed-size arrays (not `Vec`s) so short inputs still get bodies: `1 + n_bodies % 8`
    /// bodies and `n_walls % 5` walls are used.
    bodies: [BodyIn; MAX_BODIES],
    n_bodies: u8,
    walls: [(WallIn, Real3, bool); MAX_WALLS],
    n_walls: u8,
    /// Body/sphere capacity shortfall (0 = enough) and neighbour-list entries per sphere (1–16).
    capacity_short: u8,
    slots: u8,
    dt_fraction: u8,
    steps: u8,
}

/// Centre of the lattice site, m.
fn site(code: u16, jitter: [f64; 3]) -> [f64; 3] {
    let x = f64::from(code & 7) - 3.5;
    let y = f64::from((code >> 3) & 7) - 3.5;
    let z = f64::from((code >> 6) & 3) + 1.0;
    [
        x * SITE_M + jitter[0],
        y * SITE_M + jitter[1],
        z * SITE_M + jitter[2],
    ]
}

/// Build the world in `arenas` and run it; returns the per-step outcomes and digests.
fn run<S: Scalar>(inp: &Input) -> Vec<(bool, u64)> {
    let n_bodies = usize::from(inp.n_bodies) % MAX_BODIES + 1;
    let n_spheres: usize = inp.bodies[..n_bodies]
        .iter()
        .map(|b| match &b.shape {
            Shape::Sphere { .. } => 1,
            Shape::Clump { count, .. } => usize::from(count % 3 + 2),
        })
        .sum();
    let short = usize::from(inp.capacity_short % 4);
    let cap_b = n_bodies.saturating_sub(short).max(1);
    let cap_s = n_spheres.saturating_sub(short).max(1);
    let mut arenas = Arenas::<S>::with_neighbours(cap_b, cap_s, usize::from(inp.slots % 16) + 1);
    let mut w = arenas.world();
    let mut trace = Vec::new();
    let Ok(a) = w.add_material(inp.materials[0].spec()) else {
        return trace;
    };
    let Ok(b) = w.add_material(inp.materials[1].spec()) else {
        return trace;
    };
    if w.set_pair(a, a, inp.pairs[0].spec()).is_err()
        || w.set_pair(a, b, inp.pairs[1].spec()).is_err()
        || w.set_pair(b, b, inp.pairs[2].spec()).is_err()
        || w.set_gravity_m_s2(inp.gravity.get(GRAVITY_M_S2)).is_err()
    {
        return trace;
    }
    for body in &inp.bodies[..n_bodies] {
        let mat = if body.second_material { b } else { a };
        let centre = site(body.site, body.jitter.get(RADIUS_M / 4.0));
        let v = body.velocity.get(SPEED_M_S);
        let om = body.spin.get(SPIN_RAD_S);
        // Set-up errors (including capacity) skip the body: the rest must still run.
        let _ = match &body.shape {
            Shape::Sphere { radius } => {
                let mut s = SphereSpec::at_rest(mat, radius.get(RADIUS_M), centre);
                s.velocity_m_s = v;
                s.angular_velocity_rad_s = om;
                w.add_sphere(s)
            }
            Shape::Clump {
                spheres,
                count,
                integrate_mass,
                inertia,
                axes,
            } => {
                let k = usize::from(count % 3 + 2);
                let cs: Vec<ClumpSphere> = spheres[..k]
                    .iter()
                    .map(|s| {
                        let o = s.offset.get(RADIUS_M / 2.0);
                        ClumpSphere {
                            center_m: [centre[0] + o[0], centre[1] + o[1], centre[2] + o[2]],
                            radius_m: s.radius.get(RADIUS_M / 1.5),
                            material: mat,
                        }
                    })
                    .collect();
                let spec = ClumpSpec {
                    spheres: &cs,
                    velocity_m_s: v,
                    angular_velocity_rad_s: om,
                };
                if *integrate_mass && n_bodies <= 2 {
                    w.add_clump(&spec)
                } else {
                    // Caller-given mass properties: typical pod-clump values, or extreme ones.
                    let mass = 582.0 * cs.iter().map(|s| 4.19 * s.radius_m.powi(3)).sum::<f64>();
                    let i_typ = 0.4 * mass * RADIUS_M * RADIUS_M;
                    let props = MassProperties {
                        mass_kg: mass,
                        center_of_mass_m: centre,
                        principal_inertia_kg_m2: inertia.get(i_typ),
                        principal_axes: axes.map(|q| q.get(0.5)),
                    };
                    w.add_clump_with_mass(&spec, &props)
                }
            }
        };
    }
    for (wall, velocity, move_it) in inp
        .walls
        .iter()
        .take(usize::from(inp.n_walls) % (MAX_WALLS + 1))
    {
        let geometry = match *wall {
            WallIn::Plane { normal, offset } => WallGeometry::Plane {
                point_m: [0.0, 0.0, offset.get(0.004)],
                normal: normal.get(1.0),
            },
            WallIn::Cylinder {
                axis,
                radius,
                length,
            } => WallGeometry::Cylinder {
                base_m: [0.0; 3],
                axis: axis.get(1.0),
                radius_m: radius.get(0.03),
                length_m: length.map(|l| l.get(0.05)),
            },
            WallIn::AaBox { lo, hi } => WallGeometry::AaBox {
                min_m: lo.get(-0.03),
                max_m: hi.get(0.03),
            },
            WallIn::OrificePlate {
                normal,
                offset,
                hole,
            } => WallGeometry::OrificePlate {
                centre_m: [0.0, 0.0, offset.get(0.004)],
                normal: normal.get(1.0),
                hole_radius_m: hole.get(0.005),
            },
        };
        let mut spec = WallSpec::fixed(geometry, b);
        if *move_it {
            spec.velocity_m_s = velocity.get(SPEED_M_S);
        }
        if let Ok(id) = w.add_wall(spec) {
            // A moving wall also spins about its own axis (a drum); a box refuses.
            if *move_it {
                let _ = w.set_wall_spin_rad_s(id, velocity.get(SPIN_RAD_S)[2]);
            }
        }
    }
    let max_dt = w.max_timestep_s();
    let dt = if max_dt.is_finite() {
        max_dt * (f64::from(inp.dt_fraction) + 1.0) / 256.0
    } else {
        2e-5
    };
    if w.set_timestep_s(dt).is_err() {
        return trace;
    }
    outcome(&format!(
        "{} setup ok, {} bodies",
        S::NAME,
        w.bodies().len()
    ));
    for k in 0..u64::from(inp.steps % 16 + 1) {
        let r = w.step();
        if let Err(e) = r {
            outcome(&format!("{} step error {e}", S::NAME));
            trace.push((false, 0));
            break;
        }
        assert_state_valid(&w, k + 1);
        trace.push((true, w.digest()));
    }
    outcome(&format!("{} ran {} steps", S::NAME, trace.len()));
    trace
}

fuzz_target!(|inp: Input| {
    let first = run::<Fx>(&inp);
    let second = run::<Fx>(&inp);
    assert_eq!(
        first, second,
        "the same input gave different step results or digests in two fixed-point runs"
    );
    let _ = run::<f64>(&inp);
});
