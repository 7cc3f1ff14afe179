//! Shared set-up of the diagnosis tests: the tutorial template (three cheap experiments, six
//! conditions each, four replicates), the deterministic simulations computed once per case,
//! and the noise varied per seed through the same `synth::add_noise` the CLI uses.
#![allow(dead_code)]

use std::path::PathBuf;

use arachis::diagnose::fit::compare_with;
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
    let truth_base = study.calibration;
    case_with_truth(study, truth_base, hidden)
}

/// Like [`case_for`], but the truth's base parameters are `truth_base` while the study keeps
/// its (then wrong) calibration.
pub fn case_with_truth(
    study: Diagnosis,
    truth_base: arachis::diagnose::params::ModelParams,
    hidden: Option<(&str, f64)>,
) -> Case {
    let h: Vec<_> = hidden
        .iter()
        .map(|(n, v)| (effect(n).unwrap(), *v))
        .collect();
    let mut truth_study = study.clone();
    truth_study.calibration = truth_base;
    let (_, truth) = truths(&truth_study, &h).unwrap();
    let (_, plain) = truths(&truth_study, &[]).unwrap();
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

/// Replicates per condition in the fit studies.
pub const REPLICATES: usize = 12;

pub fn fit_case(kind: &str, name: &str, value: f64, seeds: u64) {
    let mut study = template();
    study.experiment.retain(|e| e.kind.name() == kind);
    for p in study.experiment[0].point.iter_mut() {
        p.replicates = Some(REPLICATES);
    }
    let sd = study.experiment[0].noise_sd.unwrap();
    let c = case_for(study, Some((name, value)));
    let info = effect(name).unwrap();
    let (mut in_band, mut covered) = (0, 0);
    let (mut sum_ratio, mut sum_est) = (0.0, 0.0);
    for seed in 0..seeds {
        let data = c.data(seed);
        let cmp = compare_with(&data, &c.study.calibration, info, false).unwrap();
        let f = &cmp.with;
        let (mut ss, mut n) = (0.0, 0);
        for (o, y) in data.obs.iter().zip(&f.predictions) {
            for v in &o.values {
                ss += (v - y).powi(2);
                n += 1;
            }
        }
        let ratio = (ss / n as f64).sqrt() / sd;
        let k = f.free.iter().position(|p| p.name == name).unwrap();
        let (est, se) = (info.get(&f.params), f.std_errors[k]);
        if (0.8..=1.3).contains(&ratio) {
            in_band += 1;
        }
        if (est - value).abs() <= 2.0 * se {
            covered += 1;
        }
        sum_ratio += ratio;
        sum_est += est;
        if seed == 0 {
            println!(
                "{name} seed 0: fitted {} ; {name} = {est:e} ± {se:e}, RMS/noise {ratio:.3}, \
                 before (base refit) SSE {:.1}, after {:.1}, LR p {:.2e}",
                f.free.iter().map(|p| p.name).collect::<Vec<_>>().join(", "),
                cmp.without.sse,
                f.sse,
                cmp.lr_p
            );
        }
    }
    let s = seeds as f64;
    println!(
        "hidden {name}={value:e} on {kind}: RMS/noise in [0.8, 1.3] {in_band}/{seeds} (mean {:.3}), \
         within 2 SE {covered}/{seeds}, mean estimate {:e}",
        sum_ratio / s,
        sum_est / s
    );
    assert!(in_band as f64 >= 0.9 * s);
    assert!(covered as f64 >= 0.85 * s);
}
