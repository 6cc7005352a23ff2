//! catena's outputs, above the simulation library: the HDF5 results file (its recorder is an
//! observer of the run), the JSON and text summaries, CSV tables and PNG plots.
//!
//! - [`h5`]: the HDF5 layout, the static writer and the streaming, restartable [`h5::Recorder`];
//! - [`report`]: `summary.json` and the text summaries of static and dynamic runs;
//! - [`soil`]: the soil element test's CSV and summary;
//! - [`series`]: time series in CSV and rainflow cycle tables;
//! - [`convergence`]: the convergence study's CSV, JSON, text and plot;
//! - [`plot`]: PNG plots (plotters, with an embedded DejaVu Sans font so no system font is needed).

pub mod convergence;
pub mod fatigue;
pub mod h5;
pub mod plot;
pub mod report;
pub mod series;
pub mod soil;
pub mod sweep;
