# Sourced by test-all.sh and scenario-binary.sh: the cargo selection of the release tests, in
# one place, so that the scenario binary scenario-binary.sh finds is the one test-all.sh
# built (another selection unifies other features and builds anew).
#
# Every test target of the workspace; not the examples, which hold no test, and not the
# benches crate, which holds none either (its criterion benchmarks run under `cargo bench`):
# clippy (`.ci/run`) checks both, and building them here would cost CI the criterion crates
# and the examples for nothing. The doc tests run in a command of their own (`--doc`).
# shellcheck disable=SC2034 # used by the scripts that source this file
RELEASE_TESTS=(--release --workspace --exclude arachis-benches --lib --bins --tests)
