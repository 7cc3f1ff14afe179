//! Issue 22 item 2: the pod world's optional effects (SJKR cohesion, EPSD rolling resistance,
//! viscoelastic damping on the pod–pod pair). A run's values or a study's pair table switch
//! them on; they reach the core; a run without them is specified exactly as before (the
//! same spec, hash and cache entry); and a diagnosis of a pod rig offers them as candidates.

use std::collections::BTreeMap;
use std::path::Path;

use arachis::diagnose::params::Catalogue;
use arachis::rigs::parameter::Role;
use arachis::rigs::pod_world::setup::RunInputs;
use arachis::rigs::pod_world::{Experiment, ModeName, ParameterValues, TemplateCache};
use arachis::study::Study;

use crate::cli_support;
use cli_support::{arachis_at_root as arachis, REPO_ROOT};

const STUDY: &str = "testdata/peanut-pods-saline/study.toml";

fn study() -> Study {
    Study::load(&Path::new(REPO_ROOT).join(STUDY)).unwrap()
}

fn inputs(study: &Study, values: &[(&str, f64)]) -> Result<RunInputs, String> {
    let values: ParameterValues = values.iter().map(|(k, v)| ((*k).to_owned(), *v)).collect();
    let condition = BTreeMap::from([("lift_speed_m_s".to_owned(), 0.05)]);
    RunInputs::resolve(
        &study.pod_world().unwrap(),
        Experiment::Repose,
        &condition,
        &values,
        ModeName::Quick,
        &TemplateCache::new(),
    )
    .map_err(|e| e.to_string())
}

#[test]
fn effects_reach_the_run_and_are_written_only_when_on() {
    let study = study();
    let off = inputs(&study, &[]).unwrap();
    assert_eq!(off.pod_pod_effects, Default::default());
    let json = off.spec.canonical_json();
    for key in [
        "cohesion_j_m3",
        "epsd_rolling_friction",
        "viscoelastic_time_s",
    ] {
        assert!(!json.contains(key), "{key} written while off: {json}");
    }
    let on = inputs(
        &study,
        &[
            ("pod-pod.cohesion_j_m3", 2.0e4),
            ("pod-pod.epsd_rolling_friction", 0.05),
            ("pod-pod.viscoelastic_time_s", 1.0e-5),
        ],
    )
    .unwrap();
    assert_eq!(on.pod_pod_effects.cohesion_energy_density_j_m3, 2.0e4);
    assert_eq!(on.pod_pod_effects.epsd_rolling_friction, 0.05);
    assert_eq!(on.pod_pod_effects.viscoelastic_time_s, 1.0e-5);
    assert_eq!(on.pod_wall_effects, Default::default());
    assert!(on.spec.canonical_json().contains("\"cohesion_j_m3\":20000"));
    assert_ne!(on.spec.spec_hash(), off.spec.spec_hash());
    // An effect is never negative.
    let err = inputs(&study, &[("pod-pod.cohesion_j_m3", -1.0)]).unwrap_err();
    assert!(err.contains("pod-pod.cohesion_j_m3"), "{err}");
}

#[test]
fn a_study_switches_an_effect_on_in_its_pair_table_and_it_is_checked() {
    let text = std::fs::read_to_string(Path::new(REPO_ROOT).join(STUDY)).unwrap();
    let with = |line: &str| {
        text.replace(
            "[pairs.\"pod-pod\"]\n",
            &format!("[pairs.\"pod-pod\"]\n{line}\n"),
        )
    };
    let dir = Path::new(REPO_ROOT).join("testdata/peanut-pods-saline");
    let on = Study::from_toml(&with("cohesion_j_m3 = 3000.0"), &dir.join("study.toml")).unwrap();
    let run = inputs(&on, &[]).unwrap();
    assert_eq!(run.pod_pod_effects.cohesion_energy_density_j_m3, 3000.0);
    // The run's value overrides the study's.
    let run = inputs(&on, &[("pod-pod.cohesion_j_m3", 0.0)]).unwrap();
    assert_eq!(run.pod_pod_effects.cohesion_energy_density_j_m3, 0.0);
    let err = Study::from_toml(&with("cohesion_j_m3 = -5.0"), &dir.join("study.toml"))
        .unwrap_err()
        .to_string();
    assert!(err.contains("cohesion_j_m3"), "{err}");
}

#[test]
fn a_diagnosis_of_a_pod_rig_offers_the_effects_as_candidates() {
    let catalogue = Catalogue::of_rigs(["repose"]);
    for name in [
        "pod-pod.cohesion_j_m3",
        "pod-pod.epsd_rolling_friction",
        "pod-pod.viscoelastic_time_s",
    ] {
        let p = catalogue.effect(name).unwrap();
        assert_eq!(p.role, Role::Effect);
    }
    // The calibrated parameters stay base parameters.
    assert!(catalogue.effect("pod-pod.rolling_friction").is_err());
}

#[test]
fn an_effect_changes_the_simulated_pile() {
    // One quick pile of the shipped study without and with pod-pod cohesion (about 7 s each):
    // the same placement, another result. The physics of each effect is tested in the core.
    let run = |extra: &[&str]| {
        let mut args = vec![
            "simulate", "--study", STUDY, "--mode", "quick", "--json", "repose",
        ];
        args.extend_from_slice(extra);
        let out = arachis(&args);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        v["observation"]["digest"].as_str().unwrap().to_owned()
    };
    let plain = run(&[]);
    let cohesive = run(&["--set", "pod-pod.cohesion_j_m3=2e4"]);
    assert_ne!(plain, cohesive);
}

#[test]
fn a_pod_rig_simulates_the_effects_its_specification_names() {
    // The rig simulates a run from its specification. Read back from the specification, the
    // values must name the effects and specify the same run; before 2026-11-27 they lost
    // them, so every pod-rig diagnosis simulated its effect steps without the effect.
    use arachis::calibration::RunRequest;
    use arachis::rigs::pod_bench::{parameter_values, PodBenchRig};
    use arachis::rigs::repose_cylinder::TEST;
    let study = study();
    let rig = PodBenchRig::new(study.pod_world().unwrap(), TEST, ModeName::Quick);
    let condition = BTreeMap::from([("lift_speed_m_s".to_owned(), 0.05)]);
    for (name, value) in [
        ("pod-pod.cohesion_j_m3", 2.0e3),
        ("pod-pod.epsd_rolling_friction", 0.02),
        ("pod-pod.viscoelastic_time_s", 2.0e-6),
    ] {
        let values = ParameterValues::from([(name.to_owned(), value)]);
        let request = RunRequest {
            values: &values,
            condition: &condition,
            replicate: 0,
        };
        let spec = rig.run_spec(&request).unwrap();
        let read = parameter_values(&spec);
        assert_eq!(read.get(name), Some(&value), "{name}");
        let again = RunRequest {
            values: &read,
            ..request
        };
        assert_eq!(rig.run_spec(&again).unwrap().spec_hash(), spec.spec_hash());
        // An effect that is off is not read back: the run is the one without it.
        let off = parameter_values(
            &rig.run_spec(&RunRequest {
                values: &ParameterValues::new(),
                ..request
            })
            .unwrap(),
        );
        assert!(!off.contains_key(name), "{name}");
    }
}
