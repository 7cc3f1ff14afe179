//! Hand-run micro-benchmark of Fx division and square root (compare default vs
//! `--features pure-integer`): `cargo run --release -p arachis-core --example fx_ops`.
use arachis_core::num::{Fx, Scalar};
use std::hint::black_box;
use std::time::Instant;

fn main() {
    let n = 20_000_000u64;
    let mut x = 0x9e37_79b9_7f4a_7c15u64;
    let vals: Vec<Fx> = (0..1024)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            Fx::from_raw((x >> 24) as i64) // values in [0, 2^8)
        })
        .collect();
    let t = Instant::now();
    let mut acc = Fx::ZERO;
    for k in 0..n {
        acc += black_box(vals[(k & 1023) as usize]).sqrt();
    }
    let ts = t.elapsed().as_secs_f64() / n as f64 * 1e9;
    let t = Instant::now();
    for k in 0..n {
        acc += black_box(vals[(k & 1023) as usize])
            / black_box(vals[((k + 7) & 1023) as usize] + Fx::ONE);
    }
    let td = t.elapsed().as_secs_f64() / n as f64 * 1e9;
    println!(
        "sqrt {ts:.1} ns, div {td:.1} ns (checksum {:?})",
        acc.raw() & 0xff
    );
}
