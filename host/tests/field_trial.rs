//! Issue 20, item 4: the seed's field trial in simulation (`arachis field --harvester
//! --replicates N`): one field per layout seed, each harvested the same way, the loss rate per
//! replicate and the pooled t-test against seed 001 Table 12's field losses.
//!
//! The run here is short: the machine is still settling before the bed, so no pod has been
//! lifted and, by the loss definition (`arachis::harvester::loss`), every pod counts as lost
//! in the soil: 100 % a replicate. It checks the trial's bookkeeping, not the harvest's
//! physics. The t-test is recomputed here from the printed losses with statrs' Student t,
//! independently of `arachis::stats`.

use serde_json::Value;
use statrs::distribution::{ContinuousCDF, StudentsT};

use crate::cli_support::{arachis, small_field_files};

/// Seed 001 Table 12's field losses, %.
const TABLE_12_FIELD_PCT: [f64; 4] = [4.01, 3.83, 4.04, 3.42];

#[test]
fn three_replicates_report_their_losses_and_the_t_test_against_table_12() {
    let dir = tempfile::tempdir().unwrap();
    let (field, machine) = small_field_files(dir.path());
    let output = dir.path().join("trial.json");
    let section = dir.path().join("section.svg");
    let pod_map = dir.path().join("pods.svg");
    let report_dir = dir.path().join("report");
    let out = arachis(&[
        "--threads",
        "2",
        "field",
        field.to_str().unwrap(),
        "--harvester",
        machine.to_str().unwrap(),
        "--replicates",
        "3",
        "--steps",
        "300",
        "--section",
        section.to_str().unwrap(),
        "--pod-map",
        pod_map.to_str().unwrap(),
        "--output",
        output.to_str().unwrap(),
        "--report",
        report_dir.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let stdout = String::from_utf8(out.stdout).unwrap();
    let report: Value = serde_json::from_str(stdout.trim()).unwrap();
    assert_eq!(std::fs::read_to_string(&output).unwrap(), stdout);

    // One line per replicate, seeds 1, 2, 3, and three different layouts.
    let reps = report["replicates"].as_array().unwrap();
    let seeds: Vec<u64> = reps.iter().map(|r| r["seed"].as_u64().unwrap()).collect();
    assert_eq!(seeds, [1, 2, 3]);
    let digests: std::collections::BTreeSet<&str> =
        reps.iter().map(|r| r["digest"].as_str().unwrap()).collect();
    assert_eq!(digests.len(), 3, "each replicate is its own field");

    // The loss per replicate is the replicate's own line's.
    let losses: Vec<f64> = report["loss_rate_pct"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let own: Vec<f64> = reps
        .iter()
        .map(|r| r["harvest"]["loss_rate_pct"].as_f64().unwrap())
        .collect();
    assert_eq!(losses, own);
    for r in reps {
        let pods = &r["harvest"]["pods"];
        assert_eq!(pods["in_soil"], pods["pods"], "nothing lifted yet: {pods}");
    }
    let pods_per_plant = reps
        .iter()
        .map(|r| r["pods"].as_f64().unwrap() / r["plants"].as_f64().unwrap())
        .sum::<f64>()
        / 3.0;
    assert!((report["pods_per_plant"].as_f64().unwrap() - pods_per_plant).abs() < 1e-12);
    assert!(pods_per_plant > 0.0);

    // Pooled t-test, recomputed: t = (ȳs − ȳf) / (sp √(1/3 + 1/4)) on 5 degrees of freedom.
    let mean = |s: &[f64]| s.iter().sum::<f64>() / s.len() as f64;
    let ss = |s: &[f64]| s.iter().map(|v| (v - mean(s)).powi(2)).sum::<f64>();
    let sp = ((ss(&losses) + ss(&TABLE_12_FIELD_PCT)) / 5.0).sqrt();
    let t = (mean(&losses) - mean(&TABLE_12_FIELD_PCT)) / (sp * (1.0 / 3.0 + 1.0 / 4.0_f64).sqrt());
    // The survival function, not 1 − cdf, which cancels to nothing at p ≈ 1e-13.
    let p = 2.0 * StudentsT::new(0.0, 1.0, 5.0).unwrap().sf(t.abs());
    let printed_p = report["p_value"].as_f64().unwrap();
    println!("losses {losses:?} %, t {t:.3}, p {p:.3e} (printed {printed_p:.3e})");
    assert!((report["t"].as_f64().unwrap() - t).abs() < 1e-9 * t.abs().max(1.0));
    assert!(
        (printed_p - p).abs() < 1e-9 * p.max(1e-300),
        "{printed_p} against {p}"
    );
    assert_eq!(report["df"].as_u64(), Some(5));
    assert_eq!(
        report["significant_difference"].as_bool(),
        Some(p < 0.05),
        "the verdict follows p"
    );

    // Each replicate wrote its own section picture.
    for r in 1..=3 {
        let svg = dir.path().join(format!("section_rep{r}.svg"));
        assert!(
            std::fs::metadata(&svg).unwrap().len() > 0,
            "{}",
            svg.display()
        );
    }
    assert!(!section.exists(), "no un-numbered picture with replicates");

    // The report: the JSON as printed, Table 12's rows from it, the verdict, the figures.
    assert_eq!(
        std::fs::read_to_string(report_dir.join("trial.json")).unwrap(),
        stdout
    );
    let md = std::fs::read_to_string(report_dir.join("report.md")).unwrap();
    for (i, (sim, field)) in losses.iter().zip(TABLE_12_FIELD_PCT).enumerate() {
        let row = format!("| {} | {sim:.2} | {field:.2} |", i + 1);
        assert!(md.contains(&row), "no row {row} in\n{md}");
    }
    let verdict = if p < 0.05 {
        "**The test rejects**"
    } else {
        "does not reject"
    };
    assert!(md.contains(verdict), "{md}");
    assert!(md.contains("df = 5"), "{md}");
    // 300 steps are not a pass, and the report says so before its tables.
    assert!(
        md.contains("**Not a field trial's result:** replicate(s) 1, 2, 3"),
        "{md}"
    );
    let svg = std::fs::read_to_string(report_dir.join("where-lost.svg")).unwrap();
    assert!(
        svg.contains("lost in the soil") && svg.contains("rep 3"),
        "{svg}"
    );
    for r in 1..=3 {
        // Beside the --pod-map ones, the report keeps the maps it links to.
        let name = format!("pods_rep{r}.svg");
        assert!(md.contains(&name));
        assert!(report_dir.join(&name).exists(), "{name}");
    }
}

#[test]
fn a_bad_field_loss_exits_2_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let (field, machine) = small_field_files(dir.path());
    let output = dir.path().join("trial.json");
    let out = arachis(&[
        "field",
        field.to_str().unwrap(),
        "--harvester",
        machine.to_str().unwrap(),
        "--replicates",
        "2",
        "--field-loss",
        "4.01,140",
        "--output",
        output.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("--field-loss") && stderr.contains("140"),
        "{stderr}"
    );
    assert!(!output.exists());
}
