//! Hand-run throughput check on the DESIGN §8 bed (not a benchmark; the criterion bench lives
//! in `benches/`). `cargo run --release -p arachis-core --example throughput -- [N] [STEPS] [f64]`
use arachis_core::prelude::*;
use std::time::Instant;

/// User CPU seconds of this process (from /proc; 0 where unavailable). Wall time is
/// unreliable on a shared machine, CPU time much less so.
fn cpu_s() -> f64 {
    std::fs::read_to_string("/proc/self/stat")
        .ok()
        .and_then(|s| {
            s.rsplit(')').next().map(|r| {
                r.split_whitespace()
                    .nth(11)
                    .unwrap_or("0")
                    .parse::<f64>()
                    .unwrap_or(0.0)
            })
        })
        .unwrap_or(0.0)
        / 100.0
}

fn run<S: Scalar>(n: usize, steps: u64) {
    let mut arenas = arachis_core::owned::OwnedStorage::<S>::new(StorageLengths::for_spheres(n, n));
    let mut w = World::new(arenas.storage()).unwrap();
    let pod = w
        .add_material(MaterialSpec {
            youngs_modulus_pa: 8.43e6,
            poisson: 0.386,
            density_kg_m3: 582.0,
        })
        .unwrap();
    let steel = w
        .add_material(MaterialSpec {
            youngs_modulus_pa: 2.05e11,
            poisson: 0.3,
            density_kg_m3: 7865.0,
        })
        .unwrap();
    w.set_pair(pod, pod, PairSpec::hertz_mindlin(0.335, 0.854, 0.346))
        .unwrap();
    w.set_pair(pod, steel, PairSpec::hertz_mindlin(0.339, 0.589, 0.159))
        .unwrap();
    w.set_gravity_m_s2([0.0, 0.0, -9.81]).unwrap();
    w.add_wall(WallSpec::fixed(
        WallGeometry::Plane {
            point_m: [0.0; 3],
            normal: [0.0, 0.0, 1.0],
        },
        steel,
    ))
    .unwrap();
    w.add_wall(WallSpec::fixed(
        WallGeometry::Cylinder {
            base_m: [0.0; 3],
            axis: [0.0, 0.0, 1.0],
            radius_m: 0.05,
            length_m: None,
        },
        steel,
    ))
    .unwrap();
    // Deterministic lattice-jittered insertion, no overlap, r ≤ 45 mm, 10 ≤ z ≤ 400 mm.
    let mut seed = 0x1234_5678_9abc_def0u64;
    let mut rnd = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    // Random insertion without overlap (rejection sampling), r ≤ 45 mm, 10 ≤ z ≤ 400 mm.
    let mut pts: Vec<[f64; 3]> = Vec::new();
    while pts.len() < n {
        let x = (rnd() * 2.0 - 1.0) * 0.041;
        let y = (rnd() * 2.0 - 1.0) * 0.041;
        if (x * x + y * y).sqrt() > 0.041 {
            continue;
        }
        let z = 0.014 + rnd() * (0.396 - 0.014);
        if pts
            .iter()
            .any(|p| (p[0] - x).powi(2) + (p[1] - y).powi(2) + (p[2] - z).powi(2) < 0.0081 * 0.0081)
        {
            continue;
        }
        pts.push([x, y, z]);
    }
    // Optional perturbation of the first sphere (nm), to measure chaotic divergence.
    let nudge_nm: f64 = std::env::var("NUDGE_NM")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(0.0);
    pts[0][0] += nudge_nm * 1e-9;
    for p in pts {
        let mut s = SphereSpec::at_rest(pod, 0.004, p);
        s.velocity_m_s = [0.0, 0.0, -0.2];
        w.add_sphere(s).unwrap();
    }
    w.set_timestep_s(2e-5).unwrap();
    let t0 = Instant::now();
    let c0 = cpu_s();
    let mut last = t0;
    let mut last_cpu = c0;
    for k in 0..steps {
        w.step().unwrap();
        if (k + 1) % 5000 == 0 {
            let now = Instant::now();
            let cpu = cpu_s();
            let top = w
                .bodies()
                .iter()
                .map(|b| b.position.z.to_f64())
                .fold(0.0, f64::max);
            let bottom = w
                .bodies()
                .iter()
                .map(|b| b.position.z.to_f64())
                .fold(f64::MAX, f64::min);
            let rmax = w
                .bodies()
                .iter()
                .map(|b| {
                    let p = b.position.to_f64();
                    (p[0] * p[0] + p[1] * p[1]).sqrt()
                })
                .fold(0.0, f64::max);
            println!("bottom {bottom:.2} mm, max radial {rmax:.2} mm");
            println!(
                "step {:6} ke {:.3e} mJ contacts {} top {:.1} mm  last block {:.3} ms/step wall, {:.3} ms/step cpu",
                k + 1,
                w.kinetic_energy_mj(),
                w.contact_count(),
                top,
                (now - last).as_secs_f64() * 1e3 / 5000.0,
                (cpu - last_cpu) * 1e3 / 5000.0
            );
            last = now;
            last_cpu = cpu;
        }
    }
    let secs = t0.elapsed().as_secs_f64();
    let cpu = cpu_s() - c0;
    println!(
        "cpu {cpu:.2} s = {:.3e} particle-steps per cpu-second",
        n as f64 * steps as f64 / cpu
    );
    let mut tops: Vec<f64> = w
        .spheres()
        .iter()
        .map(|s| (s.position.z + s.radius).to_f64())
        .collect();
    tops.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let bed = tops[(0.95 * (tops.len() - 1) as f64).round() as usize];
    let com = w
        .bodies()
        .iter()
        .map(|b| b.position.z.to_f64())
        .sum::<f64>()
        / n as f64;
    println!(
        "bed height (p95 of z+R) {bed:.4} mm, mean z {com:.4} mm, KE {:.3e} mJ",
        w.kinetic_energy_mj()
    );
    println!(
        "{}: {} spheres x {} steps in {:.3} s = {:.3e} particle-steps/s ({:.3} ms/step); digest {:016x}",
        S::NAME,
        n,
        steps,
        secs,
        n as f64 * steps as f64 / secs,
        secs * 1e3 / steps as f64,
        w.digest()
    );
}

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let n = a.get(1).and_then(|s| s.parse().ok()).unwrap_or(2000);
    let steps = a.get(2).and_then(|s| s.parse().ok()).unwrap_or(20_000);
    if a.get(3).map(|s| s == "f64").unwrap_or(false) {
        run::<f64>(n, steps);
    } else {
        run::<Fx>(n, steps);
    }
}
