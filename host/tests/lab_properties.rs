//! Properties of the bench-test analyses over wide random inputs: round trips through
//! independent forward models, monotone K(θ), and no panic or non-finite result on any
//! physically valid row.

use std::path::Path;

use arachis::io::CsvTable;
use arachis::lab::hertz_k::k_elliptic;
use arachis::lab::restitution_plate::{impact_speed, rebound_velocity, restitution_45};
use arachis::lab::{hertz_modulus, summarize};
use proptest::prelude::*;

const G: f64 = 9.81;

proptest! {
    #[test]
    fn plate_rig_round_trip(
        h in 0.05f64..1.0,
        e in 0.05f64..0.95,
        k in 0.0f64..1.0,
        d1 in 0.1f64..0.6,
        frac in 0.1f64..0.9,
    ) {
        // Forward: vertical impact at v₀ on a 45° plate; the normal part is kept at e, the
        // tangential at k; then a projectile to two depths d1 > d2.
        let v0 = (2.0 * G * h).sqrt();
        let (vx, vy) = (v0 * (e + k) / 2.0, v0 * (k - e) / 2.0);
        let land = |d: f64| {
            let t = (-vy + (vy * vy + 2.0 * G * d).sqrt()) / G;
            (d, vx * t)
        };
        let ((h1, s1), (h2, s2)) = (land(d1), land(d1 * frac));
        let (gx, gy) = rebound_velocity(h1, s1, h2, s2, G).unwrap();
        let got = restitution_45(gx, gy, impact_speed(h, G));
        prop_assert!((got - e).abs() < 1e-7, "e {e} → {got}");
    }

    #[test]
    fn k_grows_with_theta_up_to_the_sphere_value(a in 0.5f64..89.5, step in 0.01f64..0.5) {
        let k1 = k_elliptic(a.to_radians()).unwrap();
        let k2 = k_elliptic((a + step).to_radians()).unwrap();
        prop_assert!(k1 < k2 && k2 <= (std::f64::consts::PI.powi(2) / 4.0).cbrt() + 1e-12);
    }

    #[test]
    fn hertz_is_finite_for_any_valid_row(
        f in 0.01f64..1e3,
        d in 1e-3f64..5.0,
        r1 in 1e-2f64..1e3,
        ratio in 1.0f64..1e6,
        mu in 0.0f64..0.5,
    ) {
        let row = format!("{f},{d},{r1},{},{mu}\n", r1 * ratio);
        let text = format!("force_n,deformation_mm,upper_r1_mm,upper_r2_mm,poisson\n{row}{row}");
        let table = CsvTable::parse(Path::new("p.csv"), &text).unwrap();
        match hertz_modulus::analyze(&table, Default::default()) {
            Ok(r) => {
                let s = r.quantity("apparent_modulus").unwrap().summary;
                prop_assert!(s.mean.is_finite() && s.mean > 0.0);
            }
            // Only a degenerate line contact (θ rounds to 0) may be refused, with a message.
            Err(e) => prop_assert!(e.to_string().contains("line contact"), "{e}"),
        }
    }

    #[test]
    fn summary_interval_brackets_the_mean(v in prop::collection::vec(-1e6f64..1e6, 2..40)) {
        let s = summarize(&v).unwrap();
        prop_assert!(s.min <= s.mean + 1e-9 && s.mean <= s.max + 1e-9);
        prop_assert!(s.ci95_low <= s.mean && s.mean <= s.ci95_high);
        prop_assert!(s.sd >= 0.0);
    }
}
