//! Synthetic pile pictures of known slope for the repose tests: a side view of a pile drawn
//! from an exact profile (triangle or trapezoid, optionally with a rounded apex), with
//! anti-aliased or jagged edges and optional grey-level noise, and sphere piles packed
//! under a cone of known angle.

use arachis::repose::Sphere;
use image::GrayImage;

/// A pile profile in image pixels: flanks of given angles meeting at an apex, optionally
/// clipped flat at `flat_top_px` and rounded by a circle of `apex_radius_px` tangent to
/// both flanks.
#[derive(Debug, Clone, Copy)]
pub struct PileSpec {
    /// Image size (pixels).
    pub width: u32,
    /// Image size (pixels).
    pub height: u32,
    /// Image y of the plate (pixels from the top; continuous).
    pub base_y: f64,
    /// x of the (sharp) apex (pixels).
    pub apex_x: f64,
    /// Height of the sharp apex above the plate (pixels).
    pub apex_h: f64,
    /// Left flank angle (degrees).
    pub left_deg: f64,
    /// Right flank angle (degrees).
    pub right_deg: f64,
    /// Clip the pile flat at this height (pixels), if any.
    pub flat_top_px: Option<f64>,
    /// Round the apex with a circle of this radius (pixels), if any.
    pub apex_radius_px: Option<f64>,
}

/// How to draw it.
#[derive(Debug, Clone, Copy)]
pub struct Style {
    /// Sub-samples per pixel side for anti-aliasing (1 = jagged, centre sample only).
    pub samples: u32,
    /// Uniform grey noise amplitude ± (grey levels).
    pub noise: f64,
    /// Pile grey level.
    pub pile_grey: f64,
    /// Background grey level.
    pub background_grey: f64,
    /// Noise seed.
    pub seed: u64,
}

impl Default for Style {
    fn default() -> Self {
        Style {
            samples: 4,
            noise: 0.0,
            pile_grey: 60.0,
            background_grey: 225.0,
            seed: 1,
        }
    }
}

impl PileSpec {
    /// A symmetric pile of `angle_deg` as large as fits a `width` × `height` image.
    pub fn symmetric(width: u32, height: u32, angle_deg: f64) -> Self {
        let base_y = f64::from(height) * 0.9;
        let half = f64::from(width) * 0.45;
        let apex_h = (half * angle_deg.to_radians().tan()).min(base_y * 0.9);
        PileSpec {
            width,
            height,
            base_y,
            apex_x: f64::from(width) / 2.0,
            apex_h,
            left_deg: angle_deg,
            right_deg: angle_deg,
            flat_top_px: None,
            apex_radius_px: None,
        }
    }

    /// Height of the pile's top above the plate at x (pixels; ≤ 0 outside the pile).
    pub fn top(&self, x: f64) -> f64 {
        let (ta, tb) = (
            self.left_deg.to_radians().tan(),
            self.right_deg.to_radians().tan(),
        );
        let sharp =
            (self.apex_h - (self.apex_x - x) * ta).min(self.apex_h - (x - self.apex_x) * tb);
        let mut h = sharp;
        if let Some(rho) = self.apex_radius_px {
            // Centre (cx, cy) at distance ρ below both flanks: for the left flank
            // (x − xl)·sin α − y·cos α = ρ with xl = apex_x − apex_h / tan α, and likewise
            // (xr − x)·sin β − y·cos β = ρ on the right.
            let (a, b) = (self.left_deg.to_radians(), self.right_deg.to_radians());
            let xl = self.apex_x - self.apex_h / ta;
            let xr = self.apex_x + self.apex_h / tb;
            // sin a · cx − cos a · cy = ρ + xl sin a ; −sin b · cx − cos b · cy = ρ − xr sin b
            let (m11, m12, r1) = (a.sin(), -a.cos(), rho + xl * a.sin());
            let (m21, m22, r2) = (-b.sin(), -b.cos(), rho - xr * b.sin());
            let det = m11 * m22 - m12 * m21;
            let cx = (r1 * m22 - m12 * r2) / det;
            let cy = (m11 * r2 - r1 * m21) / det;
            if x > cx - rho * a.sin() && x < cx + rho * b.sin() {
                h = cy + (rho * rho - (x - cx).powi(2)).max(0.0).sqrt();
            }
        }
        if let Some(flat) = self.flat_top_px {
            h = h.min(flat);
        }
        h
    }

    /// Whether the continuous image point (x, y) is pile.
    pub fn inside(&self, x: f64, y: f64) -> bool {
        y < self.base_y && self.base_y - y < self.top(x)
    }

    /// Draws the pile.
    pub fn render(&self, style: Style) -> GrayImage {
        let mut rng = SplitMix64(style.seed);
        let n = style.samples.max(1);
        GrayImage::from_fn(self.width, self.height, |px, py| {
            let mut covered = 0u32;
            for sy in 0..n {
                for sx in 0..n {
                    let x = f64::from(px) + (f64::from(sx) + 0.5) / f64::from(n);
                    let y = f64::from(py) + (f64::from(sy) + 0.5) / f64::from(n);
                    covered += u32::from(self.inside(x, y));
                }
            }
            let coverage = f64::from(covered) / f64::from(n * n);
            let grey = style.background_grey + (style.pile_grey - style.background_grey) * coverage;
            let noisy = grey + style.noise * (2.0 * rng.unit() - 1.0);
            image::Luma([noisy.round().clamp(0.0, 255.0) as u8])
        })
    }
}

/// SplitMix64 (Steele, Lea & Flood 2014): a tiny deterministic generator for test noise.
pub struct SplitMix64(pub u64);

impl SplitMix64 {
    /// Next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The shipped CLI test picture: a symmetric 31.06° pile (seed 000's bench mean), rounded
/// apex, anti-aliased, ±12 grey levels of noise.
pub const SHIPPED_ANGLE_DEG: f64 = 31.06;
/// File name of the shipped picture under `testdata/repose/`.
pub const SHIPPED_PNG: &str = "synthetic_pile_31.06deg.png";

/// Draws the shipped CLI test picture.
pub fn shipped_pile() -> GrayImage {
    let mut spec = PileSpec::symmetric(480, 240, SHIPPED_ANGLE_DEG);
    spec.apex_radius_px = Some(25.0);
    spec.render(Style {
        noise: 12.0,
        ..Style::default()
    })
}

/// Fraction of the cone's volume that the spheres' volumes add up to: dense enough that
/// the cone's surface is covered everywhere, as in a settled pile.
pub const CONE_FILL_FRACTION: f64 = 0.8;

/// Spheres with radii uniform in `r_min..r_max` (mm) whose centres are scattered uniformly
/// at random (overlaps allowed) under a cone of base radius `base_radius` (mm) and angle
/// `angle_deg` standing on the plate z = 0: r ≤ z ≤ (R − ρ)·tan θ, ρ the centre's distance
/// from the axis. Random rather than lattice positions, so that no layering common to all
/// views puts steps into the flanks.
pub fn cone_pile(
    base_radius: f64,
    angle_deg: f64,
    r_min: f64,
    r_max: f64,
    seed: u64,
) -> Vec<Sphere> {
    let mut rng = SplitMix64(seed);
    let tan = angle_deg.to_radians().tan();
    let height = base_radius * tan;
    let cone_volume = std::f64::consts::PI * base_radius.powi(2) * height / 3.0;
    let mean_r3 = (r_max.powi(4) - r_min.powi(4)) / (4.0 * (r_max - r_min));
    let count = (CONE_FILL_FRACTION * cone_volume / (4.0 / 3.0 * std::f64::consts::PI * mean_r3))
        .round() as usize;
    let mut spheres = Vec::with_capacity(count);
    while spheres.len() < count {
        let x = base_radius * (2.0 * rng.unit() - 1.0);
        let y = base_radius * (2.0 * rng.unit() - 1.0);
        let z = height * rng.unit();
        let radius = r_min + (r_max - r_min) * rng.unit();
        if z >= radius && z <= (base_radius - x.hypot(y)) * tan {
            spheres.push(Sphere {
                centre_mm: [x, y, z],
                radius_mm: radius,
            });
        }
    }
    spheres
}
