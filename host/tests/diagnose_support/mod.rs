//! Shared set-up of the diagnosis tests: the tutorial template (three cheap experiments, six
//! conditions each, four replicates), the deterministic simulations computed once per case,
//! and the noise varied per seed through the same `synth::add_noise` the CLI uses.
#![allow(dead_code)]

use std::path::PathBuf;

use arachis::diagnose::params::effect;
use arachis::diagnose::residuals::Dataset;
use arachis::diagnose::score::{rank, Ranking};
use arachis::diagnose::sensitivity::Linearisation;
use arachis::diagnose::study::Diagnosis;
use arachis::diagnose::synth::{add_noise, truths, NoiseSpec};

/// Seeds per case (issue 5: at least 50).
pub const SEEDS: u64 = 50;

pub fn template_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../testdata/diagnosis-tutorial/template.toml")
}

pub fn template() -> Diagnosis {
    Diagnosis::load_template(&template_path()).unwrap()
}

/// One hidden-effect case, simulated once.
pub struct Case {
    pub study: Diagnosis,
    pub truth: Vec<Vec<f64>>,
    pub lin: Linearisation,
    /// Largest |truth − truth without the effect| over all conditions, in noise SDs.
    pub effect_size_sigma: f64,
}

pub fn case_for(study: Diagnosis, hidden: Option<(&str, f64)>) -> Case {
    let h: Vec<_> = hidden
        .iter()
        .map(|(n, v)| (effect(n).unwrap(), *v))
        .collect();
    let (_, truth) = truths(&study, &h).unwrap();
    let (_, plain) = truths(&study, &[]).unwrap();
    let mut size = 0.0f64;
    for (ei, e) in study.experiment.iter().enumerate() {
        let sd = e.noise_sd.unwrap();
        for (a, b) in truth[ei].iter().zip(&plain[ei]) {
            size = size.max((a - b).abs() / sd);
        }
    }
    // The linearisation depends only on the calibration and the conditions: any noisy copy
    // of the study gives the same one.
    let noisy = add_noise(&study, &truth, &NoiseSpec::default(), 0, 4).unwrap();
    let lin = Linearisation::new(&Dataset::new(&noisy).unwrap(), &study.calibration).unwrap();
    Case {
        study,
        truth,
        lin,
        effect_size_sigma: size,
    }
}

pub fn case(hidden: Option<(&str, f64)>) -> Case {
    case_for(template(), hidden)
}

impl Case {
    /// The measurements of seed `seed`.
    pub fn data(&self, seed: u64) -> Dataset {
        let noisy = add_noise(&self.study, &self.truth, &NoiseSpec::default(), seed, 4).unwrap();
        Dataset::new(&noisy).unwrap()
    }
    /// The ranking for seed `seed`.
    pub fn ranking(&self, seed: u64) -> Ranking {
        rank(&self.data(seed), &self.lin).unwrap()
    }
}
