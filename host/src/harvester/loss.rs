//! Where each pod ends up, and the loss rate.
//!
//! **Definition.** A pod is *lost* when it ends neither in the collector nor on its plant:
//! loss rate = lost pods / all pods × 100 %. Pods still bonded to their plant when the run
//! ends leave with the vines; they are counted beside the loss as *unpicked*, not in it
//! (they are the picking residue, which a separate pass or a picker can still recover).
//!
//! A pod is checked as the run goes:
//! - *collected* when it is detached from its plant and enters the collector's opening
//!   (it is then held still in the collector);
//! - *lifted* once its centre has risen above the ground;
//! - *down* when, detached and lifted, it falls [`DOWN_BELOW_SURFACE_M`] below the machine's
//!   carrying surface, or below the ground anywhere: it is lost where it went down (off the
//!   shovel, through or off the chain, behind the collector, or beside the machine), and is
//!   held still where it lies.
//!
//! At the end, a pod that was never lifted is lost *in the soil*; a detached, lifted pod that
//! is not yet down is lost *on the machine* (the run ended before it was delivered).
//!
//! ```
//! use arachis::harvester::loss::{PodEnd, LossTally, Where};
//! let mut t = LossTally::default();
//! t.add(PodEnd::Collected);
//! t.add(PodEnd::Lost(Where::InSoil));
//! assert_eq!(t.loss_percent(), Some(50.0));
//! ```

use serde::{Deserialize, Serialize};

use super::parts::Layout;

/// How far below the carrying surface a detached pod's centre must fall to count as down, m
/// (a pod lying on the shovel or a rod has its centre above the surface; one that falls
/// between rods sinks below it).
pub const DOWN_BELOW_SURFACE_M: f64 = 0.03;

/// Where a lost pod was lost.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Where {
    /// Never lifted out of the soil.
    InSoil,
    /// Fell off the shovel.
    Shovel,
    /// Fell through or off the chain.
    Chain,
    /// Thrown past the collector (behind the chain's top end, outside the opening).
    Behind,
    /// Fell beside the machine (outside the working width).
    Beside,
    /// Still on the machine when the run ended.
    OnMachine,
}

/// What became of one pod.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PodEnd {
    /// In the collector.
    Collected,
    /// Still on its plant at the end.
    Unpicked,
    /// Lost, and where.
    Lost(Where),
}

/// Pod counts by end.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct LossTally {
    /// All pods.
    pub pods: u32,
    /// Collected.
    pub collected: u32,
    /// Still on their plants.
    pub unpicked: u32,
    /// Lost in the soil.
    pub in_soil: u32,
    /// Lost off the shovel.
    pub shovel: u32,
    /// Lost through or off the chain.
    pub chain: u32,
    /// Lost behind the collector.
    pub behind: u32,
    /// Lost beside the machine.
    pub beside: u32,
    /// Still on the machine at the end.
    pub on_machine: u32,
}

impl LossTally {
    /// Count one pod.
    pub fn add(&mut self, end: PodEnd) {
        self.pods += 1;
        let slot = match end {
            PodEnd::Collected => &mut self.collected,
            PodEnd::Unpicked => &mut self.unpicked,
            PodEnd::Lost(Where::InSoil) => &mut self.in_soil,
            PodEnd::Lost(Where::Shovel) => &mut self.shovel,
            PodEnd::Lost(Where::Chain) => &mut self.chain,
            PodEnd::Lost(Where::Behind) => &mut self.behind,
            PodEnd::Lost(Where::Beside) => &mut self.beside,
            PodEnd::Lost(Where::OnMachine) => &mut self.on_machine,
        };
        *slot += 1;
    }

    /// Lost pods.
    pub fn lost(&self) -> u32 {
        self.in_soil + self.shovel + self.chain + self.behind + self.beside + self.on_machine
    }

    /// Loss rate, %: lost / pods × 100 (`None` without pods).
    pub fn loss_percent(&self) -> Option<f64> {
        (self.pods > 0).then(|| 100.0 * f64::from(self.lost()) / f64::from(self.pods))
    }

    /// Unpicked rate, %: unpicked / pods × 100 (`None` without pods).
    pub fn unpicked_percent(&self) -> Option<f64> {
        (self.pods > 0).then(|| 100.0 * f64::from(self.unpicked) / f64::from(self.pods))
    }
}

/// The check of a detached, lifted pod at machine-frame position `p_m`: collected, down
/// (lost, and where), or `None` while it is still carried or in the air.
pub fn check_detached(layout: &Layout, p_m: [f64; 3]) -> Option<PodEnd> {
    if layout.opening.contains(p_m) {
        return Some(PodEnd::Collected);
    }
    let beside = p_m[1].abs() > layout.half_width_m;
    let below_surface = layout
        .surface_z_m(p_m[0])
        .is_some_and(|z| p_m[2] < z - DOWN_BELOW_SURFACE_M);
    if !(p_m[2] < 0.0 || below_surface) {
        return None;
    }
    let place = if beside {
        Where::Beside
    } else if p_m[0] >= layout.shovel_top_m[0] {
        Where::Shovel
    } else if p_m[0] >= layout.opening.x_m.1 {
        Where::Chain
    } else {
        Where::Behind
    };
    // Below the ground ahead of the shovel's top: it fell back into the soil the shovel is
    // lifting, which is still the shovel's loss. Beside the machine: down only on the ground.
    if beside && p_m[2] >= 0.0 {
        return None;
    }
    Some(PodEnd::Lost(place))
}

/// The end of a pod not yet collected or down when the run ends.
pub fn at_end(attached: bool, lifted: bool) -> PodEnd {
    match (attached, lifted) {
        (_, false) => PodEnd::Lost(Where::InSoil),
        (true, true) => PodEnd::Unpicked,
        (false, true) => PodEnd::Lost(Where::OnMachine),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::harvester::HarvesterSpec;

    fn layout() -> Layout {
        let text = include_str!("../../../testdata/peanut-plant/harvester-digger.toml");
        Layout::of(&HarvesterSpec::from_toml(std::path::Path::new("h.toml"), text).unwrap())
    }

    #[test]
    fn every_end_counts_once_and_the_loss_excludes_unpicked() {
        let mut t = LossTally::default();
        let ends = [
            PodEnd::Collected,
            PodEnd::Unpicked,
            PodEnd::Lost(Where::InSoil),
            PodEnd::Lost(Where::Shovel),
            PodEnd::Lost(Where::Chain),
            PodEnd::Lost(Where::Behind),
            PodEnd::Lost(Where::Beside),
            PodEnd::Lost(Where::OnMachine),
        ];
        for e in ends {
            t.add(e);
        }
        assert_eq!(t.pods, 8);
        assert_eq!(t.lost(), 6);
        assert_eq!(t.loss_percent(), Some(75.0));
        assert_eq!(t.unpicked_percent(), Some(12.5));
        assert_eq!(LossTally::default().loss_percent(), None);
    }

    /// Positions on, through and around the machine land in the right place.
    #[test]
    fn detached_pods_are_placed_where_they_went_down() {
        let l = layout();
        let mid = |a: [f64; 3], b: [f64; 3]| [(a[0] + b[0]) / 2.0, 0.0, (a[2] + b[2]) / 2.0];
        let on_chain = mid(l.shovel_top_m, l.chain_top_m);
        // Riding on the chain: not down.
        assert_eq!(
            check_detached(&l, [on_chain[0], 0.0, on_chain[2] + 0.01]),
            None
        );
        // Through the chain.
        assert_eq!(
            check_detached(&l, [on_chain[0], 0.0, on_chain[2] - 0.05]),
            Some(PodEnd::Lost(Where::Chain))
        );
        let on_shovel = mid([0.0; 3], l.shovel_top_m);
        assert_eq!(
            check_detached(&l, [on_shovel[0], 0.0, -0.2]),
            Some(PodEnd::Lost(Where::Shovel))
        );
        let (rear, front) = l.opening.x_m;
        let into = [(rear + front) / 2.0, 0.0, l.opening.height_m - 0.01];
        assert_eq!(check_detached(&l, into), Some(PodEnd::Collected));
        assert_eq!(
            check_detached(&l, [rear - 0.1, 0.0, -0.01]),
            Some(PodEnd::Lost(Where::Behind))
        );
        assert_eq!(
            check_detached(&l, [on_chain[0], l.half_width_m + 0.05, -0.01]),
            Some(PodEnd::Lost(Where::Beside))
        );
        assert_eq!(
            check_detached(&l, [on_chain[0], l.half_width_m + 0.05, 0.2]),
            None
        );
        assert_eq!(at_end(true, true), PodEnd::Unpicked);
        assert_eq!(at_end(true, false), PodEnd::Lost(Where::InSoil));
        assert_eq!(at_end(false, true), PodEnd::Lost(Where::OnMachine));
    }
}
