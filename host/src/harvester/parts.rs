//! The harvester's geometry in the machine frame: x forward along the ridge, y across it,
//! z up from the ground, the origin on the ground above the shovel's edge. Everything else
//! lies behind the edge (x < 0).
//!
//! - The shovel's top surface runs from its edge E = (0, 0, −depth) along the slope
//!   d(α) = (−cos α, 0, sin α) for its length; its spheres' centres lie one radius below that
//!   surface along the normal n(α) = (sin α, 0, cos α), one row every sphere diameter.
//! - The chain's top surface continues from the shovel's top end T along d(β); rod j's axis
//!   lies at T + (p/2 + j p)·d(β) − r·n(β), pitch p, rod radius r, for the rods that fit in
//!   its length. A rod spins at ω = −v/r about +y, so its top moves rearwards (−x) at the
//!   chain speed v.
//! - The drum's axis lies above the last rod's axis by r + clearance + tooth radius + R;
//!   tooth row i sits at angle 2πi/rows about it, and the drum turns at +ω about +y, so its
//!   bottom teeth move rearwards as the chain's top does.
//! - Each row of spheres (a shovel row, a rod, a tooth row) spans the working width and is
//!   one kinematic clump; a clump holds at most [`MAX_ROW_SPHERES`].
//!
//! ```
//! use arachis::harvester::{parts::Layout, HarvesterSpec};
//! let dir = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../testdata/peanut-plant"));
//! let layout = Layout::of(&HarvesterSpec::read(&dir.join("harvester-digger.toml")).unwrap());
//! assert!(layout.drum_axis_m[0] < layout.shovel_top_m[0]);
//! ```

use arachis_core::units::LENGTH_M_TO_MM;
use glam::DVec3;

use super::{HarvesterSpec, Shake};

/// Most spheres in one row (one core clump).
pub const MAX_ROW_SPHERES: usize = arachis_core::world::MAX_CLUMP_SPHERES;

/// Which part of the machine a body is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum PartKind {
    /// A row of the shovel's plate.
    Shovel,
    /// A rod of the chain.
    Chain,
    /// A row of the drum's teeth.
    Drum,
}

/// One kinematic body of the machine, at rest in the machine frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Part {
    /// What it is.
    pub kind: PartKind,
    /// Its centre of mass, about which it spins, m.
    pub centre_m: [f64; 3],
    /// Its sphere centres, m.
    pub spheres_m: Vec<[f64; 3]>,
    /// Their radius, m.
    pub radius_m: f64,
    /// Its constant angular velocity, rad/s.
    pub spin_rad_s: [f64; 3],
    /// Its shake, along `shake_normal`.
    pub shake: Shake,
    /// Unit direction of its shake.
    pub shake_normal: [f64; 3],
}

/// The collector's opening, machine frame: x in `x_m`, |y| ≤ half the width, z ≤ `height_m`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Opening {
    /// From the rear end to the front end, m.
    pub x_m: (f64, f64),
    /// Half the working width, m.
    pub half_width_m: f64,
    /// Height above the ground, m.
    pub height_m: f64,
}

impl Opening {
    /// Whether the point `p_m` (machine frame) is in the opening.
    pub fn contains(&self, p_m: [f64; 3]) -> bool {
        (self.x_m.0..=self.x_m.1).contains(&p_m[0])
            && p_m[1].abs() <= self.half_width_m
            && p_m[2] <= self.height_m
    }
}

/// The whole machine at rest in its frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    /// Every part, shovel rows first, then rods, then tooth rows.
    pub parts: Vec<Part>,
    /// Top end of the shovel's surface, m.
    pub shovel_top_m: [f64; 3],
    /// Top end of the chain's surface, m.
    pub chain_top_m: [f64; 3],
    /// A point on the drum's axis (y = 0), m.
    pub drum_axis_m: [f64; 3],
    /// The collector's opening.
    pub opening: Opening,
    /// Half the working width, m.
    pub half_width_m: f64,
}

/// Slack allowed when counting how many pitches fit in a length, as a fraction of a pitch:
/// 0.6 m / 0.05 m is 11.999999999999998 in floating point, and is meant as 12.
const FIT_SLACK: f64 = 1e-9;

/// How many whole `pitch`es fit in `length` (both in one unit).
fn pitches_in(length: f64, pitch: f64) -> f64 {
    (length / pitch + FIT_SLACK).floor()
}

/// How many `pitch`es cover `length`, rounded up.
fn pitches_over(length: f64, pitch: f64) -> f64 {
    (length / pitch - FIT_SLACK).ceil()
}

/// Direction down a slope of `angle_deg` rearwards and up: (−cos α, 0, sin α).
fn slope(angle_deg: f64) -> [f64; 3] {
    let (s, c) = angle_deg.to_radians().sin_cos();
    [-c, 0.0, s]
}

/// Upward unit normal of that slope: (sin α, 0, cos α).
fn normal(angle_deg: f64) -> [f64; 3] {
    let (s, c) = angle_deg.to_radians().sin_cos();
    [s, 0.0, c]
}

fn along(p: [f64; 3], d: [f64; 3], k: f64) -> [f64; 3] {
    [p[0] + k * d[0], p[1] + k * d[1], p[2] + k * d[2]]
}

/// y of the spheres of a row of touching spheres of radius `r_m` over `width_m`: the two
/// ends and evenly spaced points between, no further apart than one diameter.
fn across_touching(width_m: f64, r_m: f64) -> Vec<f64> {
    let n = pitches_over(width_m, 2.0 * r_m) as usize + 1;
    spaced(width_m, n)
}

/// `n` values evenly spaced over ±width/2 (one value: 0).
fn spaced(width_m: f64, n: usize) -> Vec<f64> {
    if n <= 1 {
        return vec![0.0];
    }
    let pitch = width_m / (n - 1) as f64;
    (0..n).map(|k| -width_m / 2.0 + k as f64 * pitch).collect()
}

/// Teeth across one drum row at the tooth pitch, centred.
fn teeth_across(width_m: f64, pitch_m: f64) -> Vec<f64> {
    let n = pitches_in(width_m, pitch_m) as usize + 1;
    spaced(pitch_m * (n - 1) as f64, n)
}

/// The spheres per row of the shovel, the chain and the drum, each with the key that sets
/// it (for [`HarvesterSpec`]'s checks).
pub fn row_counts(spec: &HarvesterSpec) -> Vec<([&'static str; 2], usize)> {
    let w = spec.harvester.width_m;
    let count = |n: f64| {
        if n.is_finite() && n >= 0.0 {
            n as usize
        } else {
            0
        }
    };
    let touching = |r_mm: f64| count(pitches_over(w, 2.0 * r_mm / LENGTH_M_TO_MM) + 1.0);
    vec![
        (
            ["shovel", "sphere_radius_mm"],
            touching(spec.shovel.sphere_radius_mm),
        ),
        (
            ["chain", "rod_diameter_mm"],
            touching(spec.chain.rod_diameter_mm / 2.0),
        ),
        (
            ["drum", "tooth_pitch_mm"],
            count(pitches_in(w, spec.drum.tooth_pitch_mm / LENGTH_M_TO_MM) + 1.0),
        ),
    ]
}

fn row(kind: PartKind, axis_m: [f64; 3], ys: &[f64], r_m: f64) -> Part {
    Part {
        kind,
        centre_m: axis_m,
        spheres_m: ys.iter().map(|&y| [axis_m[0], y, axis_m[2]]).collect(),
        radius_m: r_m,
        spin_rad_s: [0.0; 3],
        shake: Shake::default(),
        shake_normal: [0.0, 0.0, 1.0],
    }
}

impl Layout {
    /// The machine of `spec` (checked).
    pub fn of(spec: &HarvesterSpec) -> Layout {
        let w = spec.harvester.width_m;
        let mm = |v: f64| v / LENGTH_M_TO_MM;
        let mut parts = Vec::new();

        let s = &spec.shovel;
        let (d_s, n_s) = (slope(s.angle_deg), normal(s.angle_deg));
        let r_s = mm(s.sphere_radius_mm);
        let edge = [0.0, 0.0, -s.depth_m];
        let ys = across_touching(w, r_s);
        let rows = pitches_in(s.length_m, 2.0 * r_s) as usize + 1;
        for k in 0..rows {
            let surface = along(edge, d_s, k as f64 * 2.0 * r_s);
            let mut p = row(PartKind::Shovel, along(surface, n_s, -r_s), &ys, r_s);
            p.shake = s.shake;
            p.shake_normal = n_s;
            parts.push(p);
        }
        let shovel_top_m = along(edge, d_s, s.length_m);

        let c = &spec.chain;
        let (d_c, n_c) = (slope(c.angle_deg), normal(c.angle_deg));
        let r_c = mm(c.rod_diameter_mm) / 2.0;
        let pitch = mm(c.rod_pitch_mm);
        let ys = across_touching(w, r_c);
        let rods = (pitches_in(c.length_m, pitch) as usize).max(1);
        let mut last_rod = shovel_top_m;
        for j in 0..rods {
            let surface = along(shovel_top_m, d_c, pitch / 2.0 + j as f64 * pitch);
            last_rod = along(surface, n_c, -r_c);
            let mut p = row(PartKind::Chain, last_rod, &ys, r_c);
            p.spin_rad_s = [0.0, -c.speed_m_s / r_c, 0.0];
            p.shake = c.shake;
            p.shake_normal = n_c;
            parts.push(p);
        }
        let chain_top_m = along(shovel_top_m, d_c, c.length_m);

        let d = &spec.drum;
        let r_t = mm(d.tooth_radius_mm);
        let drum_axis_m = [
            last_rod[0],
            0.0,
            last_rod[2] + r_c + d.clearance_m + r_t + d.radius_m,
        ];
        let ys = teeth_across(w, mm(d.tooth_pitch_mm));
        let omega = d.speed_rpm * std::f64::consts::TAU / 60.0;
        for i in 0..d.rows {
            let th = std::f64::consts::TAU * i as f64 / d.rows as f64;
            let at = [
                drum_axis_m[0] + d.radius_m * th.cos(),
                0.0,
                drum_axis_m[2] + d.radius_m * th.sin(),
            ];
            let mut p = row(PartKind::Drum, at, &ys, r_t);
            // The row turns about the drum's axis: that is its centre of mass.
            p.centre_m = drum_axis_m;
            p.spin_rad_s = [0.0, omega, 0.0];
            parts.push(p);
        }
        let k = &spec.collector;
        Layout {
            parts,
            shovel_top_m,
            chain_top_m,
            drum_axis_m,
            opening: Opening {
                x_m: (
                    drum_axis_m[0] - k.behind_drum_m,
                    drum_axis_m[0] + k.ahead_of_drum_m,
                ),
                half_width_m: w / 2.0,
                height_m: k.height_m,
            },
            half_width_m: w / 2.0,
        }
    }

    /// Spheres of every part.
    pub fn spheres(&self) -> usize {
        self.parts.iter().map(|p| p.spheres_m.len()).sum()
    }

    /// The fastest speed of any point of the machine's spheres, m/s: the forward speed, plus
    /// each part's spin about its centre at its farthest sphere (|ω × d| + |ω|·r, d from
    /// the centre to the sphere's), plus its shake's peak speed 2πf·A.
    pub fn fastest_point_m_s(&self, forward_speed_m_s: f64) -> f64 {
        self.parts
            .iter()
            .map(|p| {
                let w = DVec3::from(p.spin_rad_s);
                let centre = DVec3::from(p.centre_m);
                let turn = p
                    .spheres_m
                    .iter()
                    .map(|&c| w.cross(DVec3::from(c) - centre).length())
                    .fold(0.0, f64::max)
                    + w.length() * p.radius_m;
                let shake = std::f64::consts::TAU * p.shake.frequency_hz * p.shake.amplitude_mm
                    / LENGTH_M_TO_MM;
                forward_speed_m_s + turn + shake
            })
            .fold(0.0, f64::max)
    }

    /// Height of the machine's carrying surface (shovel, then chain) at `x_m`, m; `None`
    /// ahead of the edge or behind the chain's top end.
    pub fn surface_z_m(&self, x_m: f64) -> Option<f64> {
        let lerp = |a: [f64; 3], b: [f64; 3]| a[2] + (x_m - a[0]) / (b[0] - a[0]) * (b[2] - a[2]);
        let edge_z = self
            .parts
            .first()
            .map_or(0.0, |p| p.centre_m[2] + p.radius_m * p.shake_normal[2]);
        let edge = [0.0, 0.0, edge_z];
        if x_m > 0.0 || x_m < self.chain_top_m[0] {
            None
        } else if x_m >= self.shovel_top_m[0] {
            Some(lerp(edge, self.shovel_top_m))
        } else {
            Some(lerp(self.shovel_top_m, self.chain_top_m))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shipped() -> HarvesterSpec {
        let text = include_str!("../../../testdata/peanut-plant/harvester-digger.toml");
        HarvesterSpec::from_toml(std::path::Path::new("harvester-digger.toml"), text).unwrap()
    }

    /// The gap between neighbouring rods, measured between the built rods' axes, is the
    /// file's pitch − diameter (to 1e-12 m).
    #[test]
    fn rod_gap_is_pitch_minus_diameter() {
        let spec = shipped();
        let layout = Layout::of(&spec);
        let rods: Vec<&Part> = layout
            .parts
            .iter()
            .filter(|p| p.kind == PartKind::Chain)
            .collect();
        assert!(rods.len() >= 2);
        let gap_mm = spec.chain.rod_pitch_mm - spec.chain.rod_diameter_mm;
        for pair in rods.windows(2) {
            let [a, b] = [pair[0].centre_m, pair[1].centre_m];
            let dist = ((a[0] - b[0]).powi(2) + (a[2] - b[2]).powi(2)).sqrt();
            let gap = dist - 2.0 * pair[0].radius_m;
            assert!((gap * LENGTH_M_TO_MM - gap_mm).abs() < 1e-9, "gap {gap} m");
        }
        // Their tops move rearwards at the chain speed: ω × (r n) has x = −v cos β... its
        // magnitude is ω r = v.
        let w = rods[0].spin_rad_s[1];
        assert!((w.abs() * rods[0].radius_m - spec.chain.speed_m_s).abs() < 1e-12);
        assert!(w < 0.0, "tops would move forwards");
    }

    /// The shovel's edge is at the file's depth and its plate at the file's angle: the top
    /// points of its first and last rows lie on the line from the edge at α (to 1e-12 m).
    #[test]
    fn shovel_edge_depth_and_angle() {
        let spec = shipped();
        let layout = Layout::of(&spec);
        let rows: Vec<&Part> = layout
            .parts
            .iter()
            .filter(|p| p.kind == PartKind::Shovel)
            .collect();
        let top = |p: &Part| along(p.centre_m, p.shake_normal, p.radius_m);
        let first = top(rows[0]);
        assert!((first[2] + spec.shovel.depth_m).abs() < 1e-12);
        assert!(first[0].abs() < 1e-12);
        let last = top(rows[rows.len() - 1]);
        let angle = ((last[2] - first[2]) / (first[0] - last[0]))
            .atan()
            .to_degrees();
        assert!(
            (angle - spec.shovel.angle_deg).abs() < 1e-9,
            "angle {angle}°"
        );
        // Neighbouring rows touch (one diameter apart): soil cannot pass through the plate.
        let step = (rows[1].centre_m[0] - rows[0].centre_m[0])
            .hypot(rows[1].centre_m[2] - rows[0].centre_m[2]);
        assert!((step - 2.0 * rows[0].radius_m).abs() < 1e-12);
        assert_eq!(layout.surface_z_m(0.0), Some(-spec.shovel.depth_m));
    }

    /// Drum teeth lie at the drum radius from its axis and the bottom ones move rearwards;
    /// the tooth circle clears the last rod by the file's clearance.
    #[test]
    fn drum_teeth_and_clearance() {
        let spec = shipped();
        let layout = Layout::of(&spec);
        let teeth: Vec<&Part> = layout
            .parts
            .iter()
            .filter(|p| p.kind == PartKind::Drum)
            .collect();
        assert_eq!(teeth.len(), spec.drum.rows);
        let a = layout.drum_axis_m;
        for t in &teeth {
            for s in &t.spheres_m {
                let r = (s[0] - a[0]).hypot(s[2] - a[2]);
                assert!((r - spec.drum.radius_m).abs() < 1e-12);
            }
            // Bottom-point velocity ω × (0, 0, −R) has x = −ω R.
            assert!(-t.spin_rad_s[1] * spec.drum.radius_m < 0.0);
        }
        let last_rod = layout
            .parts
            .iter()
            .rfind(|p| p.kind == PartKind::Chain)
            .unwrap();
        let lowest_tooth = a[2] - spec.drum.radius_m - spec.drum.tooth_radius_mm / LENGTH_M_TO_MM;
        let gap = lowest_tooth - (last_rod.centre_m[2] + last_rod.radius_m);
        assert!((gap - spec.drum.clearance_m).abs() < 1e-12, "gap {gap}");
    }

    /// The shipped machine's counts, worked by hand: 0.25 m of shovel in 10 mm rows is 25
    /// pitches, 26 rows; 0.6 m in 10 mm is 60 pitches, 61 spheres; 0.8 m of chain at 40 mm
    /// is 20 rods of ⌈600/10.5⌉ + 1 = 59 spheres; 0.6 m at 50 mm is 12 pitches, 13 teeth.
    /// The shipped machine's fastest point is a drum tooth's outer surface: forward speed
    /// plus ω·(R + r_t), ω = 2π·rpm/60 (by hand: 1.0 + 49.218·0.206 = 11.139 m/s), faster than
    /// the chain rods (1.0 + 1.02) and the shaken shovel (1.0 + 2πfA).
    #[test]
    fn the_fastest_point_is_a_drum_tooth() {
        let spec = shipped();
        let layout = Layout::of(&spec);
        let v = spec.harvester.forward_speed_m_s;
        let omega = spec.drum.speed_rpm * std::f64::consts::TAU / 60.0;
        let tip = v + omega * (spec.drum.radius_m + spec.drum.tooth_radius_mm / LENGTH_M_TO_MM);
        let got = layout.fastest_point_m_s(v);
        assert!((got - tip).abs() < 1e-9, "{got} against {tip}");
    }

    #[test]
    fn the_shipped_machine_has_its_hand_worked_counts() {
        let layout = Layout::of(&shipped());
        let count = |kind| layout.parts.iter().filter(|p| p.kind == kind).count();
        let per_row = |kind| {
            layout
                .parts
                .iter()
                .find(|p| p.kind == kind)
                .map(|p| p.spheres_m.len())
        };
        assert_eq!(
            (count(PartKind::Shovel), per_row(PartKind::Shovel)),
            (26, Some(61))
        );
        assert_eq!(
            (count(PartKind::Chain), per_row(PartKind::Chain)),
            (20, Some(59))
        );
        assert_eq!(
            (count(PartKind::Drum), per_row(PartKind::Drum)),
            (6, Some(13))
        );
        assert_eq!(layout.spheres(), 26 * 61 + 20 * 59 + 6 * 13);
    }

    #[test]
    fn rows_span_the_width_within_one_clump() {
        let spec = shipped();
        let layout = Layout::of(&spec);
        for p in &layout.parts {
            assert!(p.spheres_m.len() <= MAX_ROW_SPHERES);
            let ys: Vec<f64> = p.spheres_m.iter().map(|s| s[1]).collect();
            let span = ys.iter().cloned().fold(f64::MIN, f64::max)
                - ys.iter().cloned().fold(f64::MAX, f64::min);
            assert!(span <= spec.harvester.width_m + 1e-12);
            if p.kind != PartKind::Drum {
                assert!((span - spec.harvester.width_m).abs() < 1e-12);
                // Touching or overlapping neighbours: no gap for soil across a row.
                let pitch = span / (ys.len() - 1) as f64;
                assert!(pitch <= 2.0 * p.radius_m + 1e-12);
            }
        }
    }
}
