//! Virtual harvest (issue 6): loss accounting counts every pod once, a pass is deterministic
//! (same layout → same bits; same seed → same report), bad input is a clear error, the t-test
//! in the report equals an independent calculation, and `arachis harvest` runs end to end
//! with VTK frames. Kept cheap: a 20–40 mm drum and a 2 m/s conveyor (each pass ≈ 0.05 s
//! simulated, ≈ 6e4 steps of ≈ 50 spheres; the file runs in ≈ 11 s release).

use arachis::harvest::{
    run_harvest, run_pass, HarvestConfig, HarvestError, Machine, PlantLayout, Progress,
};
use arachis::plant::topology::Kind;
use arachis::plant::{generate, PlantModel, Topology};
use arachis_core::prelude::Fx;
use serde_json::Value;
use statrs::distribution::{ContinuousCDF, StudentsT};

use crate::cli_support;
use cli_support::{arachis, file_stamps};

const SMALL: &str = include_str!("../../testdata/peanut-plant/topology-small.toml");
/// Tolerance of t and p against the independent calculation (both are f64 sums of 8 values).
const T_TOL: f64 = 1e-12;

fn plant() -> PlantModel {
    generate(&Topology::from_toml(SMALL).unwrap()).unwrap()
}

fn pods_per_plant(m: &PlantModel) -> u32 {
    m.bodies.iter().filter(|b| b.kind == Kind::Pod).count() as u32
}

/// A short drum and a fast conveyor: a cheap pass.
fn cheap_machine() -> Machine {
    Machine {
        forward_speed_m_s: 2.0,
        drum_length_m: 0.04,
        ..Machine::default()
    }
}

fn quiet(_: Progress) {}

/// One plant, two replicates, a short drum: a command of about a second.
const SMALL_HARVEST: [&str; 9] = [
    "harvest",
    "--plants",
    "1",
    "--replicates",
    "2",
    "--drum-length",
    "0.02",
    "--forward-speed",
    "2",
];

#[test]
fn every_pod_is_counted_once_and_the_t_test_matches_an_independent_calculation() {
    let model = plant();
    let config = HarvestConfig {
        machine: cheap_machine(),
        plants: 1,
        replicates: 2,
        seed: 7,
        ..HarvestConfig::default()
    };
    let out = run_harvest::<Fx>(&config, &model, &quiet).unwrap();
    assert_eq!(out.replicates.len(), 2);
    for r in &out.replicates {
        let t = r.tally;
        assert_eq!(t.pods, config.plants * pods_per_plant(&model));
        assert_eq!(t.collected + t.unpicked + t.dropped, t.pods);
        let loss = 100.0 * f64::from(t.unpicked + t.dropped) / f64::from(t.pods);
        assert_eq!(r.loss_percent, loss);
    }
    // Independent pooled t-test (seed 001 §3.3): s² = (SS₁ + SS₂)/(n₁ + n₂ − 2),
    // t = (ȳ₁ − ȳ₂)/√(s²/n₁ + s²/n₂), p two-sided from statrs' Student t directly.
    let y1: Vec<f64> = out.replicates.iter().map(|r| r.loss_percent).collect();
    let y2 = config.field_loss_percent.clone();
    let (n1, n2) = (y1.len() as f64, y2.len() as f64);
    let m1 = y1.iter().sum::<f64>() / n1;
    let m2 = y2.iter().sum::<f64>() / n2;
    let ss = y1.iter().map(|y| (y - m1).powi(2)).sum::<f64>()
        + y2.iter().map(|y| (y - m2).powi(2)).sum::<f64>();
    let s2 = ss / (n1 + n2 - 2.0);
    let t = (m1 - m2) / (s2 / n1 + s2 / n2).sqrt();
    let dist = StudentsT::new(0.0, 1.0, n1 + n2 - 2.0).unwrap();
    let p = 2.0 * (1.0 - dist.cdf(t.abs()));
    let tt = out.t_test.expect("two replicates give a t-test");
    assert!(
        (tt.t - t).abs() <= T_TOL * t.abs().max(1.0),
        "t {} vs {t}",
        tt.t
    );
    assert!((tt.p - p).abs() <= T_TOL.max(1e-9 * p), "p {} vs {p}", tt.p);
    assert_eq!(tt.df, 4);
}

#[test]
fn same_layout_gives_the_same_bits() {
    let model = plant();
    let layout = PlantLayout {
        yaw_rad: 0.7,
        lateral_offset_m: 0.003,
        drum_phase_rad: 1.1,
    };
    let machine = Machine {
        drum_length_m: 0.02,
        ..cheap_machine()
    };
    let a = run_pass::<Fx>(&machine, &model, &layout, Some(u64::MAX), &quiet).unwrap();
    let b = run_pass::<Fx>(&machine, &model, &layout, None, &quiet).unwrap();
    assert_eq!(a.digest, b.digest, "taking frames must not change the run");
    assert_eq!(a.fates, b.fates);
    assert_eq!(a.steps, b.steps);
    assert_eq!(a.fates.len() as u32, pods_per_plant(&model));

    // The machine moves as prescribed: the first tooth (the first sphere after the plant's)
    // stays on the tip circle and has turned by ω·t; the clamp (top stem sphere) has moved
    // by v·t. Tolerances: 1e-6 m on the radius and 1e-4 rad on the angle (Q32.32 quaternion
    // integration over ≈ 6e4 steps), 1e-6 m on the clamp travel.
    let (first, last) = (&a.frames[0], a.frames.last().unwrap());
    let t = last.time_s - first.time_s;
    let tooth = model.spheres.len();
    let axis_z = machine.reach_above_root_m - machine.tip_radius_m;
    let [_, y0, z0] = first.positions_m[tooth];
    let [_, y1, z1] = last.positions_m[tooth];
    let r1 = (y1 * y1 + (z1 - axis_z).powi(2)).sqrt();
    assert!(
        (r1 - machine.tip_radius_m).abs() < 1e-6,
        "tooth radius {r1}"
    );
    let turned = (z1 - axis_z).atan2(y1) - (z0 - axis_z).atan2(y0);
    let expected = machine.drum_omega_rad_s() * t;
    let tau = std::f64::consts::TAU;
    let diff = (turned - expected).rem_euclid(tau);
    assert!(
        diff.min(tau - diff) < 1e-4,
        "turned {turned} vs ω·t {expected} (mod 2π)"
    );
    let clamp = model
        .bodies
        .iter()
        .rposition(|b| b.kind == Kind::MainStem)
        .unwrap();
    let c = model.bodies[clamp].spheres[0];
    let moved = last.positions_m[c][0] - first.positions_m[c][0];
    assert!(
        (moved - machine.forward_speed_m_s * t).abs() < 1e-6,
        "clamp moved {moved} m"
    );
}

#[test]
fn bad_input_is_a_clear_error() {
    let model = plant();
    let bad = |config: HarvestConfig, name: &str| match run_harvest::<Fx>(&config, &model, &quiet) {
        Err(HarvestError::BadParameter { name: n, .. }) => assert_eq!(n, name),
        other => panic!("expected a bad {name}, got {other:?}"),
    };
    let base = HarvestConfig::default();
    for (machine, name) in [
        (
            Machine {
                forward_speed_m_s: -1.0,
                ..Machine::default()
            },
            "forward_speed_m_s",
        ),
        (
            Machine {
                drum_speed_rpm: 0.0,
                ..Machine::default()
            },
            "drum_speed_rpm",
        ),
        (
            Machine {
                tip_radius_m: f64::NAN,
                ..Machine::default()
            },
            "tip_radius_m",
        ),
        (
            Machine {
                teeth_per_ring: 0,
                ..Machine::default()
            },
            "teeth_per_ring",
        ),
        (
            Machine {
                teeth_per_ring: 60,
                ..Machine::default()
            },
            "teeth_per_ring",
        ),
        (
            Machine {
                housing_half_width_m: 0.1,
                ..Machine::default()
            },
            "housing_half_width_m",
        ),
    ] {
        bad(
            HarvestConfig {
                machine,
                ..base.clone()
            },
            name,
        );
    }
    bad(
        HarvestConfig {
            plants: 0,
            ..base.clone()
        },
        "plants",
    );
    bad(
        HarvestConfig {
            replicates: 0,
            ..base.clone()
        },
        "replicates",
    );
    bad(
        HarvestConfig {
            field_loss_percent: vec![4.0, 140.0],
            ..base.clone()
        },
        "field_loss_percent",
    );

    // Through the CLI: exit status 2 and a message naming the problem, no output file.
    let dir = tempfile::tempdir().unwrap();
    let report = dir.path().join("r.json");
    let out = arachis(&[
        "harvest",
        "--forward-speed",
        "-1",
        "--output",
        report.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("forward_speed_m_s"));
    assert!(!report.exists());
    let topo = dir.path().join("t.toml");
    std::fs::write(
        &topo,
        SMALL.replace("parent = \"peg1\"", "parent = \"nowhere\""),
    )
    .unwrap();
    let out = arachis(&["harvest", "--topology", topo.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("nowhere"));
    let machine = dir.path().join("m.toml");
    std::fs::write(&machine, "drum_speed_rpm = 500.0\ndrum_sped = 3.0\n").unwrap();
    let out = arachis(&["harvest", "--machine", machine.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("drum_sped"));
}

#[test]
fn cli_runs_with_vtk_frames_and_reports_loss_and_t_test() {
    let dir = tempfile::tempdir().unwrap();
    let vtk = dir.path().join("vtk");
    let report = dir.path().join("report.json");
    let small = |extra: &[&str]| {
        let mut args = SMALL_HARVEST.to_vec();
        args.extend_from_slice(extra);
        arachis(&args)
    };
    let out = small(&[
        "--vtk",
        vtk.to_str().unwrap(),
        "--frame-every",
        "20000",
        "--output",
        report.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: Value = serde_json::from_slice(&out.stdout).expect("one JSON report");
    let written = std::fs::read(&report).unwrap();
    let from_file: Value = serde_json::from_slice(&written).unwrap();
    // The file is the printed report without the run's timing and thread count (issue 23:
    // a file a user compares holds the same bytes on every run).
    let mut printed = v.clone();
    for timing in ["wall_seconds", "threads"] {
        assert!(printed[timing].is_number(), "{timing} not printed");
        printed.as_object_mut().unwrap().remove(timing);
    }
    assert_eq!(printed, from_file);
    assert_eq!(v["loss_percent"].as_array().unwrap().len(), 2);
    assert_eq!(
        v["field_loss_percent"],
        serde_json::json!([4.01, 3.83, 4.04, 3.42])
    );
    let p = v["t_test"]["p"].as_f64().unwrap();
    assert!((0.0..=1.0).contains(&p));
    assert_eq!(v["t_test"]["significant_difference"], p < 0.05);
    for sub in ["rep1_plant1", "rep2_plant1"] {
        let d = vtk.join(sub);
        assert!(d.join("particles.pvd").exists(), "{sub}: no series");
        assert!(d.join("frame_000000.vtk").exists(), "{sub}: no first frame");
    }
    // Once more, without frames: the report file has the same bytes.
    let again = dir.path().join("again.json");
    let out = small(&["--output", again.to_str().unwrap()]);
    assert!(out.status.success());
    assert_eq!(
        std::fs::read(&again).unwrap(),
        written,
        "the report's bytes changed"
    );
}

#[test]
fn same_seed_draws_the_same_layouts() {
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;
    let draw = |seed| {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        (0..4)
            .map(|_| PlantLayout::draw(&mut rng))
            .collect::<Vec<_>>()
    };
    assert_eq!(draw(3), draw(3));
    assert_ne!(draw(3), draw(4));
}

/// `--runs DIR` keeps every pass in a run cache: the report file has the bytes of a run
/// without it, a second run replays every pass (no stored pass is rewritten) with the same
/// bytes, and frames, which only a pass run here can draw, are refused with it.
#[test]
fn a_run_cache_keeps_the_passes_and_gives_the_same_report() {
    let dir = tempfile::tempdir().unwrap();
    let runs = dir.path().join("runs");
    let harvest = |report: &str, extra: &[&str]| {
        let path = dir.path().join(report);
        let mut args = SMALL_HARVEST.to_vec();
        args.extend_from_slice(&["--output", path.to_str().unwrap()]);
        args.extend_from_slice(extra);
        let out = arachis(&args);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        std::fs::read(path).unwrap()
    };
    let plain = harvest("plain.json", &[]);
    let cache = ["--runs", runs.to_str().unwrap()];
    assert_eq!(harvest("filled.json", &cache), plain);
    let before = file_stamps(&runs);
    assert_eq!(before.len(), 2, "one stored run per pass");
    assert_eq!(harvest("replayed.json", &cache), plain);
    assert_eq!(
        file_stamps(&runs),
        before,
        "a stored pass was simulated again"
    );

    let vtk = dir.path().join("vtk");
    let out = arachis(&[
        "harvest",
        "--runs",
        runs.to_str().unwrap(),
        "--vtk",
        vtk.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("--vtk"), "{err}");
}
