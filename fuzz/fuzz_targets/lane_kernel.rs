//! Fuzz the narrow-lane contact kernel ([`arachis_core::contact::lanes`]) with raw Q32.32
//! inputs of any magnitude in every lane.
//!
//! Checked properties:
//! 1. nothing panics (overflow checks are on in the fuzz build): lane arithmetic wraps by
//!    design in lanes outside the envelope and must never trap;
//! 2. every build this processor runs (AVX-512, AVX2) gives the portable build's bits;
//! 3. a lane reported inside the envelope has its loads inside the documented bounds: force
//!    components below 2^13 N (plus the normal force's share, so 2^14), the new history below
//!    2^3 mm.

#![no_main]

use arachis_core::contact::lanes::{evaluate_portable, evaluate_with, Isa, LaneBatch, LANES};
use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;

/// One contact's raw fields.
#[derive(Arbitrary, Debug, Clone, Copy)]
struct LaneIn {
    wall: bool,
    clump_i: bool,
    clump_j: bool,
    d: [i64; 3],
    overlap: i64,
    r_i: i64,
    r_j: i64,
    r_star: i64,
    m_star: i64,
    v: [i64; 3],
    spin_i: [i64; 3],
    spin_j: [i64; 3],
    offset_i: [i64; 3],
    offset_j: [i64; 3],
    delta: [i64; 3],
    constants: [i64; 6],
}

#[derive(Arbitrary, Debug)]
struct Input {
    contacts: [LaneIn; 4],
    dt: i64,
}

/// One Q32.32 unit.
const ONE: i64 = 1 << 32;

fuzz_target!(|input: Input| {
    let mut b = LaneBatch::default();
    for l in 0..LANES {
        let c = input.contacts[l % input.contacts.len()];
        b.wall[l] = c.wall;
        b.clump_i[l] = c.clump_i;
        b.clump_j[l] = c.clump_j;
        b.overlap[l] = c.overlap;
        b.r_i[l] = c.r_i;
        b.r_j[l] = c.r_j;
        b.r_star[l] = c.r_star;
        b.m_star[l] = c.m_star;
        for k in 0..3 {
            b.d[k][l] = c.d[k];
            b.v[k][l] = c.v[k];
            b.spin_i[k][l] = c.spin_i[k];
            b.spin_j[k][l] = c.spin_j[k];
            b.offset_i[k][l] = c.offset_i[k];
            b.offset_j[k][l] = c.offset_j[k];
            b.delta[k][l] = c.delta[k];
        }
        [b.kn[l], b.cn[l], b.kt[l], b.ct[l], b.mu[l], b.mu_r[l]] = c.constants;
    }
    // Property 1: no panic.
    let want = evaluate_portable(&b, input.dt);
    // Property 2: the same bits in every build.
    for isa in Isa::ALL.into_iter().filter(|i| i.available()) {
        assert_eq!(evaluate_with(isa, &b, input.dt), want, "{isa:?}");
    }
    // Property 3: bounds of accepted lanes.
    for l in 0..LANES {
        if !want.ok[l] {
            continue;
        }
        for k in 0..3 {
            assert!(want.force[k][l].unsigned_abs() < (1 << 14) * ONE as u64, "force");
            assert!(want.delta[k][l].unsigned_abs() < 8 * ONE as u64, "history");
        }
    }
});
