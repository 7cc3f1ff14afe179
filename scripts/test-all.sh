#!/usr/bin/env bash
# Runs every test of the workspace: all crates in a debug build, then the core again in
# release, because golden digests must be identical in both profiles.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo test --workspace
cargo test --release -p arachis-core
