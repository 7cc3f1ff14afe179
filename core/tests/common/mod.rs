//! Test support: owned storage and small world builders.

use arachis_core::owned::OwnedStorage;
use arachis_core::prelude::*;
use std::sync::{Arc, Mutex, PoisonError};

/// Owned arenas for a world (the core never allocates; tests use its `alloc` feature).
pub struct Owned<S: Scalar>(pub OwnedStorage<S>);

impl<S: Scalar> Owned<S> {
    /// Arenas for `bodies` bodies and `spheres` spheres, with room for effect history.
    pub fn new(bodies: usize, spheres: usize) -> Self {
        Self::with_lengths(StorageLengths::for_spheres(bodies, spheres).with_effects())
    }
    pub fn with_lengths(l: StorageLengths) -> Self {
        Owned(OwnedStorage::new(l))
    }
    pub fn storage(&mut self) -> Storage<'_, S> {
        self.0.storage()
    }
}

/// Adds the fixed floor plane z = 0 (normal +z) of `material`: the plate, incline or
/// ground most single-body tests roll, slide or drop onto.
pub fn add_floor<S: Scalar>(w: &mut World<'_, S>, material: MaterialId) {
    w.add_wall(WallSpec::fixed(
        WallGeometry::Plane {
            point_m: [0.0; 3],
            normal: [0.0, 0.0, 1.0],
        },
        material,
    ))
    .unwrap();
}

/// A world over `o` with pod and steel materials and `pair` for pod–pod and pod–steel
/// contacts: the set-up of the wall tests. Returns the world and the (pod, steel) ids.
pub fn pod_steel_world<S: Scalar>(
    o: &mut Owned<S>,
    pair: PairSpec,
) -> (World<'_, S>, MaterialId, MaterialId) {
    let mut w = World::new(o.storage()).unwrap();
    let pod = w.add_material(POD).unwrap();
    let steel = w.add_material(STEEL).unwrap();
    w.set_pair(pod, steel, pair).unwrap();
    w.set_pair(pod, pod, pair).unwrap();
    (w, pod, steel)
}

/// Peanut pod material (seed 000 §3.1).
pub const POD: MaterialSpec = MaterialSpec {
    youngs_modulus_pa: 8.43e6,
    poisson: 0.386,
    density_kg_m3: 582.36,
};
/// 65Mn steel (DESIGN §8).
pub const STEEL: MaterialSpec = MaterialSpec {
    youngs_modulus_pa: 2.05e11,
    poisson: 0.3,
    density_kg_m3: 7865.0,
};

/// Alumina-like stiff material for the Chung & Ooi elastic tests (E 70 GPa, ν 0.3, ρ 2700).
pub const STIFF: MaterialSpec = MaterialSpec {
    youngs_modulus_pa: 7.0e10,
    poisson: 0.3,
    density_kg_m3: 2700.0,
};

/// Only the normal terms (Hertz + damping); μ = 0, no rolling.
pub fn normal_only(e: f64) -> PairSpec {
    PairSpec {
        restitution: e,
        friction: 0.0,
        rolling_friction: 0.0,
        conventions: arachis_core::contact::Conventions::EDEM,
        terms: TermSwitches {
            hertz_normal: true,
            normal_damping: true,
            mindlin_tangential: false,
            tangential_damping: false,
            coulomb_limit: false,
            rolling_cdt: false,
        },
    }
}

/// E* in MPa of two materials (DESIGN §2).
pub fn e_star_mpa(a: &MaterialSpec, b: &MaterialSpec) -> f64 {
    let p = |m: &MaterialSpec| (1.0 - m.poisson * m.poisson) / (m.youngs_modulus_pa * 1e-6);
    1.0 / (p(a) + p(b))
}

/// Sphere mass in g for radius in mm and density in kg/m³.
pub fn sphere_mass_g(r_mm: f64, rho_kg_m3: f64) -> f64 {
    rho_kg_m3 * 1e-6 * 4.0 / 3.0 * std::f64::consts::PI * r_mm.powi(3)
}

/// Hertz elastic impact theory (units mm, g, ms, MPa, N): (max overlap, peak force, duration).
pub fn hertz_theory(m_star: f64, r_star: f64, e_star: f64, v: f64) -> (f64, f64, f64) {
    let a_max = (15.0 * m_star * v * v / (16.0 * e_star * r_star.sqrt())).powf(0.4);
    let f_max = 4.0 / 3.0 * e_star * r_star.sqrt() * a_max.powf(1.5);
    // Exact duration constant: 2·∫₀¹ dx/√(1−x^{5/2}) · (15/16)^{2/5} = 2.9432 × ... expressed as
    // t_c = 2.868 (m*²/(R* E*² v))^{1/5} (Johnson 1985; Chung & Ooi 2011 quote 2.87).
    let t_c = 2.868_265 * (m_star * m_star / (r_star * e_star * e_star * v)).powf(0.2);
    (a_max, f_max, t_c)
}

/// Independent single-contact integration (adaptive Dormand–Prince RK45 in f64) of
/// m* α'' = −max(0, (4/3)E*√(R*α)·α + 2√(5/6)(−β)√(2E*√(R*α)·m*)·α'), started at α = 0,
/// α' = v (approach speed); returns the separation speed (α' when α returns to 0).
pub fn restitution_reference(m_star: f64, r_star: f64, e_star: f64, e: f64, v: f64) -> f64 {
    let l = e.ln();
    let beta = l / (l * l + std::f64::consts::PI.powi(2)).sqrt();
    let damp = 2.0 * (5.0f64 / 6.0).sqrt() * (-beta);
    let acc = |a: f64, ad: f64| -> f64 {
        if a <= 0.0 {
            return 0.0;
        }
        let ca = (r_star * a).sqrt();
        let fel = 4.0 / 3.0 * e_star * ca * a;
        let fd = damp * (2.0 * e_star * ca * m_star).sqrt() * ad;
        -(fel + fd).max(0.0) / m_star
    };
    let f = |y: [f64; 2]| [y[1], acc(y[0], y[1])];
    let (a_max, _, t_c) = hertz_theory(m_star, r_star, e_star, v);
    let mut h = t_c * 1e-4;
    let mut y = [0.0, v];
    let mut t = 0.0;
    // Dormand–Prince 5(4) coefficients.
    let a: [[f64; 6]; 7] = [
        [0.0; 6],
        [0.2, 0.0, 0.0, 0.0, 0.0, 0.0],
        [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
        [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
        [
            19372.0 / 6561.0,
            -25360.0 / 2187.0,
            64448.0 / 6561.0,
            -212.0 / 729.0,
            0.0,
            0.0,
        ],
        [
            9017.0 / 3168.0,
            -355.0 / 33.0,
            46732.0 / 5247.0,
            49.0 / 176.0,
            -5103.0 / 18656.0,
            0.0,
        ],
        [
            35.0 / 384.0,
            0.0,
            500.0 / 1113.0,
            125.0 / 192.0,
            -2187.0 / 6784.0,
            11.0 / 84.0,
        ],
    ];
    let b5 = [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
        0.0,
    ];
    let b4 = [
        5179.0 / 57600.0,
        0.0,
        7571.0 / 16695.0,
        393.0 / 640.0,
        -92097.0 / 339200.0,
        187.0 / 2100.0,
        1.0 / 40.0,
    ];
    let tol = 1e-12;
    loop {
        let mut k = [[0.0f64; 2]; 7];
        for s in 0..7 {
            let mut ys = y;
            for (j, kj) in k.iter().enumerate().take(s) {
                ys[0] += h * a[s][j] * kj[0];
                ys[1] += h * a[s][j] * kj[1];
            }
            k[s] = f(ys);
        }
        let mut y5 = y;
        let mut y4 = y;
        for s in 0..7 {
            for d in 0..2 {
                y5[d] += h * b5[s] * k[s][d];
                y4[d] += h * b4[s] * k[s][d];
            }
        }
        let err = ((y5[0] - y4[0]).abs() / (a_max * tol)).max((y5[1] - y4[1]).abs() / (v * tol));
        if err <= 1.0 {
            if y5[0] <= 0.0 && t > 0.0 {
                // Crossed α = 0: the force is continuous (the clip reaches 0 before α does) and
                // zero from there on, so the velocity is the separation speed.
                return -y5[1];
            }
            y = y5;
            t += h;
        }
        let fac = (0.9 * err.powf(-0.2)).clamp(0.2, 5.0);
        h *= fac;
        h = h.min(t_c * 1e-3);
    }
}

/// A runner that runs the parts of a stage on a rayon pool of as many threads: real
/// concurrency by a thread pool that is not the host's, for the thread-count tests. The
/// pool of each count is built once per test binary and its idle threads sleep, so tests of
/// several counts at once do not starve each other (a runner that spawned a thread per part
/// and stage spent most of the thread-count test starting threads). It reports random job
/// times ([`Parallel::job_times`]), so the step moves its cuts at random as well: a cut that
/// changed a bit would show in the digests.
pub struct Threads {
    parts: usize,
    pool: Arc<rayon::ThreadPool>,
    /// State of the random job times (xorshift64).
    times: Mutex<u64>,
}

impl Threads {
    /// A runner of `parts` parts on the test binary's pool of `parts` threads.
    pub fn new(parts: usize) -> Self {
        static POOLS: Mutex<Vec<(usize, Arc<rayon::ThreadPool>)>> = Mutex::new(Vec::new());
        let mut pools = POOLS.lock().unwrap_or_else(PoisonError::into_inner);
        let pool = match pools.iter().find(|(n, _)| *n == parts) {
            Some((_, pool)) => pool.clone(),
            None => {
                let pool = Arc::new(
                    rayon::ThreadPoolBuilder::new()
                        .num_threads(parts)
                        .build()
                        .expect("a thread pool for the thread-count tests"),
                );
                pools.push((parts, pool.clone()));
                pool
            }
        };
        Threads {
            parts,
            pool,
            times: Mutex::new(0x9e37_79b9_7f4a_7c15 ^ parts as u64),
        }
    }
}

impl Parallel for Threads {
    fn parts(&self) -> usize {
        self.parts
    }
    fn for_each<J: Send>(&self, jobs: &mut [J], f: &(dyn Fn(&mut J) + Sync)) {
        self.pool.scope(|s| {
            for j in jobs.iter_mut() {
                s.spawn(move |_| f(j));
            }
        });
    }
    /// Random times from 1 to 10^6 units (xorshift64).
    fn job_times(&self, out: &mut [u64]) -> bool {
        let mut x = self.times.lock().unwrap_or_else(PoisonError::into_inner);
        for t in out.iter_mut() {
            *x ^= *x << 13;
            *x ^= *x >> 7;
            *x ^= *x << 17;
            *t = 1 + *x % 1_000_000;
        }
        true
    }
}

/// Run `steps` steps of `w` split into `threads` parts on as many threads.
pub fn run_threaded<S: Scalar>(w: &mut World<'_, S>, steps: u64, threads: usize) {
    let bodies = w.bodies().len();
    let mut scratch = arachis_core::owned::OwnedThreadScratch::<S>::new(threads, bodies);
    let mut arenas = scratch.arenas();
    let runner = Threads::new(threads);
    for _ in 0..steps {
        w.step_with(&runner, &mut arenas).unwrap();
    }
}
