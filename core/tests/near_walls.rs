//! Near-wall sets: the neighbour-list rebuild records which walls each sphere may touch, and
//! the contact loop tests only those. Two checks that the skipping never loses a contact:
//! - `WallShape::may_touch` is conservative: when it says "far", no relative displacement
//!   shorter than the margin (L1) brings the sphere into contact (proptest, every shape);
//! - fast walls of every shape sweep through a cloud of moving spheres, and every step the
//!   world's live wall contacts equal a brute-force test of every sphere against every wall.

use crate::common;
use arachis_core::contact::history::wall_key;
use arachis_core::contact::WALL_PARTNER_FLAG;
use arachis_core::prelude::*;
use arachis_core::wall::WallShape;
use common::*;
use std::collections::BTreeSet;

/// Margin of the proptest, mm (the bench bed's skin is 0.5 mm).
const MARGIN_MM: f64 = 0.5;

fn shape_of(geometry: WallGeometry) -> WallShape<Fx> {
    WallSpec::fixed(geometry, MaterialId(0))
        .build::<Fx>()
        .unwrap()
        .shape
}

fn touches(shape: &WallShape<Fx>, c: [f64; 3], r_mm: f64) -> bool {
    let mut hit = false;
    shape.for_each_contact(Vec3::from_f64(c), Fx::from_f64(r_mm), |_, _, _| hit = true);
    hit
}

fn geometry(kind: u8, p: [f64; 3], dir: [f64; 3], size: f64) -> WallGeometry {
    match kind {
        0 => WallGeometry::Plane {
            point_m: p,
            normal: dir,
        },
        1 | 2 => WallGeometry::Cylinder {
            base_m: p,
            axis: dir,
            radius_m: size,
            length_m: (kind == 2).then_some(2.0 * size),
        },
        _ => WallGeometry::AaBox {
            min_m: p,
            max_m: [p[0] + size, p[1] + 1.5 * size, p[2] + 2.0 * size],
        },
    }
}

/// A point of the wall's edges in mm (where "far" is hardest to judge): the plane's point,
/// the cylinder's rim at its base end, the box's lower corner.
fn edge_point_mm(kind: u8, p: [f64; 3], dir: [f64; 3], size: f64) -> [f64; 3] {
    let mm = p.map(|x| x * 1e3);
    if kind != 1 && kind != 2 {
        return mm;
    }
    // A unit vector across the axis: axis × (the basis vector least along it).
    let n = dir.iter().map(|x| x * x).sum::<f64>().sqrt();
    let a = dir.map(|x| x / n);
    let e = if a[0].abs() < 0.5 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let c = [
        a[1] * e[2] - a[2] * e[1],
        a[2] * e[0] - a[0] * e[2],
        a[0] * e[1] - a[1] * e[0],
    ];
    let cn = c.iter().map(|x| x * x).sum::<f64>().sqrt();
    [0, 1, 2].map(|k| mm[k] + size * 1e3 * c[k] / cn)
}

/// Deterministic uniform numbers in [lo, hi) (xorshift64; the test needs no shrinking).
struct Draw(u64);

impl Draw {
    fn next(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        lo + (hi - lo) * (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn three(&mut self, lo: f64, hi: f64) -> [f64; 3] {
        [(); 3].map(|_| self.next(lo, hi))
    }
}

/// A sphere judged far from a wall stays out of contact for every displacement it can make
/// before the next rebuild (here: a fan of 26 directions scaled to just under the margin,
/// L1 norm). Random walls of every shape; centres drawn within 2(R + 2 mm) of an edge of the
/// wall, where the judgement is closest.
#[test]
fn far_means_no_contact_within_margin() {
    const CASES: usize = 40_000;
    let mut draw = Draw(0x2545_f491_4f6c_dd1d);
    let mut far_cases = [0usize; 4];
    for case in 0..CASES {
        let kind = (case % 4) as u8;
        let p = draw.three(-0.02, 0.02);
        let dir = draw.three(-1.0, 1.0);
        let size = draw.next(0.01, 0.05);
        let r = draw.next(0.5, 8.0);
        let jitter = draw.three(-2.0, 2.0);
        if dir.iter().map(|x| x * x).sum::<f64>() < 0.01 {
            continue;
        }
        let shape = shape_of(geometry(kind, p, dir, size));
        let mut edge = edge_point_mm(kind, p, dir, size);
        if kind == 3 {
            // Far from a box means inside by R + margin from all six faces: centre the draw on
            // the corner of that inner region.
            edge = edge.map(|x| x + r + 2.0);
        }
        let c = [0, 1, 2].map(|k| edge[k] + (r + 2.0) * jitter[k]);
        if shape.may_touch(Vec3::from_f64(c), Fx::from_f64(r), Fx::from_f64(MARGIN_MM)) {
            continue;
        }
        far_cases[kind as usize] += 1;
        for dx in [-1.0, 0.0, 1.0] {
            for dy in [-1.0, 0.0, 1.0] {
                for dz in [-1.0, 0.0, 1.0] {
                    let l1: f64 = [dx, dy, dz].iter().map(|x: &f64| x.abs()).sum();
                    if l1 == 0.0 {
                        continue;
                    }
                    let s = 0.999 * MARGIN_MM / l1;
                    let moved = [c[0] + s * dx, c[1] + s * dy, c[2] + s * dz];
                    assert!(!touches(&shape, moved, r), "{kind} {c:?} → {moved:?}");
                }
            }
        }
    }
    println!("far cases per shape (plane, cylinder, finite cylinder, box): {far_cases:?}");
    assert!(far_cases.iter().all(|&n| n >= 1_000), "{far_cases:?}");
}

/// Live wall contacts of every sphere as (sphere, wall key) pairs.
fn live_wall_contacts(w: &World<'_, Fx>) -> BTreeSet<(u32, u32)> {
    (0..w.spheres().len() as u32)
        .flat_map(|s| {
            w.contact_slots(s)
                .filter(|c| c.partner & WALL_PARTNER_FLAG != 0)
                .map(move |c| (s, c.partner))
        })
        .collect()
}

/// Every (sphere, wall key) in contact, testing every wall.
fn brute_force_wall_contacts(w: &World<'_, Fx>) -> BTreeSet<(u32, u32)> {
    let mut set = BTreeSet::new();
    for (si, s) in w.spheres().iter().enumerate() {
        for (wi, wall) in w.walls().iter().enumerate() {
            wall.shape
                .for_each_contact(s.position, s.radius, |face, _, _| {
                    set.insert((si as u32, wall_key(wi as u32, face)));
                });
        }
    }
    set
}

#[test]
fn fast_walls_never_miss_a_contact() {
    const SPHERES: usize = 120;
    let mut o = Owned::<Fx>::new(SPHERES, SPHERES);
    let (mut w, pod, steel) = pod_steel_world(&mut o, PairSpec::hertz_mindlin(0.5, 0.5, 0.0));
    // Container walls at 1–1.5 m/s (20–30 µm per step; the skin is 0.5 mm) that close in on
    // the cloud: a rising floor, an infinite cylinder and a tall finite one moving across
    // their axes, and a box moving sideways.
    let walls = [
        (
            geometry(0, [0.0, 0.0, -0.005], [0.0, 0.0, 1.0], 0.0),
            [0.0, 0.0, 1.0],
        ),
        (
            geometry(1, [0.0; 3], [0.0, 0.0, 1.0], 0.045),
            [-1.0, 0.0, 0.0],
        ),
        (
            WallGeometry::Cylinder {
                base_m: [0.0, 0.0, -0.02],
                axis: [0.0, 0.0, 1.0],
                radius_m: 0.05,
                length_m: Some(0.1),
            },
            [0.0, 1.5, 0.0],
        ),
        (
            WallGeometry::AaBox {
                min_m: [-0.04, -0.04, -0.02],
                max_m: [0.04, 0.04, 0.1],
            },
            [1.5, 0.0, 0.0],
        ),
    ];
    for (geometry, velocity_m_s) in walls {
        w.add_wall(WallSpec {
            geometry,
            material: steel,
            velocity_m_s,
        })
        .unwrap();
    }
    // A 6 × 5 × 4 lattice of 3 mm spheres, 10 mm apart, drifting slowly without gravity: the
    // walls, not the spheres, drive the neighbour-list rebuilds until they hit.
    for k in 0..SPHERES {
        let (i, j, l) = (k % 6, (k / 6) % 5, k / 30);
        let mut s = SphereSpec::at_rest(
            pod,
            0.003,
            [
                -0.025 + 0.01 * i as f64,
                -0.02 + 0.01 * j as f64,
                0.005 + 0.01 * l as f64,
            ],
        );
        let phase = k as f64 * 2.399;
        s.velocity_m_s = [0.05 * phase.cos(), 0.05 * phase.sin(), 0.0];
        w.add_sphere(s).unwrap();
    }
    w.set_gravity_m_s2([0.0; 3]).unwrap();
    w.set_timestep_s(2e-5).unwrap();
    let mut contacts_seen = 0usize;
    for step in 0..1_000 {
        // The contacts of a step are those of the positions at its start.
        let expected = brute_force_wall_contacts(&w);
        w.step().unwrap();
        let live = live_wall_contacts(&w);
        assert_eq!(live, expected, "step {step}");
        contacts_seen += live.len();
    }
    println!("{contacts_seen} sphere–wall contact-steps checked");
    // The sweep must actually bring spheres onto the walls for the check to mean anything.
    assert!(contacts_seen > 5_000, "{contacts_seen}");
}
