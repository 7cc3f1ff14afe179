//! A human-readable summary of a validated study: what is measured, what varies, and the
//! plan, in the units a user reads (MPa for moduli, mm for sizes).

use std::fmt;

use super::plan::{ModelOrder, ScreeningDesign};
use super::Study;

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
        writeln!(f, "Study: {} ({})", s.study.name, self.path().display())?;
        writeln!(f, "  {}", s.study.description)?;
        writeln!(f, "  source: {}", s.study.citation)?;
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
        let p = &s.pods;
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
        writeln!(f, "Pairs (e, μs, μr; '-' = varied, see below):")?;
        for (name, pair) in &s.pairs {
            let show = |v: Option<f64>| v.map_or("-".to_owned(), |x| x.to_string());
            writeln!(
                f,
                "  {name}: {}, {}, {}",
                show(pair.restitution),
                show(pair.static_friction),
                show(pair.rolling_friction)
            )?;
        }
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
        writeln!(f, "Varied parameters:")?;
        for v in self.varied() {
            writeln!(
                f,
                "  {:<4} {:<28} {} … {} {}",
                v.label, v.spec.name, v.range.low, v.range.high, v.spec.unit
            )?;
        }
        let plan = &s.plan;
        let k = s.parameters.len() as u32;
        writeln!(f, "Plan:")?;
        writeln!(
            f,
            "  screening {}: {k} factors + {} dummies, {} centre points, α = {}",
            match plan.screening.design {
                ScreeningDesign::Pb12 => "Plackett–Burman, 12 runs",
                ScreeningDesign::Pb20 => "Plackett–Burman, 20 runs",
            },
            plan.screening.design.columns().saturating_sub(k),
            plan.screening.centre_points,
            plan.screening.significance
        )?;
        writeln!(
            f,
            "  steepest ascent: {} points, step {} coded from {}",
            plan.steepest_ascent.points,
            plan.steepest_ascent.step_coded,
            plan.steepest_ascent.origin_coded
        )?;
        writeln!(
            f,
            "  Box–Behnken: {} centre points; {} model",
            plan.box_behnken.centre_points,
            match plan.model.order {
                ModelOrder::Linear => "linear",
                ModelOrder::Interaction => "two-factor interaction",
                ModelOrder::Quadratic => "quadratic",
            }
        )?;
        let t = self.target();
        writeln!(
            f,
            "  target: {} {} = {} {}",
            t.experiment,
            t.quantity,
            t.mean().unwrap_or(f64::NAN),
            t.unit
        )?;
        writeln!(
            f,
            "  validation: {} {}, relative error ≤ {} %",
            plan.validation.experiment,
            plan.validation.quantity,
            plan.validation.max_relative_error_pct
        )?;
        for (name, mode) in &plan.modes {
            let mark = if *name == plan.mode { " (default)" } else { "" };
            writeln!(
                f,
                "  mode {name}{mark}: {} pods, {} spheres per pod",
                mode.pods, mode.spheres_per_pod
            )?;
        }
        let sim = &plan.simulation;
        let r = &sim.repose;
        write!(
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
