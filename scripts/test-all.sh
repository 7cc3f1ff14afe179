#!/usr/bin/env bash
# Runs every test of the workspace: all crates in a release build (the simulation-heavy
# scenario tests need optimised code, and nothing is skipped there), the core again in a
# debug build (golden digests must be identical in both profiles, and debug builds check
# integer overflow in the test code), and the core's fixed-point tests with the opt-in
# `float-estimate` square root, which must give the same bits as the default integer-only one.
#
# The cluster executor's tests (host/tests/slurm_cluster.rs) need a one-node Slurm cluster:
# it is started here (scripts/slurm-local.sh installs slurm-wlm and munge when missing) and
# stopped at the end if this script started it. Where it cannot start, this says so and why,
# and those tests skip.
set -euo pipefail
cd "$(dirname "$0")/.."

if scripts/slurm-local.sh status >/dev/null 2>&1; then
    export "$(scripts/slurm-local.sh env)"
elif conf=$(scripts/slurm-local.sh start); then
    export "$conf"
    trap 'scripts/slurm-local.sh stop' EXIT
else
    echo "NOTE: the Slurm tests (host/tests/slurm_cluster.rs) are SKIPPED: the local cluster" \
        "did not start (the reason is printed above)" >&2
fi
cargo test --release --workspace
cargo test -p arachis-core
cargo test --release -p arachis-core --features float-estimate --lib
cargo test --release -p arachis-core --features float-estimate --test scenarios digest_scenarios::
