//! A pod sphere dropped on a steel plane falls freely, bounces, and comes to rest at the Hertz
//! static overlap; fixed point and f64 agree.

use crate::common;
use arachis_core::prelude::*;
use common::*;

fn drop<S: Scalar>() -> (f64, f64, u64) {
    let mut o = Owned::<S>::new(1, 1);
    let mut w = World::new(o.storage()).unwrap();
    let pod = w.add_material(POD).unwrap();
    let steel = w.add_material(STEEL).unwrap();
    w.set_pair(pod, steel, PairSpec::hertz_mindlin(0.339, 0.589, 0.159))
        .unwrap();
    w.set_gravity_m_s2([0.0, 0.0, -9.81]).unwrap();
    common::add_floor(&mut w, steel);
    let r = 0.004;
    let h0 = 0.014; // 10 mm free fall to contact
    w.add_sphere(SphereSpec::at_rest(pod, r, [0.0, 0.0, h0]))
        .unwrap();
    w.set_timestep_s(2e-5).unwrap();
    // Free fall for 20 ms: z = h0 − g t²/2 (symplectic Euler: − g dt² n(n+1)/2).
    let n = 1000u64;
    w.run(n).unwrap();
    let dt = 2e-5;
    let z_exp = h0 - 9.81 * dt * dt * (n * (n + 1)) as f64 / 2.0;
    let z = w.body(BodyId(0)).position.z.to_f64() * 1e-3;
    assert!((z - z_exp).abs() < 1e-9, "free fall z {z} vs {z_exp}");
    // Settle.
    w.run(30_000).unwrap();
    let b = w.body(BodyId(0));
    let rest = b.position.z.to_f64(); // mm
    let v = b.velocity.norm().to_f64();
    (rest, v, w.digest())
}

#[test]
fn sphere_drop_settles_at_hertz_overlap() {
    for (name, (rest, v, _)) in [("fixed", drop::<Fx>()), ("f64", drop::<f64>())] {
        // Static Hertz overlap: m g = (4/3) E* √R α^{3/2}.
        let r = 4.0;
        let m = 582.36e-6 * 4.0 / 3.0 * std::f64::consts::PI * r * r * r;
        let pod_part = (1.0 - 0.386f64.powi(2)) / 8.43;
        let steel_part = (1.0 - 0.09) / 2.05e5;
        let e_star = 1.0 / (pod_part + steel_part);
        let alpha = (m * 9.81e-3 / (4.0 / 3.0 * e_star * r.sqrt())).powf(2.0 / 3.0);
        let measured = r - rest;
        println!("{name}: rest overlap {measured:.6e} mm, Hertz {alpha:.6e} mm, |v| {v:e}");
        assert!(
            (measured / alpha - 1.0).abs() < 0.01,
            "{name}: {measured} vs {alpha}"
        );
        assert!(v < 1e-6, "{name}: still moving {v}");
    }
}

#[test]
fn digest_is_reproducible() {
    assert_eq!(drop::<Fx>().2, drop::<Fx>().2);
}
