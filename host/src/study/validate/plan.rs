//! Checks of `[plan]`: mode, designs, target and validation references, simulation settings.

use super::{Validator, MIN_BOX_BEHNKEN_CENTRE_POINTS, MIN_GRID_CELL_RADII};
use crate::limits::Limits;
use crate::study::file_format::StudyFile;
use crate::study::key_path::KeyPath;

impl Validator<'_, '_> {
    pub(super) fn plan(&mut self, file: &StudyFile) {
        let at = KeyPath::root().key("plan");
        let plan = &file.plan;
        if !plan.modes.contains_key(&plan.mode) {
            let names: Vec<&str> = plan.modes.keys().map(String::as_str).collect();
            self.fail(
                &at.key("mode"),
                format!(
                    "no [plan.modes.{}] (modes: {})",
                    plan.mode,
                    names.join(", ")
                ),
            );
        }
        for (name, mode) in &plan.modes {
            let k = at.key("modes").key(name);
            if mode.pods == 0 {
                self.fail(&k.key("pods"), "pods must be ≥ 1");
            }
            if mode.spheres_per_pod == 0 {
                self.fail(&k.key("spheres_per_pod"), "spheres_per_pod must be ≥ 1");
            }
        }

        let s = at.key("screening");
        let k = file.parameters.len() as u32;
        let columns = plan.screening.design.columns();
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
            if let Some(d) = plan.screening.dummies {
                if d != dummies {
                    self.fail(
                        &s.key("dummies"),
                        format!(
                            "{k} parameters in {columns} columns leave {dummies} dummies, not {d}"
                        ),
                    );
                }
            }
            if dummies + plan.screening.centre_points == 0 {
                self.fail(&s.key("design"), "no degrees of freedom left for error: use a larger design, fewer parameters or centre points");
            }
        }
        self.limit(
            &s.key("significance"),
            plan.screening.significance,
            Limits::Probability,
        );

        let sa = at.key("steepest_ascent");
        if plan.steepest_ascent.points < 2 {
            self.fail(&sa.key("points"), "a path needs at least 2 points");
        }
        self.limit(
            &sa.key("step_coded"),
            plan.steepest_ascent.step_coded,
            Limits::Positive,
        );
        if let Some(max) = plan.steepest_ascent.max_points {
            if max < plan.steepest_ascent.points {
                self.fail(
                    &sa.key("max_points"),
                    format!(
                        "{max} is fewer than the path's {} planned points",
                        plan.steepest_ascent.points
                    ),
                );
            }
        }
        let origin = plan.steepest_ascent.origin_coded;
        if !(-1.0..=1.0).contains(&origin) {
            self.fail(
                &sa.key("origin_coded"),
                format!("{origin} is outside the screened region [−1, 1]"),
            );
        }
        if plan.box_behnken.centre_points < MIN_BOX_BEHNKEN_CENTRE_POINTS {
            self.fail(
                &at.key("box_behnken").key("centre_points"),
                format!("at least {MIN_BOX_BEHNKEN_CENTRE_POINTS} centre points are needed for a pure-error estimate"),
            );
        }

        let t = &plan.target;
        self.referenced(
            file,
            &at.key("target"),
            t.experiment,
            &t.quantity,
            &t.condition,
            "target",
        );
        let v = &plan.validation;
        self.referenced(
            file,
            &at.key("validation"),
            v.experiment,
            &v.quantity,
            &v.condition,
            "validation",
        );
        self.limit(
            &at.key("validation").key("max_relative_error_pct"),
            v.max_relative_error_pct,
            Limits::Positive,
        );
        if v.replicates == Some(0) {
            self.fail(
                &at.key("validation").key("replicates"),
                "the optimum needs at least one validation simulation",
            );
        }

        let sim = at.key("simulation");
        let p = &plan.simulation;
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
        self.limit(&sim.key("gravity_m_s2"), p.gravity_m_s2, Limits::Positive);
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
