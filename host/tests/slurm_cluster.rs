//! The Slurm executor on a real one-node cluster (`scripts/slurm-local.sh`, issue 21):
//! - the surrogate calibration through Slurm writes the same `calibration.json` bytes as
//!   the local executor, and a stage of three DEM piles gives the same records and the same
//!   stored runs;
//! - a driver killed (SIGKILL) while its array runs, then restarted, finishes with the same
//!   bytes, and the scheduler's job-completion log shows no run executed twice;
//! - a worker killed on its first attempt is retried and the campaign completes; a run that
//!   fails every time stops the campaign with a message naming the run and its log.
//!
//! When the cluster cannot be started here (no root, no package archive), each test says so
//! on stderr and passes without running, unless `ARACHIS_REQUIRE_SLURM=1` (set by
//! `scripts/test-all.sh` once the cluster is up), which makes that a failure.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::sync::{Mutex, OnceLock};
use std::time::{Duration, Instant};

use arachis::calibration::{Executor, PlannedRun, Progress};
use arachis::cluster::ledger::{ArrayRecord, Ledger};
use arachis::cluster::{ClusterArgs, ExecutorKind, RigRecipe, Simulator, SlurmExecutor};
use arachis::rigs::pod_world::ModeName;
use arachis::study::Study;

const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
const STUDY: &str = "testdata/peanut-pods-saline/study.toml";
/// How long a campaign may take before the test gives up.
const PATIENCE: Duration = Duration::from_secs(300);

/// The cluster's configuration file, or why it cannot start (once per test binary).
fn cluster() -> Option<&'static str> {
    static CONF: OnceLock<Result<String, String>> = OnceLock::new();
    let conf = CONF.get_or_init(|| {
        let out = Command::new(format!("{ROOT}/scripts/slurm-local.sh"))
            .arg("start")
            .output()
            .map_err(|e| e.to_string())?;
        let stdout = String::from_utf8_lossy(&out.stdout);
        match stdout.trim().strip_prefix("SLURM_CONF=") {
            Some(conf) if out.status.success() => {
                std::env::set_var("SLURM_CONF", conf);
                Ok(conf.to_owned())
            }
            _ => Err(String::from_utf8_lossy(&out.stderr).trim().to_owned()),
        }
    });
    match conf {
        Ok(c) => Some(c),
        Err(why) => {
            assert!(
                std::env::var("ARACHIS_REQUIRE_SLURM").as_deref() != Ok("1"),
                "ARACHIS_REQUIRE_SLURM=1 but the local cluster did not start: {why}"
            );
            eprintln!("SKIPPED: the Slurm tests need a local cluster, which did not start: {why}");
            None
        }
    }
}

/// The tests share two CPUs: one campaign at a time.
fn one_at_a_time() -> std::sync::MutexGuard<'static, ()> {
    static LOCK: Mutex<()> = Mutex::new(());
    LOCK.lock().unwrap_or_else(|e| e.into_inner())
}

fn arachis() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_arachis"));
    c.current_dir(ROOT);
    c
}

/// `arachis calibrate` of the shipped study on the surrogate into `out`, with `extra` flags.
fn calibrate(out: &Path, extra: &[&str]) -> Command {
    let mut c = arachis();
    c.args([
        "calibrate",
        STUDY,
        "--simulator",
        "surrogate",
        "--quiet",
        "--out",
    ])
    .arg(out)
    .args(extra);
    c
}

const SLURM: &[&str] = &["--executor", "slurm", "--poll-seconds", "1"];

fn succeeded(o: &Output) {
    assert!(
        o.status.success(),
        "arachis failed: {}\n{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
}

fn local_reference(dir: &Path) -> Vec<u8> {
    let out = dir.join("local");
    succeeded(&calibrate(&out, &[]).output().unwrap());
    std::fs::read(out.join("calibration.json")).unwrap()
}

#[test]
fn the_surrogate_calibration_through_slurm_writes_the_local_bytes() {
    let Some(_) = cluster() else { return };
    let _one = one_at_a_time();
    let dir = tempfile::tempdir().unwrap();
    let local = local_reference(dir.path());
    let out = dir.path().join("slurm");
    let o = calibrate(&out, SLURM).output().unwrap();
    succeeded(&o);
    assert_eq!(std::fs::read(out.join("calibration.json")).unwrap(), local);
    // Every stage went through the cluster: each array's record has its job id.
    let arrays = Ledger::open(&out.join("slurm")).unwrap().arrays().unwrap();
    assert_eq!(
        arrays.len(),
        4,
        "screening, path, response surface, validation"
    );
    assert!(arrays.iter().all(|a| a.job.is_some()));
}

#[test]
fn plant_calibrate_through_slurm_writes_the_local_bytes_for_a_pull_its_flags_set() {
    let Some(_) = cluster() else { return };
    let _one = one_at_a_time();
    let dir = tempfile::tempdir().unwrap();
    // A pull other than the study's: the workers must build the study the flags changed.
    let run = |out: &Path, extra: &[&str]| {
        let o = arachis()
            .args(["plant-calibrate", "--speed", "0.6", "--quiet", "--out"])
            .arg(out)
            .args(extra)
            .output()
            .unwrap();
        succeeded(&o);
        std::fs::read(out.join("plant-calibration.json")).unwrap()
    };
    let local = run(&dir.path().join("local"), &[]);
    let slurm = run(&dir.path().join("slurm"), SLURM);
    assert_eq!(slurm, local);
    let arrays = Ledger::open(&dir.path().join("slurm/slurm"))
        .unwrap()
        .arrays()
        .unwrap();
    assert!(!arrays.is_empty(), "nothing went through the cluster");
}

#[test]
fn compare_through_slurm_prints_the_local_report() {
    let Some(_) = cluster() else { return };
    let _one = one_at_a_time();
    let dir = tempfile::tempdir().unwrap();
    let measured = "testdata/diagnosis-tutorial/measured.toml";
    let local = arachis().args(["compare", measured]).output().unwrap();
    succeeded(&local);
    let runs = dir.path().join("runs");
    let slurm = arachis()
        .args([
            "compare",
            measured,
            "--executor",
            "slurm",
            "--poll-seconds",
            "1",
            "--runs",
        ])
        .arg(&runs)
        .output()
        .unwrap();
    succeeded(&slurm);
    assert_eq!(slurm.stdout, local.stdout);
    let arrays = Ledger::open(&runs.join("slurm")).unwrap().arrays().unwrap();
    let simulated: usize = arrays.iter().map(|a| a.hashes.len()).sum();
    assert!(simulated > 1, "nothing went through the cluster");
}

#[test]
fn harvest_replicates_through_slurm_write_the_local_report() {
    let Some(_) = cluster() else { return };
    let _one = one_at_a_time();
    let dir = tempfile::tempdir().unwrap();
    let harvest = |report: &str, extra: &[&str]| {
        let path = dir.path().join(report);
        let o = arachis()
            .args([
                "harvest",
                "--plants",
                "1",
                "--replicates",
                "3",
                "--drum-length",
                "0.02",
            ])
            .args(["--forward-speed", "2", "--output"])
            .arg(&path)
            .args(extra)
            .output()
            .unwrap();
        succeeded(&o);
        std::fs::read(path).unwrap()
    };
    let local = harvest("local.json", &[]);
    let runs = dir.path().join("runs");
    let mut flags = SLURM.to_vec();
    flags.extend(["--runs", runs.to_str().unwrap()]);
    assert_eq!(harvest("slurm.json", &flags), local);
    let arrays = Ledger::open(&runs.join("slurm")).unwrap().arrays().unwrap();
    assert_eq!(
        arrays.iter().map(|a| a.hashes.len()).sum::<usize>(),
        3,
        "three passes"
    );
}

/// A copy of the shipped study whose quick mode makes `pods` pods of 3 spheres, in `dir`.
fn small_pile_study(dir: &Path, pods: u32) -> PathBuf {
    let text = std::fs::read_to_string(Path::new(ROOT).join(STUDY)).unwrap();
    let text = text
        .replacen("pods = 150 ", &format!("pods = {pods} "), 1)
        .replacen("spheres_per_pod = 6 ", "spheres_per_pod = 3 ", 1);
    assert!(
        text.contains(&format!("pods = {pods} ")),
        "the quick mode moved"
    );
    let path = dir.join("study.toml");
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn a_stage_of_three_dem_piles_gives_the_same_runs_on_slurm_as_locally() {
    let Some(_) = cluster() else { return };
    let _one = one_at_a_time();
    let dir = tempfile::tempdir().unwrap();
    let study_path = small_pile_study(dir.path(), 40);
    let study = Study::load(&study_path).unwrap();
    let recipe = RigRecipe::new(&study_path, Simulator::Dem, Some(ModeName::Quick)).unwrap();
    let rig = recipe.build(&study, "repose").unwrap();
    let problem = study.problem(rig.as_ref(), rig.as_ref()).unwrap();
    let piles: Vec<PlannedRun> = (0..3)
        .map(|replicate| PlannedRun {
            coded: vec![],
            values: BTreeMap::new(),
            replicate,
        })
        .collect();
    let stage = |runs: &Path, slurm: Option<&Path>| {
        let mut executor = Executor::new(Some(2), Some(runs), Progress::hidden()).unwrap();
        if let Some(records) = slurm {
            let settings = ClusterArgs {
                executor: ExecutorKind::Slurm,
                poll_seconds: 1,
                ..ClusterArgs::default()
            };
            let remote = SlurmExecutor::new(recipe.clone(), &settings, records, true)
                .unwrap()
                .with_program(env!("CARGO_BIN_EXE_arachis").into());
            executor = executor.with_remote(Box::new(remote)).unwrap();
        }
        executor
            .run_batch("validation", &problem.target, &problem.factors, &piles)
            .unwrap()
    };
    let local = stage(&dir.path().join("local-runs"), None);
    let slurm = stage(&dir.path().join("runs"), Some(&dir.path().join("slurm")));
    let angles = |r: &[arachis::calibration::RunRecord]| -> Vec<u64> {
        r.iter().map(|x| x.response.to_bits()).collect()
    };
    eprintln!(
        "pile angles: {:?}",
        local.iter().map(|r| r.response).collect::<Vec<_>>()
    );
    assert_eq!(angles(&slurm), angles(&local));
    assert_eq!(
        serde_json::to_string(&slurm).unwrap(),
        serde_json::to_string(&local).unwrap()
    );
    for r in &local {
        let name = format!("{}.json", r.spec_hash);
        assert_eq!(
            std::fs::read(dir.path().join("runs").join(&name)).unwrap(),
            std::fs::read(dir.path().join("local-runs").join(&name)).unwrap(),
            "stored run {name}"
        );
    }
    // The three piles differ (replicates are other insertion seeds), so the check compares
    // three different numbers, not one.
    assert!(local[0].response != local[1].response || local[1].response != local[2].response);
}

/// The job-completion log's entries for the arrays in `arrays`: (spec hash, state) of every
/// task that ran.
fn completed_tasks(conf: &str, arrays: &[ArrayRecord]) -> Vec<(String, String)> {
    let log = Path::new(conf).with_file_name("jobcomp.log");
    let text = std::fs::read_to_string(log).unwrap_or_default();
    let field = |line: &str, key: &str| -> Option<String> {
        line.split_whitespace()
            .find_map(|f| f.strip_prefix(key).map(str::to_owned))
    };
    text.lines()
        .filter_map(|line| {
            let name = field(line, "Name=")?;
            let array = arrays.iter().find(|a| a.name == name)?;
            let index: usize = field(line, "ArrayTaskId=")?.parse().ok()?;
            Some((array.hashes[index].clone(), field(line, "JobState=")?))
        })
        .collect()
}

/// Waits until none of the campaign's tasks is in the queue, and the completion log has
/// caught up with `expected` entries.
fn settle(conf: &str, ledger: &Ledger, expected: usize) -> Vec<(String, String)> {
    let started = Instant::now();
    loop {
        let arrays = ledger.arrays().unwrap();
        let queued = arachis::cluster::scheduler::queued_tasks(&ledger.job_prefix()).unwrap();
        let done = completed_tasks(conf, &arrays);
        if queued.is_empty() && done.len() >= expected {
            return done;
        }
        assert!(
            started.elapsed() < Duration::from_secs(60),
            "the queue did not drain"
        );
        std::thread::sleep(Duration::from_millis(500));
    }
}

fn wait(child: &mut Child) -> std::process::ExitStatus {
    let started = Instant::now();
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            return status;
        }
        assert!(started.elapsed() < PATIENCE, "the campaign did not finish");
        std::thread::sleep(Duration::from_millis(100));
    }
}

#[test]
fn a_killed_driver_resumes_without_running_any_run_twice() {
    let Some(conf) = cluster() else { return };
    let _one = one_at_a_time();
    let dir = tempfile::tempdir().unwrap();
    let local = local_reference(dir.path());
    let out = dir.path().join("slurm");
    let mut flags = SLURM.to_vec();
    flags.extend(["--surrogate-delay-ms", "400"]);
    let mut driver = calibrate(&out, &flags)
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    // Kill it once its first array is submitted and running but not finished.
    let ledger = Ledger::open(&out.join("slurm")).unwrap();
    let started = Instant::now();
    loop {
        let stored = std::fs::read_dir(out.join("runs")).map_or(0, |d| d.count());
        let submitted = ledger
            .arrays()
            .unwrap()
            .first()
            .is_some_and(|a| a.job.is_some());
        if submitted && (1..6).contains(&stored) {
            break;
        }
        assert!(started.elapsed() < PATIENCE, "the first array never ran");
        assert!(
            driver.try_wait().unwrap().is_none(),
            "the driver finished too soon"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
    driver.kill().unwrap(); // SIGKILL
    driver.wait().unwrap();
    let first = ledger.arrays().unwrap();
    assert_eq!(first.len(), 1, "one array before the kill");
    let still_queued = arachis::cluster::scheduler::queued_tasks(&ledger.job_prefix()).unwrap();
    eprintln!(
        "killed with {} of 12 tasks still queued or running",
        still_queued.len()
    );

    let mut again = calibrate(&out, &flags)
        .stdout(Stdio::null())
        .spawn()
        .unwrap();
    assert!(wait(&mut again).success());
    assert_eq!(std::fs::read(out.join("calibration.json")).unwrap(), local);

    let arrays = ledger.arrays().unwrap();
    let runs: usize = arrays.iter().map(|a| a.hashes.len()).sum();
    let done = settle(conf, &ledger, runs);
    let mut seen = std::collections::BTreeSet::new();
    for (hash, state) in &done {
        assert_eq!(state, "COMPLETED", "run {hash}");
        assert!(seen.insert(hash), "run {hash} ran twice");
    }
    assert_eq!(done.len(), runs, "every submitted task ran once");
    // The restarted driver submitted none of the first array's runs again.
    for a in &arrays[1..] {
        assert!(a.hashes.iter().all(|h| !first[0].hashes.contains(h)));
    }
}

#[test]
fn a_killed_worker_is_retried_and_a_hopeless_run_stops_the_campaign_naming_its_log() {
    let Some(_) = cluster() else { return };
    let _one = one_at_a_time();
    let dir = tempfile::tempdir().unwrap();
    let local = local_reference(dir.path());

    // Two screening runs: the first attempt at one aborts (as a killed worker), the other
    // fails every time.
    let calibration: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("local/calibration.json")).unwrap())
            .unwrap();
    let screening: Vec<String> = calibration["screening"]["runs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["spec_hash"].as_str().unwrap().to_owned())
        .collect();
    let (killed, hopeless) = (&screening[3], &screening[5]);
    assert_ne!(killed, hopeless);

    // Markers for every other stored run: only `killed` meets the abort.
    let markers = dir.path().join("markers");
    std::fs::create_dir(&markers).unwrap();
    for entry in std::fs::read_dir(dir.path().join("local/runs")).unwrap() {
        let hash = entry
            .unwrap()
            .file_name()
            .to_string_lossy()
            .replace(".json", "");
        if &hash != killed {
            std::fs::write(markers.join(hash), b"").unwrap();
        }
    }
    let out = dir.path().join("retried");
    let o = calibrate(&out, SLURM)
        .args(["--retries", "1"])
        .env(arachis::cluster::worker::KILL_ONCE_ENV, &markers)
        .output()
        .unwrap();
    succeeded(&o);
    assert_eq!(std::fs::read(out.join("calibration.json")).unwrap(), local);
    assert!(markers.join(killed).exists(), "the worker was not killed");
    let arrays = Ledger::open(&out.join("slurm")).unwrap().arrays().unwrap();
    let attempts = arrays.iter().filter(|a| a.hashes.contains(killed)).count();
    assert_eq!(attempts, 2, "the killed run was not retried once");
    let log = std::fs::read_to_string(
        out.join("slurm/logs")
            .join(format!("{}_3.log", arrays[0].tag)),
    )
    .unwrap();
    assert!(log.contains("aborting the first attempt"), "{log}");

    let out = dir.path().join("hopeless");
    let o = calibrate(&out, SLURM)
        .args(["--retries", "1"])
        .env(arachis::cluster::worker::FAIL_RUN_ENV, hopeless)
        .output()
        .unwrap();
    assert!(!o.status.success(), "the campaign went on");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains(hopeless.as_str()),
        "the run is not named: {err}"
    );
    assert!(
        err.contains("screening run 6"),
        "the run is not named: {err}"
    );
    assert!(err.contains("failed on the cluster 2 times"), "{err}");
    assert!(err.contains("/slurm/logs/"), "no log path: {err}");
    assert!(
        err.contains("asks this run"),
        "the log's last line is not quoted: {err}"
    );
    assert!(!out.join("calibration.json").exists());
}
