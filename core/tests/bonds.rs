//! Bond behaviour around the stage: bonded pairs get no contact force and get it back once
//! the bond breaks; scheduled formation happens at its time; a full break log counts what it
//! cannot store; capacity and id errors are typed; the f64 reference path runs the same code.

use crate::common;

use arachis_core::bond::{
    Bond, BondBreak, BondError, BondSetSpec, BondStorage, BreakCriterion, FormationRule,
};
use arachis_core::prelude::*;
use common::Owned;

const STALK: MaterialSpec = MaterialSpec {
    youngs_modulus_pa: 118e6,
    poisson: 0.247,
    density_kg_m3: 1000.0,
};
const DT_S: f64 = 1.0e-6;

fn set(sigma_c_pa: f64) -> BondSetSpec {
    BondSetSpec {
        tag: 3,
        normal_stiffness_n_m3: 1e9,
        tangential_stiffness_n_m3: 1e9,
        normal_strength_pa: sigma_c_pa,
        tangential_strength_pa: 1e9,
        radius_m: 1e-3,
    }
}

/// Two free R 1 mm spheres overlapping by 0.02 mm along x, at rest, no gravity.
fn overlapping<'a, S: Scalar>(
    owned: &'a mut Owned<S>,
    bonds: &'a mut [Bond<S>],
    log: &'a mut [BondBreak<S>],
) -> World<'a, S> {
    let mut w = World::new(owned.storage()).unwrap();
    w.attach_bond_storage(BondStorage { bonds, log }).unwrap();
    let m = w.add_material(STALK).unwrap();
    w.set_pair(m, m, PairSpec::hertz_mindlin(0.21, 0.71, 0.58))
        .unwrap();
    w.add_sphere(SphereSpec::at_rest(m, 1e-3, [0.0; 3]))
        .unwrap();
    w.add_sphere(SphereSpec::at_rest(m, 1e-3, [1.98e-3, 0.0, 0.0]))
        .unwrap();
    w.set_timestep_s(DT_S).unwrap();
    w
}

#[test]
fn bonded_pairs_get_no_contact_force_until_the_bond_breaks() {
    // Unbonded: Hertz pushes the overlapping pair apart.
    let mut owned = Owned::<Fx>::new(2, 2);
    let (mut b, mut l) = (vec![Bond::default(); 1], vec![BondBreak::default(); 1]);
    let mut w = overlapping(&mut owned, &mut b, &mut l);
    w.step().unwrap();
    let push = w.body(BodyId(1)).force.x.to_f64();
    assert!(push > 0.1, "contact force {push} N expected");

    // Bonded in the overlapping configuration: no load at all.
    let mut owned = Owned::<Fx>::new(2, 2);
    let (mut b, mut l) = (vec![Bond::default(); 1], vec![BondBreak::default(); 1]);
    let mut w = overlapping(&mut owned, &mut b, &mut l);
    // Both kinematic, so the imposed motion below is exact; forces still accumulate.
    w.set_body_kinematic(BodyId(0)).unwrap();
    w.set_body_kinematic(BodyId(1)).unwrap();
    let s = w.add_bond_set(&set(1e5)).unwrap();
    w.add_bond(1, 0, s).unwrap();
    w.run(10).unwrap();
    assert_eq!(w.body(BodyId(1)).force.x.to_f64(), 0.0);
    assert_eq!(w.contact_count(), 0);
    // Pull sphere 1 away: the bond breaks in tension (σc = 0.1 MPa ↔ δ = 0.1 mm, 100 steps);
    // then push it back to show that the contact law returns.
    w.set_body_velocity(BodyId(1), [1.0, 0.0, 0.0], [0.0; 3])
        .unwrap();
    let mut steps = 0;
    while w.bonds().bonds().len() == 1 && steps < 1_000 {
        w.step().unwrap();
        steps += 1;
    }
    assert_eq!(w.bonds().breaks_total(), 1);
    let r = w.bonds().breaks()[0];
    assert_eq!(r.criterion, BreakCriterion::Normal);
    assert_eq!(r.tag, 3);
    assert_eq!(r.bond_id, 0);
    assert!(r.time_s() > 0.0);
    w.set_body_velocity(BodyId(1), [-1.0, 0.0, 0.0], [0.0; 3])
        .unwrap();
    let mut touched = false;
    for _ in 0..400 {
        w.step().unwrap();
        touched |= w.body(BodyId(1)).force.x.to_f64() > 0.0;
    }
    assert!(
        touched,
        "after the break the pair must meet the contact law"
    );
}

#[test]
fn scheduled_formation_happens_at_its_time_and_is_in_the_digest() {
    let mut owned = Owned::<Fx>::new(2, 2);
    let (mut b, mut l) = (vec![Bond::default(); 1], vec![BondBreak::default(); 1]);
    let mut w = overlapping(&mut owned, &mut b, &mut l);
    let before_set = w.digest();
    let s = w.add_bond_set(&set(1e9)).unwrap();
    assert_ne!(w.digest(), before_set, "bond sets are state");
    let rule = FormationRule {
        set: s,
        materials: None,
        max_gap_m: 0.0,
    };
    w.schedule_bond_formation(10.0 * DT_S, &rule).unwrap();
    let mut formed_at = None;
    for k in 0..20u64 {
        w.step().unwrap();
        if formed_at.is_none() && w.bonds().bonds().len() == 1 {
            formed_at = Some(k);
        }
    }
    // Step k starts at time k·dt; the formation is due at 10·dt (to dt quantisation).
    let k = formed_at.expect("never formed");
    assert!((9..=11).contains(&k), "formed in step {k}");
}

#[test]
fn full_break_log_counts_the_rest() {
    // Three spheres in a row, two bonds, a log of one: both break, one is logged.
    let mut owned = Owned::<Fx>::new(3, 3);
    let (mut b, mut l) = (vec![Bond::default(); 2], vec![BondBreak::default(); 1]);
    let mut w = World::new(owned.storage()).unwrap();
    w.attach_bond_storage(BondStorage {
        bonds: &mut b,
        log: &mut l,
    })
    .unwrap();
    let m = w.add_material(STALK).unwrap();
    w.set_pair(m, m, PairSpec::hertz_mindlin(0.21, 0.71, 0.58))
        .unwrap();
    for (i, v) in [-1.0, 0.0, 1.0].into_iter().enumerate() {
        let mut s = SphereSpec::at_rest(m, 1e-3, [2e-3 * i as f64, 0.0, 0.0]);
        s.velocity_m_s = [v, 0.0, 0.0];
        let id = w.add_sphere(s).unwrap();
        if i != 1 {
            w.set_body_kinematic(id).unwrap();
        }
    }
    let s = w.add_bond_set(&set(1e5)).unwrap();
    let formed = w
        .form_bonds(&FormationRule {
            set: s,
            materials: None,
            max_gap_m: 1e-6,
        })
        .unwrap();
    assert_eq!(formed, 2);
    w.set_timestep_s(DT_S).unwrap();
    w.run(500).unwrap();
    assert_eq!(w.bonds().breaks_total(), 2);
    assert_eq!(w.bonds().breaks().len(), 1);
    assert_eq!(w.bonds().breaks_not_logged(), 1);
}

#[test]
fn capacity_and_id_errors_are_typed() {
    let mut owned = Owned::<Fx>::new(3, 4);
    let (mut b, mut l) = (vec![Bond::default(); 1], vec![BondBreak::default(); 1]);
    let mut w = World::new(owned.storage()).unwrap();
    w.attach_bond_storage(BondStorage {
        bonds: &mut b,
        log: &mut l,
    })
    .unwrap();
    let m = w.add_material(STALK).unwrap();
    for i in 0..3 {
        w.add_sphere(SphereSpec::at_rest(m, 1e-3, [2e-3 * i as f64, 0.0, 0.0]))
            .unwrap();
    }
    let rule = |set| FormationRule {
        set,
        materials: None,
        max_gap_m: 1e-6,
    };
    assert_eq!(
        w.form_bonds(&rule(arachis_core::bond::BondSetId(0))),
        Err(BondError::UnknownSet { id: 0 })
    );
    let s = w.add_bond_set(&set(1e5)).unwrap();
    // Two pairs, one slot: nothing is formed.
    assert_eq!(
        w.form_bonds(&rule(s)),
        Err(BondError::Capacity { capacity: 1 })
    );
    assert!(w.bonds().bonds().is_empty());
    assert_eq!(w.add_bond(0, 9, s), Err(BondError::UnknownSphere { id: 9 }));
    assert_eq!(w.add_bond(0, 1, s), Ok(0));
    assert!(matches!(
        w.add_bond(1, 0, s),
        Err(BondError::AlreadyBonded { .. })
    ));
    assert!(matches!(
        w.add_bond(1, 2, s),
        Err(BondError::Capacity { .. })
    ));
    let e = w
        .form_bonds(&FormationRule {
            set: s,
            materials: None,
            max_gap_m: -1.0,
        })
        .unwrap_err();
    assert!(matches!(e, BondError::NonPositive { .. }));
    // A clump's own spheres cannot be bonded together.
    let spheres = [
        ClumpSphere {
            center_m: [0.0, 0.01, 0.0],
            radius_m: 1e-3,
            material: m,
        },
        ClumpSphere {
            center_m: [1.5e-3, 0.01, 0.0],
            radius_m: 1e-3,
            material: m,
        },
    ];
    let mut owned = Owned::<Fx>::new(1, 2);
    let (mut b, mut l) = (vec![Bond::default(); 1], vec![BondBreak::default(); 1]);
    let mut w = World::new(owned.storage()).unwrap();
    w.attach_bond_storage(BondStorage {
        bonds: &mut b,
        log: &mut l,
    })
    .unwrap();
    let m = w.add_material(STALK).unwrap();
    let spheres = spheres.map(|s| ClumpSphere { material: m, ..s });
    w.add_clump(&ClumpSpec {
        spheres: &spheres,
        velocity_m_s: [0.0; 3],
        angular_velocity_rad_s: [0.0; 3],
    })
    .unwrap();
    let s = w.add_bond_set(&set(1e5)).unwrap();
    assert_eq!(w.add_bond(0, 1, s), Err(BondError::SameBody { body: 0 }));
    assert_eq!(w.form_bonds(&rule(s)), Ok(0));
}

#[test]
fn f64_reference_runs_the_same_bond_code() {
    let mut owned = Owned::<f64>::new(2, 2);
    let (mut b, mut l) = (vec![Bond::default(); 1], vec![BondBreak::default(); 1]);
    let mut w = overlapping(&mut owned, &mut b, &mut l);
    w.set_body_kinematic(BodyId(1)).unwrap();
    let s = w.add_bond_set(&set(1e5)).unwrap();
    w.add_bond(0, 1, s).unwrap();
    w.set_body_velocity(BodyId(1), [0.1, 0.0, 0.0], [0.0; 3])
        .unwrap();
    w.run(100).unwrap();
    let f = w.bonds().bonds()[0].normal_force;
    assert!(f < 0.0, "stretched bond pulls: Fn = {f}");
}

/// Dumbbells in the thread-count test: enough bonds for three parts of the bond stage.
const DUMBBELLS: usize = 3 * arachis_core::step::bonds::MIN_BONDS_PER_PART + 64;

/// `DUMBBELLS` free pairs of touching R 1 mm spheres, 10 mm apart on a grid, each pair bonded
/// (σc 2e4 Pa: a bond breaks at 0.02 mm of stretch) and flying apart along x at its own speed,
/// 0.1–1.0 m/s by a scrambled index, so breaks fall at many steps all through the bond table.
fn dumbbells<'a>(
    owned: &'a mut Owned<Fx>,
    bonds: &'a mut [Bond<Fx>],
    log: &'a mut [BondBreak<Fx>],
) -> World<'a, Fx> {
    let mut w = World::new(owned.storage()).unwrap();
    w.attach_bond_storage(BondStorage { bonds, log }).unwrap();
    let m = w.add_material(STALK).unwrap();
    w.set_pair(m, m, PairSpec::hertz_mindlin(0.21, 0.71, 0.58))
        .unwrap();
    for k in 0..DUMBBELLS {
        let (y, z) = ((k % 40) as f64 * 1e-2, (k / 40) as f64 * 1e-2);
        let speed = 0.1 + 0.9 * ((k * 37) % 100) as f64 / 100.0;
        for (x, v) in [(0.0, -speed / 2.0), (2e-3, speed / 2.0)] {
            let mut s = SphereSpec::at_rest(m, 1e-3, [x, y, z]);
            s.velocity_m_s = [v, 0.0, 0.0];
            w.add_sphere(s).unwrap();
        }
    }
    let s = w.add_bond_set(&set(2e4)).unwrap();
    let rule = FormationRule {
        set: s,
        materials: None,
        max_gap_m: 1e-6,
    };
    assert_eq!(w.form_bonds(&rule).unwrap() as usize, DUMBBELLS);
    w.set_timestep_s(DT_S).unwrap();
    w
}

/// The bond stage splits its bonds over the threads (issue 16): loads, breaks, the break log
/// and the compacted table are the same bits for 1, 2, 3, 4 and 7 threads. Breaks fall in
/// every third of the table, so every part meets some.
#[test]
fn bond_loads_and_breaks_are_the_same_bits_for_any_thread_count() {
    let run = |threads: usize| {
        let mut owned = Owned::<Fx>::new(2 * DUMBBELLS, 2 * DUMBBELLS);
        let mut b = vec![Bond::default(); DUMBBELLS];
        let mut l = vec![BondBreak::default(); DUMBBELLS];
        let mut w = dumbbells(&mut owned, &mut b, &mut l);
        common::run_threaded(&mut w, 300, threads);
        let log: Vec<(u64, u32)> = w
            .bonds()
            .breaks()
            .iter()
            .map(|r| (r.step, r.bond_id))
            .collect();
        (w.digest(), log, w.bonds().bonds().len())
    };
    let (digest, log, left) = run(1);
    let third = DUMBBELLS as u32 / 3;
    let broke_in = |lo: u32, hi: u32| log.iter().filter(|(_, id)| (lo..hi).contains(id)).count();
    println!(
        "{} of {DUMBBELLS} bonds broke in 300 steps, {left} hold; by third of the table: {} {} {}",
        log.len(),
        broke_in(0, third),
        broke_in(third, 2 * third),
        broke_in(2 * third, u32::MAX)
    );
    assert!(left > 0 && !log.is_empty(), "some bonds break, some hold");
    assert_eq!(left + log.len(), DUMBBELLS);
    for (lo, hi) in [(0, third), (third, 2 * third), (2 * third, u32::MAX)] {
        assert!(broke_in(lo, hi) > 0, "no break among bonds {lo}..{hi}");
    }
    let steps: std::collections::BTreeSet<u64> = log.iter().map(|(s, _)| *s).collect();
    assert!(
        steps.len() > 10,
        "breaks fall at {} steps only",
        steps.len()
    );
    for threads in [2, 3, 4, 7] {
        let (d, l, n) = run(threads);
        let first_difference = l.iter().zip(&log).position(|(a, b)| a != b);
        assert!(
            l == log,
            "break log, {threads} threads: {} against {} records, first difference at {first_difference:?}",
            l.len(),
            log.len()
        );
        assert_eq!(n, left, "bonds left, {threads} threads");
        assert_eq!(d, digest, "digest, {threads} threads");
    }
}
