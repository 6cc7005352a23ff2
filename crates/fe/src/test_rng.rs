//! The tests' pseudo-random numbers: a 64-bit linear congruential generator (Knuth's MMIX
//! constants), deterministic, so a failing case repeats.

/// The next number of the sequence `state`, uniform in [0, 1) (the state's top 53 bits).
pub(crate) fn uniform(state: &mut u64) -> f64 {
    *state = state
        .wrapping_mul(6_364_136_223_846_793_005)
        .wrapping_add(1_442_695_040_888_963_407);
    (*state >> 11) as f64 / (1u64 << 53) as f64
}
