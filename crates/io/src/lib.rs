//! catena's outputs, above the simulation library: the HDF5 results file (its recorder is an
//! observer of the run), the JSON and text summaries, CSV tables and PNG plots.
//!
//! - [`h5`]: the HDF5 layout, the static writer and the streaming, restartable [`h5::Recorder`];
//! - [`report`]: `summary.json` and the text summaries of static and dynamic runs; [`lay`]: a lay's;
//! - [`soil`]: the soil element test's CSV and summary;
//! - [`series`]: time series in CSV and rainflow cycle tables;
//! - [`convergence`]: the convergence study's CSV, JSON, text and plot;
//! - [`plot`]: PNG plots (plotters, with an embedded DejaVu Sans font so no system font is needed);
//! - [`animate`]: the animated touchdown zone (GIF), from a run's records.
//!
//! HDF5 (`h5`, `fatigue`) is the default feature `hdf5`; without it (the Python module) the crate
//! has the plots, the tables and the animation.

pub mod animate;
pub mod convergence;
#[cfg(feature = "hdf5")]
pub mod fatigue;
#[cfg(feature = "hdf5")]
pub mod h5;
pub mod lay;
pub mod plot;
pub mod report;
pub mod series;
pub mod soil;
