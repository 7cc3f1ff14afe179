#!/usr/bin/env bash
# Prints how long each test of one release test binary takes, longest first, so that the
# README's test command can be kept under CI's 20 minutes on 2 cores (the standard the
# project holds) by knowing where its time goes.
#
#   scripts/test-times.sh [host|core] [FILTER]
#
# `host` (the default) times host/tests/scenarios.rs, `core` core/tests/scenarios.rs; FILTER
# is passed to the test binary as test-name filters usually are. The Slurm tests are skipped
# (test-all.sh runs them beside the rest; they mostly wait for the scheduler). Times are wall
# seconds with the harness's usual two tests at a time, so a test that shares the machine
# with another reads longer than alone: compare them within one run. Tests that use rayon
# share its one pool, so a test can also wait behind another's jobs (measured 2026-12-02:
# the harvest rig's conformance test read 150 s in the full run and takes 2.3 s alone).
#
# Why RUSTC_BOOTSTRAP: per-test times are an unstable option of the stable toolchain's test
# harness (`-Z unstable-options --report-time`); the variable lets the stable harness accept
# it, without a nightly build of the tests.
set -euo pipefail
cd "$(dirname "$0")/.."
crate=${1:-host}
filter=${2:-}
case "$crate" in
host | core) ;;
*)
    echo "test-times.sh: the crate is host or core, got '$crate'" >&2
    exit 2
    ;;
esac
binary=$(scripts/scenario-binary.sh "$crate")
log=$(mktemp)
trap 'rm -f "$log"' EXIT
start=$(date +%s)
(cd "$crate" && RUSTC_BOOTSTRAP=1 "$binary" ${filter:+"$filter"} --skip slurm_cluster:: \
    -Z unstable-options --report-time) >"$log" 2>&1 || {
    tail -40 "$log" >&2
    exit 1
}
wall=$(($(date +%s) - start))
sed -nE 's/^test (.*) \.\.\. ok <([0-9.]+)s>$/\2 \1/p' "$log" | sort -rn |
    awk -v wall="$wall" '{ sum += $1; printf "%9.3f s  %s\n", $1, $2 }
        END { printf "%d tests, %.1f s summed over the tests, %d s wall\n", NR, sum, wall }'
