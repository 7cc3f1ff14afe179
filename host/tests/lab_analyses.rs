//! Each bench-test analysis on small CSVs, against hand calculations or an independent
//! forward model written out in the test. All replicate values here are synthetic.

use std::path::Path;

use arachis::io::CsvTable;
use arachis::lab::{
    bond, density, hertz_modulus, poisson, restitution_camera, restitution_plate, rolling_friction,
    shear_modulus, static_friction, tensile_modulus, LabReport,
};

/// t(0.975, 2) and t(0.975, 9) from printed Student t tables.
const T_975_2: f64 = 4.302653;
const T_975_9: f64 = 2.262157;

fn table(text: &str) -> CsvTable {
    CsvTable::parse(Path::new("bench.csv"), text).unwrap()
}

fn mean(report: &LabReport, name: &str) -> f64 {
    report.quantity(name).unwrap().summary.mean
}

fn values(report: &LabReport, name: &str) -> Vec<f64> {
    report
        .quantity(name)
        .unwrap()
        .replicates
        .iter()
        .map(|r| r.value)
        .collect()
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs().max(f64::MIN_POSITIVE)
}

#[test]
fn density_summary_by_hand() {
    // 2.00 g / 4.0 mL = 500, 2.40/4.0 = 600, 2.20/4.0 = 550 kg/m³: mean 550, sd 50,
    // 95% CI 550 ± 4.302653·50/√3 = 550 ± 124.2069.
    let r = density::analyze(&table("mass_g,volume_ml\n2.00,4.0\n2.40,4.0\n2.20,4.0\n")).unwrap();
    let s = r.quantity("density").unwrap().summary;
    assert!(close(s.mean, 550.0, 1e-12));
    assert!(close(s.sd, 50.0, 1e-12));
    assert!(close(s.min, 500.0, 1e-12) && close(s.max, 600.0, 1e-12));
    let half = T_975_2 * 50.0 / 3f64.sqrt();
    assert!((s.ci95_low - (550.0 - half)).abs() < 1e-3);
    assert!((s.ci95_high - (550.0 + half)).abs() < 1e-3);
    // Line numbers of the replicates are kept.
    let lines: Vec<u64> = r
        .quantity("density")
        .unwrap()
        .replicates
        .iter()
        .map(|x| x.line)
        .collect();
    assert_eq!(lines, vec![2, 3, 4]);
}

#[test]
fn poisson_by_hand() {
    // (0.12/18)/(0.5/34) = 0.45333…; (0.10/20)/(0.4/32) = 0.4.
    let r = poisson::analyze(&table(
        "length_mm,width_mm,axial_deformation_mm,transverse_deformation_mm\n34,18,0.5,0.12\n32,20,0.4,0.10\n",
    ))
    .unwrap();
    let v = values(&r, "poisson_ratio");
    assert!(close(v[0], 0.12 / 18.0 * 34.0 / 0.5, 1e-12));
    assert!(close(v[1], 0.4, 1e-12));
}

#[test]
fn hertz_sphere_equals_classical_hertz() {
    // A sphere (R = R' = 10 mm) between plates: classical Hertz gives per contact
    // F = (4/3) E/(1 − μ²) √R δ^(3/2) with δ = D/2, so E = (3/4) F (1 − μ²)/(√R (D/2)^(3/2)).
    // Eq. (11) equals this times 0.338/0.337618 (the rounding of the ASAE constant).
    let r = hertz_modulus::analyze(
        &table("force_n,deformation_mm,upper_r1_mm,upper_r2_mm\n20,0.5,10,10\n30,0.6,10,10\n"),
        hertz_modulus::HertzOptions {
            poisson: Some(0.386),
            ..Default::default()
        },
    )
    .unwrap();
    let rounding = 0.338 / (3.0 / (2.0 * 2f64.sqrt() * std::f64::consts::PI));
    let hertz = |f: f64, d_mm: f64| {
        0.75 * f * (1.0 - 0.386f64.powi(2)) / (0.01f64.sqrt() * (d_mm * 1e-3 / 2.0).powf(1.5))
    };
    let e = values(&r, "apparent_modulus");
    assert!(
        close(e[0], hertz(20.0, 0.5) * rounding, 1e-9),
        "{} vs {}",
        e[0],
        hertz(20.0, 0.5)
    );
    assert!(close(e[1], hertz(30.0, 0.6) * rounding, 1e-9));
    // θ = 90° for a sphere, and G = E/(2(1 + μ)) per replicate.
    assert!(values(&r, "theta_upper")
        .iter()
        .all(|t| (t - 90.0).abs() < 1e-9));
    let g = values(&r, "shear_modulus");
    assert!(close(g[0], e[0] / (2.0 * 1.386), 1e-12));
}

#[test]
fn hertz_table_k_at_60_degrees_by_hand() {
    // R = 5 mm, R' = 15 mm: cos θ = (1/5 − 1/15)/(1/5 + 1/15) = 0.5, θ = 60°, K = 1.267
    // (Table 2). E = 0.338·F(1 − μ²)/D^1.5·[2K(1/R + 1/R')^(1/3)]^1.5 with F = 15 N,
    // D = 1 mm, μ = 0.386, in SI: (1/0.005 + 1/0.015) = 266.667 m⁻¹.
    let r = hertz_modulus::analyze(
        &table("force_n,deformation_mm,upper_r1_mm,upper_r2_mm,poisson\n15,1,5,15,0.386\n15,1,15,5,0.386\n"),
        hertz_modulus::HertzOptions { poisson: None, k_method: hertz_modulus::KMethod::Table },
    )
    .unwrap();
    let bracket: f64 = 2.0 * 1.267 * (266.666_666_666_7f64).cbrt();
    let expected = 0.338 * 15.0 * (1.0 - 0.386 * 0.386) / (1e-3f64).powf(1.5) * bracket.powf(1.5);
    for e in values(&r, "apparent_modulus") {
        assert!(close(e, expected, 1e-9), "{e} vs {expected}");
    }
    assert!((mean(&r, "theta_upper") - 60.0).abs() < 1e-9);
}

#[test]
fn hertz_distinct_lower_contact_uses_eq9() {
    // Upper a sphere of 10 mm (K90), lower R = 5, R' = 15 mm (θ = 60°): eq. (9) sums the two
    // contacts' K(1/R + 1/R')^(1/3).
    let r = hertz_modulus::analyze(
        &table("force_n,deformation_mm,upper_r1_mm,upper_r2_mm,lower_r1_mm,lower_r2_mm\n15,1,10,10,5,15\n15,1,10,10,5,15\n"),
        hertz_modulus::HertzOptions { poisson: Some(0.3), ..Default::default() },
    )
    .unwrap();
    let k90 = (std::f64::consts::PI.powi(2) / 4.0).cbrt();
    let k60 = mean(&r, "k_lower");
    assert!((k60 - 1.267).abs() < 5e-4);
    let bracket = k90 * 200f64.cbrt() + k60 * 266.666_666_666_7f64.cbrt();
    let expected = 0.338 * 15.0 * 0.91 / 1e-3f64.powf(1.5) * bracket.powf(1.5);
    assert!(close(mean(&r, "apparent_modulus"), expected, 1e-9));
}

#[test]
fn hertz_seed001_geometry_by_hand() {
    // L = 34.27, H = 15.76 mm → R = 7.88, R' = 17.194982 mm; the row with these radii given
    // directly must give the same modulus.
    let via_lh = hertz_modulus::analyze(
        &table("force_n,deformation_mm,length_mm,thickness_mm\n60,0.2,34.27,15.76\n60,0.2,34.27,15.76\n"),
        hertz_modulus::HertzOptions { poisson: Some(0.37), ..Default::default() },
    )
    .unwrap();
    let via_r = hertz_modulus::analyze(
        &table("force_n,deformation_mm,upper_r1_mm,upper_r2_mm\n60,0.2,7.88,17.1949817\n60,0.2,7.88,17.1949817\n"),
        hertz_modulus::HertzOptions { poisson: Some(0.37), ..Default::default() },
    )
    .unwrap();
    assert!(close(
        mean(&via_lh, "apparent_modulus"),
        mean(&via_r, "apparent_modulus"),
        1e-8
    ));
    // cos θ = (17.19498 − 7.88)/(17.19498 + 7.88) = 0.371485 → θ = 68.191°.
    assert!((mean(&via_lh, "theta_upper") - 0.371485f64.acos().to_degrees()).abs() < 1e-3);
}

#[test]
fn shear_modulus_by_hand() {
    let r = shear_modulus::analyze(&table("modulus_mpa,poisson\n8.43,0.386\n10,0.25\n")).unwrap();
    let g = values(&r, "shear_modulus");
    assert!(close(g[0], 8.43e6 / 2.772, 1e-12));
    assert!(close(g[1], 4e6, 1e-12));
}

#[test]
fn tensile_modulus_area_and_diameter_agree() {
    // 10 N·20 mm/(3 mm²·0.5 mm) = 133.33 MPa; a 2 mm diameter is π mm².
    let r = tensile_modulus::analyze(&table(
        "force_n,length_mm,area_mm2,elongation_mm\n10,20,3,0.5\n12,20,3,0.5\n",
    ))
    .unwrap();
    assert!(close(
        values(&r, "tensile_modulus")[0],
        10.0 * 20.0 / (3.0 * 0.5) * 1e6,
        1e-12
    ));
    let d = tensile_modulus::analyze(&table(
        "force_n,length_mm,diameter_mm,elongation_mm\n10,20,2,0.5\n12,20,2,0.5\n",
    ))
    .unwrap();
    assert!(close(
        values(&d, "tensile_modulus")[0],
        10.0 * 20.0 / (std::f64::consts::PI * 0.5) * 1e6,
        1e-12
    ));
}

/// Forward model of the 45° rig, independent of eqs. (15)–(18): a pod falling at v₀ hits the
/// plate (normal (1, 1)/√2 in x right, y up), keeps a fraction `k` of its tangential speed
/// and `e` of its normal speed, then flies as a projectile; returns (s, depth) landing
/// points (mm) for the two given depths (mm).
fn plate_rig(h_mm: f64, e: f64, k: f64, depths_mm: [f64; 2]) -> [(f64, f64); 2] {
    let g = 9.81;
    let v0 = (2.0 * g * h_mm * 1e-3).sqrt();
    let (n, t) = (
        [1.0 / 2f64.sqrt(), 1.0 / 2f64.sqrt()],
        [1.0 / 2f64.sqrt(), -1.0 / 2f64.sqrt()],
    );
    // Incoming (0, −v0): normal part −v0/√2, tangential part +v0/√2.
    let (vn, vt) = (e * v0 / 2f64.sqrt(), k * v0 / 2f64.sqrt());
    let vx = vn * n[0] + vt * t[0];
    let vy_down = -(vn * n[1] + vt * t[1]);
    depths_mm.map(|d| {
        let time = (-vy_down + (vy_down * vy_down + 2.0 * g * d * 1e-3).sqrt()) / g;
        (vx * time * 1e3, d)
    })
}

#[test]
fn restitution_plate_recovers_forward_model() {
    let mut csv = String::from("drop_height_mm,h1_mm,s1_mm,h2_mm,s2_mm\n");
    let cases = [(300.0, 0.30, 0.6), (280.0, 0.36, 0.7), (320.0, 0.39, 0.5)];
    for (h, e, k) in cases {
        let [(s1, h1), (s2, h2)] = plate_rig(h, e, k, [400.0, 200.0]);
        csv.push_str(&format!("{h},{h1},{s1},{h2},{s2}\n"));
    }
    let r = restitution_plate::analyze(&table(&csv)).unwrap();
    for (got, (_, e, _)) in values(&r, "restitution").iter().zip(cases) {
        assert!((got - e).abs() < 1e-9, "e = {got}, built with {e}");
    }
}

#[test]
fn restitution_camera_recovers_forward_model() {
    // Fall from 500 mm to 0 from rest: t_a = √(2·0.5/g), v₁ = g t_a. Rebound at e·v₁ in
    // direction (0.6, 0, 0.8), observed after 0.02 s.
    let g = 9.81_f64;
    let ta = (1.0 / g).sqrt();
    let v1 = g * ta;
    let mut csv = String::from("za_mm,z0_mm,ta_s,x0_mm,y0_mm,xn_mm,yn_mm,zn_mm,tn_s\n");
    for e in [0.3, 0.35] {
        let (vx, vz, tn) = (0.6 * e * v1, 0.8 * e * v1, 0.02);
        let zn = (vz * tn - g * tn * tn / 2.0) * 1e3;
        csv.push_str(&format!(
            "500,0,{ta},1,2,{},2,{zn},{tn}\n",
            1.0 + vx * tn * 1e3
        ));
    }
    let r = restitution_camera::analyze(&table(&csv), Default::default()).unwrap();
    let e = values(&r, "restitution");
    assert!(
        (e[0] - 0.3).abs() < 1e-9 && (e[1] - 0.35).abs() < 1e-9,
        "{e:?}"
    );
    // On a level plate the normal part is v_z/v₁ = 0.8 e.
    assert!((values(&r, "restitution_normal")[0] - 0.24).abs() < 1e-9);
}

#[test]
fn restitution_camera_inclined_plate_splits_normal_and_tangential() {
    // Plate at α = 20° about X; in seed 001 eq. (7)'s frame the normal is (0, −sin α, cos α)
    // and the in-plane slope direction (0, cos α, sin α). The vertical impact at v₁ has
    // normal part v₁ cos α and tangential part v₁ sin α. Build the rebound from e_n = 0.4,
    // e_t = 0.7 (tangential sign kept) and recover them.
    let g = 9.81_f64;
    let (alpha, en, et) = (20f64.to_radians(), 0.4, 0.7);
    let ta = (1.0 / g).sqrt();
    let v1 = g * ta;
    let (s, c) = alpha.sin_cos();
    let (vn, vt) = (en * v1 * c, -et * v1 * s);
    let (vy, vz) = (vt * c - vn * s, vt * s + vn * c);
    let tn = 0.01;
    let zn = (vz * tn - g * tn * tn / 2.0) * 1e3;
    let row = format!("500,0,{ta},0,0,0,{},{zn},{tn}\n", vy * tn * 1e3);
    let csv = format!("za_mm,z0_mm,ta_s,x0_mm,y0_mm,xn_mm,yn_mm,zn_mm,tn_s\n{row}{row}");
    let r = restitution_camera::analyze(
        &table(&csv),
        restitution_camera::CameraOptions {
            plate_angle_deg: 20.0,
        },
    )
    .unwrap();
    assert!((mean(&r, "restitution_normal") - en).abs() < 1e-9);
    assert!((mean(&r, "restitution_tangential") - et).abs() < 1e-9);
}

#[test]
fn rotational_share_by_hand() {
    // A 2 g sphere of 20 mm diameter: I = (2/5)·0.002·0.01² = 8e-8 kg·m² about every axis.
    // ω = (10, 0, 0) rad/s: E_r = ½·8e-8·100 = 4e-6 J. Rebound straight up at 0.2 m/s:
    // E_t = ½·0.002·0.04 = 4e-5 J, so η = 4e-6/4.4e-5 = 9.0909 %.
    let g = 9.81_f64;
    let ta = (1.0 / g).sqrt();
    let tn = 0.01;
    let zn = (0.2 * tn - g * tn * tn / 2.0) * 1e3;
    let row = format!("500,0,{ta},0,0,0,0,{zn},{tn},2,20,20,20,10,0,0\n");
    let csv = format!("za_mm,z0_mm,ta_s,x0_mm,y0_mm,xn_mm,yn_mm,zn_mm,tn_s,mass_g,length_mm,width_mm,thickness_mm,wx_rad_s,wy_rad_s,wz_rad_s\n{row}{row}");
    let r = restitution_camera::analyze(&table(&csv), Default::default()).unwrap();
    assert!((mean(&r, "rotational_energy") - 4e-6).abs() < 1e-15);
    assert!((mean(&r, "rotational_share") - 4e-6 / 4.4e-5).abs() < 1e-9);
}

#[test]
fn static_friction_by_hand() {
    let r = static_friction::analyze(&table("angle_deg\n45\n30\n")).unwrap();
    let v = values(&r, "static_friction");
    assert!((v[0] - 1.0).abs() < 1e-12 && (v[1] - 1.0 / 3f64.sqrt()).abs() < 1e-12);
}

#[test]
fn rolling_friction_forms_agree_and_printed_form_differs() {
    // x = 200 mm down 30°, then l = 100 mm: f = 100/(173.205 + 100) = 0.366025.
    // Seed 000's form with H = x sin 30° = 100 mm and S = 100 mm gives the same.
    let slope = rolling_friction::analyze(
        &table("angle_deg,slope_mm,level_mm\n30,200,100\n30,200,100\n"),
        Default::default(),
    )
    .unwrap();
    assert!(
        (mean(&slope, "rolling_friction") - 100.0 / (200.0 * 0.75f64.sqrt() + 100.0)).abs() < 1e-12
    );
    let height = rolling_friction::analyze(
        &table("angle_deg,height_mm,level_mm\n30,100,100\n30,100,100\n"),
        Default::default(),
    )
    .unwrap();
    assert!((mean(&height, "rolling_friction") - mean(&slope, "rolling_friction")).abs() < 1e-12);
    // As printed: 100/(100 cos 30° + 100) = 0.535898, a different number.
    let printed = rolling_friction::analyze(
        &table("angle_deg,height_mm,level_mm\n30,100,100\n30,100,100\n"),
        rolling_friction::RollingOptions { as_printed: true },
    )
    .unwrap();
    assert!(
        (mean(&printed, "rolling_friction") - 100.0 / (100.0 * 0.75f64.sqrt() + 100.0)).abs()
            < 1e-12
    );
}

#[test]
fn bond_parameters_by_hand() {
    // σ = 12.74/(π·1.1e-3²) = 3.35145e6 Pa; τ = σ tan 30° + 1e4.
    // K_n for pod (296 MPa, 0.37, 7.88 mm) and junction (118 MPa, 0.247, 0.965 mm):
    // 1/E* = (1 − 0.1369)/296e6 + (1 − 0.061009)/118e6; ((ra + rb)/(ra rb))^(−1/2).
    let opts = bond::BondOptions {
        friction_angle_deg: Some(30.0),
        cohesion_pa: 1e4,
        particles: Some(((296e6, 0.37, 7.88e-3), (118e6, 0.247, 0.965e-3))),
    };
    let r = bond::analyze(&table("force_n,radius_mm\n12.74,1.1\n12.74,1.1\n"), opts).unwrap();
    let sigma = 12.74 / (std::f64::consts::PI * 1.21e-6);
    assert!(close(mean(&r, "critical_normal_stress"), sigma, 1e-12));
    assert!(close(
        mean(&r, "critical_tangential_stress"),
        sigma * 30f64.to_radians().tan() + 1e4,
        1e-12
    ));
    let e_star = 1.0 / ((1.0 - 0.1369) / 296e6 + (1.0 - 0.061009) / 118e6);
    let kn = 4.0 / 3.0 * e_star * ((7.88e-3_f64 * 0.965e-3) / (7.88e-3 + 0.965e-3)).sqrt();
    assert!(close(
        r.derived_value("normal_stiffness_kn").unwrap(),
        kn,
        1e-12
    ));
    assert!(close(
        r.derived_value("tangential_stiffness_ks_low").unwrap(),
        kn / 2.0,
        1e-12
    ));
    assert!(close(
        r.derived_value("tangential_stiffness_ks_high").unwrap(),
        kn * 2.0 / 3.0,
        1e-12
    ));
}

#[test]
fn shipped_example_csvs_give_ten_replicate_ci() {
    // Every shipped 10-replicate example: CI half-width = t(0.975, 9)·sd/√10.
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../testdata/lab");
    let r = static_friction::analyze(&CsvTable::read(&root.join("static_friction.csv")).unwrap())
        .unwrap();
    let s = r.quantity("static_friction").unwrap().summary;
    assert_eq!(s.n, 10);
    let half = T_975_9 * s.sd / 10f64.sqrt();
    assert!(((s.ci95_high - s.mean) - half).abs() < 1e-6 * s.sd);
    // And the mean is the mean of tan(angle) over the file's angles, by hand.
    let angles = CsvTable::read(&root.join("static_friction.csv"))
        .unwrap()
        .f64_column("angle_deg")
        .unwrap();
    let by_hand = angles.iter().map(|a| a.to_radians().tan()).sum::<f64>() / angles.len() as f64;
    assert!((s.mean - by_hand).abs() < 1e-12);
}
