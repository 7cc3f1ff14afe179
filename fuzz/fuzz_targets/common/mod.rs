//! Helpers shared by the fuzz targets: numbers that reach both extreme and physical values,
//! owned world storage, and state checks.

#![allow(dead_code)] // each target uses a subset

use arachis_core::owned::OwnedStorage;
use arachis_core::prelude::*;
use arbitrary::Arbitrary;

/// A real input. Raw `f64` bits alone almost never give physical values, so most variants
/// map the fuzz bytes onto a scale: around a typical value, or log-uniform over ±40 decades.
/// `Near` comes first so that inputs cut short (arbitrary fills missing bytes with zeros) get
/// the typical value.
#[derive(Arbitrary, Debug, Clone, Copy)]
pub enum Real {
    /// `±typical × 2^(k/32)`: within a factor 16 of the typical value.
    Near { k: i8, neg: bool },
    /// Exactly zero.
    Zero,
    /// `±(1 + m/65536) × 10^e`, e clamped to ±40: extreme magnitudes.
    Log { m: u16, e: i8, neg: bool },
    /// Any bit pattern (NaN, ±∞, subnormals...).
    Raw(f64),
}

impl Real {
    /// The value, given the scale's typical value.
    pub fn get(self, typical: f64) -> f64 {
        let sign = |neg: bool, v: f64| if neg { -v } else { v };
        match self {
            Real::Near { k, neg } => sign(neg, typical * (f64::from(k) / 32.0).exp2()),
            Real::Zero => 0.0,
            Real::Log { m, e, neg } => sign(
                neg,
                (1.0 + f64::from(m) / 65536.0) * 10f64.powi(i32::from(e.clamp(-40, 40))),
            ),
            Real::Raw(x) => x,
        }
    }
}

/// A 3-vector input: each component a [`Real`] on the same scale.
#[derive(Arbitrary, Debug, Clone, Copy)]
pub struct Real3(pub [Real; 3]);

impl Real3 {
    /// The vector, given the typical component.
    pub fn get(self, typical: f64) -> [f64; 3] {
        self.0.map(|r| r.get(typical))
    }
}

/// A material input.
#[derive(Arbitrary, Debug, Clone, Copy)]
pub struct MaterialIn {
    pub youngs_modulus: Real,
    pub poisson: Real,
    pub density: Real,
}

impl MaterialIn {
    /// Typical values: pod E 8.43 MPa, ν 0.386 (a `Near` ν spans ±0.02–6: invalid ones too),
    /// ρ 582 kg/m³.
    pub fn spec(&self) -> MaterialSpec {
        MaterialSpec {
            youngs_modulus_pa: self.youngs_modulus.get(8.43e6),
            poisson: self.poisson.get(0.386),
            density_kg_m3: self.density.get(582.0),
        }
    }
}

/// A pair-interaction input.
#[derive(Arbitrary, Debug, Clone, Copy)]
pub struct PairIn {
    pub restitution: Real,
    pub friction: Real,
    pub rolling: Real,
    /// Term switches, one bit each (bits 0–5: a set bit turns that term off); bits 6 and 7
    /// put rolling friction and the Coulomb limit in LIGGGHTS' conventions, and bit 8 makes
    /// LIGGGHTS' rolling `epsd2` instead of `cdt`.
    pub terms: u16,
}

impl PairIn {
    /// Typical e 0.335, μs 0.854, μr 0.346 (pod–pod).
    pub fn spec(&self) -> PairSpec {
        let bit = |k: u16| self.terms & (1 << k) == 0; // all on for terms = 0
        PairSpec {
            restitution: self.restitution.get(0.335),
            friction: self.friction.get(0.854),
            rolling_friction: self.rolling.get(0.346),
            conventions: arachis_core::contact::Conventions {
                rolling: match (self.terms & (1 << 6) != 0, self.terms & (1 << 8) != 0) {
                    (false, _) => RollingConvention::Edem,
                    (true, false) => RollingConvention::LiggghtsCdt,
                    (true, true) => RollingConvention::LiggghtsEpsd2,
                },
                friction: if self.terms & (1 << 7) != 0 {
                    FrictionConvention::Liggghts
                } else {
                    FrictionConvention::Edem
                },
            },
            terms: TermSwitches {
                hertz_normal: bit(0),
                normal_damping: bit(1),
                mindlin_tangential: bit(2),
                tangential_damping: bit(3),
                coulomb_limit: bit(4),
                rolling_cdt: bit(5),
            },
        }
    }
}

/// Owned arenas for a small world.
pub struct Arenas<S: Scalar>(OwnedStorage<S>);

impl<S: Scalar> Arenas<S> {
    /// Arenas for `bodies` bodies and `spheres` spheres, default list and cell counts, with
    /// room for effect history.
    pub fn new(bodies: usize, spheres: usize) -> Self {
        Self::with_neighbours(
            bodies,
            spheres,
            arachis_core::body::DEFAULT_NEIGHBOURS_PER_SPHERE,
        )
    }

    /// Arenas with `per_sphere` neighbour-list entries per sphere.
    pub fn with_neighbours(bodies: usize, spheres: usize, per_sphere: usize) -> Self {
        let l = StorageLengths::for_spheres(bodies, spheres)
            .with_neighbours_per_sphere(per_sphere)
            .with_effects();
        Arenas(OwnedStorage::new(l))
    }

    /// An empty world over these arenas.
    pub fn world(&mut self) -> World<'_, S> {
        World::new(self.0.storage()).expect("storage built from StorageLengths is accepted")
    }
}

/// Panic (a fuzz crash) unless every scalar of the world's state is valid: after a step that
/// returned `Ok`, a poisoned (overflowed) value would be a silent overflow.
pub fn assert_state_valid<S: Scalar>(w: &World<'_, S>, after_step: u64) {
    for (i, b) in w.bodies().iter().enumerate() {
        let q = b.orientation;
        let ok = b.position.is_valid()
            && b.velocity.is_valid()
            && b.angular_velocity.is_valid()
            && [q.w, q.x, q.y, q.z].iter().all(|c| c.is_valid());
        assert!(
            ok,
            "{}: step {after_step} returned Ok but body {i} holds an invalid value: {b:?}",
            S::NAME
        );
    }
    for (i, s) in w.spheres().iter().enumerate() {
        assert!(
            s.position.is_valid(),
            "{}: step {after_step} returned Ok but sphere {i} position is invalid: {s:?}",
            S::NAME
        );
    }
    for s in 0..w.spheres().len() as u32 {
        for slot in w.contact_slots(s) {
            assert!(
                slot.state.delta.is_valid(),
                "{}: step {after_step} returned Ok but contact history of sphere {s} is invalid",
                S::NAME
            );
        }
    }
    for (i, wall) in w.walls().iter().enumerate() {
        assert!(
            wall.force.is_valid(),
            "{}: step {after_step} returned Ok but wall {i} force is invalid",
            S::NAME
        );
    }
}

/// With `ARACHIS_FUZZ_STATS=1`, print one outcome line per run (for checking what the corpus
/// reaches: `... -runs=0 corpus/<target> 2>&1 | grep '^outcome' | sort | uniq -c`).
pub fn outcome(what: &str) {
    static ON: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    if *ON.get_or_init(|| std::env::var_os("ARACHIS_FUZZ_STATS").is_some()) {
        eprintln!("outcome {what}");
    }
}

/// With `ARACHIS_FUZZ_STRICT=1`, the targets drop their exclusions of known, reported findings
/// (see `docs/benchmarks-and-fuzzing.md`), so the reproducers in `fuzz/regressions/` crash
/// again until the core is fixed.
pub fn strict() -> bool {
    static ON: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *ON.get_or_init(|| std::env::var_os("ARACHIS_FUZZ_STRICT").is_some())
}
