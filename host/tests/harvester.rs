//! Issue 20, item 3: a harvester described in a file (`arachis::harvester`,
//! `arachis field --harvester`).
//!
//! - The shovel digs: driven into a bare bed, it lifts the soil above the undisturbed bed,
//!   lets none through its plate, and every part stays on the path its motion law gives.
//! - Mounted on the shipped field, the machine starts before the bed and its pass lasts
//!   exactly as long as the bed takes to pass the collector at the forward speed.
//! - Bad harvester input: exit 2, the file, line and key named, nothing written.

use std::path::{Path, PathBuf};

use arachis::arena::{OwnedBonds, OwnedStorage};
use arachis::field::FieldSpec;
use arachis::harvester::parts::PartKind;
use arachis::harvester::rig::Rig;
use arachis::harvester::HarvesterSpec;
use arachis_core::prelude::*;
use arachis_core::units::LENGTH_M_TO_MM;

use crate::cli_support::{arachis, assert_refused, small_field_files, REPO_ROOT};

fn testdata(name: &str) -> PathBuf {
    Path::new(REPO_ROOT)
        .join("testdata/peanut-plant")
        .join(name)
}

fn shipped_machine() -> HarvesterSpec {
    HarvesterSpec::read(&testdata("harvester-digger.toml")).expect("the shipped harvester reads")
}

/// Height below which nothing of the settled bed lies, sampled where the machine has not yet
/// reached: grains more than this far ahead of the shovel's edge, m.
const UNDISTURBED_AHEAD_M: f64 = 0.15;

/// A bare bed 0.4 m long and 0.1 m wide under the shipped machine narrowed to 0.24 m, driven
/// until the shovel's edge is 0.12 m into the bed. (The bed was 0.2 m wide until 2026-12-07:
/// 54 s alone and a lift of 29 mm; at 0.1 m the test takes 27 s and the lift is 24 mm, against
/// the 16 mm it asks for.)
///
/// The lift is measured against the undisturbed bed of the same run, the grains more than
/// [`UNDISTURBED_AHEAD_M`] ahead of the edge: the soil over the shovel must stand at least
/// one grain diameter higher. (The first version of this test compared with the bed's height
/// at rest and failed: the bed was then laid out loose and its undisturbed top sank from
/// −10 mm to −33 mm within 0.17 s. It now settles before the run, `tests/field_settle.rs`.)
#[test]
fn the_shovel_lifts_the_soil_and_lets_none_through() {
    let mut field_spec = FieldSpec::read(&testdata("field-huayu.toml")).unwrap();
    field_spec.field.plants_per_hole = 0;
    field_spec.field.rows = 1;
    field_spec.field.ridge_length_m = 0.3;
    field_spec.soil.margin_m = 0.05;
    let mut machine = shipped_machine();
    machine.harvester.width_m = 0.24;
    // No settling first: the lift is measured against the undisturbed bed of the same run.
    machine.harvester.settle_s = 0.0;
    let field = field_spec.plant(1).unwrap();
    let (bodies, spheres) = Rig::extra_storage(&machine);
    let mut arena =
        OwnedStorage::<Fx>::new(field.storage_lengths_with(&field_spec, bodies, spheres));
    let mut bonds = OwnedBonds::<Fx>::new(1);
    let mut w = World::new(arena.storage()).unwrap();
    w.attach_bond_storage(bonds.storage()).unwrap();
    let loaded = field.load_into(&field_spec, &mut w).unwrap();
    let mut rig = Rig::mount(&machine, &field, &loaded, &mut w).unwrap();
    let into_bed_m = 0.12;
    let t_s = (machine.harvester.start_gap_m + into_bed_m) / machine.harvester.forward_speed_m_s;
    let steps = (t_s / w.timestep_s()).ceil() as u64;
    rig.advance(&mut w, steps).unwrap();
    let t = rig.elapsed_s(&w);
    let m_of = |id: BodyId| w.body(id).position.to_f64().map(|x| x / LENGTH_M_TO_MM);
    // Every part is where its motion law puts it, to 1 µm (the run ends on a chunk's end,
    // where the chords meet the law).
    for kind in [PartKind::Shovel, PartKind::Chain, PartKind::Drum] {
        let parts: Vec<_> = rig.layout.parts.iter().filter(|p| p.kind == kind).collect();
        for (part, id) in parts.iter().zip(rig.bodies_of(kind)) {
            let want = rig.travel.centre_m(part, t);
            let got = m_of(id);
            let err = (0..3).map(|i| (got[i] - want[i]).abs()).fold(0.0, f64::max);
            assert!(err < 1e-6, "{kind:?} off its path by {err} m");
        }
    }
    let grain_r_m = field_spec.soil.grain_radius_mm.mean / LENGTH_M_TO_MM;
    let mut over_top = f64::MIN;
    let mut undisturbed_top = f64::MIN;
    let mut over = 0;
    let mut under = 0;
    for &g in &loaded.grains {
        let p = rig.travel.to_machine_m(m_of(g), t);
        if p[0] > UNDISTURBED_AHEAD_M {
            undisturbed_top = undisturbed_top.max(p[2]);
        }
        let Some(surface) = rig.layout.surface_z_m(p[0]) else {
            continue;
        };
        if p[0] > rig.layout.shovel_top_m[0] && p[1].abs() < rig.layout.half_width_m {
            over += 1;
            over_top = over_top.max(p[2]);
            // No grain below the plate: a grain's centre lies above the plate's surface
            // (1 mm allowed for the contact's overlap).
            if p[2] < surface - 1e-3 {
                under += 1;
            }
        }
    }
    println!(
        "{steps} steps of {:.3e} s: {over} grains over the shovel, {under} under it; top over the shovel {over_top:.4} m, undisturbed top {undisturbed_top:.4} m",
        w.timestep_s(),
    );
    assert!(
        over > 20,
        "the shovel has not reached the soil: {over} grains over it"
    );
    assert_eq!(under, 0, "grains passed under the shovel's plate");
    assert!(
        over_top > undisturbed_top + 2.0 * grain_r_m,
        "the soil over the shovel ({over_top} m) does not stand a grain above the undisturbed bed ({undisturbed_top} m)"
    );
}

#[test]
fn on_the_shipped_field_the_pass_lasts_until_the_bed_has_passed_the_collector() {
    let field_spec = FieldSpec::read(&testdata("field-huayu.toml")).unwrap();
    let machine = shipped_machine();
    // The pass's length depends on the layout alone, not on the settled soil.
    let field = field_spec.lay_out(1).unwrap();
    let (bodies, spheres) = Rig::extra_storage(&machine);
    let mut arena =
        OwnedStorage::<Fx>::new(field.storage_lengths_with(&field_spec, bodies, spheres));
    let mut bonds = OwnedBonds::<Fx>::new(field.bond_count());
    let mut w = World::new(arena.storage()).unwrap();
    w.attach_bond_storage(bonds.storage()).unwrap();
    let loaded = field.load_into(&field_spec, &mut w).unwrap();
    let rig = Rig::mount(&machine, &field, &loaded, &mut w).unwrap();
    let dt = w.timestep_s();
    // Distance: the bed's length, the start gap and the machine's length to the collector's
    // rear end.
    let distance = field.bed_max_m[0] - field.bed_min_m[0] + machine.harvester.start_gap_m
        - rig.layout.opening.x_m.0;
    let expected = machine.harvester.settle_s + distance / machine.harvester.forward_speed_m_s;
    // Whole cycles of the soil's steps: within one cycle of the pass's end.
    let stride = w.slow_stride();
    let steps = rig.pass_steps(dt, stride);
    assert_eq!(
        steps % u64::from(stride),
        0,
        "{steps} steps, stride {stride}"
    );
    let pass_s = steps as f64 * dt;
    assert!(
        pass_s >= expected && pass_s < expected + f64::from(stride) * dt,
        "{pass_s} s against {expected} s"
    );
    // The edge starts before the bed, every part at rest behind it.
    assert!(
        (rig.travel.origin_x_m(0.0) - (field.bed_min_m[0] - machine.harvester.start_gap_m)).abs()
            < 1e-12
    );
    assert_eq!(rig.roots_let_go(), 0);
    let tally = rig.tally(&w);
    assert_eq!(tally.pods as usize, field.pods());
    assert_eq!(
        tally.in_soil as usize,
        field.pods(),
        "before the run every pod is in the soil"
    );
}

#[test]
fn bad_harvester_input_exits_2_naming_file_line_and_key_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(testdata("harvester-digger.toml")).unwrap();
    let vtk = dir.path().join("field.vtk");
    let cases = [
        ("depth_m = 0.10", "depth_m = -0.10", "shovel.depth_m"),
        (
            "rod_pitch_mm = 40.0",
            "rod_pitch_mm = 8.0",
            "chain.rod_pitch_mm",
        ),
        ("rows = 6", "rows = 0", "drum.rows"),
        (
            "sphere_radius_mm = 5.0",
            "sphere_radius_mm = 1.0",
            "shovel.sphere_radius_mm",
        ),
        (
            "speed_rpm = 470.0",
            "speed_rpm = 470.0\nsped_rpm = 1.0",
            "sped_rpm",
        ),
        (
            "friction = 0.5",
            "friction = 1e300",
            "steel_contacts.soil.friction",
        ),
        // The machine must wait out the field's calm (7.5 ms; `arachis::field::calm`).
        ("settle_s = 0.5", "settle_s = 0.005", "harvester.settle_s"),
    ];
    for (from, to, named) in cases {
        assert!(text.contains(from), "{from}");
        let path = dir.path().join("machine.toml");
        std::fs::write(&path, text.replacen(from, to, 1)).unwrap();
        let err = assert_refused(
            &[
                "field",
                testdata("field-huayu.toml").to_str().unwrap(),
                "--harvester",
                path.to_str().unwrap(),
                "--vtk",
                vtk.to_str().unwrap(),
            ],
            named,
            &vtk,
        );
        assert!(err.contains("machine.toml"), "{to}: {err}");
    }
    let path = dir.path().join("machine.toml");
    std::fs::write(
        &path,
        text.replacen("settle_s = 0.5", "settle_s = 0.005", 1),
    )
    .unwrap();
    let out = arachis(&[
        "field",
        testdata("field-huayu.toml").to_str().unwrap(),
        "--harvester",
        path.to_str().unwrap(),
    ]);
    let line = text
        .lines()
        .position(|l| l.starts_with("settle_s = "))
        .unwrap()
        + 1;
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains(&format!(":{line}:")), "line {line}: {err}");
    assert!(err.contains("calm.duration_s = 0.0075"), "{err}");
    std::fs::write(&path, text.replacen("rows = 6", "rows = 0", 1)).unwrap();
    let out = arachis(&[
        "field",
        testdata("field-huayu.toml").to_str().unwrap(),
        "--harvester",
        path.to_str().unwrap(),
    ]);
    let line = text.lines().position(|l| l.starts_with("rows = ")).unwrap() + 1;
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains(&format!(":{line}:")), "line {line}: {err}");
}

/// `--section` draws the slice through the first row: the shipped field's soil, pods and
/// plants and the machine's steel, each in its colour (plotters writes fills as hex).
#[test]
fn the_section_picture_shows_soil_plants_pods_and_steel() {
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("section.svg");
    // The one-plant cut of the shipped field under the narrowed machine: its soil settles in
    // a second, where the whole field's takes about a minute.
    let (field, machine) = small_field_files(dir.path());
    let out = arachis(&[
        "field",
        field.to_str().unwrap(),
        "--harvester",
        machine.to_str().unwrap(),
        "--section",
        svg.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&svg).unwrap();
    for (what, fill) in [
        ("soil", "#967350"),
        ("pod", "#D7AF6E"),
        ("plant", "#3C7832"),
        ("steel", "#5A5A64"),
    ] {
        assert!(
            text.to_uppercase().contains(&fill.to_uppercase()),
            "no {what} ({fill}) in the picture"
        );
    }
}
