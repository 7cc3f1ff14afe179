#!/usr/bin/env bash
# Prints the path of a crate's scenario test binary (`host` or `core`: its tests/scenarios.rs)
# from the workspace's release test build (scripts/release-tests.sh), building it first where
# needed. Used by test-all.sh and test-times.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
crate=${1:?"scenario-binary.sh: name the crate, host or core"}
source scripts/release-tests.sh
binary=$(cargo test "${RELEASE_TESTS[@]}" --no-run --message-format=json-render-diagnostics |
    grep "\"src_path\":\"[^\"]*/$crate/tests/scenarios.rs\"" |
    grep -o '"executable":"[^"]*"' | cut -d'"' -f4)
[ -x "$binary" ] || { echo "scenario-binary.sh: the $crate scenario binary was not built" >&2; exit 1; }
echo "$binary"
