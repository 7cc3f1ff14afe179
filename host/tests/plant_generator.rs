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
    // leaf 12/4 → 3; pods: 2 clumps of `pod_spheres` spheres each.
    let count = |k: Kind| m.bodies.iter().filter(|b| b.kind == k).count();
    assert_eq!(count(Kind::MainStem), 9);
    assert_eq!(count(Kind::LateralStem), 4);
    assert_eq!(count(Kind::PodStalk), 12);
    assert_eq!(count(Kind::Leaf), 3);
    assert_eq!(count(Kind::Pod), 2);
    let per_pod = t.dimensions.pod_spheres;
    assert_eq!(m.spheres.len(), 9 + 4 + 12 + 3 + 2 * per_pod);
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

/// Each pod is the normal pod of `arachis::shapes` (seed 001 Table 1's 34.27 × 18.29 ×
/// 15.76 mm), filled with `pod_spheres` spheres: placed rigidly (every pairwise centre
/// distance and radius as in the body-frame filling, 1e-9 mm), its tip sphere bonded to
/// the stalk end and no pod sphere overlapping the stalk.
#[test]
fn pods_are_the_shape_modules_normal_pod_placed_rigidly() {
    use arachis::plant::generate::pod_filling;
    use arachis::shapes::{fill_with_spheres, FillOptions, FillTarget, PodKind, PodShape};

    let t = Topology::from_toml(SMALL).unwrap();
    let d = &t.dimensions;
    assert_eq!(
        (d.pod_length_mm, d.pod_width_mm, d.pod_thickness_mm),
        (34.27, 18.29, 15.76)
    );
    let body = pod_filling(d).unwrap();
    // The same filling straight from the shape module.
    let direct = fill_with_spheres(
        &PodShape::seed001_mean(PodKind::Normal),
        &FillOptions {
            resolution: d.pod_fill_resolution,
            target: FillTarget::SphereCount(d.pod_spheres),
        },
    )
    .unwrap();
    assert_eq!(body, direct.spheres);
    assert_eq!(body.len(), d.pod_spheres);

    let m = generate(&t).unwrap();
    let dist = |a: [f64; 3], b: [f64; 3]| -> f64 {
        (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt()
    };
    for pod in m.bodies.iter().filter(|b| b.kind == Kind::Pod) {
        let world: Vec<_> = pod.spheres.iter().map(|&i| &m.spheres[i]).collect();
        for (i, (w, s)) in world.iter().zip(&body).enumerate() {
            assert!((w.radius_m * 1e3 - s.radius_mm).abs() < 1e-9);
            for (w2, s2) in world[i + 1..].iter().zip(&body[i + 1..]) {
                let dw = dist(w.centre_m, w2.centre_m) * 1e3;
                let db = dist(s.centre_mm, s2.centre_mm);
                assert!((dw - db).abs() < 1e-9, "{dw} vs {db} mm");
            }
        }
        let bond = m
            .bonds
            .iter()
            .find(|b| b.set == "pod_stalk" && pod.spheres.contains(&b.b))
            .unwrap();
        let stalk_end = &m.spheres[bond.a];
        for w in &world {
            let gap = dist(w.centre_m, stalk_end.centre_m) - w.radius_m - stalk_end.radius_m;
            assert!(gap > 0.0, "pod sphere overlaps the stalk end: gap {gap} m");
        }
    }
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

    // A pod with no sphere, or a fill grid too coarse to tell the waist from the lobes.
    for (key, value) in [("pod_spheres", "0"), ("pod_fill_resolution", "4")] {
        let e = err(&format!("[dimensions]\n{key} = {value}\n{STEM}"));
        assert!(matches!(e, PlantError::BadValue { .. }), "{e}");
        assert!(e.to_string().contains(key), "{e}");
    }

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
