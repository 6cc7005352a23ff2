//! The `catena` command line, as a library so that its commands can be tested: each command reads
//! its files, runs the library (`catena`) and writes its outputs (`catena-io`). The binary
//! (`src/main.rs`) parses the arguments with clap and installs the SIGINT/SIGTERM handler.
//!
//! - [`commands`]: one module per command;
//! - [`progress`]: the progress bar and the signal watcher, both observers.

pub mod commands;
pub mod progress;

pub use commands::{calibrate, sequence};
