//! The progress bar of a calibration: one `indicatif` bar per batch of simulations,
//! drawn on stderr, hidden when stderr is not a terminal or the user asked for quiet.

use std::io::IsTerminal;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// Progress of the simulations of one stage.
#[derive(Debug, Clone)]
pub struct Progress {
    visible: bool,
}

/// Template of the bar: stage, bar, runs done, rate, time left.
const TEMPLATE: &str = "{msg:>16} {bar:40} {pos}/{len} runs  {elapsed_precise}  eta {eta}";

impl Progress {
    /// A progress display; drawn only when `quiet` is false and stderr is a terminal.
    pub fn new(quiet: bool) -> Self {
        Self {
            visible: !quiet && std::io::stderr().is_terminal(),
        }
    }

    /// A display that never draws (library use and tests).
    pub fn hidden() -> Self {
        Self { visible: false }
    }

    /// A bar for `stage` with `total` runs of which `done` were found in the cache.
    pub fn stage(&self, stage: &str, total: usize, done: usize) -> ProgressBar {
        let bar = ProgressBar::with_draw_target(
            Some(total as u64),
            if self.visible {
                ProgressDrawTarget::stderr()
            } else {
                ProgressDrawTarget::hidden()
            },
        );
        if let Ok(style) = ProgressStyle::with_template(TEMPLATE) {
            bar.set_style(style);
        }
        bar.set_message(stage.to_owned());
        bar.set_position(done as u64);
        bar
    }
}
