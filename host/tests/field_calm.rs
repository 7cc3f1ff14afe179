//! Issue 20: the field starts at rest (`arachis::field::calm`). The settled grains press on
//! the pegs they packed against, and let go, the pegs ring; the field's run therefore starts
//! with a calm, a drag of the field file's `[calm]` for its first steps.
//!
//! - The calm's drag acts for its steps and is gone after: a 1 mm sphere thrown through the
//!   calm slows as the quadratic drag's closed form says, and from the calm's end on it keeps
//!   its horizontal speed to the bit and falls at g, as in still air.
//! - `arachis field` calms the run for the field file's steps, rounded down to whole chunks:
//!   a calm of 500 steps, one of 750 and none give three different runs, and the printed
//!   line says how many steps were calmed.
//! - A run stopped within the calm, or after it, goes on to the bits of one never stopped
//!   (the drag is set again from the steps done; the checkpoint's words do not hold it).

use std::path::Path;

use arachis::field::calm::CalmPhase;
use arachis::field::{Calm, CHUNK_STEPS};
use arachis_core::prelude::*;
use arachis_core::units::LENGTH_M_TO_MM;
use serde_json::Value;

use crate::cli_support::{arachis, small_field_files};

/// A material of water's density: a 1 mm sphere of it weighs 4.2 mg, as a peg sphere does.
const PEG_LIKE: MaterialSpec = MaterialSpec {
    youngs_modulus_pa: 1.0e8,
    poisson: 0.3,
    density_kg_m3: 1000.0,
};

#[test]
fn the_calm_slows_what_moves_for_its_steps_and_is_gone_after() {
    let r_m = 1.0e-3;
    let v0_m_s = 1.0;
    let dt_s = 5.0e-6;
    let g_m_s2 = 9.81;
    let mut arena = arachis::arena::OwnedStorage::<Fx>::new(StorageLengths::for_spheres(1, 1));
    let mut w = World::new(arena.storage()).unwrap();
    let m = w.add_material(PEG_LIKE).unwrap();
    let id = w
        .add_sphere(SphereSpec {
            velocity_m_s: [v0_m_s, 0.0, 0.0],
            ..SphereSpec::at_rest(m, r_m, [0.0; 3])
        })
        .unwrap();
    w.set_gravity_m_s2([0.0, 0.0, -g_m_s2]).unwrap();
    w.set_timestep_s(dt_s).unwrap();
    // 1.3 ms asked for: 260 steps, rounded down to one chunk of 250.
    let calm = CalmPhase::of(
        &Calm {
            duration_s: 1.3e-3,
            ..Calm::default()
        },
        dt_s,
    );
    assert_eq!(calm.steps, CHUNK_STEPS);
    assert!((calm.duration_s - CHUNK_STEPS as f64 * dt_s).abs() < 1e-15);
    let v = |w: &World<'_, Fx>| w.body(id).velocity.to_f64();
    // As `arachis field` steps: the drag set from the steps done, switched where the calm ends.
    calm.set(&mut w, 0).unwrap();
    assert!(w.air_drag().on);
    w.run(calm.steps_to_switch(0)).unwrap();
    calm.set(&mut w, calm.steps).unwrap();
    assert!(!w.air_drag().on, "no drag once the calm is over");
    // Quadratic drag alone along x: v(t) = v0 / (1 + k v0 t), k = ½ρC_dπr²/m.
    let mass_kg = PEG_LIKE.density_kg_m3 * 4.0 / 3.0 * std::f64::consts::PI * r_m.powi(3);
    let k = 0.5
        * Calm::default().medium_density_kg_m3
        * Calm::default().drag_coefficient
        * std::f64::consts::PI
        * r_m
        * r_m
        / mass_kg;
    let t_s = calm.duration_s;
    let closed_form = v0_m_s / (1.0 + k * v0_m_s * t_s);
    let after_calm = v(&w);
    println!(
        "calm: vx {:.5} m/s after {t_s} s, closed form {closed_form:.5} m/s (k {k:.1} /m)",
        after_calm[0]
    );
    assert!(
        closed_form < 0.5,
        "the calm slows a peg sphere: {closed_form}"
    );
    assert!((after_calm[0] / closed_form - 1.0).abs() < 0.01);
    // From the calm's end: still air. The horizontal speed keeps its bits, and the fall
    // gains g per second to the rounding of the fixed point.
    let vx_bits = w.body(id).velocity.x;
    w.run(2 * CHUNK_STEPS).unwrap();
    assert_eq!(w.body(id).velocity.x, vx_bits, "drag left after the calm");
    let gained = after_calm[2] - v(&w)[2];
    let want = g_m_s2 * 2.0 * CHUNK_STEPS as f64 * dt_s;
    assert!((gained - want).abs() < 1e-7, "{gained} vs {want}");
    // The sphere is where it flew: nowhere near where 1 m/s would have taken it.
    let x_m = w.body(id).position.to_f64()[0] / LENGTH_M_TO_MM;
    let elapsed_s = w.time_s();
    assert!(x_m < 0.6 * v0_m_s * elapsed_s, "{x_m} m in {elapsed_s} s");
}

/// The small field's files with the calm's duration set to `duration_s` (s).
fn small_files_calmed(dir: &Path, duration_s: f64) -> (String, String) {
    let (field, machine) = small_field_files(dir);
    let text = std::fs::read_to_string(&field).unwrap();
    let from = "duration_s = 0.0075";
    assert!(text.contains(from), "the shipped field states its calm");
    let path = dir.join(format!("field-calm-{duration_s}.toml"));
    std::fs::write(
        &path,
        text.replacen(from, &format!("duration_s = {duration_s}"), 1),
    )
    .unwrap();
    (path.display().to_string(), machine.display().to_string())
}

/// Runs `arachis --threads 2 field FIELD ARGS…` without a machine; returns the printed JSON
/// and stderr, asserting success.
fn field(file: &str, args: &[&str]) -> (Value, String) {
    let mut all = vec!["--threads", "2", "field", file];
    all.extend_from_slice(args);
    let out = arachis(&all);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "{stderr}");
    (serde_json::from_slice(&out.stdout).unwrap(), stderr)
}

#[test]
fn the_run_is_calmed_for_the_files_steps_and_a_resumed_run_keeps_its_bits() {
    let dir = tempfile::tempdir().unwrap();
    // The small field's step is about 8.3e-7 s: 4.5e-4 s is 544 steps, 500 once rounded down
    // to whole chunks, and 7e-4 s is 847, 750.
    let (calm_500, _) = small_files_calmed(dir.path(), 4.5e-4);
    let (calm_750, _) = small_files_calmed(dir.path(), 7.0e-4);
    let (none, _) = small_files_calmed(dir.path(), 0.0);
    let steps = "1000";
    let (a, _) = field(&calm_500, &["--steps", steps]);
    let (b, _) = field(&calm_750, &["--steps", steps]);
    let (c, _) = field(&none, &["--steps", steps]);
    let calmed = |v: &Value| v["calm"]["steps"].as_u64().unwrap();
    assert_eq!((calmed(&a), calmed(&b), calmed(&c)), (500, 750, 0));
    let dt = a["dt_s"].as_f64().unwrap();
    assert!((a["calm"]["duration_s"].as_f64().unwrap() - 500.0 * dt).abs() < 1e-12);
    assert_eq!(a["calm"]["medium_density_kg_m3"].as_f64(), Some(1000.0));
    assert_ne!(a["digest"], c["digest"], "the calm changed nothing");
    assert_ne!(a["digest"], b["digest"], "the calm did not end at its step");
    // Stopped within the calm (250) and after it (750), each goes on to the same bits.
    for stop in ["250", "750"] {
        let ckpt = dir.path().join(format!("stop-{stop}.ckpt"));
        let ckpt = ckpt.to_str().unwrap();
        let (first, _) = field(&calm_500, &["--steps", stop, "--checkpoint", ckpt]);
        assert_eq!(calmed(&first), 500);
        let (second, stderr) = field(&calm_500, &["--steps", steps, "--checkpoint", ckpt]);
        assert!(
            stderr.contains(&format!("at step {stop} of 1000")),
            "{stderr}"
        );
        assert_eq!(second["digest"], a["digest"], "stopped at step {stop}");
    }
    // A checkpoint of another calm is another run's: refused.
    let ckpt = dir.path().join("stop-250.ckpt");
    let out = arachis(&[
        "field",
        &calm_750,
        "--steps",
        steps,
        "--checkpoint",
        ckpt.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("other inputs"));
}
