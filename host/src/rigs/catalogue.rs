//! The catalogue of rigs: every rig of the host, by the name study files give it. A
//! study's measurements are checked against it and its rigs are built from it, so a new
//! rig is one file that declares its [`RigKind`] plus one line in [`RIGS`].

use super::kind::RigKind;
use super::pod_bench::PodTest;
use super::pod_world::Experiment;

/// Every rig, in the order studies and messages list them.
pub const RIGS: &[&RigKind] = &[
    &super::repose_cylinder::KIND,
    &super::pod_bench::PLATE_DROP,
    &super::incline::KIND,
    &super::pod_bench::ROLLING,
    &super::compression::KIND,
    &super::pull_off::KIND,
    &super::harvest::KIND,
    &super::bench_bed::KIND,
    &super::hopper::KIND,
    &super::drum::KIND,
    &super::bulk_density::KIND,
    &super::pod_bulk_density::KIND,
    &super::pod_drum::KIND,
    &super::pod_hopper::KIND,
    &super::rebound::KIND,
    &super::press::KIND,
    &super::fall::KIND,
    &super::unload::KIND,
    &super::roll::KIND,
];

/// The rig named `name`.
pub fn find(name: &str) -> Option<&'static RigKind> {
    RIGS.iter().copied().find(|k| k.name == name)
}

/// Every rig's name.
pub fn names() -> Vec<&'static str> {
    RIGS.iter().map(|k| k.name).collect()
}

/// The pod bench test of `experiment`.
pub fn pod_test(experiment: Experiment) -> PodTest {
    match experiment {
        Experiment::Repose => super::repose_cylinder::TEST,
        Experiment::InclineSlide => super::incline::TEST,
        Experiment::Compression => super::compression::TEST,
        Experiment::PodBulkDensity => super::pod_bulk_density::TEST,
        Experiment::PodDrum => super::pod_drum::TEST,
        Experiment::PodHopper => super::pod_hopper::TEST,
        Experiment::PlateDrop => super::pod_bench::PLATE_DROP_TEST,
        Experiment::Rolling => super::pod_bench::ROLLING_TEST,
    }
}
