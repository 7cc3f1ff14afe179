#!/usr/bin/env bash
# Smoke-run every cargo-fuzz target of fuzz/ for N seconds each (default 30), with debug
# assertions and overflow checks on, so a silently wrapping integer operation is a crash.
#
#   scripts/fuzz-smoke.sh [SECONDS]
#
# Needs the nightly toolchain (libFuzzer instrumentation); installs cargo-fuzz if missing.
# Crashes are written to fuzz/artifacts/<target>/; the committed reproducers in
# fuzz/regressions/<target>/ are replayed first, so a fixed crash stays fixed.
# Exit status: 0 when every target ran clean, 1 otherwise (after running all of them).
set -euo pipefail
cd "$(dirname "$0")/../fuzz"

seconds="${1:-30}"
if ! [[ "$seconds" =~ ^[0-9]+$ ]] || [ "$seconds" -eq 0 ]; then
    echo "usage: $0 [SECONDS > 0]" >&2
    exit 2
fi

if ! cargo +nightly --version >/dev/null 2>&1; then
    echo "error: the nightly toolchain is needed (rustup toolchain install nightly)" >&2
    exit 2
fi
if ! cargo fuzz --version >/dev/null 2>&1; then
    echo "cargo-fuzz not found; installing it" >&2
    cargo install --locked cargo-fuzz
fi

failed=()
for target in $(cargo +nightly fuzz list); do
    regressions="regressions/$target"
    if [ -d "$regressions" ] && [ -n "$(ls -A "$regressions")" ]; then
        echo "== $target: replaying $regressions"
        # -runs=0 executes each input once; a reproducer that still crashes fails the target.
        if ! cargo +nightly fuzz run --debug-assertions "$target" "$regressions" -- -runs=0; then
            failed+=("$target (regression)")
            continue
        fi
    fi
    echo "== $target: fuzzing for ${seconds} s"
    if ! cargo +nightly fuzz run --debug-assertions "$target" -- \
        -max_total_time="$seconds" -max_len=4096; then
        failed+=("$target")
    fi
done

if [ "${#failed[@]}" -ne 0 ]; then
    echo "fuzz smoke FAILED: ${failed[*]} (inputs in fuzz/artifacts/)" >&2
    exit 1
fi
echo "fuzz smoke passed: every target ran ${seconds} s without a crash"
