#!/usr/bin/env bash
# Prints the path of a crate's scenario test binary (`host` or `core`: its tests/scenarios.rs)
# from the workspace's release test build, building it first where needed. The workspace
# build is the one test-all.sh runs; one crate built alone unifies other features and builds
# anew. Used by test-all.sh and test-times.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
crate=${1:?"scenario-binary.sh: name the crate, host or core"}
# The selection of test-all.sh's release tests (it says why), so that nothing builds anew.
binary=$(cargo test --release --workspace --exclude arachis-benches --lib --bins --tests \
    --no-run --message-format=json-render-diagnostics |
    grep "\"src_path\":\"[^\"]*/$crate/tests/scenarios.rs\"" |
    grep -o '"executable":"[^"]*"' | cut -d'"' -f4)
[ -x "$binary" ] || { echo "scenario-binary.sh: the $crate scenario binary was not built" >&2; exit 1; }
echo "$binary"
