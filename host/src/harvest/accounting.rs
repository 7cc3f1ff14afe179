//! Loss accounting: the fate of every pod, counted once.
//!
//! Loss rate = pods not collected / all pods × 100 % (issue 6; seed 001 §3.3 "pod drop
//! rate"). A pod is:
//! - [`Fate::Collected`]: it left the plant (its bonds to the clamped stem are broken, with or
//!   without a piece of stalk) and came down over the collector;
//! - [`Fate::Unpicked`]: it is still bonded to the clamped plant when the plant leaves the
//!   machine (carried off with the vines: a loss);
//! - [`Fate::Dropped`]: it left the plant and came down outside the collector (thrown forward
//!   or backward out of the picking chamber, or fallen before the drum: a loss).
//!
//! Pods are rigid clumps, so none can be "broken"; the seed counts none separately either.

use serde::Serialize;

/// What became of one pod.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Fate {
    /// Detached and came down over the collector.
    Collected,
    /// Still on the plant when it left the machine (a loss).
    Unpicked,
    /// Detached and came down outside the collector (a loss).
    Dropped,
}

/// Pod counts of one plant pass or one replicate.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct Tally {
    /// All pods.
    pub pods: u32,
    /// Collected pods.
    pub collected: u32,
    /// Pods still on the plant.
    pub unpicked: u32,
    /// Pods that came down outside the collector.
    pub dropped: u32,
}

impl Tally {
    /// Count one pod.
    pub fn add(&mut self, fate: Fate) {
        self.pods += 1;
        match fate {
            Fate::Collected => self.collected += 1,
            Fate::Unpicked => self.unpicked += 1,
            Fate::Dropped => self.dropped += 1,
        }
    }

    /// Sum of two tallies.
    pub fn merge(self, o: Tally) -> Tally {
        Tally {
            pods: self.pods + o.pods,
            collected: self.collected + o.collected,
            unpicked: self.unpicked + o.unpicked,
            dropped: self.dropped + o.dropped,
        }
    }

    /// Loss rate, %: (unpicked + dropped) / pods × 100 (0 pods: `None`).
    pub fn loss_percent(&self) -> Option<f64> {
        (self.pods > 0)
            .then(|| 100.0 * f64::from(self.unpicked + self.dropped) / f64::from(self.pods))
    }
}

/// Where a free pod at height `z_m` (above `floor_m`), moving with `vx_m_s`, `vz_m_s`, crosses
/// the collector plane z = `floor_m` under gravity `g_m_s2` (> 0) with no further contact:
/// x_land = x + vx·t, t the positive root of z + vz·t − g t²/2 = floor.
pub fn ballistic_landing_x(
    x_m: f64,
    z_m: f64,
    vx_m_s: f64,
    vz_m_s: f64,
    floor_m: f64,
    g_m_s2: f64,
) -> f64 {
    let h = (z_m - floor_m).max(0.0);
    let t = (vz_m_s + (vz_m_s * vz_m_s + 2.0 * g_m_s2 * h).sqrt()) / g_m_s2;
    x_m + vx_m_s * t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tally_counts_each_fate_once() {
        let mut t = Tally::default();
        for f in [
            Fate::Collected,
            Fate::Unpicked,
            Fate::Dropped,
            Fate::Collected,
        ] {
            t.add(f);
        }
        assert_eq!(t.pods, t.collected + t.unpicked + t.dropped);
        assert_eq!(t.loss_percent(), Some(50.0));
        assert_eq!(Tally::default().loss_percent(), None);
    }

    #[test]
    fn ballistic_landing_matches_free_fall() {
        // Dropped from rest 0.2 m up: t = √(2h/g); moving at 1 m/s it lands 1·t further on.
        let g: f64 = 9.81;
        let t = (2.0 * 0.2 / g).sqrt();
        let x = ballistic_landing_x(0.5, 0.1, 1.0, 0.0, -0.1, g);
        assert!((x - (0.5 + t)).abs() < 1e-12);
    }
}
