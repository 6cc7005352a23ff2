//! The observers that apply the [`checks`](crate::checks) during a run, each built by the
//! registry ([`crate::run::outputs`]) when its scene table is there: [`fatigue`] (`[fatigue]`:
//! rainflow and Miner damage along the line, counted on a thread of its own), [`design`]
//! (`[design_check]`: the utilisation at every node and step) and [`extremes`] (`[extremes]`: the
//! channels' records, analysed at the end). A new check's observer goes here, beside them.

pub mod design;
pub mod extremes;
pub mod fatigue;
