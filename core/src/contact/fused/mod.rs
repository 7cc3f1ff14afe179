//! The base contact law fused into one evaluation: Hertz normal force with damping, the
//! no-attraction clip, Mindlin tangential spring with damping and the Coulomb limit, and CDT
//! rolling friction (seed 000 eqs. (1)–(7), DESIGN §2): the same law as the terms of this
//! module, written for speed. Almost every contact of a pod bed takes this path; a pair with
//! any optional effect but JKR cohesion, or a term switched off other than damping or
//! rolling, takes the terms. A JKR pair ([`jkr`]: the soil of a field) takes it while its
//! overlap is positive, and in fixed point also across its neck, held beyond touching
//! ([`fixed::evaluate_jkr`]); the `f64` law leaves a neck to the terms.
//!
//! What makes it fast:
//! - **Torques about sphere centres.** The contact point lies at c = rᵢ + n̂·Lᵢ = rⱼ − n̂·Lⱼ
//!   (Lᵢ = Rᵢ − α/2), so the contact velocity is v = vⱼ − vᵢ − (Lᵢωᵢ + Lⱼωⱼ) × n̂ (v the
//!   velocities of the sphere centres) and, since the normal force has no lever about a
//!   centre, the torques are −Lᵢ·(n̂ × F_t) on i and −Lⱼ·(n̂ × F_t) on j, plus o × F for a
//!   clump sphere whose centre lies at o from its body's centre of mass. One cross product
//!   where the terms take four.
//! - **No per-operation overflow checks.** It runs in [`Scalar::Fast`]: for fixed point,
//!   [`crate::num::FxFast`], the bits of [`crate::num::Fx`] without the poison tests. Instead
//!   [`evaluate`] checks the contact against an *envelope* in which no operation can overflow
//!   the Q32.32 range (±2^31): its inputs, the damping products, the history after its
//!   increment and the forces (below). A contact outside it returns `None` and is evaluated by
//!   the terms, which report any overflow. `f64` runs the same code without the magnitude
//!   tests (floating point has no range to leave short of infinity; the geometric conditions
//!   stay), and one test of its loads sends a contact with an infinite or NaN value to the
//!   terms.
//! - **Cheap roots.** The distance |d| comes from one reciprocal root good to 2^-38 (it sets
//!   the overlap, which needs every bit); √(R*α) and √(a·m*), which only scale stiffness and
//!   damping, from 64-bit Newton steps good to 2^-28 ([`Envelope::sqrt_coarse`]).
//!
//! The envelope, with its bounds (internal units), in the order it is checked:
//!
//! | quantity | bound | what it allows |
//! |---|---|---|
//! | Rᵢ + Rⱼ, α | 2^6 mm ([`REACH_BITS`]); centres at least (Rᵢ + Rⱼ)/2 apart | |
//! | Lᵢ, Lⱼ, R*, clump offsets | 2^5 mm ([`LENGTH_BITS`]) | spheres up to 32 mm, clumps up to 64 mm across |
//! | R*·α | 2^9 mm² ([`OVERLAP_AREA_BITS`]) | |
//! | vⱼ − vᵢ (centres) | 2^10 mm/ms ([`SPEED_BITS`]) | 1 km/s |
//! | ωᵢ, ωⱼ | 2^10 rad/ms ([`SPIN_BITS`]) | 10⁶ rad/s |
//! | m* | 2^12 g ([`MASS_BITS`]) | 4 kg |
//! | dt | 2^4 ms ([`TIMESTEP_BITS`]) | |
//! | δt, before and after the increment vt·dt | 2^4 mm ([`DELTA_BITS`]) | |
//! | (4/3)E*, 8G* | 2^19, 2^21 MPa | steel on steel (≈ 1.5e5, 6e5) |
//! | damping factors | 2^12 √MPa | any e > 0 with the moduli above |
//! | μs, μr | 4 ([`FRICTION_BITS`]) | |
//! | damping forces (checked products) | 2^30 N ([`PRODUCT_BITS`]) | |
//! | normal and tangential forces | 2^13 N ([`FORCE_BITS`]) | 8 kN |
//!
//! Why nothing else can overflow the range 2^31: |Lω| < 2^15 per component, so |v| < 2^18 and
//! vn, |vt| < 2^19; vt·dt < 2^23, so δt + vt·dt < 2^24 before its check; a < 2^4.5,
//! a·m* < 2^16.5, √(a·m*) < 2^8.3, a·α < 2^10.5 and (4/3)E*·a·α < 2^29.5, so Fn < 2^30.6;
//! St = 8G*·a < 2^25.5 and St·δt < 2^29.5; each damping factor times √(a·m*) < 2^20.3; the
//! forces below 2^13 keep |F_t|² and (μs·F_n)² < 2^30 and St·|δt| < 2^30.3; every torque is
//! below 2^21.
//!
//! ```
//! use arachis_core::contact::fused::{evaluate, FusedContact, FusedPair, Geometry};
//! use arachis_core::num::{Scalar, Vec3};
//! // Pod on pod, 0.02 mm overlap, at rest: the Hertz force (4/3)E*·√(R*α)·α.
//! let p = FusedPair::<f64> { eligible: true, four_thirds_e_star: 6.7, normal_damping: 0.0,
//!     eight_g_star: 24.0, tangential_damping: 0.0, friction: 0.8, rolling_friction: 0.0,
//!     jkr: false, jkr_c: 0.0, jkr_adhesion: 0.0 };
//! let c = FusedContact {
//!     geometry: Geometry::Wall { normal: Vec3::new(0.0, 0.0, 1.0), overlap: 0.02 },
//!     r_i: 4.0, r_star: 2.0, m_star: 0.08, v_centres: Vec3::ZERO, spin_i: Vec3::ZERO,
//!     spin_j: Vec3::ZERO, offset_i: None, offset_j: None, dt: 0.02 };
//! let mut delta = Vec3::ZERO;
//! let load = evaluate(&c, &p, &mut delta).unwrap();
//! let hertz = 6.7 * (2.0f64 * 0.02).sqrt() * 0.02;
//! assert!((load.force.z - hertz).abs() < 1e-12);
//! ```

pub mod fixed;
pub mod jkr;
#[cfg(test)]
pub(crate) mod random_contacts;

use crate::num::{Envelope, FxFast, Scalar, Vec3};

/// Lengths (lever lengths, R*, clump offsets) below 2^LENGTH_BITS mm.
pub const LENGTH_BITS: i32 = 5;
/// The overlap and the sum of radii below 2^(LENGTH_BITS + 1) mm.
pub const REACH_BITS: i32 = LENGTH_BITS + 1;
/// R*·α below 2^OVERLAP_AREA_BITS mm².
pub const OVERLAP_AREA_BITS: i32 = 9;
/// Centre velocity differences below 2^SPEED_BITS mm/ms.
pub const SPEED_BITS: i32 = 10;
/// Angular velocities below 2^SPIN_BITS rad/ms.
pub const SPIN_BITS: i32 = 10;
/// Tangential history below 2^DELTA_BITS mm, before and after the step's increment.
pub const DELTA_BITS: i32 = 4;
/// Effective mass below 2^MASS_BITS g.
pub const MASS_BITS: i32 = 12;
/// Time step below 2^TIMESTEP_BITS ms.
pub const TIMESTEP_BITS: i32 = 4;
/// (4/3)E* below 2^NORMAL_STIFFNESS_BITS MPa.
pub const NORMAL_STIFFNESS_BITS: i32 = 19;
/// 8G* below 2^TANGENTIAL_STIFFNESS_BITS MPa.
pub const TANGENTIAL_STIFFNESS_BITS: i32 = 21;
/// Damping factors below 2^DAMPING_BITS √MPa.
pub const DAMPING_BITS: i32 = 12;
/// Friction coefficients below 2^FRICTION_BITS.
pub const FRICTION_BITS: i32 = 2;
/// Damping forces checked below 2^PRODUCT_BITS N.
pub const PRODUCT_BITS: i32 = 30;
/// Normal and tangential force components checked below 2^FORCE_BITS N.
pub const FORCE_BITS: i32 = 13;

/// The constants of the fused law for one material pair
/// ([`crate::pair::PairParams::fused`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FusedPair<S> {
    /// Whether the pair may use the fused law (no optional effect, Hertz, Mindlin and the
    /// Coulomb limit on, constants inside the envelope).
    pub eligible: bool,
    /// (4/3)·E*, MPa.
    pub four_thirds_e_star: S,
    /// Normal damping factor 2√(5/6)(−β)√(2E*), √MPa (0 when off).
    pub normal_damping: S,
    /// 8·G*, MPa.
    pub eight_g_star: S,
    /// Tangential damping factor 2√(5/6)(−β)√(8G*), √MPa (0 when off).
    pub tangential_damping: S,
    /// Sliding friction μs.
    pub friction: S,
    /// CDT rolling friction μr (0 when off).
    pub rolling_friction: S,
    /// Whether JKR cohesion acts on top of the base law ([`jkr`]): its repulsive force
    /// replaces Hertz's and its adhesive force is subtracted last, as the checked terms do.
    pub jkr: bool,
    /// JKR's c = √(2πΓ/E*), √mm (0 when off).
    pub jkr_c: S,
    /// JKR's √(8πΓE*), N/mm^{3/2} (0 when off).
    pub jkr_adhesion: S,
}

impl<S: Scalar> FusedPair<S> {
    /// The same constants in [`Scalar::Fast`].
    #[inline(always)]
    pub fn fast(&self) -> FusedPair<S::Fast> {
        self.map(S::to_fast)
    }

    /// The constants through `f` (e.g. to another scalar type with the same bits).
    #[inline(always)]
    pub fn map<T: Scalar>(&self, f: impl Fn(S) -> T) -> FusedPair<T> {
        FusedPair {
            eligible: self.eligible,
            four_thirds_e_star: f(self.four_thirds_e_star),
            normal_damping: f(self.normal_damping),
            eight_g_star: f(self.eight_g_star),
            tangential_damping: f(self.tangential_damping),
            friction: f(self.friction),
            rolling_friction: f(self.rolling_friction),
            jkr: self.jkr,
            jkr_c: f(self.jkr_c),
            jkr_adhesion: f(self.jkr_adhesion),
        }
    }
}

/// Where the contact is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Geometry<T> {
    /// Between two spheres whose centres are `d` apart (j − i, mm; |d|² = `d2`); j's radius
    /// `r_j`, mm.
    Spheres {
        /// rⱼ − rᵢ, mm.
        d: Vec3<T>,
        /// |d|², mm².
        d2: T,
        /// Rⱼ, mm.
        r_j: T,
    },
    /// With a wall: unit normal from the sphere towards the wall, and the overlap, mm.
    Wall {
        /// Unit normal from i towards the wall.
        normal: Vec3<T>,
        /// Overlap α, mm.
        overlap: T,
    },
}

/// One contact as the fused law sees it (internal units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FusedContact<T> {
    /// Where the contact is.
    pub geometry: Geometry<T>,
    /// Rᵢ, mm.
    pub r_i: T,
    /// Effective radius R*, mm (wall: Rᵢ).
    pub r_star: T,
    /// Effective mass m*, g (wall: mᵢ).
    pub m_star: T,
    /// Velocity of j's centre minus i's (for a wall, the wall's velocity minus i's), mm/ms.
    pub v_centres: Vec3<T>,
    /// ωᵢ, rad/ms.
    pub spin_i: Vec3<T>,
    /// ωⱼ, rad/ms (0 for a wall).
    pub spin_j: Vec3<T>,
    /// For a clump sphere i: its centre minus its body's centre of mass, mm.
    pub offset_i: Option<Vec3<T>>,
    /// The same for j.
    pub offset_j: Option<Vec3<T>>,
    /// Time step, ms.
    pub dt: T,
}

/// The loads of one contact.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FusedLoad<T> {
    /// Force on j (i receives the opposite), N.
    pub force: Vec3<T>,
    /// Torque about i's centre of mass of the force on j's side; i receives its opposite, N·mm.
    pub torque_i: Vec3<T>,
    /// Torque on j about its centre of mass, N·mm.
    pub torque_j: Vec3<T>,
    /// Rolling-resistance torque magnitude on i, N·mm.
    pub roll_i: T,
    /// Rolling-resistance torque magnitude on j, N·mm.
    pub roll_j: T,
}

impl<T: Scalar> FusedContact<T> {
    /// The contact through `f` (e.g. to another scalar type with the same bits).
    #[inline(always)]
    pub fn map<U: Scalar>(&self, f: impl Fn(T) -> U + Copy) -> FusedContact<U> {
        FusedContact {
            geometry: match self.geometry {
                Geometry::Spheres { d, d2, r_j } => Geometry::Spheres {
                    d: d.map(f),
                    d2: f(d2),
                    r_j: f(r_j),
                },
                Geometry::Wall { normal, overlap } => Geometry::Wall {
                    normal: normal.map(f),
                    overlap: f(overlap),
                },
            },
            r_i: f(self.r_i),
            r_star: f(self.r_star),
            m_star: f(self.m_star),
            v_centres: self.v_centres.map(f),
            spin_i: self.spin_i.map(f),
            spin_j: self.spin_j.map(f),
            offset_i: self.offset_i.map(|o| o.map(f)),
            offset_j: self.offset_j.map(|o| o.map(f)),
            dt: f(self.dt),
        }
    }
}

impl<T: Scalar> FusedLoad<T> {
    /// The loads through `f` (e.g. to another scalar type with the same bits).
    #[inline(always)]
    pub fn map<U: Scalar>(&self, f: impl Fn(T) -> U + Copy) -> FusedLoad<U> {
        FusedLoad {
            force: self.force.map(f),
            torque_i: self.torque_i.map(f),
            torque_j: self.torque_j.map(f),
            roll_i: f(self.roll_i),
            roll_j: f(self.roll_j),
        }
    }
}

/// Evaluate the fused law with the fastest kernel for `T`: the integer kernel of [`fixed`]
/// when `T` is Q32.32 fixed point, else [`evaluate`]. `None` (and `delta`
/// untouched) outside the envelope.
#[inline(always)]
pub fn evaluate_fast<T: Envelope>(
    c: &FusedContact<T>,
    p: &FusedPair<T>,
    delta: &mut Vec3<T>,
) -> Option<FusedLoad<T>> {
    let mut no_root = T::ZERO;
    evaluate_fast_jkr(c, p, delta, &mut no_root)
}

/// [`evaluate_fast`] with JKR's root x = √a (√mm; [`jkr`]): in, the contact's root at its
/// last step (0: none), where the Newton loop starts; out, this step's (left as it was for a
/// pair without JKR). Untouched, as `delta` is, outside the envelope.
#[inline(always)]
pub fn evaluate_fast_jkr<T: Envelope>(
    c: &FusedContact<T>,
    p: &FusedPair<T>,
    delta: &mut Vec3<T>,
    jkr_root: &mut T,
) -> Option<FusedLoad<T>> {
    if !T::Q32_32 {
        return evaluate_jkr(c, p, delta, jkr_root);
    }
    // The same bits, seen as the integer kernel's type (the conversions compile to nothing).
    let to = |x: T| FxFast::from_raw(x.to_bits() as i64);
    let back = |x: FxFast| T::from_bits(x.raw() as u64);
    let (mut d, mut root) = (delta.map(to), to(*jkr_root));
    let load = fixed::evaluate_jkr(&c.map(to), &p.map(to), &mut d, &mut root)?;
    *delta = d.map(back);
    *jkr_root = back(root);
    Some(load.map(back))
}

/// What one contact carries from stage to stage.
#[derive(Clone, Copy, Debug, Default)]
struct Lane<T> {
    normal: Vec3<T>,
    overlap: T,
    len_i: T,
    len_j: T,
    r_star_alpha: T,
    vn: T,
    vt: Vec3<T>,
    a: T,
    root_am: T,
    f_n: T,
    f_t: Vec3<T>,
    /// JKR's adhesive force, N (0 without JKR), subtracted from the normal force last.
    attraction: T,
    /// JKR's root x = √a, √mm: the last step's on the way in, this step's on the way out.
    jkr_root: T,
}

#[inline(always)]
fn within3<T: Envelope>(v: Vec3<T>, bits: i32) -> bool {
    v.x.within(bits) & v.y.within(bits) & v.z.within(bits)
}

/// `v·s`, and whether every component is `within(bits)` (exact test, [`Envelope::mul_within`]).
#[inline(always)]
fn scale_within<T: Envelope>(v: Vec3<T>, s: T, bits: i32) -> (Vec3<T>, bool) {
    let (x, ox) = v.x.mul_within(s, bits);
    let (y, oy) = v.y.mul_within(s, bits);
    let (z, oz) = v.z.mul_within(s, bits);
    (Vec3::new(x, y, z), ox & oy & oz)
}

/// Evaluate the fused law for contact `c` of pair `p` with tangential history `delta` (mm,
/// updated in place). `None` (and `delta` untouched) outside the envelope (module docs).
#[inline(always)]
pub fn evaluate<T: Envelope>(
    c: &FusedContact<T>,
    p: &FusedPair<T>,
    delta: &mut Vec3<T>,
) -> Option<FusedLoad<T>> {
    let mut no_root = T::ZERO;
    evaluate_jkr(c, p, delta, &mut no_root)
}

/// [`evaluate`] with JKR's root, as [`evaluate_fast_jkr`] takes and gives it.
#[inline(always)]
pub fn evaluate_jkr<T: Envelope>(
    c: &FusedContact<T>,
    p: &FusedPair<T>,
    delta: &mut Vec3<T>,
    jkr_root: &mut T,
) -> Option<FusedLoad<T>> {
    let mut l = geometry(c, *delta)?;
    l.jkr_root = *jkr_root;
    // Contact velocity v_j − v_i at the contact point, and its normal and tangential parts.
    let n = l.normal;
    let spin = c.spin_i.scale(l.len_i) + c.spin_j.scale(l.len_j);
    let v = c.v_centres - spin.cross(n);
    l.vn = v.dot(n);
    l.vt = v - n.scale(l.vn);
    l.a = l.r_star_alpha.sqrt_coarse();
    l.root_am = (l.a * c.m_star).sqrt_coarse();
    let d = forces(c, p, &mut l, *delta)?;
    let load = loads(c, p, &l);
    if !T::Q32_32 {
        // The sum is infinite or NaN if any of its terms is (or if it overflows itself).
        let all = load.force + load.torque_i + load.torque_j + d;
        if !(all.x + all.y + all.z + load.roll_i + load.roll_j).is_valid() {
            return None;
        }
    }
    *delta = d;
    *jkr_root = l.jkr_root;
    Some(load)
}

/// Whether the magnitude tests of the envelope apply: for fixed point only (module docs).
#[inline(always)]
fn bounded<T: Envelope>() -> bool {
    T::Q32_32
}

/// Normal, overlap, lever lengths and R*·α, after the envelope's input checks.
#[inline(always)]
fn geometry<T: Envelope>(c: &FusedContact<T>, delta: Vec3<T>) -> Option<Lane<T>> {
    let (normal, overlap, r_j) = match c.geometry {
        Geometry::Spheres { d, d2, r_j } => {
            let rs = c.r_i + r_j;
            // Centres closer than rs/2 (or huge radii) leave the envelope.
            if !((!bounded::<T>() || rs.within(REACH_BITS)) && d2.mul_int(4) >= rs * rs) {
                return None;
            }
            let (dist, inv) = d2.sqrt_rsqrt();
            (d.scale(inv), rs - dist, r_j)
        }
        Geometry::Wall { normal, overlap } => {
            if bounded::<T>() && !c.r_i.within(REACH_BITS) {
                return None;
            }
            // Lⱼ = 0 for a wall.
            (normal, overlap, overlap * T::HALF)
        }
    };
    let half = overlap * T::HALF;
    let (len_i, len_j) = (c.r_i - half, r_j - half);
    if !((len_i > T::ZERO) & (overlap > T::ZERO) & (c.m_star > T::ZERO)) {
        return None;
    }
    let lane = |r_star_alpha| Lane {
        normal,
        overlap,
        len_i,
        len_j,
        r_star_alpha,
        ..Lane::default()
    };
    if !bounded::<T>() {
        return Some(lane(c.r_star * overlap));
    }
    let lengths_in = len_i.within(LENGTH_BITS)
        & len_j.within(LENGTH_BITS)
        & c.r_star.within(LENGTH_BITS)
        & overlap.within(REACH_BITS)
        & c.offset_i.is_none_or(|o| within3(o, LENGTH_BITS))
        & c.offset_j.is_none_or(|o| within3(o, LENGTH_BITS));
    if !lengths_in {
        return None;
    }
    let r_star_alpha = c.r_star * overlap;
    let inputs_in = r_star_alpha.within(OVERLAP_AREA_BITS)
        & within3(c.v_centres, SPEED_BITS)
        & within3(c.spin_i, SPIN_BITS)
        & within3(c.spin_j, SPIN_BITS)
        & within3(delta, DELTA_BITS)
        & c.m_star.within(MASS_BITS)
        & c.dt.within(TIMESTEP_BITS);
    inputs_in.then(|| lane(r_star_alpha))
}

/// Hertz with damping (eqs. (3), (4)) clipped at zero; Mindlin spring with history
/// projected on the tangent plane, and damping (eqs. (5), (6)); the Coulomb limit; the
/// envelope's checks of the damping products, the history and the forces. Returns the new
/// history.
#[inline(always)]
fn forces<T: Envelope>(
    c: &FusedContact<T>,
    p: &FusedPair<T>,
    l: &mut Lane<T>,
    delta: Vec3<T>,
) -> Option<Vec3<T>> {
    let n = l.normal;
    let bounded = bounded::<T>();
    let (damp_n, damp_n_in) = (p.normal_damping * l.root_am).mul_within(l.vn, PRODUCT_BITS);
    // JKR's repulsive force replaces Hertz's; its adhesion is subtracted after friction and
    // rolling, as in the checked pipeline ([`crate::pair::PairParams::evaluate`]).
    let elastic = if p.jkr {
        let (repulsive, adhesive, root) = jkr::force(
            l.overlap,
            c.r_star,
            p.jkr_c,
            p.four_thirds_e_star,
            p.jkr_adhesion,
            l.jkr_root,
        )?;
        l.attraction = adhesive;
        l.jkr_root = root;
        repulsive
    } else {
        p.four_thirds_e_star * (l.a * l.overlap)
    };
    let mut f_n = elastic - damp_n;
    if f_n < T::ZERO {
        f_n = T::ZERO;
    }
    let d = delta - n.scale(delta.dot(n)) + l.vt.scale(c.dt);
    let st = p.eight_g_star * l.a;
    let (damp_t, damp_t_in) = scale_within(l.vt, p.tangential_damping * l.root_am, PRODUCT_BITS);
    if bounded && !(damp_n_in & damp_t_in & within3(d, DELTA_BITS)) {
        return None;
    }
    let f_t = -(d.scale(st) + damp_t);
    if bounded && !(f_n.within(FORCE_BITS) & within3(f_t, FORCE_BITS)) {
        return None;
    }
    l.f_n = f_n;
    l.f_t = f_t;

    // Coulomb limit |Ft| ≤ μs·Fn; when the spring alone exceeds it, the history is rescaled
    // so that St|δt| = μs·Fn.
    let mut d = d;
    let limit = p.friction * f_n;
    let f2 = f_t.norm2();
    if f2 > limit * limit {
        if limit <= T::ZERO {
            l.f_t = Vec3::ZERO;
            d = Vec3::ZERO;
        } else {
            l.f_t = f_t.scale(limit / f2.sqrt());
            let stretch = st * d.norm();
            if stretch > limit {
                d = d.scale(limit / stretch);
            }
        }
    }
    Some(d)
}

/// The loads: force, CDT rolling friction (eq. (7): μr·Fn times the lever from each centre
/// of mass) and torques.
#[inline(always)]
fn loads<T: Envelope>(c: &FusedContact<T>, p: &FusedPair<T>, l: &Lane<T>) -> FusedLoad<T> {
    let n = l.normal;
    let (mut roll_i, mut roll_j) = (T::ZERO, T::ZERO);
    if p.rolling_friction != T::ZERO {
        let t = p.rolling_friction * l.f_n;
        let lever = |len: T, offset: Option<Vec3<T>>, towards_j: bool| match offset {
            Some(o) => (o + n.scale(if towards_j { len } else { -len })).norm(),
            None => len,
        };
        roll_i = t * lever(l.len_i, c.offset_i, true);
        roll_j = t * lever(l.len_j, c.offset_j, false);
    }
    let force = n.scale(l.f_n - l.attraction) + l.f_t;
    let tau = n.cross(l.f_t);
    let mut torque_i = tau.scale(l.len_i);
    let mut torque_j = -tau.scale(l.len_j);
    if let Some(o) = c.offset_i {
        torque_i += o.cross(force);
    }
    if let Some(o) = c.offset_j {
        torque_j += o.cross(force);
    }
    FusedLoad {
        force,
        torque_i,
        torque_j,
        roll_i,
        roll_j,
    }
}
