//! Single contacts, Arachis beside LIGGGHTS 3.8 (issue 18), to 0.5 %.
//!
//! Runs the cases of `benches/liggghts/contacts/*.in` in Arachis (fixed point, [`Fx`]) with
//! [`Conventions::LIGGGHTS`] and compares them with the LIGGGHTS traces found in the directory
//! named by `ARACHIS_LIGGGHTS_RESULTS` (one `<case>.txt` per case, written by
//! `scripts/cross-check-contacts.sh`); each quantity must agree within [`TOLERANCE`] of
//! LIGGGHTS' value. The same cases run with [`Conventions::EDEM`] too, printed for
//! information only (not asserted), so the table shows what the convention changes.
//! `#[ignore]`d: it needs LIGGGHTS' output. Without the variable it prints a message and passes.
//!
//! Cases (every one: sphere radius 10 mm, density 2500 kg/m³, E 5e7 Pa, ν 0.3 for sphere,
//! wall and fixed sphere; e 0.5, μs 0.3, μr 0.1 unless said):
//! 1. `normal_0.5`, `normal_1`, `normal_2`: normal impact on a plane wall at 0.5, 1, 2 m/s, no
//!    gravity; the rebound speed ratio vz/|vz0| (also against an independent integration of the
//!    clipped normal law, [`common::restitution_reference`]).
//! 2. `oblique_0.5`, `oblique_3`: impact at vz0 = −1 m/s with vx0 = 0.5 m/s (sticks, then
//!    slides) and 3 m/s (slides throughout); vx, vz and ω_y after the contact.
//! 3. `rolling_plate`: rolling without slip on a plate at 0.1 m/s under gravity until CDT
//!    rolling friction stops it; stopping time and distance (where vx first reaches 0).
//! 4. `spin_on_sphere`: a sphere resting on a fixed sphere spins down about the horizontal y
//!    axis from 10 rad/s under CDT rolling friction alone (μs 0, no tangential damping); the
//!    spin-down rate (least-squares slope of ω_y while 0.9 ω0 ≥ ω_y ≥ 0.1 ω0) and the time
//!    ω_y first reaches 0. (LIGGGHTS computes a run's set-up force without updating the
//!    tangential history, so a contact slipping at step 0 gets −γt·vt whatever μs; the deck
//!    turns tangential damping off, and the rolling case starts without slip, to avoid it.)
//! 5. `sphere_1`: case 1 at 1 m/s on a fixed sphere of the same size instead of the wall; the
//!    rebound ratio. With this damping law the ratio depends on β and on m*/m alone, so it
//!    checks that a fixed partner gives m* = m as a wall does (LIGGGHTS' `fix freeze`).
//! 6. `rolling_plate_epsd2`, `spin_on_sphere_epsd2`: cases 3 and 4 with LIGGGHTS'
//!    `rolling_friction epsd2` ([`RollingConvention::LiggghtsEpsd2`]; the decks'
//!    `-var rolling epsd2`); once the spin has stopped, the sphere on the fixed sphere rocks on
//!    the rolling spring, and its period (from ω_y's sign changes) is compared too.
//!
//! Units: the table prints SI (m, s, m/s, rad/s); inside the core, mm, g, ms (velocities in
//! mm/ms = m/s, spins in rad/ms, forces in N). Both engines sample the state at the same step
//! numbers (LIGGGHTS' trace decides which).
//!
//! Conventions (LIGGGHTS 3.8 sources, `src/`): every deck sets `limitForce on`
//! (`normal_model_hertz.h`), so LIGGGHTS clips the normal force at ≥ 0 as Arachis always does;
//! `tangential history` (`tangential_model_history.h`: the spring alone against μs·Fn, no
//! damping while sliding) is Arachis' [`FrictionConvention::Liggghts`]; `rolling_friction cdt`
//! (`rolling_model_cdt.h`: μr·kn·δn·R*, relative spin, no torsion) is
//! [`RollingConvention::LiggghtsCdt`]; Y*, G*, β as `global_properties.cpp`; lever R − δn/2
//! (`surface_model_default.h`); a wall has R* = R, m* = m (`fix_wall_gran_base.h`); a frozen
//! partner gives m* = m of the other (`pair_gran_base.h`, `fix freeze`). Both integrators
//! produce the same positions step for step (`fix_nve_sphere.cpp`' velocity Verlet and
//! Arachis' kick-drift leapfrog); LIGGGHTS prints full-step velocities, Arachis half-step ones,
//! which differ by a·dt/2 (nothing out of contact without gravity; a 5e-6 s shift of a stopping
//! time of 0.1 s).
//!
//! Run: `scripts/cross-check-contacts.sh`, or by hand
//! `ARACHIS_LIGGGHTS_RESULTS=dir cargo test --release -p arachis-core --test scenarios cross_check_liggghts:: -- --ignored --nocapture`.

use crate::common;
use arachis_core::prelude::*;
use common::Owned;
use std::collections::HashMap;
use std::path::Path;

/// Largest accepted |Arachis − LIGGGHTS| / |LIGGGHTS| of every quantity (issue 18: 0.5 %).
const TOLERANCE: f64 = 0.005;
/// The environment variable naming the directory of LIGGGHTS' traces.
const RESULTS_VAR: &str = "ARACHIS_LIGGGHTS_RESULTS";

/// Sphere (and fixed sphere) radius, m.
const RADIUS_M: f64 = 0.01;
/// Density of the spheres, kg/m³.
const DENSITY: f64 = 2500.0;
/// Young's modulus of spheres and wall, Pa.
const YOUNGS_PA: f64 = 5e7;
/// Poisson's ratio of spheres and wall.
const POISSON: f64 = 0.3;
/// Coefficient of restitution of every pair.
const RESTITUTION: f64 = 0.5;
/// Sliding friction coefficient (cases 1–3).
const FRICTION: f64 = 0.3;
/// Rolling friction coefficient.
const ROLLING_FRICTION: f64 = 0.1;
/// Gravity, m/s² along −z (cases 3 and 4).
const GRAVITY: f64 = 9.81;
/// Initial gap between sphere and wall in the impacts, m (impact.in `gap`).
const IMPACT_GAP_M: f64 = 1e-5;
/// Time step of the impacts, s: over 1 000 steps per contact (t_c 1.07–1.41 ms).
const IMPACT_DT_S: f64 = 1e-6;
/// Steps of an impact: 2.5 ms, the contact plus at least 1 ms of free flight.
const IMPACT_STEPS: u64 = 2500;
/// Time step of the resting cases, s: 500 steps per normal oscillation period (5 ms).
const REST_DT_S: f64 = 1e-5;
/// Steps of the rolling case: 0.2 s, 1.4× the stopping time 0.143 s.
const ROLLING_STEPS: u64 = 20_000;
/// Initial speed of the rolling case, m/s.
const ROLLING_V0: f64 = 0.1;
/// Steps of the spin case: 0.12 s, 1.5× the stopping time 0.0815 s.
const SPIN_STEPS: u64 = 12_000;
/// Initial spin of the spin case, rad/s about +y.
const SPIN_W0: f64 = 10.0;
/// Spin-down rate fit window: ω_y between these fractions of ω0.
const SPIN_FIT_WINDOW: (f64, f64) = (0.1, 0.9);
/// Position tolerance of the initial-state check, m (LIGGGHTS prints 15 digits; Arachis
/// quantises to 2⁻³² mm).
const START_TOLERANCE_M: f64 = 1e-12;

/// What a case sets up (the decks of `benches/liggghts/contacts/`).
#[derive(Clone, Copy, Debug)]
enum Setup {
    /// A sphere `gap` above a plane wall moving at (vx0, 0, vz0), m/s, no gravity.
    Impact { vx0: f64, vz0: f64 },
    /// A sphere on a plate at its equilibrium overlap rolling at v0, m/s, under gravity.
    Rolling { v0: f64 },
    /// A sphere on a fixed sphere at equilibrium, spinning at w0, rad/s, about +y.
    Spin { w0: f64 },
    /// A sphere `gap` above a fixed sphere moving at (0, 0, vz0), m/s, no gravity.
    ImpactOnSphere { vz0: f64 },
}

/// One cross-check case: its name (the trace file stem), set-up, step, step count and the
/// LIGGGHTS rolling model its deck ran (`cdt`, or `epsd2` by `-var rolling epsd2`).
struct Case {
    name: &'static str,
    setup: Setup,
    dt_s: f64,
    steps: u64,
    rolling: RollingConvention,
}

impl Case {
    /// The LIGGGHTS conventions Arachis runs this case in.
    fn conventions(&self) -> Conventions {
        Conventions {
            rolling: self.rolling,
            ..Conventions::LIGGGHTS
        }
    }

    /// The deck's name of its rolling model (`param rolling_model`).
    fn rolling_model(&self) -> &'static str {
        match self.rolling {
            RollingConvention::LiggghtsEpsd2 => "epsd2",
            _ => "cdt",
        }
    }
}

const CASES: &[Case] = &[
    Case {
        name: "normal_0.5",
        setup: Setup::Impact {
            vx0: 0.0,
            vz0: -0.5,
        },
        dt_s: IMPACT_DT_S,
        steps: IMPACT_STEPS,
        rolling: RollingConvention::LiggghtsCdt,
    },
    Case {
        name: "normal_1",
        setup: Setup::Impact {
            vx0: 0.0,
            vz0: -1.0,
        },
        dt_s: IMPACT_DT_S,
        steps: IMPACT_STEPS,
        rolling: RollingConvention::LiggghtsCdt,
    },
    Case {
        name: "normal_2",
        setup: Setup::Impact {
            vx0: 0.0,
            vz0: -2.0,
        },
        dt_s: IMPACT_DT_S,
        steps: IMPACT_STEPS,
        rolling: RollingConvention::LiggghtsCdt,
    },
    Case {
        name: "oblique_0.5",
        setup: Setup::Impact {
            vx0: 0.5,
            vz0: -1.0,
        },
        dt_s: IMPACT_DT_S,
        steps: IMPACT_STEPS,
        rolling: RollingConvention::LiggghtsCdt,
    },
    Case {
        name: "oblique_3",
        setup: Setup::Impact {
            vx0: 3.0,
            vz0: -1.0,
        },
        dt_s: IMPACT_DT_S,
        steps: IMPACT_STEPS,
        rolling: RollingConvention::LiggghtsCdt,
    },
    Case {
        name: "rolling_plate",
        setup: Setup::Rolling { v0: ROLLING_V0 },
        dt_s: REST_DT_S,
        steps: ROLLING_STEPS,
        rolling: RollingConvention::LiggghtsCdt,
    },
    Case {
        name: "rolling_plate_epsd2",
        setup: Setup::Rolling { v0: ROLLING_V0 },
        dt_s: REST_DT_S,
        steps: ROLLING_STEPS,
        rolling: RollingConvention::LiggghtsEpsd2,
    },
    Case {
        name: "spin_on_sphere",
        setup: Setup::Spin { w0: SPIN_W0 },
        dt_s: REST_DT_S,
        steps: SPIN_STEPS,
        rolling: RollingConvention::LiggghtsCdt,
    },
    Case {
        name: "spin_on_sphere_epsd2",
        setup: Setup::Spin { w0: SPIN_W0 },
        dt_s: REST_DT_S,
        steps: SPIN_STEPS,
        rolling: RollingConvention::LiggghtsEpsd2,
    },
    Case {
        name: "sphere_1",
        setup: Setup::ImpactOnSphere { vz0: -1.0 },
        dt_s: IMPACT_DT_S,
        steps: IMPACT_STEPS,
        rolling: RollingConvention::LiggghtsCdt,
    },
];

/// The state of the sphere at one step, SI: time s, position m, velocity m/s, spin rad/s.
#[derive(Clone, Copy, Debug, Default)]
struct Row {
    step: u64,
    t: f64,
    x: [f64; 3],
    v: [f64; 3],
    w: [f64; 3],
}

/// A LIGGGHTS trace: its `param` lines and rows.
struct Trace {
    params: HashMap<String, String>,
    rows: Vec<Row>,
}

fn read_trace(path: &Path) -> Trace {
    let text = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("cannot read LIGGGHTS trace {}: {e}", path.display()));
    let mut params = HashMap::new();
    let mut rows = Vec::new();
    for line in text.lines() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') || line.starts_with("columns") {
            continue;
        }
        if let Some(p) = line.strip_prefix("param ") {
            let (k, v) = p.split_once(' ').expect("param NAME VALUE");
            params.insert(k.to_string(), v.trim().to_string());
            continue;
        }
        let f: Vec<f64> = line
            .split_whitespace()
            .map(|s| s.parse().unwrap_or_else(|_| panic!("bad number {s:?}")))
            .collect();
        assert_eq!(f.len(), 11, "{}: bad row {line:?}", path.display());
        rows.push(Row {
            step: f[0] as u64,
            t: f[1],
            x: [f[2], f[3], f[4]],
            v: [f[5], f[6], f[7]],
            w: [f[8], f[9], f[10]],
        });
    }
    Trace { params, rows }
}

/// Refuse a trace whose LIGGGHTS parameters differ from this test's: the comparison would be
/// of different cases.
fn check_params(case: &Case, tr: &Trace) {
    let num = |k: &str| -> f64 {
        tr.params
            .get(k)
            .unwrap_or_else(|| panic!("{}: no param {k}", case.name))
            .parse()
            .unwrap_or_else(|_| panic!("{}: param {k} not a number", case.name))
    };
    let friction = match case.setup {
        Setup::Spin { .. } => 0.0,
        _ => FRICTION,
    };
    let mut expected = vec![
        ("radius_m", RADIUS_M),
        ("density_kg_m3", DENSITY),
        ("youngs_pa", YOUNGS_PA),
        ("poisson", POISSON),
        ("restitution", RESTITUTION),
        ("friction", friction),
        ("rolling_friction", ROLLING_FRICTION),
        ("dt_s", case.dt_s),
    ];
    match case.setup {
        Setup::Impact { vx0, vz0 } => {
            expected.extend([("vx0_m_s", vx0), ("vz0_m_s", vz0), ("gap_m", IMPACT_GAP_M)])
        }
        Setup::Rolling { v0 } => expected.extend([("v0_m_s", v0), ("gravity_m_s2", GRAVITY)]),
        Setup::Spin { w0 } => expected.extend([("w0_rad_s", w0), ("gravity_m_s2", GRAVITY)]),
        Setup::ImpactOnSphere { vz0 } => {
            expected.extend([("vz0_m_s", vz0), ("gap_m", IMPACT_GAP_M)])
        }
    }
    for (k, want) in expected {
        let got = num(k);
        assert!(
            (got - want).abs() <= 1e-12 * want.abs().max(1.0),
            "{}: LIGGGHTS ran with {k} = {got}, this test expects {want}",
            case.name
        );
    }
    assert_eq!(
        tr.params.get("rolling_model").map(String::as_str),
        Some(case.rolling_model()),
        "{}: LIGGGHTS ran another rolling model",
        case.name
    );
    assert_eq!(
        tr.params.get("limit_force").map(String::as_str),
        Some("on"),
        "{}: LIGGGHTS must run with limitForce on",
        case.name
    );
    let last = tr.rows.last().expect("empty trace");
    assert_eq!(last.step, case.steps, "{}: trace ends early", case.name);
}

/// E* of two bodies of the one material, Pa (DESIGN §2).
fn e_star_pa() -> f64 {
    YOUNGS_PA / (2.0 * (1.0 - POISSON * POISSON))
}

/// Sphere mass, kg.
fn mass_kg() -> f64 {
    4.0 / 3.0 * std::f64::consts::PI * RADIUS_M.powi(3) * DENSITY
}

/// Hertz equilibrium overlap under the sphere's weight for effective radius `r_star`, m:
/// m·g = (4/3)E*·√R*·α^{3/2} (the decks' `alpha`).
fn equilibrium_overlap_m(r_star: f64) -> f64 {
    (mass_kg() * GRAVITY / (4.0 / 3.0 * e_star_pa() * r_star.sqrt())).powf(2.0 / 3.0)
}

/// Run `case` in Arachis with `conventions`, sampling the moving sphere at `steps`.
fn run_arachis(case: &Case, conventions: Conventions, steps: &[u64]) -> Vec<Row> {
    let mut o = Owned::<Fx>::new(2, 2);
    let mut w = World::new(o.storage()).unwrap();
    let m = w
        .add_material(MaterialSpec {
            youngs_modulus_pa: YOUNGS_PA,
            poisson: POISSON,
            density_kg_m3: DENSITY,
        })
        .unwrap();
    let mut pair = PairSpec::hertz_mindlin(RESTITUTION, FRICTION, ROLLING_FRICTION);
    let r = RADIUS_M;
    match case.setup {
        Setup::Impact { vx0, vz0 } => {
            common::add_floor(&mut w, m);
            let mut s = SphereSpec::at_rest(m, r, [0.0, 0.0, r + IMPACT_GAP_M]);
            s.velocity_m_s = [vx0, 0.0, vz0];
            w.add_sphere(s).unwrap();
        }
        Setup::Rolling { v0 } => {
            common::add_floor(&mut w, m);
            w.set_gravity_m_s2([0.0, 0.0, -GRAVITY]).unwrap();
            let alpha = equilibrium_overlap_m(r);
            let mut s = SphereSpec::at_rest(m, r, [0.0, 0.0, r - alpha]);
            s.velocity_m_s = [v0, 0.0, 0.0];
            // Rolling without slip about the contact point, lever R − α/2.
            s.angular_velocity_rad_s = [0.0, v0 / (r - alpha / 2.0), 0.0];
            w.add_sphere(s).unwrap();
        }
        Setup::Spin { w0 } => {
            // μs 0 and no tangential damping: no tangential force (spin_on_sphere.in).
            pair.friction = 0.0;
            pair.terms.tangential_damping = false;
            w.set_gravity_m_s2([0.0, 0.0, -GRAVITY]).unwrap();
            let alpha = equilibrium_overlap_m(r / 2.0);
            let mut s = SphereSpec::at_rest(m, r, [0.0, 0.0, 2.0 * r - alpha]);
            s.angular_velocity_rad_s = [0.0, w0, 0.0];
            w.add_sphere(s).unwrap();
            let fixed = w.add_sphere(SphereSpec::at_rest(m, r, [0.0; 3])).unwrap();
            w.set_body_kinematic(fixed).unwrap();
        }
        Setup::ImpactOnSphere { vz0 } => {
            let mut s = SphereSpec::at_rest(m, r, [0.0, 0.0, 2.0 * r + IMPACT_GAP_M]);
            s.velocity_m_s = [0.0, 0.0, vz0];
            w.add_sphere(s).unwrap();
            let fixed = w.add_sphere(SphereSpec::at_rest(m, r, [0.0; 3])).unwrap();
            w.set_body_kinematic(fixed).unwrap();
        }
    }
    w.set_pair(m, m, pair.with_conventions(conventions))
        .unwrap();
    w.set_timestep_s(case.dt_s).unwrap();
    let mut rows = Vec::with_capacity(steps.len());
    let mut done = 0u64;
    for &s in steps {
        w.run(s - done).unwrap();
        done = s;
        let b = w.body(BodyId(0));
        let mm = |p: [f64; 3]| p.map(|c| c * 1e-3);
        rows.push(Row {
            step: s,
            t: s as f64 * case.dt_s,
            x: mm(b.position.to_f64()),
            v: b.velocity.to_f64(),
            w: b.angular_velocity.to_f64().map(|c| c * 1e3),
        });
    }
    rows
}

/// One compared quantity of a case: its name, unit and value per engine.
struct Quantity {
    name: &'static str,
    unit: &'static str,
    value: f64,
}

/// The first time `f(row)` reaches 0 from above, linearly interpolated between samples, with
/// the row pair's interpolation weight; `None` if it never does.
fn first_zero(rows: &[Row], f: impl Fn(&Row) -> f64) -> Option<(f64, usize, f64)> {
    rows.windows(2).enumerate().find_map(|(k, p)| {
        let (a, b) = (f(&p[0]), f(&p[1]));
        (a > 0.0 && b <= 0.0).then(|| {
            let s = a / (a - b);
            (p[0].t + s * (p[1].t - p[0].t), k, s)
        })
    })
}

/// The quantities of `case` read off a trace (the same code for both engines).
fn quantities(case: &Case, rows: &[Row]) -> Vec<Quantity> {
    let last = rows.last().unwrap();
    let setup = match case.setup {
        // The same quantity as a normal impact on the wall, one radius higher.
        Setup::ImpactOnSphere { vz0 } => Setup::Impact { vx0: 0.0, vz0 },
        s => s,
    };
    let touch_z = match case.setup {
        Setup::ImpactOnSphere { .. } => 2.0 * RADIUS_M,
        _ => RADIUS_M,
    };
    match setup {
        Setup::Impact { vx0, vz0 } => {
            assert!(
                last.x[2] > touch_z && last.v[2] > 0.0,
                "{}: the sphere has not left the wall by step {} (z {} m, vz {} m/s)",
                case.name,
                last.step,
                last.x[2],
                last.v[2]
            );
            if vx0 == 0.0 {
                vec![Quantity {
                    name: "rebound ratio vz/|vz0|",
                    unit: "",
                    value: last.v[2] / vz0.abs(),
                }]
            } else {
                vec![
                    Quantity {
                        name: "vx after",
                        unit: "m/s",
                        value: last.v[0],
                    },
                    Quantity {
                        name: "vz after",
                        unit: "m/s",
                        value: last.v[2],
                    },
                    Quantity {
                        name: "omega_y after",
                        unit: "rad/s",
                        value: last.w[1],
                    },
                ]
            }
        }
        Setup::Rolling { .. } => {
            let (t, k, s) = first_zero(rows, |r| r.v[0])
                .unwrap_or_else(|| panic!("{}: the sphere never stopped", case.name));
            let x = rows[k].x[0] + s * (rows[k + 1].x[0] - rows[k].x[0]);
            vec![
                Quantity {
                    name: "stopping time",
                    unit: "s",
                    value: t,
                },
                Quantity {
                    name: "stopping distance",
                    unit: "m",
                    value: x - rows[0].x[0],
                },
            ]
        }
        Setup::ImpactOnSphere { .. } => unreachable!("read as an impact"),
        Setup::Spin { w0 } => {
            let (t, _, _) = first_zero(rows, |r| r.w[1])
                .unwrap_or_else(|| panic!("{}: the spin never stopped", case.name));
            let (lo, hi) = (SPIN_FIT_WINDOW.0 * w0, SPIN_FIT_WINDOW.1 * w0);
            let pts: Vec<(f64, f64)> = rows
                .iter()
                .take_while(|r| r.w[1] >= lo)
                .filter(|r| r.w[1] <= hi)
                .map(|r| (r.t, r.w[1]))
                .collect();
            let n = pts.len() as f64;
            let (mt, mw) = pts
                .iter()
                .fold((0.0, 0.0), |(a, b), p| (a + p.0 / n, b + p.1 / n));
            let (sxy, sxx) = pts.iter().fold((0.0, 0.0), |(a, b), p| {
                (a + (p.0 - mt) * (p.1 - mw), b + (p.0 - mt).powi(2))
            });
            let mut q = vec![
                Quantity {
                    name: "spin-down rate",
                    unit: "rad/s2",
                    value: -sxy / sxx,
                },
                Quantity {
                    name: "stopping time",
                    unit: "s",
                    value: t,
                },
            ];
            if case.rolling == RollingConvention::LiggghtsEpsd2 {
                q.push(Quantity {
                    name: "rocking period",
                    unit: "s",
                    value: rocking_period(rows),
                });
            }
            q
        }
    }
}

/// The mean period of ω_y's oscillation after it first reaches 0 (twice the mean spacing of
/// its sign changes, interpolated), s; NaN without two sign changes (a spin that stays
/// stopped, as EDEM's rolling friction leaves it).
fn rocking_period(rows: &[Row]) -> f64 {
    let crossings: Vec<f64> = rows
        .windows(2)
        .filter_map(|p| {
            let (a, b) = (p[0].w[1], p[1].w[1]);
            ((a > 0.0) != (b > 0.0)).then(|| p[0].t + a / (a - b) * (p[1].t - p[0].t))
        })
        .collect();
    match crossings.as_slice() {
        [first, .., last] => 2.0 * (last - first) / (crossings.len() - 1) as f64,
        _ => f64::NAN,
    }
}

/// Closed-form values in LIGGGHTS' convention where one exists (for information):
/// restitution by [`common::restitution_reference`] (the clipped normal law integrated
/// in f64), rolling 0.7·v0²/(μr·g) and 1.4·v0/(μr·g) (DESIGN §7; wall R* = R), spin-down
/// μr·g·R*/(0.4·R²) with R* = R/2, and `epsd2`'s rocking period 2π·√(I/(8G*·a·R*²)).
fn theory(case: &Case, q: &str) -> Option<f64> {
    match (case.setup, q) {
        (
            Setup::Impact { vx0: 0.0, vz0 } | Setup::ImpactOnSphere { vz0 },
            "rebound ratio vz/|vz0|",
        ) => {
            // Units mm, g, ms, MPa; the ratio does not depend on R* (nor on m*, E*, v).
            let m_g = mass_kg() * 1e3;
            let v = vz0.abs();
            let e_star_mpa = e_star_pa() * 1e-6;
            Some(common::restitution_reference(m_g, RADIUS_M * 1e3, e_star_mpa, RESTITUTION, v) / v)
        }
        (Setup::Rolling { v0 }, "stopping time") => Some(1.4 * v0 / (ROLLING_FRICTION * GRAVITY)),
        (Setup::Rolling { v0 }, "stopping distance") => {
            Some(0.7 * v0 * v0 / (ROLLING_FRICTION * GRAVITY))
        }
        (Setup::Spin { .. }, "spin-down rate") => {
            Some(ROLLING_FRICTION * GRAVITY * (RADIUS_M / 2.0) / (0.4 * RADIUS_M * RADIUS_M))
        }
        (Setup::Spin { .. }, "rocking period") => {
            // 2π·√(I/k_r), k_r = 8G*·a·R*² at the equilibrium overlap (rolling_model_epsd2.h).
            let r_star = RADIUS_M / 2.0;
            let g_star = YOUNGS_PA / (2.0 * (1.0 + POISSON)) / (2.0 * (2.0 - POISSON));
            let a = (r_star * equilibrium_overlap_m(r_star)).sqrt();
            let k_r = 8.0 * g_star * a * r_star * r_star;
            let inertia = 0.4 * mass_kg() * RADIUS_M * RADIUS_M;
            Some(2.0 * std::f64::consts::PI * (inertia / k_r).sqrt())
        }
        (Setup::Spin { w0 }, "stopping time") => {
            Some(w0 * 0.4 * RADIUS_M * RADIUS_M / (ROLLING_FRICTION * GRAVITY * (RADIUS_M / 2.0)))
        }
        _ => None,
    }
}

/// The initial state of Arachis' run must be LIGGGHTS' row 0 (same case, same start).
fn check_start(case: &Case, lg: &Row, ar: &Row) {
    for d in 0..3 {
        assert!(
            (lg.x[d] - ar.x[d]).abs() <= START_TOLERANCE_M,
            "{}: start position differs: LIGGGHTS {:?}, Arachis {:?}",
            case.name,
            lg.x,
            ar.x
        );
    }
}

#[test]
#[ignore = "needs LIGGGHTS traces: run scripts/cross-check-contacts.sh"]
fn single_contacts_match_liggghts() {
    let Some(dir) = std::env::var_os(RESULTS_VAR) else {
        println!(
            "{RESULTS_VAR} is not set: skipping the LIGGGHTS cross-check \
             (scripts/cross-check-contacts.sh runs LIGGGHTS and sets it)"
        );
        return;
    };
    let dir = Path::new(&dir);
    println!(
        "Single contacts: Arachis (fixed point) against LIGGGHTS 3.8 with limitForce on; \
         tolerance {:.1} % of LIGGGHTS' value",
        TOLERANCE * 100.0
    );
    println!(
        "{:<21} {:<23} {:>6} {:>14} {:>14} {:>9} {:>4} {:>14} {:>9} {:>14}",
        "case",
        "quantity",
        "unit",
        "LIGGGHTS",
        "Arachis-LIG",
        "diff %",
        "ok",
        "Arachis-EDEM",
        "diff %",
        "theory-LIG"
    );
    let mut failures = Vec::new();
    for case in CASES {
        let tr = read_trace(&dir.join(format!("{}.txt", case.name)));
        check_params(case, &tr);
        let steps: Vec<u64> = tr.rows.iter().map(|r| r.step).collect();
        let lig = run_arachis(case, case.conventions(), &steps);
        let edem = run_arachis(case, Conventions::EDEM, &steps);
        check_start(case, &tr.rows[0], &lig[0]);
        let (ql, qa, qe) = (
            quantities(case, &tr.rows),
            quantities(case, &lig),
            quantities(case, &edem),
        );
        for ((l, a), e) in ql.iter().zip(&qa).zip(&qe) {
            let rel = |x: f64| (x - l.value) / l.value.abs();
            let ok = rel(a.value).abs() <= TOLERANCE;
            let th = theory(case, l.name).map_or("-".to_string(), |v| format!("{v:.8}"));
            println!(
                "{:<21} {:<23} {:>6} {:>14.8} {:>14.8} {:>+9.4} {:>4} {:>14.8} {:>+9.4} {:>14}",
                case.name,
                l.name,
                l.unit,
                l.value,
                a.value,
                100.0 * rel(a.value),
                if ok { "yes" } else { "NO" },
                e.value,
                100.0 * rel(e.value),
                th
            );
            if !ok {
                failures.push(format!(
                    "{} {}: LIGGGHTS {} Arachis {} ({:+.4} %)",
                    case.name,
                    l.name,
                    l.value,
                    a.value,
                    100.0 * rel(a.value)
                ));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "outside {:.1} % of LIGGGHTS:\n{}",
        TOLERANCE * 100.0,
        failures.join("\n")
    );
}
