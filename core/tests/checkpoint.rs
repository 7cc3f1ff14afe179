//! Checkpoints (`arachis_core::world::checkpoint`): a world read back from a checkpoint, in a
//! world set up the same way, steps on bit for bit as the writer did: with contact, effect
//! (JKR, EPSD) and bond history, moving walls, a clump, pending bond formations and breaks,
//! in fixed point and in f64, and across thread counts. A world set up differently, a short
//! stream or an impossible value is refused with an error that names it.

use crate::common::{add_floor, pod_steel_world, run_threaded, Owned};
use arachis_core::bond::{Bond, BondBreak, BondStorage};
use arachis_core::effects::EffectSpec;
use arachis_core::prelude::*;
use arachis_core::scenario::PullOff;
use arachis_core::world::checkpoint::{CheckpointError, WordReader, WordWriter};

/// Pods dropped as a loose block (per side, and layers).
const SIDE: usize = 4;
const LAYERS: usize = 3;
/// Pod radius, m.
const R_M: f64 = 0.004;
/// Time step, s.
const DT_S: f64 = 2e-6;
/// Steps before the checkpoint (the block has landed and its contacts hold history) and
/// after it.
const BEFORE: u64 = 15_000;
const AFTER: u64 = 3_000;

/// A block of pods with JKR cohesion and EPSD rolling (both keep effect history), a two-sphere
/// clump, a fixed floor and a side wall closing in: every kind of state a step carries.
fn block<S: Scalar>(o: &mut Owned<S>, pods: usize) -> World<'_, S> {
    let (mut w, pod, steel) = pod_steel_world(o, PairSpec::hertz_mindlin(0.4, 0.5, 0.1));
    let fx = EffectSpec {
        jkr_work_of_adhesion_j_m2: 0.5,
        epsd_rolling_friction: 0.2,
        epsd_damping_ratio: 0.3,
        ..EffectSpec::default()
    };
    w.set_pair_effects(pod, pod, fx).unwrap();
    w.set_gravity_m_s2([0.0, 0.0, -9.81]).unwrap();
    add_floor(&mut w, steel);
    w.add_wall(WallSpec {
        velocity_m_s: [-0.02, 0.0, 0.0],
        ..WallSpec::fixed(
            WallGeometry::Plane {
                point_m: [0.045, 0.0, 0.0],
                normal: [-1.0, 0.0, 0.0],
            },
            steel,
        )
    })
    .unwrap();
    let pitch = 2.05 * R_M;
    for k in 0..pods {
        let (i, j, l) = (k % SIDE, (k / SIDE) % SIDE, k / (SIDE * SIDE));
        let at = [i as f64 * pitch, j as f64 * pitch, R_M + l as f64 * pitch];
        w.add_sphere(SphereSpec::at_rest(pod, R_M * (1.0 + 0.005 * i as f64), at))
            .unwrap();
    }
    let top = R_M + LAYERS as f64 * pitch + R_M;
    w.add_clump(&ClumpSpec {
        spheres: &[
            ClumpSphere {
                center_m: [0.01, 0.01, top],
                radius_m: R_M,
                material: pod,
            },
            ClumpSphere {
                center_m: [0.016, 0.01, top],
                radius_m: R_M,
                material: pod,
            },
        ],
        velocity_m_s: [0.0; 3],
        angular_velocity_rad_s: [0.0, 3.0, 0.0],
    })
    .unwrap();
    w.set_timestep_s(DT_S).unwrap();
    w
}

fn words_of<S: Scalar>(w: &mut World<'_, S>) -> Vec<u64> {
    let mut words = Vec::new();
    w.write_checkpoint(&mut WordWriter::new(|x| words.push(x)))
        .unwrap();
    words
}

fn read<S: Scalar>(w: &mut World<'_, S>, words: &[u64]) -> Result<(), CheckpointError> {
    w.read_checkpoint(&mut WordReader::new(words.iter().copied()))
}

fn owned<S: Scalar>() -> Owned<S> {
    Owned::new(SIDE * SIDE * LAYERS + 1, SIDE * SIDE * LAYERS + 2)
}

/// Runs the block to the checkpoint, writes it and goes on; then resumes a second world from
/// it. Returns (digest at the checkpoint, the second world's digest right after reading, the
/// first's and the second's digests at the end).
fn resumed<S: Scalar>(threads_before: usize, threads_after: usize) -> [u64; 4] {
    let mut a = owned::<S>();
    let mut w = block(&mut a, SIDE * SIDE * LAYERS);
    run_threaded(&mut w, BEFORE, threads_before);
    // The checkpoint carries contact and effect history: tangential springs, JKR necks and
    // EPSD rolling springs.
    let slots: Vec<_> = (0..w.spheres().len() as u32)
        .flat_map(|s| w.contact_slots(s).collect::<Vec<_>>())
        .collect();
    assert!(
        slots.len() >= 10,
        "the block should have landed ({} contacts)",
        slots.len()
    );
    assert!(slots.iter().any(|c| c.state.jkr_attached));
    assert!(slots.iter().any(|c| c.state.roll_angle != Vec3::ZERO));
    let at = w.digest();
    let words = words_of(&mut w);
    assert_eq!(w.digest(), at, "writing changed the world");
    run_threaded(&mut w, AFTER, threads_before);
    let mut b = owned::<S>();
    let mut v = block(&mut b, SIDE * SIDE * LAYERS);
    read(&mut v, &words).unwrap();
    let read_at = v.digest();
    run_threaded(&mut v, AFTER, threads_after);
    [at, read_at, w.digest(), v.digest()]
}

#[test]
fn a_fixed_point_world_resumes_bit_for_bit() {
    let [at, read_at, first, second] = resumed::<Fx>(1, 1);
    assert_eq!(read_at, at);
    assert_ne!(
        first, at,
        "the world should have moved after the checkpoint"
    );
    assert_eq!(second, first);
}

#[test]
fn an_f64_world_resumes_bit_for_bit_too() {
    // The list is restored as it stood, so it is rebuilt when the writer's was and the f64
    // sums run in the same order.
    let [at, read_at, first, second] = resumed::<f64>(1, 1);
    assert_eq!(read_at, at);
    assert_eq!(second, first);
}

#[test]
fn a_checkpoint_written_on_two_threads_resumes_on_three() {
    let [_, _, first, second] = resumed::<Fx>(2, 3);
    let [_, _, serial, _] = resumed::<Fx>(1, 1);
    assert_eq!(second, first);
    assert_eq!(first, serial);
}

/// Arenas for the pull-off rig (world, bonds, break log).
struct PullOffArenas(Owned<Fx>, Vec<Bond<Fx>>, Vec<BondBreak<Fx>>);

impl PullOffArenas {
    fn new(scenario: &PullOff) -> Self {
        let cap = scenario.bond_capacity();
        PullOffArenas(
            Owned::with_lengths(scenario.storage_lengths()),
            vec![Bond::default(); cap],
            vec![BondBreak::default(); cap],
        )
    }

    fn world(&mut self, scenario: &PullOff) -> World<'_, Fx> {
        let bonds = BondStorage {
            bonds: &mut self.1,
            log: &mut self.2,
        };
        scenario.build(self.0.storage(), bonds).unwrap()
    }
}

/// The pull-off rig with its bonds formed after the first checkpoint (pending formations),
/// then a second checkpoint after the junction broke (an empty schedule, a logged break).
#[test]
fn bonds_formations_and_breaks_resume_bit_for_bit() {
    let scenario = PullOff {
        // The pod moves off at once: by 3e-5 s it has opened the 1 µm set-up gap to 4 µm,
        // still inside the 5 µm the formation bonds.
        bond_time_s: 3e-5,
        ..PullOff::default()
    };
    let mut a = PullOffArenas::new(&scenario);
    let mut w = a.world(&scenario);
    w.run(30).unwrap();
    let pending = words_of(&mut w);
    let result = scenario.run(&mut w, 20_000, |_, _| {}).unwrap();
    assert!(result.break_step.is_some(), "the junction should break");
    assert_eq!(w.bonds().breaks_total(), 1);
    let broken = words_of(&mut w);
    let broken_digest = w.digest();
    w.run(200).unwrap();
    let end = w.digest();

    let mut b = PullOffArenas::new(&scenario);
    let mut v = b.world(&scenario);
    read(&mut v, &pending).unwrap();
    assert_eq!(scenario.run(&mut v, 20_000, |_, _| {}).unwrap(), result);
    v.run(200).unwrap();
    assert_eq!(v.digest(), end, "resumed before the bonds formed");

    let mut c = PullOffArenas::new(&scenario);
    let mut x = c.world(&scenario);
    read(&mut x, &broken).unwrap();
    assert_eq!(x.digest(), broken_digest, "read after the break");
    assert_eq!(x.bonds().breaks(), w.bonds().breaks());
    x.run(200).unwrap();
    assert_eq!(x.digest(), end, "resumed after the break");
}

#[test]
fn a_world_set_up_differently_is_refused_naming_what_differs() {
    let mut a = owned::<Fx>();
    let mut w = block(&mut a, SIDE * SIDE * LAYERS);
    w.run(10).unwrap();
    let words = words_of(&mut w);
    let mut b = owned::<Fx>();
    let mut v = block(&mut b, SIDE * SIDE * LAYERS - 1);
    let err = read(&mut v, &words).unwrap_err();
    assert_eq!(
        err,
        CheckpointError::Mismatch {
            what: "the body count",
            world: (SIDE * SIDE * LAYERS) as u64,
            checkpoint: (SIDE * SIDE * LAYERS + 1) as u64,
        }
    );
    assert!(err.to_string().contains("the body count"), "{err}");
    // A f64 world cannot read a fixed-point checkpoint.
    let mut c = owned::<f64>();
    let mut x = block(&mut c, SIDE * SIDE * LAYERS);
    assert!(matches!(
        read(&mut x, &words),
        Err(CheckpointError::Mismatch {
            what: "the scalar (1 fixed point, 0 f64)",
            ..
        })
    ));
}

#[test]
fn a_short_or_damaged_stream_is_refused() {
    let mut a = owned::<Fx>();
    let mut w = block(&mut a, SIDE * SIDE * LAYERS);
    w.run(BEFORE).unwrap();
    let words = words_of(&mut w);
    let fresh = || owned::<Fx>();
    let mut b = fresh();
    let mut v = block(&mut b, SIDE * SIDE * LAYERS);
    assert_eq!(
        read(&mut v, &words[..words.len() - 1]),
        Err(CheckpointError::Truncated)
    );
    // Every word set to a sphere id far past the spheres, one at a time, in the list and
    // bond part of the stream: either refused or read as a value a world may hold (a
    // coordinate); never a panic on the next step.
    let mut refused = 0;
    for k in (words.len() / 2..words.len()).step_by(7) {
        let mut damaged = words.clone();
        damaged[k] = 0x3FFF_FFF0;
        let mut c = fresh();
        let mut x = block(&mut c, SIDE * SIDE * LAYERS);
        match read(&mut x, &damaged) {
            Err(CheckpointError::Corrupt { .. } | CheckpointError::Mismatch { .. }) => refused += 1,
            Err(e) => panic!("word {k}: unexpected {e}"),
            Ok(()) => {
                let _ = x.run(3);
            }
        }
    }
    assert!(refused > 0, "no damaged word was refused");
}
