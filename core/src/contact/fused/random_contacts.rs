//! Random contacts for the kernels' tests: the fused law's Q32.32 kernel ([`super::fixed`])
//! and the narrow-lane kernel ([`crate::contact::lanes`]) are both checked against the f64
//! law on the same kind of contacts (spheres and walls, single and clump spheres, soft and
//! stiff pairs), quantised to Q32.32 so that every kernel sees the same inputs.

use super::{FusedContact, FusedPair, Geometry};
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
