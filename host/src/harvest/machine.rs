//! The picking machine of the virtual harvest and the field numbers it is compared with.
//!
//! Seed 001 (§3.3) names neither the harvester nor its settings: it gives only the field and
//! simulated loss rates of Table 12 (four 1-m ridge sections, four simulations). The machine
//! below is therefore our own stand-in, a semi-feed picking drum: plants clamped by the top of
//! the main stem travel at [`Machine::forward_speed_m_s`] along +x over a drum whose axis is
//! the x axis; the drum carries rings of steel teeth (spheres) at
//! [`Machine::tip_radius_m`] and turns at [`Machine::drum_speed_rpm`]. Its defaults are
//! typical of semi-feed peanut pickers (400–600 r/min, tooth tips 5–15 m/s; DESIGN §4 quotes
//! about 20 m/s), not values from the seed. A steel housing (two side walls and a cover) keeps
//! thrown pods over the collector, which spans the drum's length plus
//! [`Machine::collector_margin_m`] at each end (pods keep the forward speed of the plant).

use serde::{Deserialize, Serialize};

use super::HarvestError;

/// Field loss rates of seed 001 Table 12 ("Field Trials (y2)"), %.
pub const SEED001_FIELD_LOSS_PERCENT: [f64; 4] = [4.01, 3.83, 4.04, 3.42];
/// Simulated loss rates of seed 001 Table 12 ("Simulation Testing (y1)"), % (for reference).
pub const SEED001_SIMULATED_LOSS_PERCENT: [f64; 4] = [3.75, 4.02, 4.27, 3.18];
/// Largest number of teeth on the drum (one core clump: `arachis_core::world::MAX_CLUMP_SPHERES`).
pub const MAX_TEETH: usize = arachis_core::world::MAX_CLUMP_SPHERES;

/// Operating parameters and geometry of the picking machine (SI units).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Machine {
    /// Forward (clamp-conveyor) speed of the plants along +x, m/s.
    pub forward_speed_m_s: f64,
    /// Drum speed, revolutions per minute (ω = 2π·n/60 rad/s about +x).
    pub drum_speed_rpm: f64,
    /// Radius of the tooth centres from the drum axis, m.
    pub tip_radius_m: f64,
    /// Radius of one tooth (steel sphere), m.
    pub tooth_radius_m: f64,
    /// Length of the drum along x, m (rings from x = 0 to this length).
    pub drum_length_m: f64,
    /// Axial pitch of the tooth rings, m.
    pub ring_pitch_m: f64,
    /// Teeth per ring, evenly spaced; neighbouring rings are staggered by half a pitch angle.
    pub teeth_per_ring: u32,
    /// Height of the tooth circle's top (axis + tip radius) above the stem root, m: how deep
    /// the teeth reach into the hanging plant.
    pub reach_above_root_m: f64,
    /// Half the distance between the housing's side walls, m.
    pub housing_half_width_m: f64,
    /// How far the collector extends beyond each end of the drum along x, m.
    pub collector_margin_m: f64,
}

impl Default for Machine {
    fn default() -> Self {
        Machine {
            forward_speed_m_s: 1.0,
            drum_speed_rpm: 500.0,
            tip_radius_m: 0.15,
            tooth_radius_m: 0.006,
            drum_length_m: 0.12,
            ring_pitch_m: 0.02,
            teeth_per_ring: 6,
            reach_above_root_m: 0.03,
            housing_half_width_m: 0.2,
            collector_margin_m: 0.3,
        }
    }
}

impl Machine {
    /// Drum angular speed, rad/s: ω = 2π·n/60.
    pub fn drum_omega_rad_s(&self) -> f64 {
        self.drum_speed_rpm * std::f64::consts::TAU / 60.0
    }

    /// Tooth-tip speed ω·R, m/s.
    pub fn tip_speed_m_s(&self) -> f64 {
        self.drum_omega_rad_s() * self.tip_radius_m
    }

    /// Number of tooth rings: ⌊L/pitch⌋ + 1.
    pub fn rings(&self) -> usize {
        (self.drum_length_m / self.ring_pitch_m).floor() as usize + 1
    }

    /// Total number of teeth.
    pub fn teeth(&self) -> usize {
        self.rings() * self.teeth_per_ring as usize
    }

    /// Check every number; the error names the parameter.
    pub fn check(&self) -> Result<(), HarvestError> {
        let positive = |name: &'static str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(HarvestError::BadParameter {
                    name,
                    why: format!("must be a positive number, got {v}"),
                })
            }
        };
        positive("forward_speed_m_s", self.forward_speed_m_s)?;
        positive("drum_speed_rpm", self.drum_speed_rpm)?;
        positive("tip_radius_m", self.tip_radius_m)?;
        positive("tooth_radius_m", self.tooth_radius_m)?;
        positive("drum_length_m", self.drum_length_m)?;
        positive("ring_pitch_m", self.ring_pitch_m)?;
        positive("housing_half_width_m", self.housing_half_width_m)?;
        if !(self.collector_margin_m.is_finite() && self.collector_margin_m >= 0.0) {
            return Err(HarvestError::BadParameter {
                name: "collector_margin_m",
                why: format!("must be ≥ 0, got {}", self.collector_margin_m),
            });
        }
        if !self.reach_above_root_m.is_finite() {
            return Err(HarvestError::BadParameter {
                name: "reach_above_root_m",
                why: "must be finite".to_owned(),
            });
        }
        if self.tooth_radius_m >= self.tip_radius_m {
            return Err(HarvestError::BadParameter {
                name: "tooth_radius_m",
                why: "must be smaller than tip_radius_m".to_owned(),
            });
        }
        if self.teeth_per_ring == 0 || self.teeth() > MAX_TEETH {
            return Err(HarvestError::BadParameter {
                name: "teeth_per_ring",
                why: format!(
                    "rings × teeth per ring must be between 1 and {MAX_TEETH}, got {} × {}",
                    self.rings(),
                    self.teeth_per_ring
                ),
            });
        }
        if self.housing_half_width_m <= self.tip_radius_m + self.tooth_radius_m {
            return Err(HarvestError::BadParameter {
                name: "housing_half_width_m",
                why: "the housing must clear the drum (> tip radius + tooth radius)".to_owned(),
            });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shipped_machine_file_is_the_default() {
        let text = include_str!("../../../testdata/peanut-plant/harvest-machine.toml");
        let m: Machine = toml::from_str(text).unwrap();
        assert_eq!(m, Machine::default());
        m.check().unwrap();
    }
}
