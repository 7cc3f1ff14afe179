//! The lane kernel against the f64 law and across its builds.

use super::*;
use crate::contact::fused::random_contacts::{self, contact, placed, Stream, POD, STEEL};
use crate::contact::fused::{evaluate as evaluate_f64, FusedContact, FusedPair, Geometry};
use crate::material::MaterialSpec;
use crate::num::{FxFast, Scalar, Vec3};

/// Q32.32 raw of x.
fn raw(x: f64) -> i64 {
    libm::round(x * 4294967296.0) as i64
}
/// x rounded to Q32.32.
fn q(x: f64) -> f64 {
    raw(x) as f64 / 4294967296.0
}
fn real(x: i64) -> f64 {
    x as f64 / 4294967296.0
}

/// The pair's constants, quantised to Q32.32 as the lane batch holds them.
fn pair(a: MaterialSpec, b: MaterialSpec, e: f64, mu: f64, mu_r: f64) -> FusedPair<f64> {
    random_contacts::pair(a, b, e, mu, mu_r).map(q)
}

/// Put contact `c` of pair `p` with history `delta` into lane `l` of `b`.
fn load_lane(
    b: &mut LaneBatch,
    l: usize,
    c: &FusedContact<f64>,
    p: &FusedPair<f64>,
    delta: Vec3<f64>,
) {
    let set3 = |v: &mut [Lanes; 3], x: Vec3<f64>| {
        v[0][l] = raw(x.x);
        v[1][l] = raw(x.y);
        v[2][l] = raw(x.z);
    };
    match c.geometry {
        Geometry::Spheres { d, r_j, .. } => {
            b.wall[l] = false;
            set3(&mut b.d, d);
            b.r_j[l] = raw(r_j);
        }
        Geometry::Wall { normal, overlap } => {
            b.wall[l] = true;
            set3(&mut b.d, normal);
            b.overlap[l] = raw(overlap);
        }
    }
    b.r_i[l] = raw(c.r_i);
    b.r_star[l] = raw(c.r_star);
    b.m_star[l] = raw(c.m_star);
    set3(&mut b.v, c.v_centres);
    set3(&mut b.spin_i, c.spin_i);
    set3(&mut b.spin_j, c.spin_j);
    set3(&mut b.offset_i, c.offset_i.unwrap_or(Vec3::ZERO));
    set3(&mut b.offset_j, c.offset_j.unwrap_or(Vec3::ZERO));
    b.clump_i[l] = c.offset_i.is_some();
    b.clump_j[l] = c.offset_j.is_some();
    set3(&mut b.delta, delta);
    b.set_pair(l, &p.map(FxFast::from_f64));
}

fn lane3(v: &[Lanes; 3], l: usize) -> Vec3<f64> {
    Vec3::new(real(v[0][l]), real(v[1][l]), real(v[2][l]))
}

/// Velocity error of the narrow formats: a few rounding units of Q.23, mm/ms.
const VELOCITY_ABS: f64 = 4.0 / 8388608.0;
/// History error of one step besides vt·dt: the Q.27 projection and narrowing, mm.
const HISTORY_ABS: f64 = 4.0 / 134217728.0;
/// Lever error: a few units of Q.25, mm.
const LEVER_ABS: f64 = 4.0 / 33554432.0;
/// Absolute rounding of a Q.32 output in a chain of a few products, N.
const FORCE_ABS: f64 = 3e-9;
/// Relative error of the block values: a dozen roundings of 2^-31 and the 2^-28 roots.
const RELATIVE: f64 = 2e-7;
/// Longest lever of the random contacts (sphere radius plus clump offset), mm.
const LEVER_MM: f64 = 24.0;

/// The lane kernel against the f64 law on 200 000 random contacts (spheres and walls, single
/// and clump spheres, soft and stiff pairs), within the error budget of the module docs:
/// [`RELATIVE`] of each vector's largest component, plus what the narrow velocities
/// ([`VELOCITY_ABS`]) move the damping forces and the history by, plus what the narrow
/// history and levers move forces and torques by.
#[test]
fn agrees_with_the_f64_law_inside_its_error_budget() {
    let mut s = Stream(0x2545_F491_4F6C_DD1D);
    let pairs = random_contacts::test_pairs().map(|(p, stiff)| (p.map(q), stiff));
    let (mut inside, mut both) = (0, 0);
    for batch in 0..200_000 / LANES {
        let mut b = LaneBatch::default();
        let mut cases = heapless::Vec::<_, LANES>::new();
        for l in 0..LANES {
            let k = batch * LANES + l;
            let (p, stiff) = pairs[k % 3];
            let (c, delta) = contact(&mut s, k % 4 == 0, k % 5 == 0, stiff);
            load_lane(&mut b, l, &c, &p, delta);
            let _ = cases.push((c, p, delta, k));
        }
        let dt = raw(cases[0].0.dt);
        for l in 0..LANES {
            cases[l].0.dt = real(dt);
        }
        let out = evaluate(&b, dt);
        for (l, (c, p, delta, k)) in cases.iter().enumerate() {
            let mut d_ref = *delta;
            let want = evaluate_f64(c, p, &mut d_ref);
            if out.ok[l] {
                inside += 1;
            }
            let Some(want) = want else { continue };
            if !out.ok[l] {
                continue;
            }
            both += 1;
            let alpha = match c.geometry {
                Geometry::Spheres { d, r_j, .. } => c.r_i + r_j - d.norm(),
                Geometry::Wall { overlap, .. } => overlap,
            };
            let a = libm::sqrt(c.r_star * alpha);
            let root_am = libm::sqrt(a * c.m_star);
            let st = p.eight_g_star * a;
            let damping = (p.normal_damping.abs() + p.tangential_damping.abs()) * root_am;
            let history_abs = HISTORY_ABS + VELOCITY_ABS * c.dt;
            let force_abs = FORCE_ABS + damping * VELOCITY_ABS + st * history_abs;
            let force_scale = want
                .force
                .x
                .abs()
                .max(want.force.y.abs())
                .max(want.force.z.abs());
            let torque_abs = LEVER_MM * force_abs + force_scale * LEVER_ABS;
            let check = |name: &str, g: Vec3<f64>, w: Vec3<f64>, abs: f64| {
                let scale = w.x.abs().max(w.y.abs()).max(w.z.abs());
                let err = (g - w).map(f64::abs);
                let e = err.x.max(err.y).max(err.z);
                let tol = RELATIVE * scale + abs;
                assert!(
                    e <= tol,
                    "{name} off by {e:e} (tolerance {tol:e}) in case {k}: {g:?} vs {w:?}; {c:?}"
                );
            };
            check("force", lane3(&out.force, l), want.force, force_abs);
            check(
                "torque i",
                lane3(&out.torque_i, l),
                want.torque_i,
                torque_abs,
            );
            check(
                "torque j",
                lane3(&out.torque_j, l),
                want.torque_j,
                torque_abs,
            );
            // A sliding contact's history is μs·Fn/St: the force budget over St.
            check(
                "history",
                lane3(&out.delta, l),
                d_ref,
                history_abs + force_abs / st,
            );
            let roll_abs =
                p.rolling_friction * (force_abs * LEVER_MM + want.force.norm() * LEVER_ABS);
            for (g, w) in [(out.roll_i[l], want.roll_i), (out.roll_j[l], want.roll_j)] {
                let tol = RELATIVE * w.abs() + roll_abs;
                assert!(
                    (real(g) - w).abs() <= tol,
                    "rolling off by {:e} ({tol:e}) in case {k}",
                    real(g) - w
                );
            }
        }
    }
    assert!(
        inside > 190_000,
        "only {inside} contacts inside the envelope"
    );
    assert!(both > 190_000, "only {both} contacts inside both envelopes");
}

/// Every build this processor runs gives the portable build's bits on random batches.
#[test]
fn every_build_gives_the_same_bits() {
    let mut s = Stream(0x0123_4567_89AB_CDEF);
    let pairs = [
        pair(POD, POD, 0.335, 0.854, 0.346),
        pair(STEEL, STEEL, 0.5, 0.3, 0.0),
    ];
    for batch in 0..20_000 / LANES {
        let mut b = LaneBatch::default();
        for l in 0..LANES {
            let k = batch * LANES + l;
            let (c, delta) = contact(&mut s, k % 3 == 0, k % 2 == 0, k % 7 == 0);
            load_lane(&mut b, l, &c, &pairs[k % 2], delta);
        }
        let want = evaluate_portable(&b, raw(0.02));
        for isa in Isa::ALL.into_iter().filter(|i| i.available()) {
            assert_eq!(
                evaluate_with(isa, &b, raw(0.02)),
                want,
                "{isa:?} in batch {batch}"
            );
        }
    }
}

/// A random contact anywhere in the envelope, up to its bounds: radii to 31 mm, centre
/// velocities to 31 mm/ms, spins to 63 rad/ms, histories to 7.9 mm, offsets to 31 mm.
fn extreme_contact(s: &mut Stream, wall: bool, clump: bool) -> (FusedContact<f64>, Vec3<f64>) {
    let r_i = q(s.range(0.01, 31.0));
    let r_j = q(s.range(0.01, 31.0));
    let rs = r_i + r_j;
    let overlap = s.range(1e-9, 0.49) * if wall { r_i } else { rs };
    let (geometry, _) = placed(s, r_i, r_j, overlap, wall);
    let c = FusedContact {
        geometry,
        r_i,
        r_star: if wall { r_i } else { q(r_i * r_j / rs) },
        m_star: q(s.log_range(1e-6, 1000.0)),
        v_centres: s.vec(31.0).map(q),
        spin_i: s.vec(63.0).map(q),
        spin_j: if wall { Vec3::ZERO } else { s.vec(63.0).map(q) },
        offset_i: clump.then(|| s.vec(31.0).map(q)),
        offset_j: (clump && !wall).then(|| s.vec(31.0).map(q)),
        dt: q(s.log_range(1e-6, 0.124)),
    };
    (c, s.vec(7.9).map(q))
}

/// No product of a lane inside the envelope reads an operand wider than 32 bits (which
/// [`crate::num::lanes::mul32`] would truncate): the formats' bounds hold, on contacts of the
/// bed and on contacts up to every bound of the envelope.
#[test]
fn narrow_products_see_every_bit() {
    let mut s = Stream(0x5851_F42D_4C95_7F2D);
    let pairs = [
        pair(POD, POD, 0.335, 0.854, 0.346),
        pair(POD, STEEL, 0.339, 0.589, 0.159),
        pair(STEEL, STEEL, 0.05, 4.0, 3.9),
    ];
    let mut checked = 0;
    for batch in 0..80_000 / LANES {
        let mut b = LaneBatch::default();
        let mut dt = 0;
        for l in 0..LANES {
            let k = batch * LANES + l;
            let (c, delta) = if batch % 2 == 0 {
                contact(&mut s, k % 4 == 0, k % 3 == 0, k % 5 == 0)
            } else {
                extreme_contact(&mut s, k % 4 == 0, k % 3 == 0)
            };
            dt = raw(c.dt);
            load_lane(&mut b, l, &c, &pairs[k % 3], delta);
        }
        crate::num::lanes::take_wide_operands();
        let out = evaluate_portable(&b, dt);
        let wide = crate::num::lanes::take_wide_operands();
        if out.ok.iter().all(|&ok| ok) {
            checked += 1;
            assert_eq!(wide, 0, "a truncated product in batch {batch}");
        }
    }
    assert!(
        checked > 1_000,
        "only {checked} batches lay wholly inside the envelope"
    );
}
