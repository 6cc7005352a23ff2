//! The checks computed from a run, each a pure function of one step's numbers (no run, no scene
//! file): the layer that the run's observers apply at every converged step and that the studies
//! summarise.
//!
//! - [`fatigue`]: wall tension and fibre stresses, streaming rainflow counting, S-N curves and
//!   Miner's sum, spectral fatigue;
//! - [`design`]: the strength criteria at one node (DNV-ST-F201 combined loading, API STD 2RD von
//!   Mises, the Euler load) and the `Evaluator` of each node's corroded section;
//! - [`extremes`]: short-term extreme statistics of a record (Rayleigh, Weibull of peaks, Gumbel
//!   of block maxima).

pub mod design;
pub mod extremes;
pub mod fatigue;
