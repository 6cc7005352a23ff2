//! Fatigue: rainflow counting ([`rainflow`], ASTM E1049-85, streaming) and S-N curves with Miner's
//! damage ([`sn`], DNV-RP-C203).

pub mod rainflow;
pub mod sn;
