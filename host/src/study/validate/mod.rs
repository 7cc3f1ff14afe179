//! Semantic checks of a decoded study: everything serde cannot see, all of it before any
//! simulation starts, every failure collected.
//!
//! - header: a name, and a `kind` (seed 001's study has one) that fits the study;
//! - names: materials referenced by pods and pairs exist; parameter names are in the
//!   registry (else the nearest name is suggested) and their material or pair exists;
//! - ranges: low < high, both within the physical limits of [`Limits`];
//! - values: every material and pair value within its limits; every pair property has a
//!   value or a range; shape-mix fractions sum to 1;
//! - measurements: the experiment is a rig of the catalogue whose world the study has,
//!   quantity and unit known for it, condition keys known, replicates or a summary (never
//!   both), no duplicate blocks;
//! - plan: mode exists, the screening design has room for the factors and an error
//!   estimate, one response surface with its settings, the target and validation
//!   measurements exist and are unambiguous;
//! - the pull-off study's `[rig]`, `[measurement]` and `[factors]`, and `[diagnosis]`
//!   (their own modules);
//! - files: every STL and topology resolves (relative to the study file), is readable and
//!   parses.

use std::collections::BTreeSet;
use std::path::Path;

mod measurements;
pub mod plan;
pub mod ranges;

use crate::io::file_name::check_name_component;
use crate::limits::Limits;
use crate::nearest_name::nearest_name;
use crate::plant::topology::BondSet;
use crate::plausible::{Plausible, DENSITY_KG_M3, SHEAR_MODULUS_PA};
use crate::rigs::pod_world::parameters;
use crate::rigs::pod_world::sections::{Particles, Spheres};
use crate::rigs::pod_world::Pods;
use crate::shapes::stl::read_stl;
use crate::study::error::StudyError;
use crate::study::file_format::{StudyFile, PAIR_EFFECTS, PAIR_PROPERTIES};
use crate::study::key_path::KeyPath;
use crate::study::pull_off::{ReadFile, KIND_PULL_OFF};
use crate::study::source::Source;

/// The shape-mix fractions must sum to 1 within this (they are proportions of a count,
/// typed with a few decimals; a larger gap is a mistake, not rounding).
pub const SHAPE_MIX_TOLERANCE: f64 = 1e-6;

/// Smallest broad-phase cell, in sphere radii: a cell must hold a whole sphere diameter so
/// neighbour cells find every contact.
pub const MIN_GRID_CELL_RADII: f64 = 2.0;

/// Fewest replicated centre points that give a pure-error estimate (DESIGN §9).
pub const MIN_BOX_BEHNKEN_CENTRE_POINTS: u32 = 2;

/// Collects every semantic error of `file`; `dir` is the study file's directory, `read`
/// reads the files it names. Returns the pull-off rig's junction and stalk bond sets too,
/// when the study has that rig and they could be read.
pub(crate) fn validate(
    src: &Source<'_>,
    file: &StudyFile,
    dir: &Path,
    read: ReadFile<'_>,
) -> (Option<(BondSet, BondSet)>, Vec<StudyError>) {
    let mut v = Validator {
        src,
        errors: Vec::new(),
    };
    v.header(file);
    if let Some(pods) = &file.pods {
        v.pods(pods, file, dir);
    }
    if let Some(spheres) = &file.spheres {
        v.spheres(spheres, file);
    }
    if let Some(particles) = particles(file) {
        v.materials(file);
        v.pairs(file);
        v.contacts(particles, file);
    }
    v.measurements(file);
    v.parameters(file);
    if let Some(plan) = &file.plan {
        v.plan(file, plan);
    }
    if let Some(d) = &file.diagnosis {
        v.errors.extend(crate::study::diagnosis::validate(src, d));
    }
    v.priors(file);
    let mut sets = None;
    if let Some(rig) = &file.rig {
        let (found, errors) = crate::study::pull_off::validate(
            src,
            rig,
            file.measurement.as_ref(),
            &file.factors,
            dir,
            read,
        );
        sets = found;
        v.errors.extend(errors);
    }
    (sets, v.errors)
}

struct Validator<'s, 'i> {
    src: &'s Source<'i>,
    errors: Vec<StudyError>,
}

impl Validator<'_, '_> {
    fn fail(&mut self, key: &KeyPath, reason: impl Into<String>) {
        self.errors.push(self.src.error(key, reason));
    }

    fn limit(&mut self, key: &KeyPath, value: f64, limits: Limits) {
        if let Err(reason) = limits.check(value) {
            self.fail(key, reason);
        }
    }

    /// `limit`, then the plausible range (only for a value the model admits, so one fault
    /// gets one message).
    fn plausible(&mut self, key: &KeyPath, value: f64, limits: Limits, range: Plausible) {
        match limits.check(value) {
            Err(reason) => self.fail(key, reason),
            Ok(()) => {
                if let Err(reason) = range.check(value) {
                    self.fail(key, reason);
                }
            }
        }
    }

    fn header(&mut self, file: &StudyFile) {
        let Some(header) = &file.study else { return };
        let at = KeyPath::root().key("study");
        if header.name.trim().is_empty() {
            self.fail(&at.key("name"), "the study needs a name");
        } else if let Err(reason) = check_name_component(&header.name) {
            // The name names the output folder (calibration-NAME-MODE).
            self.fail(&at.key("name"), reason);
        }
        match &header.kind {
            Some(kind) if kind != KIND_PULL_OFF => self.fail(
                &at.key("kind"),
                format!(
                    "the one kind is '{KIND_PULL_OFF}' (a study's rigs follow from its \
                     measurements), got '{kind}'"
                ),
            ),
            Some(_) if file.rig.is_none() => self.fail(
                &at.key("kind"),
                format!("kind '{KIND_PULL_OFF}' needs the pull-off rig's [rig]"),
            ),
            _ => {}
        }
    }

    fn materials(&mut self, file: &StudyFile) {
        let at = KeyPath::root().key("materials");
        if file.materials.is_empty() {
            self.fail(&at, "no materials: add at least [materials.pod]");
        }
        for (name, m) in &file.materials {
            let k = at.key(name);
            if !is_material_name(name) {
                self.fail(&k, "a material name may hold only lower-case letters, digits and '_' ('-' joins pair names)");
            }
            let (density, shear) = (m.density_kg_m3, m.shear_modulus_pa);
            self.plausible(
                &k.key("density_kg_m3"),
                density,
                Limits::Positive,
                DENSITY_KG_M3,
            );
            self.limit(&k.key("poisson"), m.poisson, Limits::Poisson);
            self.plausible(
                &k.key("shear_modulus_pa"),
                shear,
                Limits::Positive,
                SHEAR_MODULUS_PA,
            );
        }
    }

    fn pods(&mut self, p: &Pods, file: &StudyFile, dir: &Path) {
        let at = KeyPath::root().key("pods");
        if !file.materials.contains_key(&p.material) {
            self.fail(
                &at.key("material"),
                format!("no [materials.{}] in this study", p.material),
            );
        }
        self.limit(&at.key("length_mm"), p.length_mm, Limits::Positive);
        self.limit(&at.key("width_mm"), p.width_mm, Limits::Positive);
        self.limit(&at.key("thickness_mm"), p.thickness_mm, Limits::Positive);
        let mix = at.key("shape_mix");
        let mut sum = 0.0;
        for (shape, fraction) in p.shape_mix.entries() {
            self.limit(&mix.key(shape), fraction, Limits::Fraction);
            sum += fraction;
        }
        if sum.is_finite() && (sum - 1.0).abs() > SHAPE_MIX_TOLERANCE {
            self.fail(
                &mix,
                format!(
                    "the fractions normal + cocoon + single_grain sum to {}, not 1",
                    round_for_message(sum)
                ),
            );
        }
        for (shape, written) in p.stl.entries() {
            let resolved = dir.join(written);
            // The reader itself: a closed surface of finite vertices, as the filling needs.
            if let Err(reason) = read_stl(&resolved) {
                self.fail(
                    &at.key("stl").key(shape),
                    format!("unreadable STL '{written}': {reason}"),
                );
            }
        }
    }

    fn spheres(&mut self, p: &Spheres, file: &StudyFile) {
        let at = KeyPath::root().key("spheres");
        if file.pods.is_some() {
            self.fail(
                &at,
                "a study has either [pods] or [spheres], not both: which particles should the \
                 rigs simulate?",
            );
        }
        if !file.materials.contains_key(&p.material) {
            self.fail(
                &at.key("material"),
                format!("no [materials.{}] in this study", p.material),
            );
        }
        match (p.radius_mm, p.sizes.is_empty()) {
            (Some(r), true) => self.limit(&at.key("radius_mm"), r, Limits::Positive),
            (None, false) => {
                let sizes = at.key("sizes");
                let mut sum = 0.0;
                for (i, class) in p.sizes.iter().enumerate() {
                    let k = sizes.index(i);
                    self.limit(&k.key("radius_mm"), class.radius_mm, Limits::Positive);
                    self.limit(&k.key("fraction"), class.fraction, Limits::Fraction);
                    sum += class.fraction;
                }
                if sum.is_finite() && (sum - 1.0).abs() > SHAPE_MIX_TOLERANCE {
                    self.fail(
                        &sizes,
                        format!(
                            "the size fractions sum to {}, not 1",
                            round_for_message(sum)
                        ),
                    );
                }
            }
            (Some(_), false) => self.fail(
                &at,
                "give either radius_mm (one size) or [[spheres.sizes]] (a distribution), not both",
            ),
            (None, true) => self.fail(
                &at,
                "no size: give radius_mm (one size) or [[spheres.sizes]] (radius_mm and fraction \
                 per class)",
            ),
        }
    }

    fn pairs(&mut self, file: &StudyFile) {
        let at = KeyPath::root().key("pairs");
        let mut seen = BTreeSet::new();
        let known = parameters::names();
        let intended: BTreeSet<&str> = file
            .parameters
            .keys()
            .filter(|n| parameters::lookup(n).is_none())
            .filter_map(|n| nearest_name(n, &known))
            .collect();
        for (name, pair) in &file.pairs {
            let k = at.key(name);
            match name.split_once('-') {
                Some((a, b)) if is_material_name(a) && is_material_name(b) => {
                    for m in [a, b] {
                        if !file.materials.contains_key(m) {
                            self.fail(
                                &k,
                                format!("pair names material '{m}', which has no [materials.{m}]"),
                            );
                        }
                    }
                    let unordered = if a <= b { (a, b) } else { (b, a) };
                    if !seen.insert(unordered) {
                        self.fail(
                            &k,
                            format!("the pair {b}-{a} is given twice (as {a}-{b} and {b}-{a})"),
                        );
                    }
                }
                _ => self.fail(
                    &k,
                    "a pair is named '<material>-<material>', e.g. \"pod-steel\"",
                ),
            }
            for property in PAIR_PROPERTIES {
                let pk = k.key(property);
                let registered = parameters::for_property(name, property);
                // A misspelt parameter name is reported once, with its suggestion; the
                // property it meant to vary is then not reported missing as well.
                let varied = registered.is_some_and(|p| {
                    file.parameters.contains_key(p.name) || intended.contains(p.name)
                });
                match (pair.property(property), registered) {
                    (Some(value), Some(spec)) => match crate::plausible::for_property(property) {
                        Some(range) => self.plausible(&pk, value, spec.limits, range),
                        None => self.limit(&pk, value, spec.limits),
                    },
                    (Some(value), None) => self.limit(&pk, value, pair_limits(property)),
                    (None, _) if varied => {}
                    (None, Some(spec)) => self.fail(
                        &k,
                        format!(
                            "no {property}: give a value, or vary it under [parameters.\"{}\"]",
                            spec.name
                        ),
                    ),
                    (None, None) => self.fail(&k, format!("no {property}: give a value")),
                }
            }
            // An optional effect is off when absent; when given, it is ≥ 0 and finite.
            for property in PAIR_EFFECTS {
                if let Some(value) = pair.property(property) {
                    self.limit(&k.key(property), value, Limits::NonNegative);
                }
            }
        }
    }
}

impl Validator<'_, '_> {
    /// `[priors]`: each a base parameter of a rig the study measures, with a mean inside its
    /// limits and an SD > 0.
    fn priors(&mut self, file: &StudyFile) {
        let parameters: Vec<&crate::rigs::parameter::RigParameter> = file
            .measurements
            .iter()
            .filter_map(|m| crate::rigs::catalogue::find(&m.experiment))
            .flat_map(|k| k.parameters)
            .collect();
        for (name, prior) in &file.priors {
            let key = KeyPath::root().key("priors").key(name);
            if let Err(reason) =
                crate::study::diagnosis::check_prior_among(name, prior, &parameters)
            {
                self.fail(&key, reason);
            }
        }
    }

    /// The pods touch each other and the walls, so those pairs must exist.
    fn contacts(&mut self, particles: Particles<'_>, file: &StudyFile) {
        let pod = particles.material();
        let Some(sim) = file.plan.as_ref().and_then(|p| p.simulation.as_ref()) else {
            return;
        };
        let wall = &sim.wall_material;
        let wall_key = KeyPath::root()
            .key("plan")
            .key("simulation")
            .key("wall_material");
        if !file.materials.contains_key(wall) {
            self.fail(&wall_key, format!("no [materials.{wall}] in this study"));
        }
        for (other, key) in [
            (
                pod,
                KeyPath::root().key(particles.section()).key("material"),
            ),
            (wall, wall_key),
        ] {
            let forward = format!("{pod}-{other}");
            let backward = format!("{other}-{pod}");
            if !file.pairs.contains_key(&forward) && !file.pairs.contains_key(&backward) {
                self.fail(
                    &key,
                    format!("no contact pair [pairs.\"{forward}\"]: the simulation needs it"),
                );
            }
        }
    }
}

/// The study's particles, pods or spheres (pods when, wrongly, it has both).
fn particles(file: &StudyFile) -> Option<Particles<'_>> {
    file.pods
        .as_ref()
        .map(Particles::Pods)
        .or(file.spheres.as_ref().map(Particles::Spheres))
}

/// Material names: lower-case letters, digits and '_' (so '-' can join pair names).
fn is_material_name(name: &str) -> bool {
    !name.is_empty()
        && name
            .chars()
            .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
}

/// Limits of a pair property that has no registry entry.
fn pair_limits(property: &str) -> Limits {
    if property == "restitution" {
        Limits::Restitution
    } else {
        Limits::Friction
    }
}

/// `x` without the binary-rounding tail (0.7 + 0.2 + 0.2 prints 1.1, not 1.0999999999999999).
fn round_for_message(x: f64) -> f64 {
    const DIGITS: f64 = 1e9;
    (x * DIGITS).round() / DIGITS
}
