//! Bench-test analysis: turns replicate measurements into parameter values (issue 3).
