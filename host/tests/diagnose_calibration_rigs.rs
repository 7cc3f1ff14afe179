//! Issue 17: the diagnosis commands take the same study files and the same rigs as a
//! calibration. Seed 001's pull-off study, with its printed force replaced by replicated
//! pulls, is compared and diagnosed on the pull-off rig the calibration runs; the
//! prediction is the rig's own pull at the study's held values.

use std::path::{Path, PathBuf};

use arachis::diagnose::model::Model;
use arachis::diagnose::residuals::Dataset;
use arachis::diagnose::sensitivity::predict;
use arachis::rigs::pull_off::{PullOffRig, DETACHMENT_FORCE};
use arachis::study::Study;

use crate::cli_support;
use cli_support::arachis;

/// Seed 001's study with four replicated pulls instead of its printed force, beside a copy
/// of its topology in `dir`.
fn replicated_pull_study(dir: &Path) -> PathBuf {
    let shipped = Path::new(env!("CARGO_MANIFEST_DIR")).join("../testdata/peanut-plant");
    std::fs::copy(
        shipped.join("topology-small.toml"),
        dir.join("topology-small.toml"),
    )
    .unwrap();
    let text = std::fs::read_to_string(shipped.join("study.toml")).unwrap();
    let (start, end) = (
        text.find("[measurement]").unwrap(),
        text.find("# The nine factors").unwrap(),
    );
    let edited = format!(
        "{}[[measurements]]\nexperiment = \"pull_off\"\nquantity = \"detachment_force\"\n\
         unit = \"N\"\nvalues = [7.1, 7.3, 7.2, 7.25]\n\n{}",
        &text[..start],
        &text[end..]
    );
    let path = dir.join("study.toml");
    std::fs::write(&path, edited).unwrap();
    path
}

#[test]
fn the_pull_off_rig_is_a_diagnosis_rig() {
    let dir = tempfile::tempdir().unwrap();
    let path = replicated_pull_study(dir.path());
    let study = Study::load(&path).unwrap();
    let data = Dataset::new(&study).unwrap();
    assert_eq!(data.experiments.len(), 1);
    assert_eq!(data.experiments[0].rig, "pull_off");
    let model = Model::new(&study, &data.experiments).unwrap();
    // Base parameters the rig declares, at the study's held values (the factors' centres).
    let current = study.current_values();
    assert_eq!(current.len(), 9);
    assert_eq!(model.catalogue.base().count(), 9);
    let predicted = predict(&data, &model, &current).unwrap();
    let rig = PullOffRig {
        base: study.pull_off_setup().unwrap(),
    };
    let pulled = rig.pull(&current).unwrap()[DETACHMENT_FORCE];
    assert_eq!(predicted, [pulled]);

    // The commands run it too.
    let path = path.to_str().unwrap();
    let o = arachis(&["compare", path]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        out.contains("experiment 1 pull_off: detachment force, N vs (one condition)"),
        "{out}"
    );
    assert!(out.contains(&format!("{pulled:.6}")), "{out}");
    let o = arachis(&["diagnose", path]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(out.contains("junction.strength_pa"), "{out}");
    // The rig has no optional effects to rank: said, not hidden.
    assert!(out.contains("no candidate effect is identifiable"), "{out}");
}

#[test]
fn a_printed_mean_is_refused_for_want_of_replicates() {
    let o = arachis(&[
        "compare",
        concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../testdata/peanut-plant/study.toml"
        ),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("experiment 1 (pull_off) point 1: no values"),
        "{err}"
    );
}
