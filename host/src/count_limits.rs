//! Count limits: the largest counts a command or a study accepts, checked where the input is
//! read (command-line parsing, `study check`), before anything is allocated or simulated
//! (issue 23: `doe design --points 1000000000` once grew to 24 GB before the kernel killed
//! it). Each limit is far above what the seeds and their calibrations use and far below what
//! exhausts a workstation; raise one here, with its reason, when research needs more.
//!
//! ```
//! use arachis::count_limits::{check_count, MAX_DESIGN_POINTS};
//! assert!(check_count("points", 17, 1, MAX_DESIGN_POINTS).is_ok());
//! let e = check_count("points", 1_000_000_000, 1, MAX_DESIGN_POINTS).unwrap_err();
//! assert!(e.contains("at most 10000"));
//! ```

use clap::builder::RangedU64ValueParser;

/// Runs of one design or points of one steepest-ascent path: seed 000 uses a 17-run
/// Box–Behnken and a 6-point path; every point is a simulation, so 10 000 is a campaign of
/// weeks at the seed's scale.
pub const MAX_DESIGN_POINTS: u64 = 10_000;
/// Centre points of one design (seed 001 Table 6 has 3): replicates for the pure error.
pub const MAX_CENTRE_POINTS: u64 = 1_000;
/// Simulations run at once (`--jobs`): more than the cores of any one machine only queue.
pub const MAX_JOBS: u64 = 1_024;
/// Plants per harvest replicate (seed 001's field plots hold a few hundred per row).
pub const MAX_PLANTS: u64 = 10_000;
/// Replicates of one harvest or measurement (seed 001's field trials: 4).
pub const MAX_REPLICATES: u64 = 1_000;
/// Pods of one simulated experiment (seed 000's pile: 900; a bulk bin of a million pods is
/// 20 million spheres, about 4 GB).
pub const MAX_PODS: u64 = 1_000_000;
/// Spheres of one multi-sphere pod (seed 000's pods: 20).
pub const MAX_SPHERES_PER_POD: u64 = 1_000;

/// `Ok` when `value` lies in `min..=max`; else the reason, naming `what` and the range.
pub fn check_count(what: &str, value: u64, min: u64, max: u64) -> Result<(), String> {
    if value < min {
        return Err(format!("{what} must be at least {min}, got {value}"));
    }
    if value > max {
        return Err(format!(
            "{what} is {value}; at most {max} are accepted (src/count_limits.rs says why; \
             raise the limit there if you need more)"
        ));
    }
    Ok(())
}

/// A command-line parser for a count in `min..=max`: clap refuses anything else, naming the
/// option and the range, with exit status 2.
pub fn count<T>(min: u64, max: u64) -> RangedU64ValueParser<T>
where
    T: TryFrom<u64> + Clone + Send + Sync + 'static,
    <T as TryFrom<u64>>::Error: std::error::Error + Send + Sync + 'static,
{
    RangedU64ValueParser::<T>::new().range(min..=max)
}
