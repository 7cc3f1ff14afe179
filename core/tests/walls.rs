//! Walls: cylinder containment, a moving plane pushing a sphere, and a finite cylinder lifted
//! off a sphere (the repose-test motion) releasing it.

use crate::common;
use arachis_core::prelude::*;
use common::*;

fn world_with<S: Scalar>(o: &mut Owned<S>) -> (World<'_, S>, MaterialId, MaterialId) {
    pod_steel_world(o, PairSpec::hertz_mindlin(0.9, 0.0, 0.0))
}

#[test]
fn cylinder_contains_and_reflects() {
    let mut o = Owned::<Fx>::new(1, 1);
    let (mut w, pod, steel) = world_with(&mut o);
    w.add_wall(WallSpec::fixed(
        WallGeometry::Cylinder {
            base_m: [0.0; 3],
            axis: [0.0, 0.0, 1.0],
            radius_m: 0.02,
            length_m: None,
        },
        steel,
    ))
    .unwrap();
    let mut s = SphereSpec::at_rest(pod, 0.004, [0.0, 0.0, 0.0]);
    s.velocity_m_s = [0.6, 0.8, 0.0]; // 1 m/s radially
    w.add_sphere(s).unwrap();
    w.set_timestep_s(1e-6).unwrap();
    let mut max_r: f64 = 0.0;
    for _ in 0..40_000 {
        w.step().unwrap();
        let p = w.body(BodyId(0)).position.to_f64();
        max_r = max_r.max((p[0] * p[0] + p[1] * p[1]).sqrt());
    }
    let v = w.body(BodyId(0)).velocity.to_f64();
    let radial_out = v[0] * 0.6 + v[1] * 0.8;
    println!("max centre radius {max_r:.4} mm, velocity after {v:?}");
    // Centre never gets further than Rc − R + a small overlap (< 0.2 mm at 1 m/s).
    assert!(max_r < 16.2 && max_r > 15.9, "{max_r}");
    // Bounced back inwards with |v| ≈ e_eff < 1.
    assert!(radial_out < -0.5, "{radial_out}");
}

#[test]
fn moving_plane_pushes_sphere() {
    let mut o = Owned::<Fx>::new(1, 1);
    let (mut w, pod, steel) = world_with(&mut o);
    let wall = w
        .add_wall(WallSpec {
            geometry: WallGeometry::Plane {
                point_m: [0.0; 3],
                normal: [1.0, 0.0, 0.0],
            },
            material: steel,
            velocity_m_s: [0.1, 0.0, 0.0],
        })
        .unwrap();
    w.add_sphere(SphereSpec::at_rest(pod, 0.004, [0.0045, 0.0, 0.0]))
        .unwrap();
    w.set_timestep_s(1e-6).unwrap();
    w.run(20_000).unwrap();
    let vx = w.body(BodyId(0)).velocity.x.to_f64();
    // An elastic-ish kick from a wall moving at 0.1 m/s: the sphere leaves faster than the wall.
    println!("sphere vx after push {vx} m/s");
    assert!(vx > 0.1 && vx < 0.2, "{vx}");
    // The wall moved 20 ms × 0.1 m/s = 2 mm.
    let WallShapeView(x) = plane_x(&w, wall);
    // (dt = 1e-3 ms is quantised to the nearest 2^-32 ms: relative error 7e-8 per step.)
    assert!((x - 2.0).abs() < 1e-5, "{x}");
}

struct WallShapeView(f64);
fn plane_x(w: &World<Fx>, id: WallId) -> WallShapeView {
    match w.walls()[id.0 as usize].shape {
        arachis_core::wall::WallShape::Plane(p) => WallShapeView(p.point.x.to_f64()),
        _ => unreachable!(),
    }
}

#[test]
fn lifted_finite_cylinder_releases_sphere() {
    let mut o = Owned::<Fx>::new(1, 1);
    let (mut w, pod, steel) = world_with(&mut o);
    // Sphere pressed against the inside of a finite cylinder (ends z = 0..10 mm), cylinder
    // lifted at 0.05 m/s: once the bottom end passes the centre (z = 5 mm), contact ends.
    let cyl = w
        .add_wall(WallSpec::fixed(
            WallGeometry::Cylinder {
                base_m: [0.0; 3],
                axis: [0.0, 0.0, 1.0],
                radius_m: 0.01,
                length_m: Some(0.01),
            },
            steel,
        ))
        .unwrap();
    w.add_sphere(SphereSpec::at_rest(pod, 0.004, [0.00601, 0.0, 0.005]))
        .unwrap();
    w.set_timestep_s(1e-5).unwrap();
    w.step().unwrap();
    assert!(
        w.walls()[0].force.norm().to_f64() > 0.0,
        "no initial contact"
    );
    w.set_wall_velocity_m_s(cyl, [0.0, 0.0, 0.05]).unwrap();
    // Bottom passes z = 5 mm after 100 ms = 10 000 steps; the sphere was pushed away anyway,
    // so check there is no contact at the end and the wall has moved 5.5 mm.
    w.run(11_000).unwrap();
    assert_eq!(w.walls()[0].force.norm().to_f64(), 0.0);
    match w.walls()[0].shape {
        arachis_core::wall::WallShape::Cylinder(c) => {
            assert!((c.base.z.to_f64() - 5.5).abs() < 1e-3)
        }
        _ => unreachable!(),
    }
}
