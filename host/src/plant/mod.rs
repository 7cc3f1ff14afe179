//! Plant generator (issue 6, part 2): a bonded-sphere peanut plant from a topology file.
//!
//! A topology (TOML, [`topology`]) lists named parts — main stem, lateral stems, pod stalks,
//! pods and simplified leaves — each attached to a parent part at a fraction of its length,
//! with a direction, plus the bond sets by name (`stem`, `stalk`, `stalk_stem`, `pod_stalk`,
//! `stem_leaf`, `leaf`). Default dimensions are seed 001 Table 1 (stem 763.81 × 6.74 mm,
//! pod stalk 108.26 × 1.93 mm, pod 34.27 × 18.29 × 15.76 mm). [`generate`] turns it into
//! spheres, bodies and bonds ([`generate::PlantModel`]) and loads them into a core world.
//!
//! Bad topologies are clear errors ([`error::PlantError`]): an unknown part or kind, a pod
//! stalk with no pod (dangling), a bond radius ≤ 0, a missing bond set, a pod not on a stalk.
//!
//! Simplifications (stated, not hidden): stems, stalks and leaves are straight chains of
//! touching spheres of the part's radius; a pod is one clump, the normal pod of
//! `crate::shapes` (L × W × H, default seed 001 Table 1) filled with a few spheres
//! (`dimensions.pod_spheres`, default 5, so plants stay cheap); a leaf is a short chain.

pub mod error;
pub mod generate;
pub mod overlap;
pub mod picture;
pub mod summary;
pub mod topology;

pub use error::PlantError;
pub use generate::{generate, PlantModel};
pub use summary::PlantSummary;
pub use topology::Topology;

/// The shipped small plant, `testdata/peanut-plant/topology-small.toml` (built in, so the
/// commands that default to it work from any folder).
pub const SHIPPED_TOPOLOGY: &str =
    include_str!("../../../testdata/peanut-plant/topology-small.toml");
/// Its file name, as the shipped plant study names it.
pub const SHIPPED_TOPOLOGY_FILE: &str = "topology-small.toml";

/// The text of the topology at `path` (the shipped small plant when `None`), and the name
/// messages give it.
pub fn topology_text(path: Option<&std::path::Path>) -> std::io::Result<(String, String)> {
    Ok(match path {
        Some(p) => (crate::io::text::read_text(p)?, p.display().to_string()),
        None => (
            SHIPPED_TOPOLOGY.to_owned(),
            format!("the shipped topology ({SHIPPED_TOPOLOGY_FILE})"),
        ),
    })
}
