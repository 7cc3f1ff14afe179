//! Issue 6 build item 2: the named bond sets of a generated plant. The generator's counts
//! are checked against counts taken from the topology alone: one pod–stalk bond per pod,
//! one stalk–stem bond per pod stalk, one stem–leaf bond per leaf, and each chain's own
//! bonds from its sphere count n = max(2, round(L/D)) (`arachis::plant::generate`) — and
//! `arachis plant` prints the same counts with seed 001's 191 / 201 / 150 beside them.

use std::fmt::Write as _;
use std::path::Path;
use std::process::Command;

use arachis::plant::generate;
use arachis::plant::topology::{Kind, Topology};

const SMALL: &str = include_str!("../../testdata/peanut-plant/topology-small.toml");

/// A bushier plant than the shipped one: the small plant's bond sets, three laterals, and
/// pods and leaves spread over the stems.
fn bushy() -> String {
    let bonds_end = SMALL.find("[[part]]").unwrap();
    let mut t = SMALL[..bonds_end].to_owned();
    let mut part = |name: &str, kind: &str, parent: Option<&str>, at: f64, dir: [f64; 3]| {
        let _ = writeln!(t, "[[part]]\nname = \"{name}\"\nkind = \"{kind}\"");
        if let Some(p) = parent {
            let _ = writeln!(t, "parent = \"{p}\"\nat = {at}");
        }
        let _ = writeln!(t, "direction = {dir:?}\n");
    };
    part("stem", "main_stem", None, 0.0, [0.0, 0.0, 1.0]);
    for l in 0..3 {
        let lateral = format!("lat{l}");
        let a = f64::from(l) * 2.1;
        part(
            &lateral,
            "lateral_stem",
            Some("stem"),
            0.2 + 0.3 * f64::from(l),
            [a.cos(), a.sin(), 0.2],
        );
        for s in 0..(l + 2) {
            let stalk = format!("peg{l}_{s}");
            let at = 0.25 * f64::from(s + 1);
            part(
                &stalk,
                "pod_stalk",
                Some(&lateral),
                at.min(1.0),
                [0.0, 1.0, -0.5],
            );
            part(
                &format!("pod{l}_{s}"),
                "pod",
                Some(&stalk),
                0.0,
                [0.0, 1.0, -0.5],
            );
        }
        part(
            &format!("leaf{l}"),
            "leaf",
            Some(&lateral),
            1.0,
            [-1.0, 0.0, 0.2],
        );
    }
    part("peg_main", "pod_stalk", Some("stem"), 0.9, [1.0, 1.0, -0.5]);
    part("pod_main", "pod", Some("peg_main"), 0.0, [1.0, 1.0, -0.5]);
    part("leaf_top", "leaf", Some("stem"), 1.0, [0.0, -1.0, 0.2]);
    t
}

/// Bonds per set counted from the topology, without generating the plant.
fn expected(t: &Topology) -> [(&'static str, usize); 6] {
    let d = &t.dimensions;
    let count = |k: Kind| t.parts.iter().filter(|p| p.kind == k).count();
    let chain_bonds = |k: Kind, length: f64, dia: f64| -> usize {
        t.parts
            .iter()
            .filter(|p| p.kind == k)
            .map(|p| ((p.length_mm.unwrap_or(length) / dia).round() as usize).max(2) - 1)
            .sum()
    };
    [
        ("pod_stalk", count(Kind::Pod)),
        ("stalk_stem", count(Kind::PodStalk)),
        ("stem_leaf", count(Kind::Leaf)),
        (
            "stem",
            chain_bonds(Kind::MainStem, d.stem_length_mm, d.stem_diameter_mm)
                + chain_bonds(Kind::LateralStem, d.lateral_length_mm, d.stem_diameter_mm)
                + count(Kind::LateralStem),
        ),
        (
            "stalk",
            chain_bonds(Kind::PodStalk, d.stalk_length_mm, d.stalk_diameter_mm),
        ),
        (
            "leaf",
            chain_bonds(Kind::Leaf, d.leaf_length_mm, d.leaf_diameter_mm),
        ),
    ]
}

#[test]
fn generated_bond_sets_match_counts_from_the_topology() {
    for text in [SMALL.to_owned(), bushy()] {
        let t = Topology::from_toml(&text).unwrap();
        let m = generate(&t).unwrap();
        let counts = m.bond_counts();
        let want = expected(&t);
        for (set, n) in want {
            assert_eq!(counts.get(set).copied().unwrap_or(0), n, "set {set}");
        }
        assert_eq!(counts.values().sum::<usize>(), m.bonds.len());
        assert_eq!(counts.len(), want.len(), "{counts:?}");
        let s = m.summary();
        assert_eq!(s.named.pod_stalk, want[0].1);
        assert_eq!(s.named.stalk_stem, want[1].1);
        assert_eq!(s.named.stem_leaf, want[2].1);
        assert_eq!(
            s.parts["pod"],
            t.parts.iter().filter(|p| p.kind == Kind::Pod).count()
        );
    }
    // The bushy plant is not the shipped one in disguise.
    let t = Topology::from_toml(&bushy()).unwrap();
    assert_eq!(expected(&t)[0].1, 2 + 3 + 4 + 1);
}

/// `arachis plant --topology FILE`, with FILE holding `text` in `dir`.
fn plant(dir: &Path, name: &str, text: &str) -> std::process::Output {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    Command::new(env!("CARGO_BIN_EXE_arachis"))
        .args(["plant", "--topology", path.to_str().unwrap()])
        .output()
        .unwrap()
}

#[test]
fn plant_command_prints_the_counts_beside_seed_001s() {
    let dir = tempfile::tempdir().unwrap();
    let out = plant(dir.path(), "bushy.toml", &bushy());
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let t = Topology::from_toml(&bushy()).unwrap();
    for (set, n) in expected(&t) {
        assert_eq!(v["bond_sets"][set], n, "set {set}");
    }
    assert_eq!(v["named"]["pod_stalk"], expected(&t)[0].1);
    assert_eq!(v["seed001"]["pod_stalk"], 191);
    assert_eq!(v["seed001"]["pod_pod"], 201);
    assert_eq!(v["seed001"]["stem_leaf"], 150);

    let out = plant(
        dir.path(),
        "bad.toml",
        "[[part]]\nname = \"peg\"\nkind = \"pod_stalk\"\n",
    );
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("bad plant topology"), "{err}");
    // Issue 23: the message names the file.
    assert!(err.contains("bad.toml"), "{err}");

    // A bond set no bond uses is a misspelt one: refused, naming it and the sets used
    // (`[bonds.stemm]` was once accepted silently).
    let set = "\n[bonds.stemm]\nkn_n_m3 = 1.0e10\nkt_n_m3 = 4.0e9\nsigma_c_pa = 1e6\ntau_c_pa = 1e6\nradius_m = 1e-3\n";
    let out = plant(dir.path(), "extra.toml", &format!("{SMALL}{set}"));
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("extra.toml"), "{err}");
    assert!(err.contains("bond set `stemm` is defined"), "{err}");
    assert!(err.contains("sets used: leaf, pod_stalk, stalk, stalk_stem, stem, stem_leaf"));
}
