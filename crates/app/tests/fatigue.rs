//! Rainflow counting (ASTM E1049-85) and S-N curves (DNV-RP-C203) against their published values.

use catena::fatigue::rainflow::{count, Cycle, Rainflow};
use catena::fatigue::sn::{miner, SnCurve, NAMES};

/// Total counts per range, ranges ascending.
fn by_range(cycles: &[Cycle]) -> Vec<(f64, f64)> {
    let mut v: Vec<(f64, f64)> = Vec::new();
    for c in cycles {
        match v.iter_mut().find(|(r, _)| *r == c.range) {
            Some(e) => e.1 += c.count,
            None => v.push((c.range, c.count)),
        }
    }
    v.sort_by(|a, b| a.0.total_cmp(&b.0));
    v
}

/// ASTM E1049-85 §5.4.4's example: `[−2, 1, −3, 5, −1, 3, −4, 4, −2]` counts ranges 3 (½), 4 (1½),
/// 6 (½), 8 (1) and 9 (½); in the order found: 3 ½, 4 ½, 4 1, 8 ½, 9 ½, 8 ½, 6 ½ (the last three the
/// residue).
#[test]
fn astm_example() {
    let c = count(&[-2.0, 1.0, -3.0, 5.0, -1.0, 3.0, -4.0, 4.0, -2.0]);
    assert_eq!(
        by_range(&c),
        vec![(3.0, 0.5), (4.0, 1.5), (6.0, 0.5), (8.0, 1.0), (9.0, 0.5)]
    );
    let order: Vec<(f64, f64, f64)> = c.iter().map(|c| (c.range, c.mean, c.count)).collect();
    assert_eq!(
        order,
        vec![
            (3.0, -0.5, 0.5),
            (4.0, -1.0, 0.5),
            (4.0, 1.0, 1.0),
            (8.0, 1.0, 0.5),
            (9.0, 0.5, 0.5),
            (8.0, 0.0, 0.5),
            (6.0, 1.0, 0.5),
        ]
    );
    // Samples between reversals and plateaus change nothing.
    let dense = count(&[
        -2.0, -1.0, 1.0, 1.0, -3.0, 0.0, 5.0, -1.0, 3.0, 3.0, -4.0, 4.0, 1.0, -2.0,
    ]);
    assert_eq!(by_range(&dense), by_range(&c));
}

/// A pseudo-random series (a fixed linear congruential generator) of 216 000 samples, the length
/// of a 3-hour storm at 0.05 s.
fn series(n: usize, seed: u64) -> Vec<f64> {
    let mut s = seed;
    (0..n)
        .map(|i| {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let u = (s >> 11) as f64 / (1u64 << 53) as f64;
            (i as f64 * 0.05).sin() * 3.0 + 10.0 * (u - 0.5)
        })
        .collect()
}

/// Invariances: adding a constant shifts every mean and no range (to rounding, 1e-9); reversing the series in time
/// gives the same counts per range. The counter streams: over 216 000 samples its residue stays
/// short (it keeps reversals, not the history).
#[test]
fn invariances_and_bounded_memory() {
    let s = series(216_000, 7);
    let base = count(&s);
    let shifted: Vec<f64> = s.iter().map(|x| x + 123.25).collect();
    let sh = count(&shifted);
    assert_eq!(sh.len(), base.len());
    for (a, b) in base.iter().zip(&sh) {
        assert!((a.range - b.range).abs() < 1e-9 && a.count == b.count);
        assert!((b.mean - a.mean - 123.25).abs() < 1e-9);
    }
    let mut rev = s.clone();
    rev.reverse();
    let damage = |c: &[Cycle]| c.iter().map(|c| c.count * c.range.powi(3)).sum::<f64>();
    let (d1, d2) = (damage(&base), damage(&count(&rev)));
    assert!((d1 / d2 - 1.0).abs() < 1e-12, "{d1} vs {d2}");
    let total = |c: &[Cycle]| c.iter().map(|c| c.count).sum::<f64>();
    assert_eq!(total(&base), total(&count(&rev)));
    let mut rf = Rainflow::new();
    let mut most = 0;
    for x in &s {
        rf.push(*x, &mut |_| {});
        most = most.max(rf.residue_len());
    }
    println!("{} cycles; residue at most {most} points", base.len());
    assert!(most < 64, "{most}");
}

/// DNV-RP-C203 curve E in seawater with cathodic protection: N(20 MPa) = 6.996e8, N(40) = 2.186e7,
/// N(50) = 7.164e6, N(74.13) = 1.000e6 (the knee), N(100) = 4.074e5, to 1e-3; the thickness
/// correction at t = 25.4 mm is 1.00318. Every named curve exists, and a name catena does not know is
/// `None`.
#[test]
fn dnv_curve_e_in_seawater_check_values() {
    let e = SnCurve::dnv("dnv-e-seawater-cp").expect("curve");
    for (ds, n) in [
        (20.0, 6.996e8),
        (40.0, 2.186e7),
        (50.0, 7.164e6),
        (74.13, 1.000e6),
        (100.0, 4.074e5),
    ] {
        let got = e.cycles(ds);
        println!("N({ds} MPa) = {got:.4e} (DNV-RP-C203: {n:.3e})");
        assert!((got / n - 1.0).abs() < 1e-3, "{ds}: {got}");
    }
    assert!((e.knee_range().expect("knee") - 74.13).abs() < 0.01);
    assert!((e.thickness_factor(0.0254) - 1.00318).abs() < 1e-5);
    assert_eq!(e.thickness_factor(0.020), 1.0);
    for name in NAMES {
        assert!(SnCurve::dnv(name).is_some(), "{name}");
    }
    assert!(SnCurve::dnv("dnv-x-air").is_none());
}

/// Miner's damage scales with the stress amplitude as `2^m` on a single slope (free corrosion,
/// m = 3), exactly; and it adds up count by count.
#[test]
fn damage_scales_with_the_cube_of_the_range() {
    let curve = SnCurve::dnv("dnv-e-free-corrosion").expect("curve");
    let s = series(20_000, 3);
    let c = count(&s);
    let d1 = miner(c.iter().map(|c| (c.range, c.count)), &curve, 1.0);
    let d2 = miner(c.iter().map(|c| (c.range, c.count)), &curve, 2.0);
    assert!((d2 / d1 - 8.0).abs() < 1e-12, "{}", d2 / d1);
    // One cycle of 100 MPa on E free corrosion: 1/10^(11.533 − 6).
    let one = miner([(100.0, 1.0)], &curve, 1.0);
    assert!((one * 10f64.powf(11.533 - 6.0) - 1.0).abs() < 1e-12);
}
