//! Issue 20, item 2: a field of plants in ridge rows with their pods in a soil bed
//! (`arachis::field`, `arachis field`).
//!
//! - The shipped field plants every hole, and every pod hangs at a depth within the
//!   variety's stated spread (10–70 mm for the junction).
//! - No two bodies of the laid-out field interpenetrate (plants of different holes, grains,
//!   pods), since every contact between them is on; the soil then settles around the held
//!   plants (`tests/field_settle.rs`).
//! - A bare bed settles onto its floor: at rest, the floor carries the grains' weight
//!   (static equilibrium; the bed has no side walls, so nothing else can carry it).
//! - The field's world steps with contacts between plants and with the soil, with the same
//!   bits on 1 and 2 threads.
//! - Bad field input: exit 2, the file, line and key named, nothing written.
//! - The printed line names the bonds that broke: by set, and the first break.

use std::path::{Path, PathBuf};

use arachis::arena::{OwnedBonds, OwnedStorage};
use arachis::field::layout::holes;
use arachis::field::{Field, FieldSpec};
use arachis::plant::overlap::SphereGrid;
use arachis_core::prelude::*;

use crate::cli_support::{arachis, assert_refused, small_field_files, REPO_ROOT};

/// Standard gravity used by the field's world, m/s².
const G_M_S2: f64 = 9.81;

fn shipped_path() -> PathBuf {
    Path::new(REPO_ROOT).join("testdata/peanut-plant/field-huayu.toml")
}

fn shipped() -> FieldSpec {
    FieldSpec::read(&shipped_path()).expect("the shipped field file reads")
}

/// Steps `field` in a fresh fixed-point world on `threads` threads; returns the digest, the
/// bonds left and the floor's vertical force, N (the force the grains push it with).
fn step(spec: &FieldSpec, field: &Field, steps: u64, threads: usize) -> (u64, usize, f64, f64) {
    let mut arena = OwnedStorage::<Fx>::new(field.storage_lengths(spec));
    let mut bonds = OwnedBonds::<Fx>::new(field.bond_count());
    let mut w = World::new(arena.storage()).unwrap();
    w.attach_bond_storage(bonds.storage()).unwrap();
    let loaded = field.load_into(spec, &mut w).unwrap();
    arachis::stepping::with_threads(threads, || arachis::stepping::run(&mut w, steps)).unwrap();
    let floor_n = -w.walls()[loaded.floor.0 as usize].force.z.to_f64();
    let ke_j = w.kinetic_energy_mj() / 1000.0;
    (w.digest(), w.bonds().bonds().len(), floor_n, ke_j)
}

#[test]
fn the_shipped_field_plants_every_hole_with_its_pods_at_their_depth() {
    let spec = shipped();
    // The plants are held while the soil settles (`tests/field_settle.rs`), so the layout
    // places them for good.
    let field = spec.lay_out(1).unwrap();
    let holes = holes(&spec);
    assert_eq!(
        holes.len(),
        spec.field.rows * 5,
        "1 m of ridge at 0.2 m holes"
    );
    assert_eq!(field.plants.len(), holes.len() * spec.field.plants_per_hole);
    for (p, hole) in field.plants.iter().zip(&holes) {
        assert_eq!([p.root_m[0], p.root_m[1]], *hole);
        let root = &p.model.spheres[p.model.bodies[0].spheres[0]];
        assert!((root.centre_m[0] - hole[0]).abs() < 1e-12);
    }
    let depth = spec.variety.as_ref().unwrap().pods.depth_mm;
    let mut pods = 0;
    for p in &field.plants {
        for d in p.model.junction_depths_mm() {
            assert!(
                (depth.low() - 1e-6..=depth.high() + 1e-6).contains(&d),
                "junction at {d} mm, outside the variety's {}–{} mm",
                depth.low(),
                depth.high()
            );
            pods += 1;
        }
    }
    assert_eq!(pods, field.pods());
    assert!(
        field.pods() > 5 * field.plants.len(),
        "{} pods",
        field.pods()
    );
    assert!(!field.grains.is_empty());
}

#[test]
fn no_two_bodies_of_the_laid_out_field_interpenetrate() {
    let spec = shipped();
    // Before the soil settles (the settled grains press on each other and on the plants
    // within their weight's Hertz overlap: `tests/field_settle.rs`).
    let field = spec.lay_out(1).unwrap();
    // Each sphere with its body: plant p's body b, or a grain.
    let mut spheres: Vec<([f64; 3], f64, (usize, usize))> = Vec::new();
    for (p, plant) in field.plants.iter().enumerate() {
        for s in &plant.model.spheres {
            spheres.push((s.centre_m, s.radius_m, (p, s.body)));
        }
    }
    for (g, grain) in field.grains.iter().enumerate() {
        spheres.push((grain.centre_m, grain.radius_m, (usize::MAX, g)));
    }
    let largest = spheres.iter().map(|s| s.1).fold(0.0, f64::max);
    let mut grid = SphereGrid::new(largest);
    for s in &spheres {
        grid.insert(s.0, s.1);
    }
    // Bonded neighbours of one plant are placed 1 µm apart; nothing may overlap by more
    // than 0.1 µm.
    let mut clashes = Vec::new();
    for (a, s) in spheres.iter().enumerate() {
        for b in grid.overlapping(s.0, s.1, 1e-7).filter(|&b| b > a) {
            if spheres[b].2 != s.2 {
                clashes.push((s.2, spheres[b].2));
            }
        }
    }
    assert!(
        clashes.is_empty(),
        "{} clashes, first {:?}",
        clashes.len(),
        &clashes[..clashes.len().min(5)]
    );
    assert!(spheres.len() > 30_000, "{} spheres", spheres.len());
}

#[test]
fn one_seed_gives_one_field_and_another_seed_another() {
    let spec = shipped();
    // The layout; the settling gives the same grains on any thread count
    // (`tests/field_settle.rs`).
    let a = spec.lay_out(3).unwrap();
    assert_eq!(a, spec.lay_out(3).unwrap());
    let b = spec.lay_out(4).unwrap();
    assert_ne!(a.plants[0].model, b.plants[0].model);
}

#[test]
fn a_bare_bed_settles_until_its_floor_carries_the_grains_weight() {
    let mut spec = shipped();
    spec.field.plants_per_hole = 0;
    spec.field.rows = 1;
    spec.field.ridge_length_m = 0.2;
    spec.soil.margin_m = 0.05;
    spec.soil.depth_m = 0.06;
    let field = spec.plant(1).unwrap();
    assert!(field.plants.is_empty());
    let weight_n: f64 = field
        .grains
        .iter()
        .map(|g| {
            spec.soil.density_kg_m3 * 4.0 / 3.0 * std::f64::consts::PI * g.radius_m.powi(3) * G_M_S2
        })
        .sum();
    let probe = {
        let mut arena = OwnedStorage::<Fx>::new(field.storage_lengths(&spec));
        let mut w = World::new(arena.storage()).unwrap();
        field.load_into(&spec, &mut w).unwrap();
        w.timestep_s()
    };
    // 0.5 s: the grains fall at most a few millimetres into place, then their contacts
    // damp the rebounds (restitution 0.4).
    let steps = (0.5 / probe).ceil() as u64;
    let (_, _, floor_n, ke_j) = step(&spec, &field, steps, 2);
    let ratio = floor_n / weight_n;
    println!(
        "{} grains, weight {weight_n:.3} N, floor {floor_n:.3} N (ratio {ratio:.4}), KE {ke_j:.2e} J after {steps} steps",
        field.grains.len()
    );
    // At rest the floor carries the whole weight; the residual motion after 0.5 s is
    // allowed 2 %.
    assert!((ratio - 1.0).abs() < 0.02, "floor/weight = {ratio}");
}

/// The shipped field's digest after 40 steps (seed 1): `arachis field
/// testdata/peanut-plant/field-huayu.toml --steps 40`. The field's 44 007 sphere records
/// outgrow the second-level cache, so its steps take the hinted loads
/// (`arachis_core::step::prefetch`), which must change no bit. Since the soil steps on a
/// stride of 10 (multi-rate stepping) the digest is this one; with every grain stepping
/// every step it was 1f54e69f92bc78c7, as before the hints (05f0b85). Since the soil settles
/// around the held plants before the run (`arachis::field::settle`) it was db57a548ba0489ca
/// (on the loose lattice d5b48f0ea61b608b); since the pods settle with the soil and their
/// pegs follow them (`arachis::field::peg`: 30 595 of 39 078 laid grains kept, 44 007
/// spheres, a time step of 7.46e-7 s) it is 9651ca8564892a48.
const SHIPPED_DIGEST_40_STEPS: u64 = 0x9651_ca85_6489_2a48;

#[test]
fn the_field_steps_with_the_same_bits_on_one_and_two_threads() {
    let spec = shipped();
    let field = spec.plant(1).unwrap();
    let one = step(&spec, &field, 40, 1);
    let two = step(&spec, &field, 40, 2);
    assert_eq!(one.0, two.0, "digest on 1 and 2 threads");
    assert_eq!(
        one.0, SHIPPED_DIGEST_40_STEPS,
        "digest {:016x} after 40 steps, against the one before the memory hints",
        one.0
    );
    assert_eq!(
        one.1,
        field.bond_count(),
        "no bond breaks in 40 steps of settling"
    );
}

#[test]
fn bad_field_input_exits_2_naming_file_line_and_key_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(shipped_path()).unwrap();
    std::fs::copy(
        Path::new(REPO_ROOT).join("testdata/peanut-plant/variety-huayu.toml"),
        dir.path().join("variety-huayu.toml"),
    )
    .unwrap();
    let vtk = dir.path().join("field.vtk");
    let cases = [
        ("depth_m = 0.10", "depth_m = -0.10", "soil.depth_m"),
        ("rows = 2", "rows = 0", "field.rows"),
        (
            "friction = 0.6",
            "friction = 1e300",
            "soil.contacts.soil.friction",
        ),
        (
            "ridge_length_m = 1.0",
            "ridge_length_m = 1.0\nridge_lenght_m = 2.0",
            "ridge_lenght_m",
        ),
        (
            "variety-huayu.toml",
            "no-such-variety.toml",
            "no-such-variety.toml",
        ),
        ("slow_stride = 10", "slow_stride = 3", "soil.slow_stride"),
        ("settle_s = 0.3", "settle_s = -1.0", "soil.settle_s"),
        (
            "duration_s = 0.0075",
            "duration_s = -1.0",
            "calm.duration_s",
        ),
        (
            "drag_coefficient = 2.5",
            "drag_coefficient = 1e9",
            "calm.drag_coefficient",
        ),
        (
            "medium_density_kg_m3 = 1000.0",
            "medium_density_kg_m3 = inf",
            "calm.medium_density_kg_m3",
        ),
        // A calm of no medium calms nothing: said at its duration.
        (
            "drag_coefficient = 2.5",
            "drag_coefficient = 0.0",
            "calm.duration_s",
        ),
        (
            "drag_coefficient = 2.5",
            "drag_coefficient = 2.5\ndrag_coeficient = 1.0",
            "drag_coeficient",
        ),
    ];
    for (from, to, named) in cases {
        assert!(text.contains(from), "{from}");
        let path = dir.path().join("field.toml");
        std::fs::write(&path, text.replacen(from, to, 1)).unwrap();
        assert_refused(
            &[
                "field",
                path.to_str().unwrap(),
                "--vtk",
                vtk.to_str().unwrap(),
            ],
            named,
            &vtk,
        );
    }
    // A line number for a key the file has.
    std::fs::write(
        dir.path().join("field.toml"),
        text.replacen("rows = 2", "rows = 0", 1),
    )
    .unwrap();
    let out = arachis(&["field", dir.path().join("field.toml").to_str().unwrap()]);
    let line = text.lines().position(|l| l.starts_with("rows = ")).unwrap() + 1;
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains(&format!(":{line}:")), "line {line}: {err}");
    // A run that would end within a cycle of the soil's steps (its last checkpoint could not
    // be written) is refused before any step. The world's stride is known once the settled
    // field is loaded: the one-plant cut of the shipped field (`small_field_files`, the same
    // stride of 10) settles in a second where the whole field takes about a minute.
    let (small, _) = small_field_files(dir.path());
    let out = arachis(&[
        "field",
        small.to_str().unwrap(),
        "--steps",
        "45",
        "--vtk",
        vtk.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("--steps 45") && err.contains("multiple of 10"),
        "{err}"
    );
    assert!(!vtk.exists());
}

#[test]
fn the_soil_takes_its_long_step_only_where_its_own_bound_allows() {
    let stride_of = |spec: &FieldSpec| {
        let field = spec.lay_out(1).unwrap();
        let mut arena = OwnedStorage::<Fx>::new(field.storage_lengths(spec));
        let mut bonds = OwnedBonds::<Fx>::new(field.bond_count());
        let mut w = World::new(arena.storage()).unwrap();
        w.attach_bond_storage(bonds.storage()).unwrap();
        field.load_into(spec, &mut w).unwrap();
        let bound = arachis::field::world::TIMESTEP_SAFETY * w.max_slow_timestep_s();
        (w.slow_stride(), w.timestep_s(), bound)
    };
    // The shipped field: the stalks' bonds set dt, and the grains take the file's 10 steps.
    let spec = shipped();
    assert_eq!(spec.soil.slow_stride, 10);
    let (k, dt, bound) = stride_of(&spec);
    assert_eq!(k, 10);
    assert!(f64::from(k) * dt <= bound);
    // 250 asked for: the largest divisor of 250 within the grains' bound (dt ≈ 8.3e-7 s,
    // bound ≈ 2.2e-4 s: 250 steps are 2.1e-4 s).
    let mut wide = shipped();
    wide.soil.slow_stride = 250;
    let (k, dt, bound) = stride_of(&wide);
    assert!(f64::from(k) * dt <= bound && 250 % k == 0, "{k}");
    // A bare bed: the grains set dt themselves, so they step every step.
    let mut bare = shipped();
    bare.field.plants_per_hole = 0;
    bare.field.ridge_length_m = 0.2;
    bare.field.rows = 1;
    assert_eq!(stride_of(&bare).0, 1);
}

/// The printed line says which bonds broke: a count by bond set and the first break. A
/// one-plant field whose pod–stalk bonds hold 1 Pa loses them as soon as it steps.
#[test]
fn the_line_names_the_bonds_that_broke() {
    let dir = tempfile::tempdir().unwrap();
    let (small, _) = small_field_files(dir.path());
    let variety = dir.path().join("variety-huayu.toml");
    let text = std::fs::read_to_string(&variety).unwrap();
    let junction = "[bonds.pod_stalk]\nkn_n_m3 = 1.33e10\nkt_n_m3 = 5.35e9\nsigma_c_pa = 9.35e5";
    assert!(text.contains(junction), "the shipped junction");
    let weak = junction.replace("sigma_c_pa = 9.35e5", "sigma_c_pa = 1.0");
    std::fs::write(&variety, text.replacen(junction, &weak, 1)).unwrap();
    let out = arachis(&["field", small.to_str().unwrap(), "--steps", "500"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let line: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let broken = line["bonds_broken"].as_u64().unwrap();
    assert!(broken > 0, "{line}");
    assert_eq!(
        line["bonds_broken_by_set"]["pod_stalk"].as_u64(),
        Some(broken)
    );
    let first = &line["first_break"];
    assert_eq!(first["set"], "pod_stalk", "{first}");
    assert_eq!(first["criterion"], "Normal", "{first}");
    assert!(first["step"].as_u64().unwrap() < 500, "{first}");
    assert!(
        first["sigma_max_mpa"].as_f64().unwrap() >= 1.0e-6,
        "{first}"
    );
}
