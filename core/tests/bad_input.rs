//! Bad input: each invalid set-up is a typed error with a clear message; a proptest drives
//! random valid and invalid inputs through set-up and a few steps and never sees a panic.

use crate::common;
use arachis_core::error::CapacityKind;
use arachis_core::prelude::*;
use common::*;
use proptest::prelude::*;

fn world_parts() -> Owned<Fx> {
    Owned::<Fx>::new(2, 2)
}

fn msg(e: impl std::fmt::Display) -> String {
    e.to_string()
}

#[test]
fn material_errors() {
    let bad = |e: f64, nu: f64, rho: f64| {
        MaterialSpec {
            youngs_modulus_pa: e,
            poisson: nu,
            density_kg_m3: rho,
        }
        .validate()
    };
    assert!(matches!(
        bad(f64::NAN, 0.3, 1000.0),
        Err(SetupError::NonFinite { .. })
    ));
    assert!(matches!(
        bad(1e9, f64::INFINITY, 1000.0),
        Err(SetupError::NonFinite { .. })
    ));
    assert!(matches!(
        bad(0.0, 0.3, 1000.0),
        Err(SetupError::NonPositiveYoungsModulus { .. })
    ));
    assert!(matches!(
        bad(-5.0, 0.3, 1000.0),
        Err(SetupError::NonPositiveYoungsModulus { .. })
    ));
    for nu in [0.5, 0.7, -1.0, -2.0] {
        assert!(
            matches!(
                bad(1e9, nu, 1000.0),
                Err(SetupError::PoissonOutOfRange { .. })
            ),
            "ν {nu}"
        );
    }
    assert!(bad(1e9, -0.99, 1000.0).is_ok());
    assert!(matches!(
        bad(1e9, 0.3, 0.0),
        Err(SetupError::NonPositiveDensity { .. })
    ));
    let m = msg(bad(1e9, 0.7, 1.0).unwrap_err());
    assert!(m.contains("Poisson") && m.contains("0.7"), "{m}");
    let m = msg(bad(-1.0, 0.3, 1.0).unwrap_err());
    assert!(m.contains("Young") && m.contains("-1"), "{m}");
}

#[test]
fn pair_errors() {
    for e in [0.0, -0.1, 1.0001, 2.0] {
        let r = PairSpec::hertz_mindlin(e, 0.5, 0.1).validate();
        assert!(
            matches!(r, Err(SetupError::RestitutionOutOfRange { .. })),
            "e {e}"
        );
        assert!(msg(r.unwrap_err()).contains("restitution"));
    }
    assert!(PairSpec::hertz_mindlin(1.0, 0.0, 0.0).validate().is_ok());
    assert!(matches!(
        PairSpec::hertz_mindlin(0.5, -0.1, 0.1).validate(),
        Err(SetupError::NegativeFriction {
            what: "sliding",
            ..
        })
    ));
    assert!(matches!(
        PairSpec::hertz_mindlin(0.5, 0.1, -0.1).validate(),
        Err(SetupError::NegativeFriction {
            what: "rolling",
            ..
        })
    ));
    assert!(matches!(
        PairSpec::hertz_mindlin(f64::NAN, 0.1, 0.1).validate(),
        Err(SetupError::NonFinite { .. })
    ));
}

#[test]
fn body_and_capacity_errors() {
    let mut o = world_parts();
    let mut w = World::new(o.storage()).unwrap();
    let pod = w.add_material(POD).unwrap();
    // Unknown material.
    assert!(matches!(
        w.add_sphere(SphereSpec::at_rest(MaterialId(7), 0.004, [0.0; 3])),
        Err(SetupError::UnknownMaterial { id: 7 })
    ));
    for r in [0.0, -0.001] {
        let e = w
            .add_sphere(SphereSpec::at_rest(pod, r, [0.0; 3]))
            .unwrap_err();
        assert!(matches!(e, SetupError::NonPositiveRadius { .. }));
        assert!(msg(e).contains("radius"));
    }
    assert!(matches!(
        w.add_sphere(SphereSpec::at_rest(pod, f64::NAN, [0.0; 3])),
        Err(SetupError::NonFinite { .. })
    ));
    assert!(matches!(
        w.add_sphere(SphereSpec::at_rest(pod, 0.004, [0.0, f64::INFINITY, 0.0])),
        Err(SetupError::NonFinite { .. })
    ));
    assert!(matches!(
        w.add_sphere(SphereSpec::at_rest(pod, 0.004, [1e10, 0.0, 0.0])),
        Err(SetupError::NotRepresentable { .. })
    ));
    // Clumps: empty, zero mass, zero inertia.
    assert!(matches!(
        w.add_clump(&ClumpSpec {
            spheres: &[],
            velocity_m_s: [0.0; 3],
            angular_velocity_rad_s: [0.0; 3]
        }),
        Err(SetupError::EmptyClump)
    ));
    let one = [ClumpSphere {
        center_m: [0.0; 3],
        radius_m: 0.004,
        material: pod,
    }];
    let spec = ClumpSpec {
        spheres: &one,
        velocity_m_s: [0.0; 3],
        angular_velocity_rad_s: [0.0; 3],
    };
    let zero = MassProperties {
        mass_kg: 0.0,
        center_of_mass_m: [0.0; 3],
        principal_inertia_kg_m2: [1e-9; 3],
        principal_axes: [1.0, 0.0, 0.0, 0.0],
    };
    let e = w.add_clump_with_mass(&spec, &zero).unwrap_err();
    assert!(matches!(e, SetupError::ZeroMassClump));
    assert!(msg(e).contains("zero mass"));
    let no_inertia = MassProperties {
        mass_kg: 1e-3,
        principal_inertia_kg_m2: [1e-9, 0.0, 1e-9],
        ..zero
    };
    assert!(matches!(
        w.add_clump_with_mass(&spec, &no_inertia),
        Err(SetupError::ZeroMassClump)
    ));
    // Capacity: 2 bodies / 2 spheres.
    w.add_sphere(SphereSpec::at_rest(pod, 0.004, [0.0; 3]))
        .unwrap();
    let two = [
        one[0],
        ClumpSphere {
            center_m: [0.005, 0.0, 0.0],
            ..one[0]
        },
    ];
    let e = w
        .add_clump(&ClumpSpec {
            spheres: &two,
            velocity_m_s: [0.0; 3],
            angular_velocity_rad_s: [0.0; 3],
        })
        .unwrap_err();
    assert!(
        matches!(
            e,
            SetupError::Capacity {
                kind: CapacityKind::Spheres,
                capacity: 2
            }
        ),
        "{e:?}"
    );
    assert!(msg(e).contains("capacity"));
    w.add_sphere(SphereSpec::at_rest(pod, 0.004, [0.01, 0.0, 0.0]))
        .unwrap();
    assert!(matches!(
        w.add_sphere(SphereSpec::at_rest(pod, 0.004, [0.02, 0.0, 0.0])),
        Err(SetupError::Capacity {
            kind: CapacityKind::Bodies,
            ..
        })
    ));
    for _ in 1..8 {
        w.add_material(POD).unwrap();
    }
    assert!(matches!(
        w.add_material(POD),
        Err(SetupError::Capacity {
            kind: CapacityKind::Materials,
            ..
        })
    ));
    let plane = WallSpec::fixed(
        WallGeometry::Plane {
            point_m: [0.0; 3],
            normal: [0.0, 0.0, 1.0],
        },
        pod,
    );
    for _ in 0..16 {
        w.add_wall(plane).unwrap();
    }
    assert!(matches!(
        w.add_wall(plane),
        Err(SetupError::Capacity {
            kind: CapacityKind::Walls,
            ..
        })
    ));
}

#[test]
fn wall_errors() {
    let mut o = world_parts();
    let mut w = World::new(o.storage()).unwrap();
    let m = w.add_material(STEEL).unwrap();
    let bad = |g: WallGeometry| WallSpec::fixed(g, m);
    assert!(matches!(
        w.add_wall(bad(WallGeometry::Plane {
            point_m: [0.0; 3],
            normal: [0.0; 3]
        })),
        Err(SetupError::BadWall { .. })
    ));
    assert!(matches!(
        w.add_wall(bad(WallGeometry::Cylinder {
            base_m: [0.0; 3],
            axis: [0.0, 0.0, 1.0],
            radius_m: -1.0,
            length_m: None
        })),
        Err(SetupError::BadWall { .. })
    ));
    assert!(matches!(
        w.add_wall(bad(WallGeometry::AaBox {
            min_m: [0.0; 3],
            max_m: [1.0, 0.0, 1.0]
        })),
        Err(SetupError::BadWall { .. })
    ));
    assert!(matches!(
        w.add_wall(bad(WallGeometry::Plane {
            point_m: [f64::NAN, 0.0, 0.0],
            normal: [0.0, 0.0, 1.0]
        })),
        Err(SetupError::NonFinite { .. })
    ));
}

#[test]
fn timestep_errors() {
    let mut o = world_parts();
    let mut w = World::new(o.storage()).unwrap();
    assert_eq!(w.step(), Err(StepError::NoTimeStep));
    let pod = w.add_material(POD).unwrap();
    w.add_sphere(SphereSpec::at_rest(pod, 0.004, [0.0; 3]))
        .unwrap();
    let max = w.max_timestep_s();
    let e = w.set_timestep_s(max * 1.01).unwrap_err();
    assert!(matches!(e, SetupError::TimeStepTooLarge { .. }));
    assert!(msg(e).contains("stable bound"));
    assert!(matches!(
        w.set_timestep_s(0.0),
        Err(SetupError::NonPositiveTimeStep { .. })
    ));
    assert!(matches!(
        w.set_timestep_s(f64::NAN),
        Err(SetupError::NonFinite { .. })
    ));
    w.set_timestep_s(max * 0.99).unwrap();
    w.step().unwrap();
    // A smaller sphere added later lowers the bound: step() refuses.
    w.add_sphere(SphereSpec::at_rest(pod, 0.001, [0.1, 0.0, 0.0]))
        .unwrap();
    let e = w.step().unwrap_err();
    assert!(matches!(e, StepError::TimeStepTooLarge { .. }));
    assert!(msg(e).contains("stable bound"));
}

#[test]
fn undefined_pair_is_a_step_error() {
    let mut o = world_parts();
    let mut w = World::new(o.storage()).unwrap();
    let pod = w.add_material(POD).unwrap();
    w.add_sphere(SphereSpec::at_rest(pod, 0.004, [0.0; 3]))
        .unwrap();
    w.add_sphere(SphereSpec::at_rest(pod, 0.004, [0.007, 0.0, 0.0]))
        .unwrap();
    w.set_timestep_s(1e-5).unwrap();
    let e = w.step().unwrap_err();
    assert_eq!(
        e,
        StepError::UndefinedPair {
            material_a: 0,
            material_b: 0
        }
    );
    assert!(msg(e).contains("no pair parameters"));
}

#[test]
fn overflow_is_reported_not_wrapped() {
    // A sphere at 5e8 m/s leaves the Q32.32 position range (±2.1e9 mm) after ~430 steps.
    let mut o = world_parts();
    let mut w = World::new(o.storage()).unwrap();
    let pod = w.add_material(POD).unwrap();
    w.set_pair(pod, pod, PairSpec::hertz_mindlin(0.5, 0.5, 0.1))
        .unwrap();
    let mut a = SphereSpec::at_rest(pod, 0.004, [0.0; 3]);
    a.velocity_m_s = [5e8, 0.0, 0.0];
    w.add_sphere(a).unwrap();
    w.set_timestep_s(1e-5).unwrap();
    let mut err = None;
    for _ in 0..1000 {
        if let Err(e) = w.step() {
            err = Some(e);
            break;
        }
    }
    let e = err.expect("overflow must be reported");
    assert!(
        matches!(
            e,
            StepError::Overflow {
                stage: arachis_core::error::Stage::Integration,
                body: 0,
                ..
            }
        ),
        "{e:?}"
    );
    assert!(
        w.step_count() > 400 && w.step_count() < 440,
        "{}",
        w.step_count()
    );
    assert!(msg(e).contains("overflow"));
}

/// Two spheres of `radius_m` whose centres lie `gap_m` apart along x, the second moving at
/// `vy_m_s` along y, under `pair`, after one step: the step's result.
fn one_contact_step(
    material: MaterialSpec,
    pair: PairSpec,
    radius_m: f64,
    gap_m: f64,
    vy_m_s: f64,
) -> Result<(), StepError> {
    let mut o = world_parts();
    let mut w = World::new(o.storage()).unwrap();
    let m = w.add_material(material).unwrap();
    w.set_pair(m, m, pair).unwrap();
    w.add_sphere(SphereSpec::at_rest(m, radius_m, [0.0; 3]))
        .unwrap();
    let mut b = SphereSpec::at_rest(m, radius_m, [gap_m, 0.0, 0.0]);
    b.velocity_m_s = [0.0, vy_m_s, 0.0];
    w.add_sphere(b).unwrap();
    w.set_timestep_s(1e-7).unwrap();
    w.step()
}

/// A contact force beyond the Q32.32 range must fail the step, not be swallowed by a branch:
/// the no-attraction clip once turned an overflowed normal force (the poison value, the most
/// negative integer) into 0, and the Coulomb test turned an overflowed μs·Fn into "no
/// tangential force", so two spheres passed through each other without a word.
#[test]
fn an_overflowed_contact_force_is_reported_not_clipped_away() {
    // Stiff spheres of R 100 mm overlapping by 100 mm: (4/3)E*·a·α = 7.3e5 MPa · 70.7 mm ·
    // 100 mm = 5.2e9 N, beyond 2^31 N (and (4/3)E* beyond the fused law's envelope, so the
    // terms evaluate it).
    let stiff = MaterialSpec {
        youngs_modulus_pa: 1e12,
        poisson: 0.3,
        density_kg_m3: 7800.0,
    };
    let e =
        one_contact_step(stiff, PairSpec::hertz_mindlin(0.5, 0.5, 0.1), 0.1, 0.1, 0.0).unwrap_err();
    assert!(
        matches!(
            e,
            StepError::Overflow {
                stage: arachis_core::error::Stage::SphereContact,
                ..
            }
        ),
        "{e:?}"
    );
    // Pods overlapping by 0.5 mm (Fn ≈ 3.3 N) sliding at 1 m/s with μs = 1e9: μs·Fn = 3.3e9 N
    // is beyond the range (μs > 4 is outside the fused law's envelope).
    let e = one_contact_step(
        POD,
        PairSpec::hertz_mindlin(0.5, 1e9, 0.1),
        0.004,
        0.0075,
        1.0,
    )
    .unwrap_err();
    assert!(
        matches!(
            e,
            StepError::Overflow {
                stage: arachis_core::error::Stage::SphereContact,
                ..
            }
        ),
        "{e:?}"
    );
    // Contacts of the same laws in range step without error (stiff spheres of R 4 mm
    // overlapping by 1 µm: 33 N; the pods with μs = 1e3: μs·Fn = 3.3e3 N).
    one_contact_step(
        stiff,
        PairSpec::hertz_mindlin(0.5, 0.5, 0.1),
        0.004,
        0.007999,
        0.0,
    )
    .unwrap();
    one_contact_step(
        POD,
        PairSpec::hertz_mindlin(0.5, 1e3, 0.1),
        0.004,
        0.0075,
        1.0,
    )
    .unwrap();
}

fn any_f64() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => -1.0f64..1.0,
        2 => -1e12f64..1e12,
        1 => Just(f64::NAN),
        1 => Just(f64::INFINITY),
        1 => Just(0.0),
        1 => Just(1e-300),
    ]
}

proptest! {
    // 96 cases by default (fast in debug CI); PROPTEST_CASES raises it for longer runs.
    #![proptest_config(ProptestConfig {
        cases: std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(96),
        ..ProptestConfig::default()
    })]
    #[test]
    fn random_setup_and_steps_never_panic(
        e_pa in prop_oneof![Just(8.43e6), any_f64().prop_map(|x| x * 1e9)],
        nu in prop_oneof![Just(0.3), any_f64()],
        rho in prop_oneof![Just(582.0), any_f64().prop_map(|x| x * 1e4)],
        rest in prop_oneof![Just(0.5), any_f64()],
        mu in prop_oneof![Just(0.5), any_f64()],
        mur in prop_oneof![Just(0.1), any_f64()],
        spheres in prop::collection::vec((any_f64(), any_f64(), any_f64(), any_f64(), any_f64()), 0..6),
        wall_kind in 0u8..4,
        wall_v in any_f64(),
        dt in prop_oneof![Just(1e-6), any_f64().prop_map(|x| x.abs() * 1e-4)],
        fixed in any::<bool>(),
    ) {
        #[allow(clippy::too_many_arguments)]
        fn go<S: Scalar>(
            e_pa: f64, nu: f64, rho: f64, rest: f64, mu: f64, mur: f64,
            spheres: &[(f64, f64, f64, f64, f64)], wall_kind: u8, wall_v: f64, dt: f64,
        ) {
            let mut o = Owned::<S>::new(4, 4);
            let mut w = World::new(o.storage()).unwrap();
            let Ok(m) = w.add_material(MaterialSpec { youngs_modulus_pa: e_pa, poisson: nu, density_kg_m3: rho }) else { return };
            let _ = w.set_pair(m, m, PairSpec::hertz_mindlin(rest, mu, mur));
            let _ = w.set_gravity_m_s2([0.0, 0.0, -9.81]);
            let geom = match wall_kind {
                0 => WallGeometry::Plane { point_m: [0.0; 3], normal: [0.0, wall_v, 1.0] },
                1 => WallGeometry::Cylinder { base_m: [0.0; 3], axis: [0.0, 0.0, 1.0], radius_m: 0.01 + wall_v.abs(), length_m: Some(0.05) },
                2 => WallGeometry::AaBox { min_m: [-0.01; 3], max_m: [0.01, 0.01, 0.01 + wall_v.abs()] },
                _ => WallGeometry::Cylinder { base_m: [0.0; 3], axis: [wall_v, 0.0, 1.0], radius_m: 0.02, length_m: None },
            };
            let _ = w.add_wall(WallSpec { geometry: geom, material: m, velocity_m_s: [0.0, 0.0, wall_v] });
            for &(x, y, z, r, v) in spheres {
                let mut s = SphereSpec::at_rest(m, r.abs() * 0.01, [x * 0.01, y * 0.01, z * 0.01]);
                s.velocity_m_s = [v, -v, v * 10.0];
                s.angular_velocity_rad_s = [v * 100.0, 0.0, 0.0];
                let _ = w.add_sphere(s);
            }
            if spheres.len() >= 2 {
                let c = [
                    ClumpSphere { center_m: [0.0, 0.0, 0.02], radius_m: 0.003, material: m },
                    ClumpSphere { center_m: [spheres[0].0 * 0.004, 0.0, 0.02], radius_m: 0.003, material: m },
                ];
                let _ = w.add_clump(&ClumpSpec { spheres: &c, velocity_m_s: [spheres[1].4, 0.0, 0.0], angular_velocity_rad_s: [0.0, spheres[1].3, 0.0] });
            }
            if w.set_timestep_s(dt).is_err() {
                let _ = w.set_timestep_s(w.max_timestep_s() * 0.5);
            }
            for _ in 0..20 {
                if w.step().is_err() {
                    break;
                }
            }
            let _ = w.digest();
            let _: Vec<String> = w.body_records().map(|r| r.to_string()).collect();
        }
        if fixed {
            go::<Fx>(e_pa, nu, rho, rest, mu, mur, &spheres, wall_kind, wall_v, dt);
        } else {
            go::<f64>(e_pa, nu, rho, rest, mu, mur, &spheres, wall_kind, wall_v, dt);
        }
    }
}
