#!/usr/bin/env bash
# Runs every test of the workspace: all crates in a debug build, then the core again in
# release (golden digests must be identical in both profiles, and the release-only physics
# checks run there), and the core's fixed-point unit tests with the opt-in `float-estimate`
# square root, which must give the same bits as the default integer-only one.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo test --workspace
cargo test --release -p arachis-core
cargo test --release -p arachis-core --features float-estimate --lib --test digest_scenarios
