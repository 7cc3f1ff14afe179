//! The cheap rigs against independent calculations, determinism, and bad input.

use std::path::Path;

use arachis::rigs::pod_world::*;
use arachis::study::Experiment as ExperimentKind;
use arachis::study::Study;

const STUDY: &str = "../testdata/peanut-pods-saline/study.toml";

/// The shipped study with the quick mode's sphere count replaced.
fn study_with_spheres(spheres_per_pod: u32) -> Study {
    let text = std::fs::read_to_string(STUDY).unwrap();
    let line = text
        .lines()
        .find(|l| l.starts_with("spheres_per_pod") && l.contains("quick mode"))
        .or_else(|| text.lines().find(|l| l.starts_with("spheres_per_pod")))
        .unwrap()
        .to_owned();
    let text = text.replacen(&line, &format!("spheres_per_pod = {spheres_per_pod}"), 1);
    Study::from_toml(&text, Path::new(STUDY)).unwrap()
}

fn values(pairs: &[(&str, f64)]) -> ParameterValues {
    pairs.iter().map(|(k, v)| (k.to_string(), *v)).collect()
}

/// DESIGN §7: a block on an incline sticks for θ < atan μ. The pod lies flat and slides
/// (it neither tips nor rolls at these angles), so its slide angle is atan μs of the
/// pod–steel pair. Tolerance 1°: the onset is read at a 0.1 mm slip while the tilt rises
/// at 5°/s.
#[test]
fn slide_angle_matches_atan_mu() {
    let study = study_with_spheres(4);
    for mu in [0.3, 0.589] {
        let v = values(&[("pod-steel.static_friction", mu)]);
        let obs = study
            .run_experiment(
                ExperimentKind::InclineSlide,
                &v,
                ModeName::Quick,
                1,
                &RunOptions::default(),
            )
            .unwrap();
        let expected = mu.atan().to_degrees();
        assert_eq!(obs.unit, "deg");
        assert!(
            (obs.value - expected).abs() < 1.0,
            "μs {mu}: slide angle {} vs atan μ {expected}",
            obs.value
        );
    }
}

/// A one-sphere pod squeezed between two steel plates follows Hertz with two contacts in
/// series, so the apparent modulus recovers the pod's E = 2G(1 + ν) (seed 000 eq. (12));
/// the steel's compliance (E 2e11 Pa) shifts it by < 0.01 %. Tolerance 3 % (damping force
/// at the 0.01 m/s plate speed and the read-out at one instant).
#[test]
fn compression_of_one_sphere_recovers_youngs_modulus() {
    let study = study_with_spheres(1);
    let obs = study
        .run_experiment(
            ExperimentKind::Compression,
            &ParameterValues::new(),
            ModeName::Quick,
            1,
            &RunOptions::default(),
        )
        .unwrap();
    let pod = &study.file().materials["pod"];
    let e = 2.0 * pod.shear_modulus_pa * (1.0 + pod.poisson);
    assert_eq!(obs.unit, "Pa");
    assert!(
        (obs.value / e - 1.0).abs() < 0.03,
        "apparent modulus {} Pa vs E {e} Pa",
        obs.value
    );
}

#[test]
fn same_inputs_give_the_same_bits() {
    let study = study_with_spheres(4);
    let v = values(&[("pod-steel.static_friction", 0.5)]);
    let run = || {
        study
            .run_experiment(
                ExperimentKind::InclineSlide,
                &v,
                ModeName::Quick,
                7,
                &RunOptions::default(),
            )
            .unwrap()
    };
    let (a, b) = (run(), run());
    assert_eq!(a.digest, b.digest);
    assert_eq!(a.value.to_bits(), b.value.to_bits());
}

#[test]
fn poisson_above_half_runs_only_with_the_study_opt_in() {
    let study = study_with_spheres(1);
    // The shipped study opts in (seed 000 Table 3 screens ν = 0.586).
    let v = values(&[("pod.poisson", 0.586)]);
    let obs = study
        .run_experiment(
            ExperimentKind::Compression,
            &v,
            ModeName::Quick,
            1,
            &RunOptions::default(),
        )
        .unwrap();
    assert!(obs.value.is_finite() && obs.value > 0.0);
    // Without the opt-in the same value is refused before any simulation.
    let text = std::fs::read_to_string(STUDY)
        .unwrap()
        .replace("poisson_above_half = true", "");
    let strict = Study::from_toml(&text, Path::new(STUDY));
    if let Ok(strict) = strict {
        let err = strict
            .run_experiment(
                ExperimentKind::Compression,
                &v,
                ModeName::Quick,
                1,
                &RunOptions::default(),
            )
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("pod.poisson") && err.contains("0.586"),
            "{err}"
        );
    }
}

#[test]
fn bad_input_is_refused_with_a_clear_message() {
    let e = parse_experiment("repos").unwrap_err().to_string();
    assert!(
        e.contains("unknown experiment 'repos'") && e.contains("repose"),
        "{e}"
    );
    let e = parse_assignment("pod-pod.static_fricton=0.5")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("unknown parameter 'pod-pod.static_fricton'")
            && e.contains("did you mean 'pod-pod.static_friction'"),
        "{e}"
    );
    let e = parse_assignment("pod-pod.static_friction=abc")
        .unwrap_err()
        .to_string();
    assert!(e.contains("'abc' is not a number"), "{e}");
    let e = parse_assignment("pod-pod.static_friction")
        .unwrap_err()
        .to_string();
    assert!(e.contains("KEY=VALUE"), "{e}");
    let e = "medium".parse::<ModeName>().unwrap_err().to_string();
    assert!(e.contains("unknown mode 'medium'"), "{e}");
    let study = Study::load(Path::new(STUDY)).unwrap();
    for (key, value, words) in [
        (
            "pod-pod.static_friction",
            -0.1,
            "outside the physical limits",
        ),
        ("pod-pod.restitution", 1.5, "outside the physical limits"),
        ("pod.poisson", 1.2, "outside the physical limits"),
        ("pod.shear_modulus_pa", f64::NAN, "not a finite number"),
    ] {
        let v = values(&[(key, value)]);
        let e = study
            .run_experiment(
                ExperimentKind::Repose,
                &v,
                ModeName::Quick,
                1,
                &RunOptions::default(),
            )
            .unwrap_err()
            .to_string();
        assert!(e.contains(key) && e.contains(words), "{key}={value}: {e}");
    }
}
