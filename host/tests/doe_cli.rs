//! `arachis doe design` end to end: the CSV it writes, and its errors (exit code 2, a clear
//! message, no output file).

use std::path::{Path, PathBuf};
use std::process::Output;

use arachis::io::CsvTable;

use crate::cli_support;
use cli_support::arachis;

fn design_to_file(dir: &Path, name: &str, args: &[&str]) -> (PathBuf, Output) {
    let out = dir.join(name);
    let mut all = vec!["doe", "design"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["--out", out.to_str().unwrap()]);
    (out.clone(), arachis(&all))
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

const SEED000_TABLE7: &str = "x3:0.327:0.340,x4:0.848:0.858,x5:0.332:0.350";

#[test]
fn bbd_csv_has_run_std_order_coded_and_actual_columns() {
    let dir = tempfile::tempdir().unwrap();
    let (path, o) = design_to_file(
        dir.path(),
        "bbd.csv",
        &[
            "--type",
            "bbd",
            "--factors",
            SEED000_TABLE7,
            "--center",
            "5",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let t = CsvTable::read(&path).unwrap();
    assert_eq!(
        t.headers,
        [
            "run",
            "std_order",
            "point",
            "x3_coded",
            "x4_coded",
            "x5_coded",
            "x3",
            "x4",
            "x5"
        ]
    );
    assert_eq!(t.rows.len(), 17);
    let x3 = t.f64_column("x3").unwrap();
    let x3c = t.f64_column("x3_coded").unwrap();
    for (a, c) in x3.iter().zip(&x3c) {
        // actual = 0.3335 + 0.0065 × coded (seed 001 §2.5 coding with Table 7's levels).
        assert!(
            (a - (0.3335 + 0.0065 * c)).abs() < 1e-12,
            "{a} vs coded {c}"
        );
    }
    let centre_rows = t.rows.iter().filter(|r| r.cells[2] == "centre").count();
    assert_eq!(centre_rows, 5);
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("# factor x3: unit -, coded -1 = 0.327, 0 = 0.3335, +1 = 0.34"));
}

#[test]
fn ccd_with_alpha_1414_reproduces_seed001_table9_levels() {
    let dir = tempfile::tempdir().unwrap();
    let (path, o) = design_to_file(
        dir.path(),
        "ccd.csv",
        &[
            "--type",
            "ccd",
            "--factors",
            "X7:4.293:5.707:1e5 N/m^3,X8:8.586:11.414:1e5 Pa",
            "--alpha",
            "1.414",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let t = CsvTable::read(&path).unwrap();
    assert_eq!(t.rows.len(), 13); // 4 + 4 + 5 default centre points
    let x7 = t.f64_column("X7").unwrap();
    // Axial: 5.00 ± 1.414 × 0.707 = 4.0003 / 5.9997, printed 4.00 / 6.00 in Table 9.
    let min = x7.iter().cloned().fold(f64::MAX, f64::min);
    let max = x7.iter().cloned().fold(f64::MIN, f64::max);
    assert!(
        (min - 4.00).abs() < 0.005 && (max - 6.00).abs() < 0.005,
        "{min} {max}"
    );
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("# factor X7: unit 1e5 N/m^3"), "{text}");
}

#[test]
fn pb12_with_named_dummies_and_fractional_with_generators() {
    let dir = tempfile::tempdir().unwrap();
    let factors = "x1:0.186:0.586,x2:1.02:5.06:MPa,x3:0.314:0.366,x4:0.837:0.878,\
                   x5:0.314:0.356,x6:0.282:0.396,x7:0.578:0.601,x8:0.145:0.172";
    let (path, o) = design_to_file(
        dir.path(),
        "pb.csv",
        &[
            "--type",
            "pb12",
            "--factors",
            factors,
            "--dummy-names",
            "x9,x10,x11",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let t = CsvTable::read(&path).unwrap();
    assert_eq!(t.rows.len(), 12);
    assert!(t.column_index("x11_coded").is_ok());
    assert!(
        t.column_index("x11").is_err(),
        "dummy columns have no actual levels"
    );

    let (path, o) = design_to_file(
        dir.path(),
        "frac.csv",
        &[
            "--type",
            "fractional",
            "--factors",
            "a:0:1,b:0:1,c:0:1,d:0:1",
            "--generators",
            "D=-ABC",
            "--center",
            "2",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let t = CsvTable::read(&path).unwrap();
    assert_eq!(t.rows.len(), 10);
    let col = |n: &str| t.f64_column(n).unwrap();
    let (a, b, c, d) = (
        col("a_coded"),
        col("b_coded"),
        col("c_coded"),
        col("d_coded"),
    );
    for i in 0..8 {
        assert_eq!(d[i], -a[i] * b[i] * c[i]);
    }
}

#[test]
fn steepest_path_reproduces_seed001_table8() {
    let dir = tempfile::tempdir().unwrap();
    let (path, o) = design_to_file(
        dir.path(),
        "path.csv",
        &[
            "--type",
            "steepest",
            "--factors",
            "X7:3:7,X8:6:14",
            "--coefficients",
            "1,1",
            "--origin",
            "-1,-1",
            "--step",
            "0.5",
            "--points",
            "5",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let t = CsvTable::read(&path).unwrap();
    assert_eq!(t.f64_column("X7").unwrap(), [3.0, 4.0, 5.0, 6.0, 7.0]);
    assert_eq!(t.f64_column("X8").unwrap(), [6.0, 8.0, 10.0, 12.0, 14.0]);
}

#[test]
fn bad_input_exits_2_with_a_clear_message_and_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [(&[&str], &str); 8] = [
        (
            &["--type", "rsm", "--factors", "a:0:1"],
            "invalid value 'rsm'",
        ),
        (
            &["--type", "bbd", "--factors", "a:0:1,b:0:1"],
            "Box-Behnken: 2 factors given, but it needs 3 to 7",
        ),
        (
            &[
                "--type",
                "bbd",
                "--factors",
                "a:0:1,b:0:1,c:0:1,d:0:1,e:0:1,f:0:1,g:0:1,h:0:1",
            ],
            "Box-Behnken: 8 factors given, but it needs 3 to 7",
        ),
        (
            &["--type", "ccd", "--factors", "a:1:1,b:0:1"],
            "factor 'a': low level 1 must be below high level 1",
        ),
        (
            &["--type", "factorial", "--factors", "a:0:x,b:0:1"],
            "high level 'x' is not a number",
        ),
        (
            &[
                "--type",
                "fractional",
                "--factors",
                "a:0:1,b:0:1,c:0:1,d:0:1",
            ],
            "needs --generators",
        ),
        (
            &["--type", "ccd", "--factors", "a:0:1,b:0:1", "--alpha", "-2"],
            "alpha -2",
        ),
        (
            &[
                "--type",
                "bbd",
                "--factors",
                "a:0:1,b:0:1,c:0:1",
                "--alpha",
                "face",
            ],
            "--alpha applies to ccd",
        ),
    ];
    for (i, (args, message)) in cases.iter().enumerate() {
        let name = format!("bad{i}.csv");
        let (path, o) = design_to_file(dir.path(), &name, args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        assert!(stderr(&o).contains(message), "{args:?}: {}", stderr(&o));
        assert!(!path.exists(), "{args:?} left {}", path.display());
    }
    // Nothing else (no temporary file) was left in the directory either.
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}
