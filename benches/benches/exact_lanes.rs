//! Exact Q32.32 arithmetic in AVX-512 IFMA lanes, eight values at a time, against the scalar
//! 128-bit arithmetic of the fused kernel ([`arachis_core::contact::fused::fixed`]): the
//! measurements behind issue 16's vector plan (`core/API_NOTES.md`, "Exact Q32.32 products in
//! AVX-512 IFMA lanes"). Nothing here is used by the step yet.
//! - `exact_lanes/product`: the kernel's rounded product (a·b + 2^31) >> 32 of signed
//!   operands below 2^52;
//! - `exact_lanes/coarse_root`: the kernel's coarse root (`sqrt_coarse`) of radicands below
//!   2^64 (an even normalising shift, the 768-entry reciprocal-root table, two Newton steps,
//!   one product, the shift back rounded);
//! - `exact_lanes/law_arithmetic`: the kernel's formulas after its geometry and roots (spin
//!   velocity, contact velocity, Hertz and both dampings, projected history and its
//!   increment, spring, tangential force, the Coulomb test on exact squares, force and both
//!   torques: 59 products) on settled pod contacts.
//!
//! Each group first checks that the lanes give the scalar bits on every input (it panics
//! otherwise), then times both; criterion's elements are products, roots or contacts. On a
//! processor without AVX-512 IFMA the groups print a note and time nothing.
//!
//! Run: `cargo bench -p arachis-benches --bench exact_lanes`.

// The scalar references index several component arrays by one component index, as the
// kernel writes them.
#![allow(clippy::needless_range_loop)]
// The AVX-512 intrinsics are stable since Rust 1.89, above the workspace's declared 1.85: this
// bench needs 1.89 to compile (the core and the host do not use them).
#![allow(clippy::incompatible_msrv)]

use arachis_core::contact::fused::fixed::{dot_wide, mul_sub_wide, mul_wide, sqrt_coarse};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::arch::x86_64::*;
use std::hint::black_box;

/// Inputs per group (a multiple of the eight lanes).
const COUNT: usize = 4096;
/// Fraction bits of the state (Q.32).
const STATE: u32 = 32;
/// Fraction bits of the unit normal (Q.30).
const UNIT: u32 = 30;
/// Entries of the reciprocal-root table: top-10-bit values 256..=1023 of a normalised input.
const TABLE_LEN: usize = 768;

/// Whether this processor runs the lane code.
fn has_ifma() -> bool {
    is_x86_feature_detected!("avx512f")
        && is_x86_feature_detected!("avx512dq")
        && is_x86_feature_detected!("avx512cd")
        && is_x86_feature_detected!("avx512ifma")
}

/// A deterministic xorshift64 stream.
struct Stream(u64);
impl Stream {
    fn bits(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    /// Uniform in [lo, hi).
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * ((self.bits() >> 11) as f64 / (1u64 << 53) as f64)
    }
}

/// A value in raw Q32.32.
fn q(x: f64) -> i64 {
    (x * 4294967296.0).round() as i64
}

// ---- Scalar references: the kernel's own 128-bit arithmetic. ----

/// The kernel's reciprocal-root table (`num::fixed_fast`, private there, and of `u32`): entry
/// i = ⌊√(2^71/(2(i + 256) + 1))⌋, as 64-bit entries for the lanes' gather. The root group
/// checks the lanes against the kernel's own [`sqrt_coarse`], so an entry that differed would
/// fail it.
fn rsqrt_table() -> Vec<u64> {
    (0..TABLE_LEN)
        .map(|i| ((1u128 << 71) / (2 * (i as u128 + 256) + 1)).isqrt() as u64)
        .collect()
}

/// Settled pod contacts after geometry and roots, structure of arrays (raw Q32.32; the
/// normal Q.30).
#[derive(Default)]
struct Contacts {
    n: [Vec<i64>; 3],
    li: Vec<i64>,
    lj: Vec<i64>,
    alpha: Vec<i64>,
    v: [Vec<i64>; 3],
    wi: [Vec<i64>; 3],
    wj: [Vec<i64>; 3],
    d0: [Vec<i64>; 3],
    a: Vec<i64>,
    root_am: Vec<i64>,
}

/// The pair constants (raw Q32.32): (4/3)E*, normal damping, 8G*, tangential damping, μs,
/// and the time step.
struct Pair {
    kn: i64,
    cn: i64,
    kt: i64,
    ct: i64,
    mu: i64,
    dt: i64,
}

/// What the law's arithmetic gives per contact: force, torques, new history, Fn, sliding.
#[derive(Clone, PartialEq, Debug)]
struct Loads {
    force: [Vec<i64>; 3],
    torque_i: [Vec<i64>; 3],
    torque_j: [Vec<i64>; 3],
    history: [Vec<i64>; 3],
    normal: Vec<i64>,
    sliding: Vec<i64>,
}

impl Loads {
    fn zeros(m: usize) -> Self {
        let z = || [vec![0; m], vec![0; m], vec![0; m]];
        Loads {
            force: z(),
            torque_i: z(),
            torque_j: z(),
            history: z(),
            normal: vec![0; m],
            sliding: vec![0; m],
        }
    }
}

/// Pod–pod contacts of a settled bed: R 4 mm, overlaps 0.001–0.03 mm, m* 0.08 g, slow
/// motion and a small history.
fn settled_contacts(m: usize) -> (Contacts, Pair) {
    let mut s = Stream(0x2545_F491_4F6C_DD1D);
    let mut c = Contacts::default();
    for _ in 0..m {
        let (turn, z) = (s.range(0.0, std::f64::consts::TAU), s.range(-1.0, 1.0));
        let r = (1.0 - z * z).sqrt();
        let n = [r * turn.cos(), r * turn.sin(), z];
        for k in 0..3 {
            c.n[k].push((n[k] * (1u64 << UNIT) as f64).round() as i64);
        }
        let alpha = s.range(0.001, 0.03);
        let a = (2.0 * alpha).sqrt();
        c.alpha.push(q(alpha));
        c.li.push(q(4.0 - alpha / 2.0));
        c.lj.push(q(4.0 - alpha / 2.0));
        c.a.push(q(a));
        c.root_am.push(q((a * 0.08).sqrt()));
        for k in 0..3 {
            c.v[k].push(q(s.range(-0.05, 0.05)));
            c.wi[k].push(q(s.range(-0.02, 0.02)));
            c.wj[k].push(q(s.range(-0.02, 0.02)));
            c.d0[k].push(q(s.range(-2e-4, 2e-4)));
        }
    }
    let pair = Pair {
        kn: q(6.7),
        cn: q(2.0),
        kt: q(24.0),
        ct: q(3.5),
        mu: q(0.854),
        dt: q(0.02),
    };
    (c, pair)
}

/// The law's arithmetic of the fused kernel (`fused::fixed::evaluate_jkr` after its
/// geometry and roots, without JKR, clumps or rolling), contact by contact.
fn law_scalar(p: &Pair, x: &Contacts, o: &mut Loads) {
    for c in 0..x.li.len() {
        let at = |v: &[Vec<i64>; 3]| [v[0][c], v[1][c], v[2][c]];
        let (n, v, wi, wj, d0) = (at(&x.n), at(&x.v), at(&x.wi), at(&x.wj), at(&x.d0));
        let (li, lj, alpha, a, root_am) = (x.li[c], x.lj[c], x.alpha[c], x.a[c], x.root_am[c]);
        let spin: [i64; 3] = std::array::from_fn(|k| {
            ((wi[k] as i128 * li as i128 + wj[k] as i128 * lj as i128 + (1i128 << 31)) >> STATE)
                as i64
        });
        let vc = [
            v[0] - mul_sub_wide(spin[1], n[2], spin[2], n[1], UNIT),
            v[1] - mul_sub_wide(spin[2], n[0], spin[0], n[2], UNIT),
            v[2] - mul_sub_wide(spin[0], n[1], spin[1], n[0], UNIT),
        ];
        let vn = dot_wide(vc, n, UNIT);
        let vt: [i64; 3] = std::array::from_fn(|k| vc[k] - mul_wide(n[k], vn, UNIT));
        let elastic = mul_wide(mul_wide(p.kn, a, STATE), alpha, STATE);
        let f_n = (elastic - mul_wide(mul_wide(p.cn, root_am, STATE), vn, STATE)).max(0);
        let dn = dot_wide(d0, n, UNIT);
        let d1: [i64; 3] = std::array::from_fn(|k| {
            d0[k] - mul_wide(n[k], dn, UNIT) + mul_wide(vt[k], p.dt, STATE)
        });
        let st = mul_wide(p.kt, a, STATE);
        let damp_t = mul_wide(p.ct, root_am, STATE);
        let f_t: [i64; 3] =
            std::array::from_fn(|k| -(mul_wide(st, d1[k], STATE) + mul_wide(damp_t, vt[k], STATE)));
        let limit = mul_wide(p.mu, f_n, STATE);
        let f2: i128 = f_t.iter().map(|&f| f as i128 * f as i128).sum();
        let tau = [
            mul_sub_wide(n[1], f_t[2], n[2], f_t[1], UNIT),
            mul_sub_wide(n[2], f_t[0], n[0], f_t[2], UNIT),
            mul_sub_wide(n[0], f_t[1], n[1], f_t[0], UNIT),
        ];
        for k in 0..3 {
            o.force[k][c] = mul_wide(n[k], f_n, UNIT) + f_t[k];
            o.torque_i[k][c] = mul_wide(tau[k], li, STATE);
            o.torque_j[k][c] = -mul_wide(tau[k], lj, STATE);
            o.history[k][c] = d1[k];
        }
        o.normal[c] = f_n;
        o.sliding[c] = (f2 > limit as i128 * limit as i128) as i64;
    }
}

/// The lane code: each signed product is a 104-bit pair (hi, lo), value hi·2^52 + lo with
/// lo in [0, 2^52), from the two IFMA halves of |a|·|b| and the sign; sums of pairs (lo below
/// 2^54) are rounded once, as the kernel rounds a dot product.
mod lanes {
    use super::*;

    /// The signed product a·b of operands below 2^52 as a pair (hi, lo).
    #[inline(always)]
    unsafe fn product(a: __m512i, b: __m512i) -> (__m512i, __m512i) {
        let negative = _mm512_movepi64_mask(_mm512_xor_si512(a, b));
        let (ua, ub) = (_mm512_abs_epi64(a), _mm512_abs_epi64(b));
        let zero = _mm512_setzero_si512();
        let lo = _mm512_madd52lo_epu64(zero, ua, ub);
        let hi = _mm512_madd52hi_epu64(zero, ua, ub);
        // −(hi·2^52 + lo) = (−hi − [lo ≠ 0])·2^52 + (2^52 − lo)·[lo ≠ 0].
        let nonzero = _mm512_test_epi64_mask(lo, lo);
        let neg_lo = _mm512_maskz_sub_epi64(nonzero, _mm512_set1_epi64(1 << 52), lo);
        let neg_hi = _mm512_sub_epi64(
            _mm512_sub_epi64(zero, hi),
            _mm512_maskz_set1_epi64(nonzero, 1),
        );
        (
            _mm512_mask_blend_epi64(negative, hi, neg_hi),
            _mm512_mask_blend_epi64(negative, lo, neg_lo),
        )
    }

    /// The sum of two pairs.
    #[inline(always)]
    unsafe fn add(
        (h1, l1): (__m512i, __m512i),
        (h2, l2): (__m512i, __m512i),
    ) -> (__m512i, __m512i) {
        (_mm512_add_epi64(h1, h2), _mm512_add_epi64(l1, l2))
    }

    /// A pair rounded to nearest (ties up) and shifted right by S (L = 52 − S): exact, since
    /// hi·2^52 is a multiple of 2^S.
    #[inline(always)]
    unsafe fn round<const S: u32, const L: u32>((hi, lo): (__m512i, __m512i)) -> __m512i {
        let half = _mm512_set1_epi64(1 << (S - 1));
        _mm512_add_epi64(
            _mm512_slli_epi64::<L>(hi),
            _mm512_srli_epi64::<S>(_mm512_add_epi64(lo, half)),
        )
    }

    /// The kernel's `mul_wide(a, b, 32)`.
    #[inline(always)]
    unsafe fn mul32(a: __m512i, b: __m512i) -> __m512i {
        round::<32, 20>(product(a, b))
    }

    /// The kernel's `mul_wide(a, b, 30)`.
    #[inline(always)]
    unsafe fn mul30(a: __m512i, b: __m512i) -> __m512i {
        round::<30, 22>(product(a, b))
    }

    /// The kernel's `mul_sub_wide(a, b, c, d, 30)`.
    #[inline(always)]
    unsafe fn mul_sub30(a: __m512i, b: __m512i, c: __m512i, d: __m512i) -> __m512i {
        let minus_d = _mm512_sub_epi64(_mm512_setzero_si512(), d);
        round::<30, 22>(add(product(a, b), product(c, minus_d)))
    }

    /// The kernel's `dot_wide(a, b, 30)`.
    #[inline(always)]
    unsafe fn dot30(a: [__m512i; 3], b: [__m512i; 3]) -> __m512i {
        round::<30, 22>(add(
            add(product(a[0], b[0]), product(a[1], b[1])),
            product(a[2], b[2]),
        ))
    }

    /// [`super::mul_wide`]`(a, b, 32)` on every element.
    #[target_feature(enable = "avx512f,avx512dq,avx512ifma")]
    pub unsafe fn products(a: &[i64], b: &[i64], out: &mut [i64]) {
        for c in (0..a.len()).step_by(8) {
            let x = _mm512_loadu_si512(a.as_ptr().add(c) as *const _);
            let y = _mm512_loadu_si512(b.as_ptr().add(c) as *const _);
            _mm512_storeu_si512(out.as_mut_ptr().add(c) as *mut _, mul32(x, y));
        }
    }

    /// The kernel's [`sqrt_coarse`] on every element (each nonzero, below 2^64).
    #[target_feature(enable = "avx512f,avx512dq,avx512cd")]
    pub unsafe fn roots(table: &[u64], v: &[u64], out: &mut [u64]) {
        // Entry i of the table answers the top ten bits 256 + i.
        let base = table.as_ptr().sub(256) as *const i64;
        let three = _mm512_set1_epi64(3 << 30);
        for c in (0..v.len()).step_by(8) {
            let radicand = _mm512_loadu_si512(v.as_ptr().add(c) as *const _);
            let k = _mm512_andnot_si512(_mm512_set1_epi64(1), _mm512_lzcnt_epi64(radicand));
            let x = _mm512_sllv_epi64(radicand, k);
            let x32 = _mm512_srli_epi64::<32>(x);
            let mut y = _mm512_i64gather_epi64::<8>(_mm512_srli_epi64::<54>(x), base);
            for _ in 0..2 {
                let y2 = _mm512_srli_epi64::<30>(_mm512_mullo_epi64(y, y));
                let t = _mm512_srli_epi64::<32>(_mm512_mullo_epi64(x32, y2));
                let f = _mm512_max_epi64(_mm512_sub_epi64(three, t), _mm512_setzero_si512());
                y = _mm512_srli_epi64::<31>(_mm512_mullo_epi64(y, f));
            }
            let r = _mm512_srli_epi64::<30>(_mm512_mullo_epi64(x32, y));
            // Back by half the normalising shift, rounded to nearest as the kernel's `shr`
            // (no rounding for a shift of zero: half of 2^0 is 0).
            let back = _mm512_srli_epi64::<1>(k);
            let half = _mm512_srli_epi64::<1>(_mm512_sllv_epi64(_mm512_set1_epi64(1), back));
            let r = _mm512_srlv_epi64(_mm512_add_epi64(r, half), back);
            _mm512_storeu_si512(out.as_mut_ptr().add(c) as *mut _, r);
        }
    }

    /// [`super::law_scalar`], eight contacts at a time.
    #[target_feature(enable = "avx512f,avx512dq,avx512ifma")]
    pub unsafe fn law(p: &Pair, x: &Contacts, o: &mut Loads) {
        let zero = _mm512_setzero_si512();
        let all = |w: i64| _mm512_set1_epi64(w);
        for c in (0..x.li.len()).step_by(8) {
            let ld = |v: &Vec<i64>| _mm512_loadu_si512(v.as_ptr().add(c) as *const _);
            let ld3 = |v: &[Vec<i64>; 3]| [ld(&v[0]), ld(&v[1]), ld(&v[2])];
            let (n, v, wi, wj, d0) = (ld3(&x.n), ld3(&x.v), ld3(&x.wi), ld3(&x.wj), ld3(&x.d0));
            let (li, lj, alpha, a, root_am) =
                (ld(&x.li), ld(&x.lj), ld(&x.alpha), ld(&x.a), ld(&x.root_am));
            let spin: [__m512i; 3] = std::array::from_fn(|k| {
                round::<32, 20>(add(product(wi[k], li), product(wj[k], lj)))
            });
            let vc = [
                _mm512_sub_epi64(v[0], mul_sub30(spin[1], n[2], spin[2], n[1])),
                _mm512_sub_epi64(v[1], mul_sub30(spin[2], n[0], spin[0], n[2])),
                _mm512_sub_epi64(v[2], mul_sub30(spin[0], n[1], spin[1], n[0])),
            ];
            let vn = dot30(vc, n);
            let vt: [__m512i; 3] =
                std::array::from_fn(|k| _mm512_sub_epi64(vc[k], mul30(n[k], vn)));
            let elastic = mul32(mul32(all(p.kn), a), alpha);
            let damping = mul32(mul32(all(p.cn), root_am), vn);
            let f_n = _mm512_max_epi64(_mm512_sub_epi64(elastic, damping), zero);
            let dn = dot30(d0, n);
            let d1: [__m512i; 3] = std::array::from_fn(|k| {
                _mm512_add_epi64(
                    _mm512_sub_epi64(d0[k], mul30(n[k], dn)),
                    mul32(vt[k], all(p.dt)),
                )
            });
            let st = mul32(all(p.kt), a);
            let damp_t = mul32(all(p.ct), root_am);
            let f_t: [__m512i; 3] = std::array::from_fn(|k| {
                _mm512_sub_epi64(
                    zero,
                    _mm512_add_epi64(mul32(st, d1[k]), mul32(damp_t, vt[k])),
                )
            });
            let limit = mul32(all(p.mu), f_n);
            // The Coulomb test on exact squares: pairs carried to lo < 2^52, then compared.
            let carry = |(h, l): (__m512i, __m512i)| {
                (
                    _mm512_add_epi64(h, _mm512_srli_epi64::<52>(l)),
                    _mm512_and_si512(l, all((1 << 52) - 1)),
                )
            };
            let (fh, fl) = carry(add(
                add(product(f_t[0], f_t[0]), product(f_t[1], f_t[1])),
                product(f_t[2], f_t[2]),
            ));
            let (lh, ll) = carry(product(limit, limit));
            let sliding = _mm512_cmpgt_epi64_mask(fh, lh)
                | (_mm512_cmpeq_epi64_mask(fh, lh) & _mm512_cmpgt_epi64_mask(fl, ll));
            let tau = [
                mul_sub30(n[1], f_t[2], n[2], f_t[1]),
                mul_sub30(n[2], f_t[0], n[0], f_t[2]),
                mul_sub30(n[0], f_t[1], n[1], f_t[0]),
            ];
            let st_ = |v: &mut Vec<i64>, w: __m512i| {
                _mm512_storeu_si512(v.as_mut_ptr().add(c) as *mut _, w)
            };
            for k in 0..3 {
                st_(&mut o.force[k], _mm512_add_epi64(mul30(n[k], f_n), f_t[k]));
                st_(&mut o.torque_i[k], mul32(tau[k], li));
                st_(
                    &mut o.torque_j[k],
                    _mm512_sub_epi64(zero, mul32(tau[k], lj)),
                );
                st_(&mut o.history[k], d1[k]);
            }
            st_(&mut o.normal, f_n);
            st_(&mut o.sliding, _mm512_maskz_set1_epi64(sliding, 1));
        }
    }
}

fn bench_product(c: &mut Criterion) {
    if !has_ifma() {
        eprintln!("exact_lanes/product: no AVX-512 IFMA on this processor, not timed");
        return;
    }
    let mut s = Stream(0x9E37_79B9_7F4A_7C15);
    // Signed operands of 0 to 52 bits whose product fits the kernel's i64 results.
    let operand = |s: &mut Stream| {
        let magnitude = (s.bits() >> 12) >> (s.bits() % 52);
        let sign = if s.bits() & 1 == 0 { 1 } else { -1 };
        magnitude as i64 * sign
    };
    let (mut a, mut b) = (Vec::new(), Vec::new());
    while a.len() < COUNT {
        let (x, y) = (operand(&mut s), operand(&mut s));
        if ((x as i128 * y as i128) >> 32).unsigned_abs() < 1 << 62 {
            a.push(x);
            b.push(y);
        }
    }
    let want: Vec<i64> = a
        .iter()
        .zip(&b)
        .map(|(&x, &y)| mul_wide(x, y, STATE))
        .collect();
    let mut got = vec![0; COUNT];
    // SAFETY: the processor has the features (`has_ifma`); the slices have COUNT elements, a
    // multiple of eight.
    unsafe { lanes::products(&a, &b, &mut got) };
    assert_eq!(got, want, "the lanes' products differ from the kernel's");
    let mut g = c.benchmark_group("exact_lanes/product");
    g.throughput(Throughput::Elements(COUNT as u64));
    g.bench_function("scalar_i128", |bench| {
        bench.iter(|| {
            for k in 0..COUNT {
                got[k] = mul_wide(black_box(a[k]), b[k], STATE);
            }
            black_box(&got);
        })
    });
    g.bench_function("ifma_lanes", |bench| {
        // SAFETY: as above.
        bench.iter(|| unsafe { lanes::products(black_box(&a), &b, &mut got) })
    });
    g.finish();
}

fn bench_root(c: &mut Criterion) {
    if !has_ifma() {
        eprintln!("exact_lanes/coarse_root: no AVX-512 IFMA on this processor, not timed");
        return;
    }
    let table = rsqrt_table();
    let mut s = Stream(0x2545_F491_4F6C_DD1D);
    let v: Vec<u64> = (0..COUNT)
        .map(|_| {
            let x = s.bits();
            (x >> (x % 40)) | 1
        })
        .collect();
    let want: Vec<u64> = v.iter().map(|&x| sqrt_coarse(x as u128) as u64).collect();
    let mut got = vec![0; COUNT];
    // SAFETY: the processor has the features; the slices have COUNT elements, a multiple of
    // eight; every radicand is nonzero, so its top ten bits after normalising are 256..=1023.
    unsafe { lanes::roots(&table, &v, &mut got) };
    assert_eq!(got, want, "the lanes' roots differ from the kernel's");
    let mut g = c.benchmark_group("exact_lanes/coarse_root");
    g.throughput(Throughput::Elements(COUNT as u64));
    g.bench_function("scalar", |bench| {
        bench.iter(|| {
            for k in 0..COUNT {
                got[k] = sqrt_coarse(black_box(v[k]) as u128) as u64;
            }
            black_box(&got);
        })
    });
    g.bench_function("lanes", |bench| {
        // SAFETY: as above.
        bench.iter(|| unsafe { lanes::roots(&table, black_box(&v), &mut got) })
    });
    g.finish();
}

fn bench_law(c: &mut Criterion) {
    if !has_ifma() {
        eprintln!("exact_lanes/law_arithmetic: no AVX-512 IFMA on this processor, not timed");
        return;
    }
    let (x, p) = settled_contacts(COUNT);
    let (mut want, mut got) = (Loads::zeros(COUNT), Loads::zeros(COUNT));
    law_scalar(&p, &x, &mut want);
    // SAFETY: the processor has the features; every array has COUNT elements, a multiple of
    // eight; the settled contacts keep every operand below 2^52.
    unsafe { lanes::law(&p, &x, &mut got) };
    assert_eq!(got, want, "the lanes' loads differ from the kernel's");
    let mut g = c.benchmark_group("exact_lanes/law_arithmetic");
    g.throughput(Throughput::Elements(COUNT as u64));
    g.bench_function("scalar_i128", |bench| {
        bench.iter(|| law_scalar(&p, black_box(&x), &mut got))
    });
    g.bench_function("ifma_lanes", |bench| {
        // SAFETY: as above.
        bench.iter(|| unsafe { lanes::law(&p, black_box(&x), &mut got) })
    });
    g.finish();
}

criterion_group!(benches, bench_product, bench_root, bench_law);
criterion_main!(benches);
