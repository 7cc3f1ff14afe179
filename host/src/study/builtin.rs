//! Seed 001's pull-off study built into the program, and the changes the `plant-calibrate`
//! alias makes to it from its flags (the target force, the pull, the factors the plan
//! names).

use std::path::Path;

use super::validate::plan::{check_named, factor_labels};
use super::Study;

/// Seed 001's study as shipped, built into the program.
const SHIPPED_STUDY: &str = include_str!("../../../testdata/peanut-plant/study.toml");
/// Where the shipped study lies in the repository (it names the built-in study in messages).
const SHIPPED_STUDY_PATH: &str = "testdata/peanut-plant/study.toml";

impl Study {
    /// Seed 001's pull-off study as shipped (`testdata/peanut-plant/study.toml` and its
    /// topology), built into the program.
    pub fn shipped_pull_off() -> Self {
        let read = |p: &Path| {
            if p.file_name() == Some(std::ffi::OsStr::new(crate::plant::SHIPPED_TOPOLOGY_FILE)) {
                Ok(crate::plant::SHIPPED_TOPOLOGY.to_owned())
            } else {
                crate::io::text::read_text(p)
            }
        };
        Self::from_toml_reading(SHIPPED_STUDY, Path::new(SHIPPED_STUDY_PATH), &read)
            .expect("the shipped study is valid")
    }

    /// Sets the measured detachment force of a pull-off study, N (checked by the caller).
    pub fn set_target_n(&mut self, force_n: f64) {
        if let Some(m) = &mut self.file.measurement {
            m.value_n = force_n;
        }
        self.measurements = super::measurements::study_measurements(&self.file);
    }

    /// Sets the pull's speed (m/s) and direction from the stalk axis (degrees) of a
    /// pull-off study, checked by the caller.
    pub fn set_pull(&mut self, speed_m_s: f64, angle_deg: f64) {
        if let Some(rig) = &mut self.file.rig {
            rig.pull_speed_m_s = speed_m_s;
            rig.pull_angle_deg = angle_deg;
        }
    }

    /// Names the factors of the path and the central composite design (2–3 distinct labels
    /// of the study's factors), and why; `None` leaves the choice to the screening.
    pub fn set_named_factors(
        &mut self,
        labels: Option<Vec<String>>,
        why: &str,
    ) -> Result<(), String> {
        if let Some(l) = &labels {
            check_named(l, &factor_labels(&self.file))?;
        }
        let c = self
            .file
            .plan
            .as_mut()
            .and_then(|p| p.central_composite.as_mut())
            .ok_or("the study's plan has no [plan.central_composite]")?;
        c.why = labels.as_ref().map(|_| why.to_owned());
        c.factors = labels;
        Ok(())
    }
}
