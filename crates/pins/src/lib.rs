//! No code: this crate only pins the features of the dependencies the workspace's crates share
//! (its `Cargo.toml`), so that one crate built alone resolves them as the workspace does and reuses
//! the workspace's build (the mutation check, `scripts/mutations.py`, builds crate by crate).
