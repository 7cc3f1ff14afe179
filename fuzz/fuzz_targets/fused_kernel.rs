//! Fuzz the fused base law's integer kernel ([`arachis_core::contact::fused::fixed`]) directly,
//! with raw Q32.32 inputs of any magnitude: the kernel that every base-law contact takes.
//!
//! Checked properties:
//! 1. nothing panics (overflow checks are on in the fuzz build, so a product or sum that
//!    wraps inside the kernel is a crash): the envelope tests must reject every input that
//!    could overflow before the arithmetic it protects;
//! 2. a result is `Some` only inside the documented bounds: force components below 2^13 N,
//!    the new history below 2^3 mm;
//! 3. for inputs that the f64 law also accepts, the two agree on the force to the error
//!    budget of the kernel's own test (2e-6 of the force, plus what the Q.32 rounding of the
//!    overlap moves it by, plus the history's rounding times the tangential stiffness);
//! 4. with JKR cohesion on the pair and a last root (an attached contact, which the kernel
//!    also evaluates apart, across its neck; the overlap may be negative), properties 1 and 2
//!    hold, and a neck that breaks comes back with no load, no history and no root.

#![no_main]

#[path = "common/mod.rs"]
mod common;

use arachis_core::contact::fused::{
    evaluate, evaluate_fast_jkr, FusedContact, FusedLoad, Geometry,
};
use arachis_core::contact::CohesionJkr;
use arachis_core::num::{FxFast, Scalar, Vec3};
use arachis_core::pair::PairParams;
use arbitrary::Arbitrary;
use common::{MaterialIn, PairIn, Real, Real3};
use libfuzzer_sys::fuzz_target;

#[derive(Arbitrary, Debug)]
struct Input {
    a: MaterialIn,
    b: MaterialIn,
    pair: PairIn,
    wall: bool,
    /// Sphere: centre offset j − i, mm. Wall: normal direction (normalised in f64).
    d: Real3,
    r_i: Real,
    r_j: Real,
    overlap: Real,
    m_star: Real,
    v: Real3,
    w_i: Real3,
    w_j: Real3,
    offset_i: Option<Real3>,
    offset_j: Option<Real3>,
    delta: Real3,
    dt: Real,
    /// JKR work of adhesion, J/m² (absolute value), and the contact's last root √a, √mm.
    jkr: Option<(Real, Real)>,
}

/// Absolute force tolerance, N: a dozen Q32.32 units.
const FORCE_ABS: f64 = 3e-9;
/// Bounds of a result, as in the kernel's envelope: force < 2^13 N, history < 2^3 mm.
const FORCE_LIMIT: f64 = 8192.0;
const DELTA_LIMIT: f64 = 8.0;

fuzz_target!(|input: Input| {
    let (Ok(a), Ok(b)) = (input.a.spec().validate(), input.b.spec().validate()) else {
        return;
    };
    let spec = input.pair.spec();
    if spec.validate().is_err() {
        return;
    }
    let mut params = PairParams::<f64>::new(&a, &b, &spec);
    if let Some((gamma, _)) = input.jkr {
        params.jkr = CohesionJkr::new(gamma.get(2.0).abs(), params.e_star_mpa);
        params.fuse();
    }
    let pair = params.fused;
    if !pair.eligible {
        return;
    }
    let q = |x: f64| FxFast::from_f64(x).to_f64();
    let v3 = |r: Real3, t: f64| {
        let v = r.get(t);
        Vec3::new(q(v[0]), q(v[1]), q(v[2]))
    };
    let r_i = q(input.r_i.get(4.0).abs());
    let r_j = q(input.r_j.get(4.0).abs());
    let dir = {
        let v = input.d.get(1.0);
        let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        if !(n > 0.0 && n.is_finite()) {
            return;
        }
        [v[0] / n, v[1] / n, v[2] / n]
    };
    let overlap = input.overlap.get(0.02);
    let geometry = if input.wall {
        Geometry::Wall {
            normal: Vec3::new(q(dir[0]), q(dir[1]), q(dir[2])),
            overlap: q(overlap),
        }
    } else {
        let dist = r_i + r_j - overlap;
        let d = Vec3::new(q(dir[0] * dist), q(dir[1] * dist), q(dir[2] * dist));
        Geometry::Spheres {
            d,
            d2: d.norm2(),
            r_j,
        }
    };
    let c = FusedContact {
        geometry,
        r_i,
        r_star: if input.wall {
            r_i
        } else {
            q(r_i * r_j / (r_i + r_j))
        },
        m_star: q(input.m_star.get(0.1).abs()),
        v_centres: v3(input.v, 0.1),
        spin_i: v3(input.w_i, 0.01),
        spin_j: if input.wall {
            Vec3::ZERO
        } else {
            v3(input.w_j, 0.01)
        },
        offset_i: input.offset_i.map(|o| v3(o, 4.0)),
        offset_j: if input.wall {
            None
        } else {
            input.offset_j.map(|o| v3(o, 4.0))
        },
        dt: q(input.dt.get(0.02).abs()),
    };
    let delta0 = v3(input.delta, 0.001);
    let to = |x: f64| FxFast::from_f64(x);
    let fixed_pair = pair.map(to);
    let mut delta = delta0.map(to);
    let last_root = input.jkr.map_or(0.0, |(_, x)| x.get(0.5).abs());
    let mut root = to(last_root);
    // Property 1: no panic, whatever the inputs.
    let Some(got) = evaluate_fast_jkr(&c.map(to), &fixed_pair, &mut delta, &mut root) else {
        return;
    };
    // Property 4: a broken neck carries nothing.
    if pair.jkr && root == FxFast::ZERO {
        assert_eq!(got, FusedLoad::default(), "a broken neck with a load");
        assert_eq!(delta, Vec3::ZERO, "a broken neck with history");
    }
    // Property 2: inside the bounds.
    let f = got.force.map(|x| x.to_f64());
    let d = delta.map(|x| x.to_f64());
    for x in [f.x, f.y, f.z] {
        assert!(
            x.abs() < 2.0 * FORCE_LIMIT,
            "force {f:?} beyond the envelope"
        );
    }
    for x in [d.x, d.y, d.z] {
        assert!(x.abs() < DELTA_LIMIT, "history {d:?} beyond the envelope");
    }
    // Property 3: agreement with the f64 law where both accept the contact (the base law;
    // the JKR root's own budget is the kernel's unit test's).
    if pair.jkr {
        return;
    }
    let mut d_ref = delta0;
    let Some(want) = evaluate(&c, &pair, &mut d_ref) else {
        return;
    };
    let alpha = match c.geometry {
        Geometry::Spheres { d, r_j, .. } => c.r_i + r_j - d.norm(),
        Geometry::Wall { overlap, .. } => overlap,
    };
    let a_ref = (c.r_star * alpha).sqrt();
    let scale = want
        .force
        .x
        .abs()
        .max(want.force.y.abs())
        .max(want.force.z.abs());
    let tol = (2e-6 + 1.5 * 4.7e-10 / alpha) * scale
        + FORCE_ABS
        + pair.eight_g_star * a_ref * 8.0 * 2.33e-10;
    let err = (f - want.force).map(|x| x.abs());
    // The tangential history can be at its Coulomb limit in one law and just under it in the
    // other; the comparison is meaningful for well-conditioned, sticking contacts.
    let sticking = d_ref.norm() * pair.eight_g_star * a_ref < 0.5 * pair.friction * scale;
    if sticking && alpha > 1e-6 {
        assert!(
            err.x.max(err.y).max(err.z) <= tol,
            "force {f:?} vs f64 {:?} (tolerance {tol:e})",
            want.force
        );
    }
});
