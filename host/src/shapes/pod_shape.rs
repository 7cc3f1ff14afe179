//! The three harvest-time pod shapes of seed 000 §2.2 (Figure 1): normal (two kernels with a
//! waist), cocoon (a shallow waist) and single-grain (an ellipsoid), as implicit solids.
//!
//! Body frame (seed 001 §2.1): origin at the pod's geometric centre, x along the width W
//! (between the two lateral sutures), y along the thickness H, z along the length L.
//!
//! Every shape is the union of two equal ellipsoidal lobes (kernels) with semi-axes
//! a = W/2, b = H/2, c along z, centred at z = ±d. With the lobe offset ratio s = d/c the
//! cross-section at the waist (z = 0) is scaled by the waist ratio w = √(1 − s²), and the
//! overall length is L = 2(c + d), so c = L / (2(1 + s)). The shape therefore spans exactly
//! L × W × H; w = 1 gives one ellipsoid (single-grain), smaller w a deeper waist.
//! Its volume is V = 2πabc (2/3 + s − s³/3) (integral of the lobe's cross-section from the
//! waist to the tip).
//!
//! The seeds print no waist depth (Figure 1 of seed 000 is a photograph), so the default
//! waist ratios below are our assumptions, exposed as a parameter.
//!
//! ```
//! use arachis::shapes::{PodKind, PodShape};
//! let pod = PodShape::seed001_mean(PodKind::SingleGrain);
//! let (a, b, c) = (18.29 / 2.0, 15.76 / 2.0, 34.27 / 2.0);
//! let exact = 4.0 / 3.0 * std::f64::consts::PI * a * b * c;
//! assert!((pod.analytic_volume_mm3() - exact).abs() < 1e-9 * exact);
//! assert_eq!(PodKind::from_key("single_grain"), Some(PodKind::SingleGrain));
//! ```

use std::f64::consts::PI;

use super::error::ShapeError;
use super::solid::Solid;
use super::voxel_grid::Aabb;

/// Mean pod length L, mm (seed 001 Table 1).
pub const SEED001_POD_LENGTH_MM: f64 = 34.27;
/// Mean pod width W, mm (seed 001 Table 1).
pub const SEED001_POD_WIDTH_MM: f64 = 18.29;
/// Mean pod thickness H, mm (seed 001 Table 1).
pub const SEED001_POD_THICKNESS_MM: f64 = 15.76;

/// Assumed waist ratio of the normal pod: the waist section is 80% of the kernel section
/// (seed 000 prints no number; Figure 1 shows a clear waist).
pub const NORMAL_WAIST_RATIO: f64 = 0.80;
/// Assumed waist ratio of the cocoon pod: a shallow waist, 92% of the kernel section.
pub const COCOON_WAIST_RATIO: f64 = 0.92;
/// The single-grain pod has no waist: one ellipsoid.
pub const SINGLE_GRAIN_WAIST_RATIO: f64 = 1.0;

/// The three pod shapes at harvest (seed 000 §2.2.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum PodKind {
    /// Two kernels with a waist.
    Normal,
    /// Elongated, with a shallow waist.
    Cocoon,
    /// One kernel: an ellipsoid.
    SingleGrain,
}

impl PodKind {
    /// All kinds, in the order used by [`super::ShapeMix`].
    pub const ALL: [PodKind; 3] = [PodKind::Normal, PodKind::Cocoon, PodKind::SingleGrain];

    /// The default waist ratio of this kind (see the module notes).
    pub fn default_waist_ratio(self) -> f64 {
        match self {
            PodKind::Normal => NORMAL_WAIST_RATIO,
            PodKind::Cocoon => COCOON_WAIST_RATIO,
            PodKind::SingleGrain => SINGLE_GRAIN_WAIST_RATIO,
        }
    }

    /// The key of this kind in study files (`[pods.shape_mix]`, `[pods.stl]`):
    /// `normal`, `cocoon`, `single_grain`.
    pub fn key(self) -> &'static str {
        match self {
            PodKind::Normal => "normal",
            PodKind::Cocoon => "cocoon",
            PodKind::SingleGrain => "single_grain",
        }
    }

    /// The kind whose study-file key is `key`.
    pub fn from_key(key: &str) -> Option<PodKind> {
        PodKind::ALL.into_iter().find(|k| k.key() == key)
    }

    /// A lower-case name for files and labels.
    pub fn name(self) -> &'static str {
        match self {
            PodKind::Normal => "normal",
            PodKind::Cocoon => "cocoon",
            PodKind::SingleGrain => "single-grain",
        }
    }
}

/// A pod shape: two ellipsoidal lobes spanning length × width × thickness, mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PodShape {
    kind: PodKind,
    length_mm: f64,
    width_mm: f64,
    thickness_mm: f64,
    waist_ratio: f64,
}

fn check_positive(name: &'static str, value: f64) -> Result<f64, ShapeError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(ShapeError::InvalidParameter {
            name,
            value,
            reason: "must be a finite number > 0",
        })
    }
}

impl PodShape {
    /// A pod of `kind` with length L, width W and thickness H in mm, and the kind's
    /// default waist ratio.
    pub fn new(
        kind: PodKind,
        length_mm: f64,
        width_mm: f64,
        thickness_mm: f64,
    ) -> Result<Self, ShapeError> {
        Ok(PodShape {
            kind,
            length_mm: check_positive("length L (mm)", length_mm)?,
            width_mm: check_positive("width W (mm)", width_mm)?,
            thickness_mm: check_positive("thickness H (mm)", thickness_mm)?,
            waist_ratio: kind.default_waist_ratio(),
        })
    }

    /// The same pod with waist ratio `w` (waist section / kernel section), 0 < w ≤ 1.
    pub fn with_waist_ratio(mut self, w: f64) -> Result<Self, ShapeError> {
        if !(w.is_finite() && w > 0.0 && w <= 1.0) {
            return Err(ShapeError::InvalidParameter {
                name: "waist ratio",
                value: w,
                reason: "must lie in (0, 1]",
            });
        }
        self.waist_ratio = w;
        Ok(self)
    }

    /// A pod of `kind` with the mean dimensions of seed 001 Table 1:
    /// 34.27 × 18.29 × 15.76 mm.
    pub fn seed001_mean(kind: PodKind) -> Self {
        PodShape {
            kind,
            length_mm: SEED001_POD_LENGTH_MM,
            width_mm: SEED001_POD_WIDTH_MM,
            thickness_mm: SEED001_POD_THICKNESS_MM,
            waist_ratio: kind.default_waist_ratio(),
        }
    }

    /// The pod's kind.
    pub fn kind(&self) -> PodKind {
        self.kind
    }

    /// Length L along z, mm.
    pub fn length_mm(&self) -> f64 {
        self.length_mm
    }

    /// Width W along x, mm.
    pub fn width_mm(&self) -> f64 {
        self.width_mm
    }

    /// Thickness H along y, mm.
    pub fn thickness_mm(&self) -> f64 {
        self.thickness_mm
    }

    /// Waist ratio w (waist section / kernel section).
    pub fn waist_ratio(&self) -> f64 {
        self.waist_ratio
    }

    /// Lobe offset ratio s = d/c = √(1 − w²).
    fn offset_ratio(&self) -> f64 {
        (1.0 - self.waist_ratio * self.waist_ratio).max(0.0).sqrt()
    }

    /// Lobe semi-axes (a, b, c), mm, and lobe-centre offset d, mm.
    pub fn lobes_mm(&self) -> ([f64; 3], f64) {
        let s = self.offset_ratio();
        let c = self.length_mm / (2.0 * (1.0 + s));
        ([0.5 * self.width_mm, 0.5 * self.thickness_mm, c], s * c)
    }

    /// Section scale ρ(z) ∈ [0, 1] at `z_mm`: the cross-section there is the ellipse with
    /// semi-axes ρ·W/2 and ρ·H/2 (0 beyond the tips).
    pub fn section_scale(&self, z_mm: f64) -> f64 {
        let ([_, _, c], d) = self.lobes_mm();
        let u = (z_mm.abs() - d) / c;
        if u.abs() >= 1.0 {
            0.0
        } else {
            (1.0 - u * u).sqrt()
        }
    }

    /// Volume, mm³: V = 2πabc (2/3 + s − s³/3) (module notes).
    pub fn analytic_volume_mm3(&self) -> f64 {
        let ([a, b, c], _) = self.lobes_mm();
        let s = self.offset_ratio();
        2.0 * PI * a * b * c * (2.0 / 3.0 + s - s.powi(3) / 3.0)
    }
}

impl Solid for PodShape {
    fn bounds_mm(&self) -> Aabb {
        let half = [
            0.5 * self.width_mm,
            0.5 * self.thickness_mm,
            0.5 * self.length_mm,
        ];
        Aabb {
            min_mm: half.map(|h| -h),
            max_mm: half,
        }
    }

    fn contains_mm(&self, p: [f64; 3]) -> bool {
        let ([a, b, c], d) = self.lobes_mm();
        let radial = (p[0] / a).powi(2) + (p[1] / b).powi(2);
        // The lobe nearer to p decides: the union of the two ellipsoids.
        let u = (p[2].abs() - d) / c;
        radial + u * u <= 1.0
    }
}
