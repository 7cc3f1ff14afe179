//! Chung & Ooi (2011) test 4, oblique impact in gross sliding: a sphere hits a plane with a
//! large tangential speed, slides throughout the contact, and leaves with
//! ω = 2.5·μ·(1 + e)·vn/R (solid sphere). `e` here is the normal restitution actually produced
//! (measured from the same run), since the formula is an impulse balance: ∫Ft = μ∫Fn =
//! μ·m·(1+e)·vn.

use crate::common;
use arachis_core::prelude::*;
use common::*;

fn oblique<S: Scalar>(mu: f64, e_in: f64) -> (f64, f64) {
    let mut o = Owned::<S>::new(1, 1);
    let mut w = World::new(o.storage()).unwrap();
    let m = w.add_material(STIFF).unwrap();
    w.set_pair(
        m,
        m,
        PairSpec {
            restitution: e_in,
            friction: mu,
            rolling_friction: 0.0,
            conventions: arachis_core::contact::Conventions::EDEM,
            terms: TermSwitches::ALL,
        },
    )
    .unwrap();
    common::add_floor(&mut w, m);
    let r_m = 0.01;
    let vn = 0.2;
    let vt = 2.0; // tan θ = 10 ≫ 3.5 μ (1 + e): gross sliding
    let mut s = SphereSpec::at_rest(m, r_m, [0.0, 0.0, r_m + 1e-7]);
    s.velocity_m_s = [vt, 0.0, -vn];
    w.add_sphere(s).unwrap();
    let r = r_m * 1e3;
    let (_, _, t_c) = hertz_theory(
        sphere_mass_g(r, STIFF.density_kg_m3),
        r,
        e_star_mpa(&STIFF, &STIFF),
        vn,
    );
    w.set_timestep_s(t_c / 2000.0 * 1e-3).unwrap();
    let mut touched = false;
    for _ in 0..100_000 {
        w.step().unwrap();
        if w.walls()[0].force.norm().to_f64() > 0.0 {
            touched = true;
        } else if touched {
            break;
        }
    }
    let b = w.body(BodyId(0));
    let e = b.velocity.z.to_f64() / vn;
    // ω about −y for motion along +x sliding on a floor below (ω_y > 0 rolls forward).
    let omega_rad_s = b.angular_velocity.y.to_f64() * 1e3;
    let expected = 2.5 * mu * (1.0 + e) * vn / r_m;
    (omega_rad_s, expected)
}

fn check<S: Scalar>() {
    for (mu, e) in [(0.3, 0.5), (0.1, 1.0), (0.5, 0.3)] {
        let (got, expected) = oblique::<S>(mu, e);
        let rel = got / expected - 1.0;
        println!(
            "{} μ {mu} e_in {e}: ω {got:.6} rad/s, theory {expected:.6} rad/s ({:+.4}%)",
            S::NAME,
            100.0 * rel
        );
        assert!(rel.abs() < 0.02, "{} μ {mu}: {got} vs {expected}", S::NAME);
    }
}

#[test]
fn oblique_gross_sliding_fixed() {
    check::<Fx>();
}

#[test]
fn oblique_gross_sliding_f64() {
    check::<f64>();
}
