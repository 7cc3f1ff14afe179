//! Bad bench-test input: every case is a clear error naming the file, the line and the
//! column(s), never a panic.

use std::path::Path;

use arachis::io::CsvTable;
use arachis::lab::{
    bond, density, hertz_modulus, poisson, restitution_camera, restitution_plate, rolling_friction,
    shear_modulus, static_friction, LabError,
};

fn table(text: &str) -> CsvTable {
    CsvTable::parse(Path::new("bench.csv"), text).unwrap()
}

fn message(result: Result<arachis::lab::LabReport, LabError>) -> String {
    result.unwrap_err().to_string()
}

#[test]
fn ragged_csv() {
    let err =
        CsvTable::parse(Path::new("bench.csv"), "mass_g,volume_ml\n2.1,3.9\n2.2\n").unwrap_err();
    assert_eq!(
        err.to_string(),
        "bench.csv:3: row has 1 cells but the header has 2"
    );
}

#[test]
fn non_numeric_cell() {
    let m = message(density::analyze(&table(
        "mass_g,volume_ml\n2.1,3.9\n2.2,abc\n",
    )));
    assert_eq!(
        m,
        "bench.csv:3: column 'volume_ml': 'abc' is not a finite number"
    );
}

#[test]
fn negative_deformation_hertz() {
    let m = message(hertz_modulus::analyze(
        &table("force_n,deformation_mm,upper_r1_mm,upper_r2_mm\n15,1.0,8,16\n15,-0.5,8,16\n"),
        hertz_modulus::HertzOptions {
            poisson: Some(0.386),
            ..Default::default()
        },
    ));
    assert_eq!(
        m,
        "bench.csv:3: column 'deformation_mm': deformation must be positive, got -0.5"
    );
}

#[test]
fn negative_deformation_poisson() {
    let m = message(poisson::analyze(&table(
        "length_mm,width_mm,axial_deformation_mm,transverse_deformation_mm\n34,18,0.5,0.1\n34,18,0.5,-0.1\n",
    )));
    assert_eq!(
        m,
        "bench.csv:3: column 'transverse_deformation_mm': transverse deformation must not be negative, got -0.1"
    );
}

#[test]
fn non_positive_mass_and_volume() {
    let m = message(density::analyze(&table(
        "mass_g,volume_ml\n2.1,3.9\n0,3.9\n",
    )));
    assert_eq!(
        m,
        "bench.csv:3: column 'mass_g': mass must be positive, got 0"
    );
    let m = message(density::analyze(&table(
        "mass_g,volume_ml\n2.1,-3.9\n2.0,3.9\n",
    )));
    assert_eq!(
        m,
        "bench.csv:2: column 'volume_ml': displaced volume must be positive, got -3.9"
    );
}

#[test]
fn angle_outside_physical_range() {
    let m = message(static_friction::analyze(&table("angle_deg\n30\n95\n")));
    assert_eq!(
        m,
        "bench.csv:3: column 'angle_deg': tilt angle must be in [0°, 90°), got 95°"
    );
    let m = message(static_friction::analyze(&table("angle_deg\n-1\n30\n")));
    assert!(
        m.starts_with("bench.csv:2: column 'angle_deg': tilt angle must be in [0°, 90°)"),
        "{m}"
    );
    let m = message(rolling_friction::analyze(
        &table("angle_deg,slope_mm,level_mm\n30,200,100\n0,200,100\n"),
        Default::default(),
    ));
    assert!(
        m.starts_with("bench.csv:3: column 'angle_deg': plate inclination must be in"),
        "{m}"
    );
}

#[test]
fn angle_options_outside_physical_range() {
    let csv = "za_mm,z0_mm,ta_s,x0_mm,y0_mm,xn_mm,yn_mm,zn_mm,tn_s\n500,0,0.3,0,0,1,1,5,0.02\n500,0,0.3,0,0,1,1,5,0.02\n";
    let m = message(restitution_camera::analyze(
        &table(csv),
        restitution_camera::CameraOptions {
            plate_angle_deg: 90.0,
        },
    ));
    assert_eq!(
        m,
        "option --plate-angle-deg: plate inclination must be in [0°, 90°), got 90°"
    );
    let m = message(bond::analyze(
        &table("force_n,radius_mm\n12,1.1\n13,1.1\n"),
        bond::BondOptions {
            friction_angle_deg: Some(120.0),
            ..Default::default()
        },
    ));
    assert_eq!(
        m,
        "option --friction-angle-deg: must be in [0°, 90°), got 120°"
    );
}

#[test]
fn theta_outside_printed_k_table() {
    // R = 2, R' = 20 mm: cos θ = 18/22, θ = 35.1° < 50°: the table has no K there.
    let m = message(hertz_modulus::analyze(
        &table("force_n,deformation_mm,upper_r1_mm,upper_r2_mm\n15,1,2,20\n15,1,8,16\n"),
        hertz_modulus::HertzOptions {
            poisson: Some(0.386),
            k_method: hertz_modulus::KMethod::Table,
        },
    ));
    assert_eq!(
        m,
        "bench.csv:2: columns 'upper_r1_mm', 'upper_r2_mm': θ = 35.10° is outside seed 000 Table 2 (50°–85°); use --k-from elliptic"
    );
}

#[test]
fn poisson_outside_physical_range() {
    let m = message(shear_modulus::analyze(&table(
        "modulus_mpa,poisson\n8.4,0.386\n8.4,0.7\n",
    )));
    assert_eq!(
        m,
        "bench.csv:3: column 'poisson': Poisson's ratio must be in [0, 0.5], got 0.7"
    );
}

#[test]
fn fewer_than_two_replicates() {
    let m = message(density::analyze(&table("mass_g,volume_ml\n2.1,3.9\n")));
    assert_eq!(
        m,
        "bench.csv: density: 1 replicate(s); a standard deviation and a 95% confidence interval need at least 2"
    );
}

#[test]
fn impossible_rebound_geometry() {
    // Equal landing distances fit no parabola through O.
    let m = message(restitution_plate::analyze(&table(
        "drop_height_mm,h1_mm,s1_mm,h2_mm,s2_mm\n300,400,250,200,180\n300,400,200,200,200\n",
    )));
    assert!(m.starts_with("bench.csv:3: columns 'h1_mm', 's1_mm', 'h2_mm', 's2_mm': the two landing points fit no rebound parabola"), "{m}");
}

#[test]
fn fall_starting_below_impact() {
    let m = message(restitution_camera::analyze(
        &table("za_mm,z0_mm,ta_s,x0_mm,y0_mm,xn_mm,yn_mm,zn_mm,tn_s\n500,0,0.3,0,0,1,1,5,0.02\n-5,0,0.3,0,0,1,1,5,0.02\n"),
        Default::default(),
    ));
    assert_eq!(
        m,
        "bench.csv:3: columns 'za_mm', 'z0_mm': start height -5 mm is below the impact height 0 mm"
    );
}

#[test]
fn missing_geometry_and_poisson() {
    let m = message(hertz_modulus::analyze(
        &table("force_n,deformation_mm\n15,1\n15,1\n"),
        hertz_modulus::HertzOptions {
            poisson: Some(0.3),
            ..Default::default()
        },
    ));
    assert!(
        m.starts_with("bench.csv: needs the contact radii 'upper_r1_mm', 'upper_r2_mm'"),
        "{m}"
    );
    let m = message(hertz_modulus::analyze(
        &table("force_n,deformation_mm,upper_r1_mm,upper_r2_mm\n15,1,8,16\n15,1,8,16\n"),
        Default::default(),
    ));
    assert_eq!(
        m,
        "bench.csv: needs Poisson's ratio: give --poisson or a 'poisson' column"
    );
}
