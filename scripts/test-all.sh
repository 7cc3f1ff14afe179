#!/usr/bin/env bash
# Runs every test of the workspace: every crate's tests in a release build (the simulation-heavy
# scenario tests need optimised code, and nothing is skipped there), the core's unit and
# scenario tests again in the test profile, with debug assertions and overflow checks on
# (golden digests must be identical in both profiles, and overflow checks catch a wrapping
# operation in the core's unchecked paths and in the test code; the workspace's Cargo.toml
# says why that profile optimises the core at level 1; its doc tests ran above), and the
# core's fixed-point tests with the opt-in `float-estimate` square root, which must give the
# same bits as the default integer-only one.
#
# The cluster executor's tests (host/tests/slurm_cluster.rs) need a one-node Slurm cluster:
# it is started here (scripts/slurm-local.sh installs slurm-wlm and munge when missing) and
# stopped at the end if this script started it. Where it cannot start, this says so and why,
# and those tests skip; where it is up, they must run (`ARACHIS_REQUIRE_SLURM=1`).
set -euo pipefail
cd "$(dirname "$0")/.."

if scripts/slurm-local.sh status >/dev/null 2>&1; then
    export "$(scripts/slurm-local.sh env)" ARACHIS_REQUIRE_SLURM=1
elif conf=$(scripts/slurm-local.sh start); then
    export "$conf" ARACHIS_REQUIRE_SLURM=1
    trap 'scripts/slurm-local.sh stop' EXIT
else
    echo "NOTE: the Slurm tests (host/tests/slurm_cluster.rs) are SKIPPED: the local cluster" \
        "did not start (the reason is printed above)" >&2
fi
# The Slurm tests spend about 100 s waiting for the scheduler and use a few CPU-seconds of
# their own: run inside the harness they hold one of its slots (and, one campaign at a time,
# often both) while the cores idle. So they run from the host's scenario binary beside the
# rest; its path is read from cargo's record of the build.
scenarios=$(scripts/scenario-binary.sh host)
slurm_log=$(mktemp)
(cd host && "$scenarios" slurm_cluster:: >"$slurm_log" 2>&1) &
slurm_tests=$!
rest_status=0
# Every test target, then the doc tests (scripts/release-tests.sh says what is left out).
source scripts/release-tests.sh
cargo test "${RELEASE_TESTS[@]}" -- --skip slurm_cluster:: || rest_status=$?
cargo test --release --workspace --exclude arachis-benches --doc || rest_status=$?
slurm_status=0
wait "$slurm_tests" || slurm_status=$?
echo "--- the Slurm tests, run beside the rest ---"
cat "$slurm_log"
rm -f "$slurm_log"
[ "$rest_status" -eq 0 ] || exit "$rest_status"
[ "$slurm_status" -eq 0 ] || { echo "the Slurm tests failed (above)" >&2; exit 1; }

cargo test -p arachis-core --lib --test scenarios
# Both float-estimate test binaries are built by one command, so that they compile at once.
float_estimate=(--release -p arachis-core --features float-estimate)
cargo test "${float_estimate[@]}" --lib --test scenarios --no-run
cargo test "${float_estimate[@]}" --lib
cargo test "${float_estimate[@]}" --test scenarios digest_scenarios::
