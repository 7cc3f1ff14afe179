//! A pod's peg: the stalk that runs from its lateral down to the pod, followed along as the
//! pod settles into the soil ([`super::settle`]).
//!
//! A pod freed in the settling sinks onto the compacted soil below it, by 2.7 mm on average in
//! the shipped field and by up to 17 mm where the soil under it had shrunk away. Its bond to the
//! peg is formed from the geometry the field's run starts with, so a pod moved alone would
//! hang on a bond as long as its fall: that bond's lever arm sets the field's time step
//! (`arachis_core::bond::formation`), which fell from 8.3e-7 s to 2.2e-7 s when it was tried.
//! So the peg follows its pod: its k-th of n spheres, counted from the lateral, moves by
//! (k + 1)/n of the displacement of the pod sphere it is bonded to. Its end then keeps its
//! place beside the pod, and each of its n links is stretched by 1/n of the fall.
//!
//! ```
//! use arachis::field::peg::Peg;
//! use arachis::plant::{generate, Topology, SHIPPED_TOPOLOGY};
//! let model = generate(&Topology::from_toml(SHIPPED_TOPOLOGY).unwrap()).unwrap();
//! let pod = model.bodies.iter().position(|b| b.kind == arachis::plant::topology::Kind::Pod).unwrap();
//! let peg = Peg::of(&model, pod).expect("every pod hangs from a stalk");
//! // The peg's last sphere follows the pod all the way, its first hardly.
//! assert_eq!(peg.share(peg.chain.len() - 1), 1.0);
//! assert!(peg.share(0) < 1.0);
//! ```

use crate::plant::topology::Kind;
use crate::plant::PlantModel;

/// The peg of one pod, as sphere indices of its plant's model.
#[derive(Debug, Clone, PartialEq)]
pub struct Peg {
    /// The pod's sphere the peg is bonded to.
    pub tip: usize,
    /// The peg's spheres, from its lateral to the pod.
    pub chain: Vec<usize>,
}

impl Peg {
    /// The peg of pod `body` (an index into [`PlantModel::bodies`]): the chain part whose last
    /// sphere is bonded to a sphere of the pod. `None` when no such part exists.
    pub fn of(model: &PlantModel, body: usize) -> Option<Peg> {
        let pod = &model.bodies[body].spheres;
        let body_of = |sphere: usize| model.spheres[sphere].body;
        let (tip, end) = model.bonds.iter().find_map(|b| {
            let pair = if pod.contains(&b.a) {
                (b.a, b.b)
            } else if pod.contains(&b.b) {
                (b.b, b.a)
            } else {
                return None;
            };
            (model.bodies[body_of(pair.1)].kind != Kind::Pod).then_some(pair)
        })?;
        let part = &model.bodies[body_of(end)].part;
        let chain: Vec<usize> = model
            .bodies
            .iter()
            .filter(|b| &b.part == part)
            .flat_map(|b| b.spheres.iter().copied())
            .collect();
        (chain.last() == Some(&end)).then_some(Peg { tip, chain })
    }

    /// The fraction of the pod's displacement that the peg's `k`-th sphere (from the lateral)
    /// takes: (k + 1)/n.
    pub fn share(&self, k: usize) -> f64 {
        (k + 1) as f64 / self.chain.len() as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plant::{generate, Topology, SHIPPED_TOPOLOGY};

    #[test]
    fn every_pod_of_the_shipped_plant_has_a_peg_ending_at_its_bond() {
        let model = generate(&Topology::from_toml(SHIPPED_TOPOLOGY).unwrap()).unwrap();
        let pods: Vec<usize> = (0..model.bodies.len())
            .filter(|&b| model.bodies[b].kind == Kind::Pod)
            .collect();
        assert!(!pods.is_empty());
        for pod in pods {
            let peg = Peg::of(&model, pod).expect("a peg");
            let end = *peg.chain.last().unwrap();
            assert!(model
                .bonds
                .iter()
                .any(|b| (b.a, b.b) == (end, peg.tip) || (b.a, b.b) == (peg.tip, end)));
            assert!(model.bodies[pod].spheres.contains(&peg.tip));
            assert!(peg.chain.len() >= 2, "chains have at least two spheres");
            // Shares rise evenly to the whole displacement at the pod.
            for k in 1..peg.chain.len() {
                assert!(peg.share(k) > peg.share(k - 1));
            }
        }
    }
}
