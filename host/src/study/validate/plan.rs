//! Checks of `[plan]`: mode, designs, the response surface, target and validation
//! references, simulation settings.

use super::{Validator, MIN_BOX_BEHNKEN_CENTRE_POINTS, MIN_GRID_CELL_RADII};
use crate::calibration::plan::central_composite::{MAX_FACTORS, MIN_FACTORS};
use crate::limits::Limits;
use crate::study::file_format::StudyFile;
use crate::study::key_path::KeyPath;
use crate::study::measurements::study_measurements;
use crate::study::plan::{
    Plan, ScreeningDesign, Simulation, DEFAULT_ORIGIN_CODED, GOAL_TARGET, PLACKETT_BURMAN_RUNS,
};

/// Fewest path points of a central composite plan: a best point and its two neighbours.
pub const MIN_CENTRAL_COMPOSITE_PATH_POINTS: u32 = 3;
/// Largest accepted validation limit, %.
const MAX_RELATIVE_ERROR_LIMIT_PCT: f64 = 100.0;

/// Refuses a list of factors for the path and the central composite design that is not
/// [`MIN_FACTORS`]–[`MAX_FACTORS`] distinct labels of `known`.
pub fn check_named(named: &[String], known: &[String]) -> Result<(), String> {
    if !(MIN_FACTORS..=MAX_FACTORS).contains(&named.len()) {
        return Err(format!(
            "the central composite stage takes {MIN_FACTORS} to {MAX_FACTORS} factors, got {}",
            named.len()
        ));
    }
    for (i, l) in named.iter().enumerate() {
        if !known.contains(l) {
            return Err(format!(
                "unknown factor '{l}' (the study varies {})",
                known.join(", ")
            ));
        }
        if named[..i].contains(l) {
            return Err(format!("factor '{l}' given twice"));
        }
    }
    Ok(())
}

impl Validator<'_, '_> {
    pub(super) fn plan(&mut self, file: &StudyFile, plan: &Plan) {
        let at = KeyPath::root().key("plan");
        self.counts(plan, &at);
        self.modes(plan, &at);
        self.screening(file, plan, &at);
        self.path(plan, &at);
        self.surface(file, plan, &at);
        if let Some(o) = &plan.optimisation {
            if o.goal != GOAL_TARGET {
                self.fail(
                    &at.key("optimisation").key("goal"),
                    format!(
                        "the optimisation goal is '{GOAL_TARGET}' (desirability toward the \
                         measured value), got '{}'",
                        o.goal
                    ),
                );
            }
        }
        self.references(file, plan, &at);
        if let Some(sim) = &plan.simulation {
            self.simulation(sim, &at.key("simulation"));
        }
    }

    /// Every count of the plan against its limit ([`crate::count_limits`]), so a study that
    /// `study check` accepts cannot exhaust memory in `calibrate`.
    fn counts(&mut self, plan: &Plan, at: &KeyPath) {
        use crate::count_limits::*;
        let sa = at.key("steepest_ascent");
        let mut counts = vec![
            (
                at.key("screening").key("centre_points"),
                u64::from(plan.screening.centre_points),
                MAX_CENTRE_POINTS,
            ),
            (
                sa.key("points"),
                u64::from(plan.steepest_ascent.points),
                MAX_DESIGN_POINTS,
            ),
        ];
        if let Some(max) = plan.steepest_ascent.max_points {
            counts.push((sa.key("max_points"), u64::from(max), MAX_DESIGN_POINTS));
        }
        if let Some(b) = &plan.box_behnken {
            let k = at.key("box_behnken").key("centre_points");
            counts.push((k, u64::from(b.centre_points), MAX_CENTRE_POINTS));
        }
        if let Some(c) = &plan.central_composite {
            let k = at.key("central_composite").key("centre_points");
            counts.push((k, u64::from(c.centre_points), MAX_CENTRE_POINTS));
        }
        for (name, mode) in &plan.modes {
            let k = at.key("modes").key(name);
            counts.push((k.key("pods"), u64::from(mode.pods), MAX_PODS));
            counts.push((
                k.key("spheres_per_pod"),
                u64::from(mode.spheres_per_pod),
                MAX_SPHERES_PER_POD,
            ));
        }
        for (key, value, max) in counts {
            // The lower bounds are each count's own rule, checked with its reason below.
            if let Err(reason) = check_count("the count", value, 0, max) {
                self.fail(&key, reason);
            }
        }
    }

    fn modes(&mut self, plan: &Plan, at: &KeyPath) {
        if let Some(mode) = &plan.mode {
            if !plan.modes.contains_key(mode) {
                let names: Vec<&str> = plan.modes.keys().map(String::as_str).collect();
                self.fail(
                    &at.key("mode"),
                    format!("no [plan.modes.{mode}] (modes: {})", names.join(", ")),
                );
            }
        }
        for (name, mode) in &plan.modes {
            let k = at.key("modes").key(name);
            if let Err(reason) = crate::io::file_name::check_name_component(name) {
                // The mode names the output folder (calibration-NAME-MODE).
                self.fail(&k, reason);
            }
            if mode.pods == 0 {
                self.fail(&k.key("pods"), "pods must be ≥ 1");
            }
            if mode.spheres_per_pod == 0 {
                self.fail(&k.key("spheres_per_pod"), "spheres_per_pod must be ≥ 1");
            }
        }
    }

    fn screening(&mut self, file: &StudyFile, plan: &Plan, at: &KeyPath) {
        let s = at.key("screening");
        let screening = &plan.screening;
        match (screening.design, screening.runs) {
            (ScreeningDesign::PlackettBurman, Some(runs))
                if PLACKETT_BURMAN_RUNS.contains(&runs) => {}
            (ScreeningDesign::PlackettBurman, runs) => self.fail(
                &s.key("runs"),
                format!(
                    "a Plackett–Burman design has 12 or 20 runs, got {}",
                    runs.map_or("none".to_owned(), |r| r.to_string())
                ),
            ),
            (_, Some(runs)) if runs != screening.design_runs() => self.fail(
                &s.key("runs"),
                format!(
                    "the design has {} runs, not {runs}",
                    screening.design_runs()
                ),
            ),
            _ => {}
        }
        let k = (file.parameters.len() + file.factors.len()) as u32;
        let columns = screening.columns();
        if k == 0 {
            self.fail(
                &KeyPath::root().key("parameters"),
                "no parameters vary: nothing to calibrate",
            );
        } else if k > columns {
            self.fail(
                &s.key("design"),
                format!("{k} varied parameters do not fit the {columns} columns of this design"),
            );
        } else {
            let dummies = columns - k;
            if let Some(d) = screening.dummies {
                if d != dummies {
                    self.fail(
                        &s.key("dummies"),
                        format!(
                            "{k} parameters in {columns} columns leave {dummies} dummies, not {d}"
                        ),
                    );
                }
            }
            if dummies + screening.centre_points == 0 {
                self.fail(
                    &s.key("design"),
                    "no degrees of freedom left for error: use a larger design, fewer \
                     parameters or centre points",
                );
            }
        }
        self.limit(
            &s.key("significance"),
            screening.significance,
            Limits::Probability,
        );
        if let Some(level) = screening.carry_level {
            self.limit(&s.key("carry_level"), level, Limits::Probability);
        }
    }

    fn path(&mut self, plan: &Plan, at: &KeyPath) {
        let sa = at.key("steepest_ascent");
        let path = &plan.steepest_ascent;
        let fewest = if plan.central_composite.is_some() {
            MIN_CENTRAL_COMPOSITE_PATH_POINTS
        } else {
            2
        };
        if path.points < fewest {
            self.fail(
                &sa.key("points"),
                format!(
                    "a path needs at least {fewest} points{}",
                    if fewest > 2 {
                        " (a best one and its neighbours)"
                    } else {
                        ""
                    }
                ),
            );
        }
        self.limit(&sa.key("step_coded"), path.step_coded, Limits::Positive);
        if let Some(max) = path.max_points {
            if max < path.points {
                self.fail(
                    &sa.key("max_points"),
                    format!(
                        "{max} is fewer than the path's {} planned points",
                        path.points
                    ),
                );
            }
        }
        let origin = path.origin_coded.unwrap_or(DEFAULT_ORIGIN_CODED);
        if !(-1.0..=1.0).contains(&origin) {
            self.fail(
                &sa.key("origin_coded"),
                format!("{origin} is outside the screened region [−1, 1]"),
            );
        }
    }

    fn surface(&mut self, file: &StudyFile, plan: &Plan, at: &KeyPath) {
        if let (Some(_), Some(_)) = (&plan.box_behnken, &plan.central_composite) {
            self.fail(
                &at.key("central_composite"),
                "a plan has one response surface: [plan.box_behnken] or \
                 [plan.central_composite], not both",
            );
        }
        if let Some(b) = &plan.box_behnken {
            if b.centre_points < MIN_BOX_BEHNKEN_CENTRE_POINTS {
                self.fail(
                    &at.key("box_behnken").key("centre_points"),
                    format!(
                        "at least {MIN_BOX_BEHNKEN_CENTRE_POINTS} centre points are needed for \
                         a pure-error estimate"
                    ),
                );
            }
        }
        let Some(c) = &plan.central_composite else {
            return;
        };
        let cc = at.key("central_composite");
        if let Some(named) = &c.factors {
            if let Err(reason) = check_named(named, &factor_labels(file)) {
                self.fail(&cc.key("factors"), reason);
            }
            if c.why.as_deref().is_none_or(|w| w.trim().is_empty()) {
                self.fail(
                    &cc.key("why"),
                    "a plan that names its factors says why (the report states it)",
                );
            }
        }
        if !(c.alpha.is_finite() && c.alpha >= 1.0) {
            self.fail(
                &cc.key("alpha"),
                format!("α must be at least 1, got {}", c.alpha),
            );
        }
        if c.centre_points < 1 {
            self.fail(
                &cc.key("centre_points"),
                "the design needs at least one centre point",
            );
        }
    }

    fn references(&mut self, file: &StudyFile, plan: &Plan, at: &KeyPath) {
        let measurements = study_measurements(file);
        match &plan.target {
            Some(t) => self.referenced(
                file,
                &measurements,
                &at.key("target"),
                &t.experiment,
                &t.quantity,
                &t.condition,
                "target",
            ),
            None if measurements.len() != 1 => self.fail(
                &at.key("target"),
                format!(
                    "missing key 'target' in [plan]: the study has {} measurements, so the \
                     plan must name the one it calibrates to",
                    measurements.len()
                ),
            ),
            None => {}
        }
        let v = &plan.validation;
        let vk = at.key("validation");
        if let (Some(experiment), Some(quantity)) = (&v.experiment, &v.quantity) {
            self.referenced(
                file,
                &measurements,
                &vk,
                experiment,
                quantity,
                &v.condition,
                "validation",
            );
        } else if v.experiment.is_some() != v.quantity.is_some() {
            self.fail(
                &vk,
                "give both the validation's experiment and quantity, or neither (then it is \
                 the target)",
            );
        }
        let limit = v.max_relative_error_pct;
        if !(limit.is_finite() && limit > 0.0 && limit <= MAX_RELATIVE_ERROR_LIMIT_PCT) {
            self.fail(
                &vk.key("max_relative_error_pct"),
                format!("must be in (0, {MAX_RELATIVE_ERROR_LIMIT_PCT}] %, got {limit}"),
            );
        }
        if v.replicates == Some(0) {
            self.fail(
                &vk.key("replicates"),
                "the optimum needs at least one validation simulation",
            );
        }
    }

    fn simulation(&mut self, p: &Simulation, sim: &KeyPath) {
        let dt = p.dt_rayleigh_fraction;
        if !(dt > 0.0 && dt <= 1.0) {
            self.fail(
                &sim.key("dt_rayleigh_fraction"),
                format!("{dt} is outside (0, 1]"),
            );
        }
        if p.grid_cell_radii.is_nan() || p.grid_cell_radii < MIN_GRID_CELL_RADII {
            self.fail(
                &sim.key("grid_cell_radii"),
                format!(
                    "{} is below {MIN_GRID_CELL_RADII}: a cell must hold a sphere diameter",
                    p.grid_cell_radii
                ),
            );
        }
        self.plausible(
            &sim.key("gravity_m_s2"),
            p.gravity_m_s2,
            Limits::Positive,
            crate::plausible::GRAVITY_M_S2,
        );
        let r = sim.key("repose");
        let rs = &p.repose;
        for (key, value) in [
            ("cylinder_diameter_mm", rs.cylinder_diameter_mm),
            ("cylinder_height_mm", rs.cylinder_height_mm),
            ("fill_time_s", rs.fill_time_s),
            ("fill_speed_m_s", rs.fill_speed_m_s),
            ("lift_speed_m_s", rs.lift_speed_m_s),
        ] {
            self.limit(&r.key(key), value, Limits::Positive);
        }
        self.limit(
            &r.key("settle_after_lift_s"),
            rs.settle_after_lift_s,
            Limits::NonNegative,
        );
        if !rs.lift_start_s.is_finite() {
            self.fail(
                &r.key("lift_start_s"),
                format!("{} is not a finite number", rs.lift_start_s),
            );
        } else if rs.lift_start_s < rs.fill_time_s {
            self.fail(
                &r.key("lift_start_s"),
                format!(
                    "the cylinder rises at {} s, before filling ends at {} s",
                    rs.lift_start_s, rs.fill_time_s
                ),
            );
        }
    }
}

/// The labels of the factors `file` varies: its `[parameters]` (the range's label, else
/// the registry's) and its `[factors]`.
pub fn factor_labels(file: &StudyFile) -> Vec<String> {
    let registry = |name: &str| {
        crate::rigs::pod_world::parameters::lookup(name)
            .map_or(name.to_owned(), |s| s.label.to_owned())
    };
    file.parameters
        .iter()
        .map(|(name, r)| r.label.clone().unwrap_or_else(|| registry(name)))
        .chain(file.factors.keys().cloned())
        .collect()
}
