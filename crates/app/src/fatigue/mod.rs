//! Fatigue: rainflow counting ([`rainflow`], ASTM E1049-85, streaming), S-N curves with Miner's
//! damage ([`sn`], DNV-RP-C203), stress recovery ([`stress`]: wall tension, fibre stresses) and the
//! fatigue observer of a run ([`observer`]).

pub mod observer;
pub mod rainflow;
pub mod sn;
pub mod stress;
pub mod study;
