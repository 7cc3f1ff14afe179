//! Random contacts for the kernels' tests: the fused law's Q32.32 kernel ([`super::fixed`])
//! and the narrow-lane kernel ([`crate::contact::lanes`]) are both checked against the f64
//! law on the same kind of contacts (spheres and walls, single and clump spheres, soft and
//! stiff pairs), quantised to Q32.32 so that every kernel sees the same inputs.

use super::{evaluate as evaluate_f64, FusedContact, FusedLoad, FusedPair, Geometry};
use crate::contact::CohesionJkr;
use crate::material::MaterialSpec;
use crate::num::{FxFast, Scalar, Vec3};
use crate::pair::{PairParams, PairSpec};

/// A deterministic stream of uniform numbers in [0, 1).
pub(crate) struct Stream(pub(crate) u64);
impl Stream {
    /// The next 64 raw bits (Marsaglia's xorshift64).
    pub(crate) fn bits(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    pub(crate) fn next(&mut self) -> f64 {
        (self.bits() >> 11) as f64 / (1u64 << 53) as f64
    }
    pub(crate) fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
    pub(crate) fn log_range(&mut self, lo: f64, hi: f64) -> f64 {
        libm::exp(self.range(libm::log(lo), libm::log(hi)))
    }
    /// A vector with components in ±(a log-uniform scale in [lo, hi]).
    pub(crate) fn vec_log(&mut self, lo: f64, hi: f64) -> Vec3<f64> {
        let scale = self.log_range(lo, hi);
        self.vec(scale)
    }
    pub(crate) fn vec(&mut self, scale: f64) -> Vec3<f64> {
        Vec3::new(
            self.range(-scale, scale),
            self.range(-scale, scale),
            self.range(-scale, scale),
        )
    }
}

/// The fused-law constants of a Hertz–Mindlin pair of `a` and `b` (e, μs, μr).
pub(crate) fn pair(a: MaterialSpec, b: MaterialSpec, e: f64, mu: f64, mu_r: f64) -> FusedPair<f64> {
    let (a, b) = (a.validate().unwrap(), b.validate().unwrap());
    PairParams::<f64>::new(&a, &b, &PairSpec::hertz_mindlin(e, mu, mu_r)).fused
}

/// The pairs of [`test_pairs`] with JKR cohesion: pod–pod sticky as the field's soil (work
/// of adhesion 2 J/m²), pod–steel 0.5 J/m², steel–steel 0.1 J/m².
pub(crate) fn jkr_pairs() -> [(FusedPair<f64>, bool); 3] {
    [
        (sticky(POD, POD, 0.335, 0.854, 0.346, 2.0).fused, false),
        (sticky(POD, STEEL, 0.339, 0.589, 0.159, 0.5).fused, false),
        (sticky(STEEL, STEEL, 0.5, 0.3, 0.0, 0.1).fused, true),
    ]
}

/// The pair of materials `a`, `b` with Hertz–Mindlin (e, μs, μr) and JKR cohesion of work of
/// adhesion `gamma` (J/m²), fused (and checked eligible for the fused law with JKR).
pub(crate) fn sticky(
    a: MaterialSpec,
    b: MaterialSpec,
    e: f64,
    mu: f64,
    mu_r: f64,
    gamma: f64,
) -> PairParams<f64> {
    let (a, b) = (a.validate().unwrap(), b.validate().unwrap());
    let mut p = PairParams::<f64>::new(&a, &b, &PairSpec::hertz_mindlin(e, mu, mu_r));
    p.jkr = CohesionJkr::new(gamma, p.e_star_mpa);
    p.fuse();
    assert!(p.fused.eligible && p.fused.jkr);
    p
}

/// The pairs the kernels are tested on, and whether each is stiff (steel on steel, whose
/// overlaps are ten times smaller): pod–pod and pod–steel of seed 000, steel–steel.
pub(crate) fn test_pairs() -> [(FusedPair<f64>, bool); 3] {
    [
        (pair(POD, POD, 0.335, 0.854, 0.346), false),
        (pair(POD, STEEL, 0.339, 0.589, 0.159), false),
        (pair(STEEL, STEEL, 0.5, 0.3, 0.0), true),
    ]
}

/// Pod material (DESIGN §8).
pub(crate) const POD: MaterialSpec = MaterialSpec {
    youngs_modulus_pa: 8.43e6,
    poisson: 0.386,
    density_kg_m3: 582.0,
};
/// 65Mn steel (DESIGN §8).
pub(crate) const STEEL: MaterialSpec = MaterialSpec {
    youngs_modulus_pa: 2.05e11,
    poisson: 0.3,
    density_kg_m3: 7865.0,
};

/// A random contact inside the envelope, quantised to Q32.32 so that both kernels see the
/// same inputs.
pub(crate) fn contact(
    s: &mut Stream,
    wall: bool,
    clump: bool,
    stiff: bool,
) -> (FusedContact<f64>, Vec3<f64>) {
    let q = |x: f64| FxFast::from_f64(x).to_f64();
    let r_i = q(s.range(1.0, 10.0));
    let r_j = q(s.range(1.0, 10.0));
    let rs = r_i + r_j;
    // Overlaps from 1e-7 of the reach (onset) to 2 % (a hard impact); 10x smaller on steel.
    let overlap = s.log_range(1e-7, 2e-2) * rs * if stiff { 0.1 } else { 1.0 };
    let (geometry, n) = placed(s, r_i, r_j, overlap, wall);
    let r_star = if wall { r_i } else { q(r_i * r_j / rs) };
    let c = FusedContact {
        geometry,
        r_i,
        r_star,
        m_star: q(s.log_range(0.01, 50.0)),
        v_centres: s.vec_log(1e-6, 10.0).map(q),
        spin_i: s.vec_log(1e-6, 1.0).map(q),
        spin_j: if wall {
            Vec3::ZERO
        } else {
            s.vec_log(1e-6, 1.0).map(q)
        },
        offset_i: clump.then(|| s.vec(8.0).map(q)),
        offset_j: (clump && !wall).then(|| s.vec(8.0).map(q)),
        dt: q(s.log_range(5e-4, 5e-2)),
    };
    // History nearly in the tangent plane, as the law keeps it: projected each step, it
    // leans out of the plane only by the normal's turn in one step.
    let delta = s.vec_log(1e-9, 0.05);
    let delta = delta - n.scale(delta.dot(n) * (1.0 - 1e-3));
    (c, delta.map(q))
}

/// A contact of radii `r_i`, `r_j` (mm) and overlap `overlap` (mm) along a random unit
/// normal, with a wall (`wall`) or a sphere, quantised: its geometry and the normal.
pub(crate) fn placed(
    s: &mut Stream,
    r_i: f64,
    r_j: f64,
    overlap: f64,
    wall: bool,
) -> (Geometry<f64>, Vec3<f64>) {
    let q = |x: f64| FxFast::from_f64(x).to_f64();
    let n = {
        let v = s.vec(1.0);
        v.scale(1.0 / v.norm())
    };
    let geometry = if wall {
        Geometry::Wall {
            normal: n.map(q),
            overlap: q(overlap),
        }
    } else {
        let d = n.scale(r_i + r_j - overlap).map(q);
        Geometry::Spheres {
            d,
            d2: d.norm2(),
            r_j,
        }
    };
    (geometry, n)
}

/// A Q32.32 kernel under test: the fused law on raw contacts, `None` outside its envelope.
pub(crate) type Kernel =
    fn(&FusedContact<FxFast>, &FusedPair<FxFast>, &mut Vec3<FxFast>) -> Option<FusedLoad<FxFast>>;

/// What a kernel's own formats add to the shared budget of [`agreement`] for one contact:
/// on the force (N), the torques (N·mm), the rolling torques (N·mm) and the history (mm).
pub(crate) struct Extra {
    pub(crate) force: f64,
    pub(crate) torque: f64,
    pub(crate) roll: f64,
    pub(crate) history: f64,
}

/// Absolute part of the tolerance on forces (N) and history (mm): a dozen Q32.32 units of
/// rounding in a chain of products.
pub(crate) const FORCE_ABS: f64 = 3e-9;
/// One unit of a Q.32 force, N.
pub(crate) const FORCE_UNIT_N: f64 = 2.33e-10;
/// The longest lever of the random contacts (sphere radius plus clump offset), mm.
pub(crate) const LEVER_MM: f64 = 24.0;
/// The same on torques (N·mm): the force's rounding times the longest lever.
pub(crate) const TORQUE_ABS: f64 = LEVER_MM * FORCE_ABS;
/// The Q32.32 overlap is rounded (to within a unit, 2^-32 mm, with the distance's own
/// rounding) in both this kernel and the checked terms, where the f64 law has it
/// exact: an error of the fixed-point format, not of the kernel.
pub(crate) const OVERLAP_ROUNDING_MM: f64 = 2.0 * 2.33e-10;
/// The Q32.32 history is rounded in every step's projection and increment (up to eight units
/// of 2^-32 mm) in both this kernel and the checked terms.
pub(crate) const HISTORY_ROUNDING_MM: f64 = 8.0 * 2.33e-10;
/// Relative tolerance: the kernel's own error budget (module docs), a few 1e-7, with
/// margin.
pub(crate) const RELATIVE: f64 = 2e-6;

/// A kernel against the f64 law on 200 000 random contacts of `pairs` (spheres and walls,
/// single and clump spheres, soft and stiff pairs): every force, torque, rolling torque and
/// new history component agrees within [`RELATIVE`] of the largest component of its vector,
/// plus what the Q.32 rounding of the overlap and the history ([`OVERLAP_ROUNDING_MM`],
/// [`HISTORY_ROUNDING_MM`]) moves it by, plus [`FORCE_ABS`] or [`TORQUE_ABS`], plus the
/// kernel's own `extra`. Returns how many contacts lay inside the kernel's envelope.
pub(crate) fn agreement(
    pairs: &[(FusedPair<f64>, bool); 3],
    seed: u64,
    kernel: Kernel,
    extra: impl Fn(&FusedPair<f64>, &FusedContact<f64>, f64, &FusedLoad<f64>) -> Extra,
) -> usize {
    let mut s = Stream(seed);
    let mut inside = 0;
    for k in 0..200_000 {
        let (p, stiff) = pairs[k % 3];
        let (c, delta0) = contact(&mut s, k % 4 == 0, k % 5 == 0, stiff);
        let mut d_ref = delta0;
        let Some(want) = evaluate_f64(&c, &p, &mut d_ref) else {
            continue;
        };
        let to = |x: f64| FxFast::from_f64(x);
        let mut d_fix = delta0.map(to);
        let Some(got) = kernel(&c.map(to), &p.map(to), &mut d_fix) else {
            continue;
        };
        inside += 1;
        // Loads scale at most as α^1.5 (Hertz), so the Q.32 overlap's rounding moves them
        // by at most 1.5·δα/α of themselves.
        let alpha = match c.geometry {
            Geometry::Spheres { d, r_j, .. } => c.r_i + r_j - d.norm(),
            Geometry::Wall { overlap, .. } => overlap,
        };
        let rel = RELATIVE + 1.5 * OVERLAP_ROUNDING_MM / alpha;
        // The Q.32 history's rounding times the tangential stiffness 8G*·a.
        let st = p.eight_g_star * libm::sqrt(c.r_star * alpha);
        let history_abs = st * HISTORY_ROUNDING_MM;
        let more = extra(&p, &c, alpha, &want);
        let (force_abs, torque_abs) = (
            FORCE_ABS + history_abs + more.force,
            TORQUE_ABS + LEVER_MM * history_abs + more.torque,
        );
        let check = |name: &str, g: Vec3<FxFast>, w: Vec3<f64>, abs: f64| {
            let scale = w.x.abs().max(w.y.abs()).max(w.z.abs());
            let err = (g.map(|x| x.to_f64()) - w).map(|x| x.abs());
            let e = err.x.max(err.y).max(err.z);
            let tol = rel * scale + abs;
            assert!(
                e <= tol,
                "{name} off by {e:e} (tolerance {tol:e}) in case {k}: {g:?} vs {w:?}; {c:?}; history {delta0:?}; α {alpha:e}"
            );
        };
        let roll = |g: FxFast, w: f64| g.to_f64() - w;
        check("force", got.force, want.force, force_abs);
        check("torque i", got.torque_i, want.torque_i, torque_abs);
        check("torque j", got.torque_j, want.torque_j, torque_abs);
        // A sliding contact's history is μs·Fn/St: the Q.32 limit's rounding over St.
        check(
            "history",
            d_fix,
            d_ref,
            FORCE_ABS + 2.0 * FORCE_UNIT_N / st + more.history,
        );
        for (g, w) in [(got.roll_i, want.roll_i), (got.roll_j, want.roll_j)] {
            assert!(
                roll(g, w).abs() <= rel * w.abs() + TORQUE_ABS + more.roll,
                "rolling off in case {k}: {g:?} vs {w:e}; {c:?}"
            );
        }
    }
    inside
}
