//! Golden digests of the three standard scenarios (issue 2, "Bit-exact digests"), plus the
//! properties that make a digest worth having: two runs dump identical per-body states, and a
//! one-bit change of an input changes the digest.
//!
//! The goldens live in `testdata/digests/<scenario>.txt` and are checked in debug *and*
//! release (`scripts/test-all.sh` runs the core tests in both profiles), so they also prove
//! that the two profiles step to the same bits. After an intended change of the physics or
//! of a scenario, regenerate them deliberately with
//!
//! ```sh
//! ARACHIS_BLESS=1 cargo test -p arachis-core --test scenarios digest_scenarios::
//! ```
//!
//! and say why in the commit message. A mismatch prints both digests, this command, and the
//! path of a per-body dump of the new state (diff it against a dump of the old build to find
//! the first body that diverged).

use crate::common;
use arachis_core::bond::{Bond, BondBreak, BondStorage};
use arachis_core::prelude::*;
use arachis_core::scenario::bulk_density::{slab_bulk_density_kg_m3, BulkDensity};
use arachis_core::scenario::drum::{bed_angle_deg, Drum};
use arachis_core::scenario::hopper::{discharged_mass_g, CATCH_DEPTH_M, SHUTTER};
use arachis_core::scenario::{BenchBed, ClumpSlide, Hopper, MovingWallPile, PullOff};
use common::{run_threaded, Owned};
use std::fmt::Write as _;
use std::path::PathBuf;

/// Environment variable that makes the golden checks rewrite the files instead.
const BLESS_VAR: &str = "ARACHIS_BLESS";
/// The command that regenerates the goldens.
const BLESS_COMMAND: &str =
    "ARACHIS_BLESS=1 cargo test -p arachis-core --test scenarios digest_scenarios::";

/// Pour: steps before the digest. Early in the DESIGN §8 pour (0.1 s), when the lowest
/// spheres have reached the floor and pile up, so the history is well populated, while a
/// debug run stays at about 20 s.
const POUR_STEPS: u64 = 5_000;
/// Pour: live contacts required at the digest (about 500 measured), so that the digest covers
/// a substantial contact history.
const POUR_MIN_CONTACTS: u32 = 400;
/// Pour: sphere–sphere contacts required among them (not only floor contacts).
const POUR_MIN_SPHERE_CONTACTS: u32 = 100;
/// Clump slide: steps before the digest (80 ms: the chain closes up and hits the stop wall).
const CLUMP_STEPS: u64 = 4_000;
/// Moving wall: steps of blade motion after the pile has settled (40 mm of travel).
const BLADE_STEPS: u64 = 2_000;
/// Moving wall: live contacts required at the digest.
const PILE_MIN_CONTACTS: u32 = 40;
/// Pull-off: steps before the digest (2.5 ms; the junction breaks in step 4 196, so the
/// digest covers the break log, the surviving stalk bonds and the detached pod).
const PULL_OFF_STEPS: u64 = 5_000;
/// Pull-off: largest relative difference between the measured detachment force and σc·A of
/// the junction (measured −3.7e-4). The gripper starts at full speed, so the undamped stalk
/// rings; its force amplitude is at most v·√(k·m) ≈ 0.08 N, 2 % of 3.55 N.
const PULL_OFF_FORCE_TOL: f64 = 0.01;

/// Live contacts split into (sphere–sphere, sphere–wall).
fn contact_kinds<S: Scalar>(world: &World<'_, S>) -> (u32, u32) {
    let (mut spheres, mut walls) = (0, 0);
    for s in 0..world.spheres().len() as u32 {
        for slot in world.contact_slots(s) {
            if slot.partner & arachis_core::contact::WALL_PARTNER_FLAG != 0 {
                walls += 1;
            } else {
                spheres += 1;
            }
        }
    }
    (spheres, walls)
}

/// The per-body dump, one line per body.
fn dump<S: Scalar>(world: &World<'_, S>) -> Vec<String> {
    world.body_records().map(|r| r.to_string()).collect()
}

/// What a golden file records.
#[derive(Debug, PartialEq)]
struct Golden {
    steps: u64,
    digest: u64,
}

fn golden_path(scenario: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../testdata/digests")
        .join(format!("{scenario}.txt"))
}

fn parse_golden(text: &str) -> Option<Golden> {
    let value = |key: &str| {
        text.lines()
            .filter(|l| !l.starts_with('#'))
            .filter_map(|l| l.split_once('='))
            .find(|(k, _)| k.trim() == key)
            .map(|(_, v)| v.trim().to_string())
    };
    Some(Golden {
        steps: value("steps")?.parse().ok()?,
        digest: u64::from_str_radix(value("digest")?.trim_start_matches("0x"), 16).ok()?,
    })
}

fn render_golden(scenario: &str, about: &str, got: &Golden) -> String {
    let mut s = String::new();
    for line in about.lines() {
        writeln!(s, "# {line}").unwrap();
    }
    writeln!(
        s,
        "# Checked by core/tests/digest_scenarios.rs in debug and release."
    )
    .unwrap();
    writeln!(
        s,
        "# Regenerate deliberately, after an intended change only:"
    )
    .unwrap();
    writeln!(s, "#   {BLESS_COMMAND}").unwrap();
    writeln!(s, "scenario = {scenario}").unwrap();
    writeln!(s, "scalar = fixed (Q32.32)").unwrap();
    writeln!(s, "steps = {}", got.steps).unwrap();
    writeln!(s, "digest = 0x{:016x}", got.digest).unwrap();
    s
}

/// Compare `world`'s digest with the golden of `scenario`, or rewrite it when blessing.
fn check_golden(scenario: &str, about: &str, world: &World<'_, Fx>) {
    let got = Golden {
        steps: world.step_count(),
        digest: world.digest(),
    };
    let path = golden_path(scenario);
    if std::env::var(BLESS_VAR).is_ok_and(|v| v == "1") {
        std::fs::write(&path, render_golden(scenario, about, &got)).unwrap();
        eprintln!("blessed {}: {:#018x}", path.display(), got.digest);
        return;
    }
    let expected = std::fs::read_to_string(&path)
        .ok()
        .and_then(|t| parse_golden(&t));
    if expected.as_ref() == Some(&got) {
        return;
    }
    let dump_path = std::env::temp_dir().join(format!("arachis-digest-{scenario}.dump"));
    let dump_note = match std::fs::write(&dump_path, dump(world).join("\n") + "\n") {
        Ok(()) => format!("per-body dump of the new state: {}", dump_path.display()),
        Err(e) => format!("(could not write the per-body dump: {e})"),
    };
    panic!(
        "golden digest of `{scenario}` does not match.\n  file:     {}\n  expected: {}\n  \
         got:      steps = {}, digest = 0x{:016x}\n  {dump_note}\nIf the change is intended, \
         regenerate the goldens deliberately with\n  {BLESS_COMMAND}\nand say why in the commit.",
        path.display(),
        match expected {
            Some(e) => format!("steps = {}, digest = 0x{:016x}", e.steps, e.digest),
            None => "(missing or unreadable file)".to_string(),
        },
        got.steps,
        got.digest,
    );
}

#[test]
fn bench_bed_pour_matches_golden_digest() {
    let bed = BenchBed::design();
    let mut arenas = Owned::<Fx>::with_lengths(bed.storage_lengths());
    let mut world = bed.build(arenas.storage()).unwrap();
    world.run(POUR_STEPS).unwrap();
    check_golden(
        "bench_bed_pour",
        "DESIGN §8 bench bed (2 000 spheres R 4 mm poured into a steel cylinder R 50 mm),\n\
         default seed, early in the pour: the lowest spheres have reached the floor.",
        &world,
    );
    let (sphere_contacts, wall_contacts) = contact_kinds(&world);
    println!("pour: {sphere_contacts} sphere-sphere + {wall_contacts} sphere-wall contacts");
    assert!(
        sphere_contacts + wall_contacts >= POUR_MIN_CONTACTS,
        "only {} contacts at step {POUR_STEPS}: the digest would barely cover contact history",
        sphere_contacts + wall_contacts
    );
    assert!(sphere_contacts >= POUR_MIN_SPHERE_CONTACTS);
}

#[test]
fn clump_slide_matches_golden_digest() {
    let scenario = ClumpSlide::default();
    let mut arenas = Owned::<Fx>::with_lengths(scenario.storage_lengths());
    let mut world = scenario.build(arenas.storage()).unwrap();
    let start: Vec<[f64; 3]> = world.bodies().iter().map(|b| b.position.to_f64()).collect();
    // Count the steps on which clumps touch each other, to show that they do collide.
    let mut colliding_steps = 0;
    for _ in 0..CLUMP_STEPS {
        world.step().unwrap();
        colliding_steps += u32::from(contact_kinds(&world).0 > 0);
    }
    check_golden(
        "clump_slide",
        "Four two- and three-sphere pod clumps sliding down a 35° steel incline into each\n\
         other and a stop wall (core/src/scenario/clump_slide.rs), default seed.",
        &world,
    );
    println!("clump slide: clump-clump contact on {colliding_steps} of {CLUMP_STEPS} steps");
    assert!(colliding_steps > 0, "the clumps never collided");
    for (b, s) in world.bodies().iter().zip(&start) {
        // Every clump went down the slope (x grows downhill).
        assert!(b.position.to_f64()[0] > s[0], "a clump did not slide");
    }
}

#[test]
fn moving_wall_pile_matches_golden_digest() {
    let scenario = MovingWallPile::default();
    let mut arenas = Owned::<Fx>::with_lengths(scenario.storage_lengths());
    let mut world = scenario.build(arenas.storage()).unwrap();
    let blade_start = world.walls()[1].shape;
    world.run(BLADE_STEPS).unwrap();
    check_golden(
        "moving_wall_pile",
        "A 150-sphere pod pile (R 3 and 4 mm) settled on a steel floor for 6 000 steps, then a\n\
         plane blade moving through it at 1 m/s (core/src/scenario/moving_wall.rs).",
        &world,
    );
    let (s, w) = contact_kinds(&world);
    println!("moving wall: {s} sphere-sphere + {w} sphere-wall contacts");
    assert!(s + w >= PILE_MIN_CONTACTS);
    assert_ne!(
        world.walls()[1].shape,
        blade_start,
        "the blade did not move"
    );
}

#[test]
fn pull_off_matches_golden_digest() {
    let scenario = PullOff::default();
    let mut arenas = Owned::<Fx>::with_lengths(scenario.storage_lengths());
    let mut bonds = vec![Bond::<Fx>::default(); scenario.bond_capacity()];
    let mut log = vec![BondBreak::<Fx>::default(); scenario.bond_capacity()];
    let mut world = scenario
        .build(
            arenas.storage(),
            BondStorage {
                bonds: &mut bonds,
                log: &mut log,
            },
        )
        .unwrap();
    let result = scenario.run(&mut world, PULL_OFF_STEPS, |_, _| {}).unwrap();
    world.run(PULL_OFF_STEPS - world.step_count()).unwrap();
    check_golden(
        "pull_off",
        "Virtual tensile test (core/src/scenario/pull_off.rs): an 8-sphere bonded pod stalk\n\
         clamped at one end, a 3-sphere pod clump bonded to the other and pulled axially at\n\
         0.1 m/s until the junction breaks, dt 5e-7 s.",
        &world,
    );
    let predicted = scenario.predicted_axial_detachment_n();
    println!(
        "pull-off: detachment {:.4} N at {:.4} mm (step {:?}); criterion σc·A = {predicted:.4} N",
        result.detachment_force_n, result.detachment_displacement_mm, result.break_step
    );
    assert!(result.break_step.is_some(), "the pod never came off");
    assert!(!result.stalk_broke_first);
    let err = (result.detachment_force_n - predicted) / predicted;
    assert!(
        err.abs() < PULL_OFF_FORCE_TOL,
        "detachment off by {err:.3e}"
    );
    assert_eq!(world.bonds().breaks_total(), 1);
    assert_eq!(world.bonds().bonds().len(), scenario.bond_capacity() - 1);
}

/// Hopper: spheres, seed and orifice (µm) of the golden run.
const HOPPER: Hopper = Hopper {
    particles: 150,
    seed: 7,
    orifice_diameter_um: 40_000,
};
/// Hopper: steps before the shutter opens (0.2 s: the lowest spheres rest on it).
const HOPPER_SETTLE_STEPS: u64 = 10_000;
/// Hopper: steps while the shutter drops to the catch floor (0.1 s at 2 m/s).
const HOPPER_SHUTTER_STEPS: u64 = 5_000;
/// Hopper: steps of discharge after the shutter stopped.
const HOPPER_FLOW_STEPS: u64 = 1_000;

/// The golden hopper run, stepped by `run` (steps): settle, open, drop the shutter, stop it
/// as the catch floor, discharge.
fn hopper_run(world: &mut World<'_, Fx>, mut run: impl FnMut(&mut World<'_, Fx>, u64)) {
    run(world, HOPPER_SETTLE_STEPS);
    Hopper::open(world).unwrap();
    run(world, HOPPER_SHUTTER_STEPS);
    Hopper::catch(world).unwrap();
    run(world, HOPPER_FLOW_STEPS);
}

#[test]
fn hopper_matches_golden_digest() {
    let mut arenas = Owned::<Fx>::with_lengths(HOPPER.storage_lengths());
    let mut world = HOPPER.build(arenas.storage()).unwrap();
    hopper_run(&mut world, |w, n| w.run(n).unwrap());
    check_golden(
        "hopper",
        "A silo of 150 pod spheres (R 4 mm) with a 40 mm orifice plate: settled 0.2 s on the\n\
         shutter, which then drops 0.2 m at 2 m/s and stops as the catch floor; 1 000 steps\n\
         of discharge (core/src/scenario/hopper.rs).",
        &world,
    );
    // The run exercises the orifice (spheres went through it) and the stopped shutter.
    let discharged = discharged_mass_g(&world);
    let shutter_z_mm = match world.walls()[SHUTTER.0 as usize].shape {
        arachis_core::wall::WallShape::Plane(p) => p.point.z.to_f64(),
        _ => unreachable!("the shutter is a plane"),
    };
    println!("hopper: {discharged:.2} g discharged, shutter at {shutter_z_mm:.3} mm");
    assert!(discharged > 0.0, "nothing went through the orifice");
    assert!((shutter_z_mm + CATCH_DEPTH_M * 1e3).abs() < 1e-3);
}

/// Drum: spheres and seed of the golden run.
const DRUM: Drum = Drum {
    particles: 100,
    seed: 3,
};
/// Drum: steps before it spins (0.2 s: the bed has landed), its speed (rad/s) and the steps
/// it spins (0.1 s, a turn of 0.1 rad).
const DRUM_SETTLE_STEPS: u64 = 10_000;
const DRUM_SPEED_RAD_S: f64 = 1.0;
const DRUM_SPIN_STEPS: u64 = 5_000;

/// The golden drum run, stepped by `run` (steps); returns the bed's angle (degrees) before
/// the drum turns.
fn drum_run(world: &mut World<'_, Fx>, mut run: impl FnMut(&mut World<'_, Fx>, u64)) -> f64 {
    run(world, DRUM_SETTLE_STEPS);
    let before = bed_angle_deg(world, DRUM_SPEED_RAD_S);
    Drum::spin(world, DRUM_SPEED_RAD_S).unwrap();
    run(world, DRUM_SPIN_STEPS);
    before
}

#[test]
fn drum_matches_golden_digest() {
    let mut arenas = Owned::<Fx>::with_lengths(DRUM.storage_lengths());
    let mut world = DRUM.build(arenas.storage()).unwrap();
    let before = drum_run(&mut world, |w, n| w.run(n).unwrap());
    check_golden(
        "drum",
        "100 pod spheres (R 4 mm) settled 0.2 s in a steel drum of radius 60 mm and length\n\
         40 mm, then the drum and its end plates spin at 1 rad/s about the horizontal axis\n\
         for 0.1 s (core/src/scenario/drum.rs).",
        &world,
    );
    // The spinning walls carried the bed round with them, as a block: its angle rose by the
    // drum's turn (5.73°), within a degree.
    let rise = bed_angle_deg(&world, DRUM_SPEED_RAD_S) - before;
    let turn = (DRUM_SPEED_RAD_S * DRUM_SPIN_STEPS as f64 * world.timestep_s()).to_degrees();
    println!("drum: the bed rose {rise:.2}° while the drum turned {turn:.2}°");
    assert!((rise - turn).abs() < 1.0);
}

/// Bulk-density pour: spheres, seed and drop height (µm) of the golden run.
const POURED: BulkDensity = BulkDensity {
    particles: 100,
    seed: 5,
    drop_height_um: 150_000,
};
/// Bulk-density pour: steps (0.2 s: the lowest spheres have landed, the highest still fall).
const POURED_STEPS: u64 = 10_000;

#[test]
fn bulk_density_pour_matches_golden_digest() {
    let mut arenas = Owned::<Fx>::with_lengths(POURED.storage_lengths());
    let mut world = POURED.build(arenas.storage()).unwrap();
    world.run(POURED_STEPS).unwrap();
    check_golden(
        "bulk_density",
        "100 pod spheres (R 4 mm) falling from a column 150–450 mm above the floor of a steel\n\
         cylinder of radius 30 mm, 0.2 s (core/src/scenario/bulk_density.rs).",
        &world,
    );
    // The run exercises impacts on the floor and the landed spheres: some lie in the slab.
    let density = slab_bulk_density_kg_m3(&world);
    println!("bulk density pour: {density:.1} kg/m³ in the slab so far");
    assert!(density > 0.0, "nothing landed in the measuring slab");
}

/// Thread counts the goldens must not depend on.
const THREAD_COUNTS: [usize; 5] = [1, 2, 3, 4, 7];

/// The golden digest of `scenario` as recorded in its file.
fn golden(scenario: &str) -> Golden {
    let text = std::fs::read_to_string(golden_path(scenario)).unwrap();
    parse_golden(&text).unwrap()
}

/// Every golden scenario, stepped with its work split over 1, 2, 3, 4 and 7 threads, ends on
/// the golden digest: fixed-point forces are exact integer sums, so the partition cannot
/// change a bit (issue 16). It runs in the plain release build of `scripts/test-all.sh`; the
/// debug and `float-estimate` passes, which check the goldens themselves, skip its 30 runs.
#[test]
#[cfg_attr(
    any(debug_assertions, feature = "float-estimate"),
    ignore = "run in the release build without float-estimate"
)]
fn golden_digests_are_identical_for_any_thread_count() {
    for threads in THREAD_COUNTS {
        let bed = BenchBed::design();
        let mut arenas = Owned::<Fx>::with_lengths(bed.storage_lengths());
        let mut world = bed.build(arenas.storage()).unwrap();
        run_threaded(&mut world, POUR_STEPS, threads);
        assert_eq!(
            world.digest(),
            golden("bench_bed_pour").digest,
            "bed, {threads} threads"
        );

        let scenario = ClumpSlide::default();
        let mut arenas = Owned::<Fx>::with_lengths(scenario.storage_lengths());
        let mut world = scenario.build(arenas.storage()).unwrap();
        run_threaded(&mut world, CLUMP_STEPS, threads);
        assert_eq!(
            world.digest(),
            golden("clump_slide").digest,
            "clumps, {threads} threads"
        );

        let scenario = MovingWallPile::default();
        let mut arenas = Owned::<Fx>::with_lengths(scenario.storage_lengths());
        let mut world = scenario.build(arenas.storage()).unwrap();
        run_threaded(&mut world, BLADE_STEPS, threads);
        assert_eq!(
            world.digest(),
            golden("moving_wall_pile").digest,
            "pile, {threads} threads"
        );

        let mut arenas = Owned::<Fx>::with_lengths(DRUM.storage_lengths());
        let mut world = DRUM.build(arenas.storage()).unwrap();
        let _ = drum_run(&mut world, |w, n| run_threaded(w, n, threads));
        assert_eq!(
            world.digest(),
            golden("drum").digest,
            "drum, {threads} threads"
        );

        let mut arenas = Owned::<Fx>::with_lengths(HOPPER.storage_lengths());
        let mut world = HOPPER.build(arenas.storage()).unwrap();
        hopper_run(&mut world, |w, n| run_threaded(w, n, threads));
        assert_eq!(
            world.digest(),
            golden("hopper").digest,
            "hopper, {threads} threads"
        );

        let mut arenas = Owned::<Fx>::with_lengths(POURED.storage_lengths());
        let mut world = POURED.build(arenas.storage()).unwrap();
        run_threaded(&mut world, POURED_STEPS, threads);
        assert_eq!(
            world.digest(),
            golden("bulk_density").digest,
            "bulk density, {threads} threads"
        );

        let scenario = PullOff::default();
        let mut arenas = Owned::<Fx>::with_lengths(scenario.storage_lengths());
        let mut bonds = vec![Bond::<Fx>::default(); scenario.bond_capacity()];
        let mut log = vec![BondBreak::<Fx>::default(); scenario.bond_capacity()];
        let storage = BondStorage {
            bonds: &mut bonds,
            log: &mut log,
        };
        let mut world = scenario.build(arenas.storage(), storage).unwrap();
        run_threaded(&mut world, PULL_OFF_STEPS, threads);
        assert_eq!(
            world.digest(),
            golden("pull_off").digest,
            "pull-off, {threads} threads"
        );
    }
}

/// A short variant of the moving-wall scenario for the property tests below.
fn short_pile(seed_flip: u64, nudge_body_0: bool) -> (u64, Vec<String>) {
    let scenario = MovingWallPile {
        settle_steps: 1_000,
        seed: MovingWallPile::default().seed ^ seed_flip,
    };
    let mut arenas = Owned::<Fx>::with_lengths(scenario.storage_lengths());
    let mut world = scenario.build(arenas.storage()).unwrap();
    if nudge_body_0 {
        // Add one least-significant bit (2⁻³² m/s) to body 0's x velocity: the smallest
        // change the fixed-point state can carry.
        let b = *world.body(BodyId(0));
        let mut v = b.velocity.to_f64();
        v[0] += (-32f64).exp2();
        let w_rad_s = b.angular_velocity.to_f64().map(|x| x * 1e3);
        world.set_body_velocity(BodyId(0), v, w_rad_s).unwrap();
        let after = world.body(BodyId(0)).velocity.x;
        assert_eq!(after.raw() - b.velocity.x.raw(), 1, "the nudge is one bit");
        assert_eq!(world.body(BodyId(0)).angular_velocity, b.angular_velocity);
    }
    world.run(500).unwrap();
    (world.digest(), dump(&world))
}

#[test]
fn two_runs_dump_identical_per_body_states() {
    let (d1, dump1) = short_pile(0, false);
    let (d2, dump2) = short_pile(0, false);
    if let Some(i) = dump1.iter().zip(&dump2).position(|(a, b)| a != b) {
        panic!("runs diverge at body {i}:\n  {}\n  {}", dump1[i], dump2[i]);
    }
    assert_eq!(dump1.len(), MovingWallPile::SPHERES as usize);
    assert_eq!(d1, d2);
}

#[test]
fn one_bit_of_input_changes_the_digest() {
    let (base, _) = short_pile(0, false);
    let (seed_flipped, _) = short_pile(1, false);
    let (nudged, nudged_dump) = short_pile(0, true);
    assert_ne!(
        base, seed_flipped,
        "flipping the lowest seed bit left the digest unchanged"
    );
    assert_ne!(
        base, nudged,
        "a one-bit velocity change left the digest unchanged"
    );
    assert_eq!(nudged_dump.len(), MovingWallPile::SPHERES as usize);
}
