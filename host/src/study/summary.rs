//! A human-readable summary of a validated study: what is measured, what varies, and the
//! plan, in the units a user reads (MPa for moduli, mm for sizes): a pod study's, a
//! pull-off study's, a diagnosis study's, and a study of other rigs' measurements.

use std::fmt;

use super::plan::{ModelOrder, Plan};
use super::Study;
use crate::rigs::pod_world::{Particles, Pods};

/// Significant digits of derived numbers in the summary.
const SUMMARY_DIGITS: i32 = 4;

/// `x` rounded to [`SUMMARY_DIGITS`] significant digits, printed without trailing zeros.
fn significant(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return x.to_string();
    }
    let scale = 10f64.powi(SUMMARY_DIGITS - 1 - x.abs().log10().floor() as i32);
    ((x * scale).round() / scale).to_string()
}

/// Pascals per megapascal, for display.
const PA_PER_MPA: f64 = 1e6;

impl Study {
    /// The summary as text (same as `Display`).
    pub fn summary(&self) -> String {
        self.to_string()
    }
}

impl fmt::Display for Study {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = self.file();
        if let (Some(world), Some(plan)) = (self.pod_world(), &s.plan) {
            self.pod_summary(f, world.particles, plan)?;
        }
        if let Some(plan) = &s.plan {
            if s.rig.is_some() {
                self.pull_off_summary(f, plan)?;
            }
        }
        if s.diagnosis.is_some() {
            self.diagnosis_summary(f)?;
        }
        if s.pods.is_none() && s.spheres.is_none() && s.rig.is_none() && s.diagnosis.is_none() {
            self.rig_summary(f)?;
        }
        Ok(())
    }
}

impl Study {
    /// The `[study]` header: name, file, description and source.
    fn header(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(h) = &self.file().study {
            writeln!(f, "Study: {} ({})", h.name, self.path().display())?;
            writeln!(f, "  {}", h.description)?;
            writeln!(f, "  source: {}", h.citation)?;
        }
        Ok(())
    }

    /// The `[pods]` line and the scanned shapes.
    fn pods_line(&self, f: &mut fmt::Formatter<'_>, p: &Pods) -> fmt::Result {
        writeln!(
            f,
            "Pods ({}): {} × {} × {} mm; mix normal {}, cocoon {}, single-grain {}",
            p.material,
            p.length_mm,
            p.width_mm,
            p.thickness_mm,
            p.shape_mix.normal,
            p.shape_mix.cocoon,
            p.shape_mix.single_grain
        )?;
        for (shape, path) in self.stl_paths() {
            writeln!(f, "  {shape} scan: {}", path.display())?;
        }
        Ok(())
    }

    fn pod_summary(
        &self,
        f: &mut fmt::Formatter<'_>,
        particles: Particles<'_>,
        plan: &Plan,
    ) -> fmt::Result {
        let s = self.file();
        self.header(f)?;
        writeln!(f, "Materials:")?;
        for (name, m) in &s.materials {
            writeln!(
                f,
                "  {name}: ρ {} kg/m³, ν {}, G {} MPa (E = 2G(1 + ν) = {} MPa)",
                m.density_kg_m3,
                m.poisson,
                m.shear_modulus_pa / PA_PER_MPA,
                significant(m.youngs_modulus_pa() / PA_PER_MPA)
            )?;
        }
        match particles {
            Particles::Pods(p) => self.pods_line(f, p)?,
            Particles::Spheres(sp) => {
                let sizes: Vec<String> = sp
                    .classes()
                    .iter()
                    .map(|c| format!("R {} mm × {}", c.radius_mm, c.fraction))
                    .collect();
                writeln!(f, "Spheres ({}): {}", sp.material, sizes.join(", "))?;
            }
        }
        writeln!(f, "Pairs (e, μs, μr; '-' = varied, see below):")?;
        for (name, pair) in &s.pairs {
            let show = |v: Option<f64>| v.map_or("-".to_owned(), |x| x.to_string());
            let c = pair.conventions();
            let conventions = if c.is_edem() {
                String::new()
            } else {
                format!(" (rolling {}, friction {})", c.rolling, c.friction)
            };
            writeln!(
                f,
                "  {name}: {}, {}, {}{conventions}",
                show(pair.restitution),
                show(pair.static_friction),
                show(pair.rolling_friction)
            )?;
        }
        self.measurements_list(f)?;
        let pods = self.varied();
        let varied: Vec<_> = pods
            .iter()
            .map(|v| {
                (
                    v.label.as_str(),
                    v.spec.name,
                    v.range.low,
                    v.range.high,
                    v.spec.unit,
                )
            })
            .collect();
        self.varied_list(f, &varied)?;
        self.plan_lines(f, plan)
    }

    /// A study of rigs without a world section: what it measures, what varies, the plan.
    fn rig_summary(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.header(f)?;
        self.measurements_list(f)?;
        let factors = self.factors();
        let varied: Vec<_> = factors
            .iter()
            .map(|v| {
                // A label that only repeats the name says nothing.
                let label = if v.label == v.name { "" } else { &v.label };
                (label, v.name.as_str(), v.low, v.high, v.unit.as_str())
            })
            .collect();
        self.varied_list(f, &varied)?;
        match &self.file().plan {
            Some(plan) => self.plan_lines(f, plan),
            None => Ok(()),
        }
    }

    /// Every `[[measurements]]` entry: mean, replicates, SD and condition.
    fn measurements_list(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = self.file();
        writeln!(f, "Measurements:")?;
        for m in &s.measurements {
            let cond: Vec<String> = m
                .condition
                .iter()
                .map(|(k, v)| format!("{k} = {v}"))
                .collect();
            let kind = if m.has_replicates() {
                "replicates"
            } else {
                "printed mean"
            };
            writeln!(
                f,
                "  {} {}: {} {} (n = {}, {kind}{}){}",
                m.experiment,
                m.quantity,
                m.mean().map_or("?".to_owned(), |x| format!("{x}")),
                m.unit,
                m.replicates().map_or("?".to_owned(), |n| n.to_string()),
                m.sd.map_or(String::new(), |sd| format!(", SD {sd}")),
                if cond.is_empty() {
                    String::new()
                } else {
                    format!(" at {}", cond.join(", "))
                }
            )?;
        }
        Ok(())
    }

    /// The varied parameters: label, name, range and unit of each.
    fn varied_list(
        &self,
        f: &mut fmt::Formatter<'_>,
        varied: &[(&str, &str, f64, f64, &str)],
    ) -> fmt::Result {
        writeln!(f, "Varied parameters:")?;
        for (label, name, low, high, unit) in varied {
            writeln!(f, "  {label:<4} {name:<28} {low} … {high} {unit}")?;
        }
        Ok(())
    }

    /// The plan: screening, path, box, target, validation, run modes and simulation.
    fn plan_lines(&self, f: &mut fmt::Formatter<'_>, plan: &Plan) -> fmt::Result {
        let s = self.file();
        let k = s.parameters.len() as u32;
        writeln!(f, "Plan:")?;
        writeln!(
            f,
            "  screening {}: {k} factors + {} dummies, {} centre points, α = {}",
            match plan.screening.design_runs() {
                20 => "Plackett–Burman, 20 runs",
                _ => "Plackett–Burman, 12 runs",
            },
            plan.screening.columns().saturating_sub(k),
            plan.screening.centre_points,
            plan.screening.significance
        )?;
        writeln!(
            f,
            "  steepest ascent: {} points, step {} coded from {}",
            plan.steepest_ascent.points,
            plan.steepest_ascent.step_coded,
            plan.steepest_ascent
                .origin_coded
                .unwrap_or(super::plan::DEFAULT_ORIGIN_CODED)
        )?;
        let model = match plan.model.as_ref().map(|m| m.order) {
            Some(ModelOrder::Linear) => "linear",
            Some(ModelOrder::Interaction) => "two-factor interaction",
            Some(ModelOrder::Quadratic) | None => "quadratic",
        };
        match (&plan.box_behnken, &plan.central_composite) {
            (Some(b), _) => writeln!(
                f,
                "  Box–Behnken: {} centre points; {model} model",
                b.centre_points
            )?,
            (None, Some(c)) => writeln!(
                f,
                "  central composite: α = {}, {} centre points; {model} model",
                c.alpha, c.centre_points
            )?,
            (None, None) => {}
        }
        if let Some(t) = self.target() {
            writeln!(
                f,
                "  target: {} {} = {} {}",
                t.experiment,
                t.quantity,
                t.mean().unwrap_or(f64::NAN),
                t.unit
            )?;
        }
        if let Some(v) = self.validation() {
            writeln!(
                f,
                "  validation: {} {}, relative error ≤ {} %",
                v.experiment, v.quantity, plan.validation.max_relative_error_pct
            )?;
        }
        for (name, mode) in &plan.modes {
            let mark = if Some(name) == plan.mode.as_ref() {
                " (default)"
            } else {
                ""
            };
            writeln!(
                f,
                "  mode {name}{mark}: {} pods, {} spheres per pod",
                mode.pods, mode.spheres_per_pod
            )?;
        }
        let Some(sim) = &plan.simulation else {
            return Ok(());
        };
        let r = &sim.repose;
        writeln!(
            f,
            "  simulation: dt = {} T_R, cells {}R, g {} m/s², seed {}; cylinder Ø{} × {} mm, \
             fill {} s at {} m/s, lift at {} s at {} m/s, settle {} s",
            sim.dt_rayleigh_fraction,
            sim.grid_cell_radii,
            sim.gravity_m_s2,
            sim.random_seed,
            r.cylinder_diameter_mm,
            r.cylinder_height_mm,
            r.fill_time_s,
            r.fill_speed_m_s,
            r.lift_start_s,
            r.lift_speed_m_s,
            r.settle_after_lift_s
        )
    }
}

impl Study {
    fn pull_off_summary(&self, f: &mut fmt::Formatter<'_>, p: &Plan) -> fmt::Result {
        let s = self.file();
        let (Some(rig), Some(m)) = (&s.rig, &s.measurement) else {
            return Ok(());
        };
        writeln!(
            f,
            "plant pull-off study {} ({})",
            self.name(),
            self.path().display()
        )?;
        writeln!(
            f,
            "measured {} = {} N ({})",
            m.quantity, m.value_n, m.source
        )?;
        writeln!(
            f,
            "rig: {} m/s at {}°, {} stalk spheres, bond sets {} / {} of {}",
            rig.pull_speed_m_s,
            rig.pull_angle_deg,
            rig.stalk_spheres,
            rig.junction_bond_set,
            rig.stalk_bond_set,
            rig.topology
        )?;
        for factor in self.factors() {
            if let Some(p) = crate::rigs::pull_off::by_name(&factor.name) {
                writeln!(
                    f,
                    "  {} {} ({}): {} … {}",
                    factor.label, p.description, factor.unit, factor.low, factor.high
                )?;
            }
        }
        let Some(c) = &p.central_composite else {
            return Ok(());
        };
        writeln!(
            f,
            "plan: Plackett–Burman {} runs + {} centre points; steepest ascent step {} coded, \
             {}–{} points; central composite on {} (α = {}, {} centre points); goal {}; \
             validation within {} %",
            p.screening.design_runs(),
            p.screening.centre_points,
            p.steepest_ascent.step_coded,
            p.steepest_ascent.points,
            p.steepest_ascent
                .max_points
                .unwrap_or(p.steepest_ascent.points),
            c.factors
                .as_ref()
                .map_or("the screening's choice".to_owned(), |f| f.join(", ")),
            c.alpha,
            c.centre_points,
            p.optimisation
                .as_ref()
                .map_or(super::plan::GOAL_TARGET, |o| o.goal.as_str()),
            p.validation.max_relative_error_pct
        )
    }

    fn diagnosis_summary(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let Some(d) = &self.file().diagnosis else {
            return Ok(());
        };
        writeln!(f, "diagnosis study {} ({})", d.name, self.path().display())?;
        let values: Vec<String> = d
            .calibration
            .values()
            .iter()
            .map(|(k, v)| format!("{k} = {v}"))
            .collect();
        writeln!(f, "calibration: {}", values.join(", "))?;
        for e in &d.experiment {
            let replicates: usize = e.point.iter().map(|p| p.values.len()).sum();
            writeln!(
                f,
                "  {}: {} conditions, {replicates} replicates",
                e.kind,
                e.point.len()
            )?;
        }
        Ok(())
    }
}
