//! Benchmarks for catena live in this package as `[[bench]]` targets; see `benches/README.md`.
