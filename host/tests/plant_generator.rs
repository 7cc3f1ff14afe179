//! Plant generator: a small topology (testdata/peanut-plant/topology-small.toml) becomes the
//! expected chains, pods and named bond sets, loads into a core world that steps under
//! gravity with its root clamped; bad topologies (dangling stalk, bond radius ≤ 0, unknown
//! part or kind) are clear errors.

use arachis::arena::{OwnedBonds, OwnedStorage};
use arachis::plant::topology::Kind;
use arachis::plant::{generate, PlantError, Topology};
use arachis_core::prelude::*;

const SMALL: &str = include_str!("../../testdata/peanut-plant/topology-small.toml");

#[test]
fn small_plant_has_the_expected_parts_and_bonds() {
    let t = Topology::from_toml(SMALL).unwrap();
    let m = generate(&t).unwrap();
    // Chains: n = round(L/D): stem 60/6.74 → 9, branch 30/6.74 → 4, stalks 12/1.93 → 6,
    // leaf 12/4 → 3; pods: 2 clumps of 3 spheres.
    let count = |k: Kind| m.bodies.iter().filter(|b| b.kind == k).count();
    assert_eq!(count(Kind::MainStem), 9);
    assert_eq!(count(Kind::LateralStem), 4);
    assert_eq!(count(Kind::PodStalk), 12);
    assert_eq!(count(Kind::Leaf), 3);
    assert_eq!(count(Kind::Pod), 2);
    assert_eq!(m.spheres.len(), 9 + 4 + 12 + 3 + 6);
    assert_eq!(m.bond_count("pod_stalk"), 2);
    assert_eq!(m.bond_count("stalk_stem"), 2);
    assert_eq!(m.bond_count("stem_leaf"), 1);
    assert_eq!(m.bond_count("stem"), 8 + 3 + 1); // chains + the lateral's attachment
    assert_eq!(m.bond_count("stalk"), 10);
    assert_eq!(m.bond_count("leaf"), 2);
    // Bonded neighbours are 1 µm apart at set-up (no overlap, no slack).
    for b in &m.bonds {
        let (p, q) = (&m.spheres[b.a], &m.spheres[b.b]);
        let d: f64 = (0..3)
            .map(|k| (p.centre_m[k] - q.centre_m[k]).powi(2))
            .sum::<f64>()
            .sqrt();
        let gap = d - p.radius_m - q.radius_m;
        assert!(gap > 0.0 && gap < 2e-6, "{b:?} gap {gap}");
    }
    assert_eq!(m.set_name(m.sets["pod_stalk"].tag), Some("pod_stalk"));
}

#[test]
fn small_plant_loads_and_steps_with_its_root_clamped() {
    let m = generate(&Topology::from_toml(SMALL).unwrap()).unwrap();
    let l = StorageLengths::for_spheres(m.bodies.len(), m.spheres.len());
    let mut arena = OwnedStorage::<Fx>::new(l);
    let mut bond_arena = OwnedBonds::<Fx>::new(m.bonds.len());
    let mut w = World::new(arena.storage()).unwrap();
    w.attach_bond_storage(bond_arena.storage()).unwrap();
    let plant = w
        .add_material(MaterialSpec {
            youngs_modulus_pa: 118e6,
            poisson: 0.247,
            density_kg_m3: 1000.0,
        })
        .unwrap();
    let pod = w
        .add_material(MaterialSpec {
            youngs_modulus_pa: 296e6,
            poisson: 0.37,
            density_kg_m3: 582.36,
        })
        .unwrap();
    for (a, b) in [(plant, plant), (plant, pod), (pod, pod)] {
        w.set_pair(a, b, PairSpec::hertz_mindlin(0.34, 0.62, 0.47))
            .unwrap();
    }
    w.set_gravity_m_s2([0.0, 0.0, -9.81]).unwrap();
    let root = m.load_into(&mut w, plant, pod).unwrap();
    w.set_body_kinematic(root).unwrap();
    assert_eq!(w.bonds().bonds().len(), m.bonds.len());
    let dt = 0.9 * w.bond_max_timestep_s().min(w.max_timestep_s());
    w.set_timestep_s(dt).unwrap();
    w.run(300).unwrap();
    assert_eq!(
        w.bonds().breaks_total(),
        0,
        "the plant must hold its own weight"
    );
    // The root stayed put; the plant sags but does not fall.
    assert_eq!(w.body(root).position.to_f64(), [0.0, 0.0, 0.0]);
}

fn err(text: &str) -> PlantError {
    Topology::from_toml(text).unwrap_err()
}

const STEM: &str = "[[part]]\nname = \"stem\"\nkind = \"main_stem\"\n";
const SET: &str = "kn_n_m3 = 1e10\nkt_n_m3 = 1e10\nsigma_c_pa = 1e6\ntau_c_pa = 1e6\n";

#[test]
fn bad_topologies_are_clear_errors() {
    let dangling =
        format!("{STEM}[[part]]\nname = \"peg\"\nkind = \"pod_stalk\"\nparent = \"stem\"\n");
    let e = err(&dangling);
    assert_eq!(e, PlantError::DanglingStalk("peg".into()));
    assert!(e.to_string().contains("dangling"));

    let radius = format!("{STEM}[bonds.stem]\n{SET}radius_m = 0.0\n");
    let e = err(&radius);
    assert!(matches!(e, PlantError::NonPositiveBondRadius { .. }), "{e}");
    assert!(e.to_string().contains("bond radius must be > 0"));

    let unknown = format!("{STEM}[[part]]\nname = \"leaf\"\nkind = \"leaf\"\nparent = \"stme\"\n");
    let e = err(&unknown);
    assert!(matches!(e, PlantError::UnknownPart { .. }), "{e}");
    assert!(e.to_string().contains("unknown part `stme`"));

    let kind = format!("{STEM}[[part]]\nname = \"x\"\nkind = \"flower\"\nparent = \"stem\"\n");
    let e = err(&kind);
    assert!(matches!(e, PlantError::Parse(_)), "{e}");
    assert!(e.to_string().contains("flower"), "{e}");

    let pod_on_stem = format!("{STEM}[[part]]\nname = \"p\"\nkind = \"pod\"\nparent = \"stem\"\n");
    assert!(matches!(err(&pod_on_stem), PlantError::BadParent { .. }));

    // A set the plant needs but the file lacks.
    let t = Topology::from_toml(&format!(
        "{STEM}[[part]]\nname = \"l\"\nkind = \"leaf\"\nparent = \"stem\"\n"
    ))
    .unwrap();
    assert!(matches!(
        generate(&t),
        Err(PlantError::MissingBondSet("stem"))
    ));
}
