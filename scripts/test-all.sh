#!/usr/bin/env bash
# Runs every test of the workspace: all crates in a release build (the simulation-heavy
# scenario tests need optimised code, and nothing is skipped there), the core again in a
# debug build (golden digests must be identical in both profiles, and debug builds check
# integer overflow in the test code), and the core's fixed-point tests with the opt-in
# `float-estimate` square root, which must give the same bits as the default integer-only one.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo test --release --workspace
cargo test -p arachis-core
cargo test --release -p arachis-core --features float-estimate --lib --test digest_scenarios
