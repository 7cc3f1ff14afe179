//! Criterion benchmarks of Arachis live in `benches/benches/`; this library is empty.
