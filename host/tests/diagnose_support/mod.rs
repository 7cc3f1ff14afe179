//! Shared set-up of the diagnosis tests: the tutorial template (three cheap experiments, six
//! conditions each, four replicates), the deterministic simulations computed once per case,
//! and the noise varied per seed through the same `synth::add_noise` the CLI uses.

use std::path::{Path, PathBuf};

use arachis::diagnose::fit::{compare_with, Comparison};
use arachis::diagnose::model::Model;
use arachis::diagnose::params::{value as param_value, Catalogue};
use arachis::diagnose::residuals::{experiments, Dataset};
use arachis::diagnose::score::{rank, Ranking};
use arachis::diagnose::sensitivity::Linearisation;
use arachis::diagnose::synth::{add_noise, truths, NoiseSpec};
use arachis::rigs::single_sphere::ModelParams;
use arachis::study::diagnosis::DiagnosisSection;
use arachis::study::Study;

/// Seeds per case (issue 5: at least 50).
pub const SEEDS: u64 = 50;

pub fn template_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../testdata/diagnosis-tutorial/template.toml")
}

/// The tutorial template's `[diagnosis]` section (edited by the tests, then loaded again
/// with [`study_of`]).
pub fn template() -> DiagnosisSection {
    Study::load(&template_path())
        .unwrap()
        .file()
        .diagnosis
        .clone()
        .unwrap()
}

/// The study of `section`, loaded and checked like a file.
pub fn study_of(section: &DiagnosisSection) -> Study {
    Study::from_toml(&section.to_toml().unwrap(), Path::new("test-study.toml")).unwrap()
}

/// The effect named `name` of the single-sphere rigs (the roll rig declares them all).
pub fn effect(name: &str) -> &'static arachis::diagnose::params::ParamInfo {
    Catalogue::of_rigs(["roll"]).effect(name).unwrap()
}

/// One hidden-effect case, simulated once.
pub struct Case {
    pub study: Study,
    pub truth: Vec<Vec<f64>>,
    pub lin: Linearisation,
    /// Largest |truth − truth without the effect| over all conditions, in noise SDs.
    pub effect_size_sigma: f64,
}

pub fn case_for(section: DiagnosisSection, hidden: Option<(&str, f64)>) -> Case {
    let truth_base = section.calibration;
    case_with_truth(section, truth_base, hidden)
}

/// Like [`case_for`], but the truth's base parameters are `truth_base` while the study keeps
/// its (then wrong) calibration.
pub fn case_with_truth(
    section: DiagnosisSection,
    truth_base: ModelParams,
    hidden: Option<(&str, f64)>,
) -> Case {
    let h: Vec<_> = hidden.iter().map(|(n, v)| (effect(n), *v)).collect();
    let study = study_of(&section);
    let (truth, plain) = {
        let series = study.series();
        let model = Model::new(&study, &experiments(&study)).unwrap();
        let (_, truth) = truths(&model, &series, &truth_base.values(), &h).unwrap();
        let (_, plain) = truths(&model, &series, &truth_base.values(), &[]).unwrap();
        (truth, plain)
    };
    let mut size = 0.0f64;
    for (ei, e) in section.experiment.iter().enumerate() {
        let sd = e.noise_sd.unwrap();
        for (a, b) in truth[ei].iter().zip(&plain[ei]) {
            size = size.max((a - b).abs() / sd);
        }
    }
    Case {
        effect_size_sigma: size,
        ..case_from_truth(study, truth)
    }
}

/// The case of `study` whose true values are `truth` (per experiment, per point), made
/// elsewhere (e.g. by another engine); its effect size is left at 0.
pub fn case_from_truth(study: Study, truth: Vec<Vec<f64>>) -> Case {
    // The linearisation depends only on the calibration and the conditions: any noisy copy
    // of the study gives the same one.
    let lin = {
        let noisy = noisy_study(&study, &truth, 0);
        let data = Dataset::new(&noisy).unwrap();
        let model = Model::new(&noisy, &data.experiments).unwrap();
        Linearisation::new(&data, &model, &study.current_values()).unwrap()
    };
    Case {
        study,
        truth,
        lin,
        effect_size_sigma: 0.0,
    }
}

/// `study` with replicates drawn around `truth` with noise seed `seed` (4 per point unless
/// the study says).
fn noisy_study(study: &Study, truth: &[Vec<f64>], seed: u64) -> Study {
    let values = add_noise(&study.series(), truth, &NoiseSpec::default(), seed, 4).unwrap();
    Study::from_toml(
        &study.toml_with_replicates(&values, None).unwrap(),
        Path::new("noisy-study.toml"),
    )
    .unwrap()
}

pub fn case(hidden: Option<(&str, f64)>) -> Case {
    case_for(template(), hidden)
}

impl Case {
    /// The measured study of seed `seed`.
    pub fn measured(&self, seed: u64) -> Study {
        noisy_study(&self.study, &self.truth, seed)
    }
    /// The measurements of seed `seed`.
    pub fn data(&self, seed: u64) -> Dataset {
        Dataset::new(&self.measured(seed)).unwrap()
    }
    /// The ranking for seed `seed`.
    pub fn ranking(&self, seed: u64) -> Ranking {
        rank(&self.data(seed), &self.lin).unwrap()
    }
    /// `fit`'s comparison for seed `seed`: the base refit without and with `effect` (and the
    /// leave-one-condition-out refits when `loco`); a failed fit panics, naming the seed.
    pub fn compare(
        &self,
        seed: u64,
        effect: &'static arachis::diagnose::params::ParamInfo,
        loco: bool,
    ) -> Comparison {
        let measured = self.measured(seed);
        let data = Dataset::new(&measured).unwrap();
        let model = Model::new(&measured, &data.experiments).unwrap();
        compare_with(&data, &model, &self.study.current_values(), effect, loco)
            .unwrap_or_else(|e| panic!("seed {seed}: {e:#}"))
    }
}

/// Replicates per condition in the fit studies.
pub const REPLICATES: usize = 12;

pub fn fit_case(kind: &str, name: &str, value: f64, seeds: u64) {
    let mut section = template();
    section.experiment.retain(|e| e.kind == kind);
    for p in section.experiment[0].point.iter_mut() {
        p.replicates = Some(REPLICATES);
    }
    let sd = section.experiment[0].noise_sd.unwrap();
    let c = case_for(section, Some((name, value)));
    let info = effect(name);
    let (mut in_band, mut covered) = (0, 0);
    let (mut sum_ratio, mut sum_est) = (0.0, 0.0);
    for seed in 0..seeds {
        let data = c.data(seed);
        let cmp = c.compare(seed, info, false);
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
        let (est, se) = (param_value(info, &f.params), f.std_errors[k]);
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
