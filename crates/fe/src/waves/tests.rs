use super::*;

#[test]
fn simd_and_scalar_agree_to_the_bit() {
    let w = Waves::jonswap(
        5.0,
        9.9,
        None,
        23,
        400,
        Direction::PlusX,
        1000.0,
        9.80665,
        10.0,
    )
    .expect("storm");
    let (mut a, mut b) = (w.scratch(), w.scratch());
    let mut checked = 0;
    for i in 0..400 {
        let t = 5.0 + 0.37 * i as f64;
        let (x, z) = (900.0 - 0.7 * i as f64, 2.0 - 2.5 * i as f64);
        let fast = w.kinematics_with(x, z, t, &mut a);
        let plain = w.kinematics_scalar(x, z, t, &mut b);
        assert_eq!(
            fast.map(|k| k.velocity.map(f64::to_bits)),
            plain.map(|k| k.velocity.map(f64::to_bits)),
            "{i}"
        );
        assert_eq!(
            fast.map(|k| k.acceleration.map(f64::to_bits)),
            plain.map(|k| k.acceleration.map(f64::to_bits))
        );
        checked += usize::from(fast.is_some_and(|k| k.velocity[0] != 0.0));
    }
    assert!(checked > 100, "{checked}");
}

#[test]
fn dispersion_limits() {
    let g = 9.80665;
    // Deep water: k = ω²/g.
    let w = 1.0;
    assert!((wavenumber(w, 1000.0, g) / (w * w / g) - 1.0).abs() < 1e-12);
    // Shallow water: k ≈ ω/√(gd) for kd ≪ 1.
    let w = 0.01;
    assert!((wavenumber(w, 10.0, g) / (w / (g * 10.0f64).sqrt()) - 1.0).abs() < 1e-4);
    // The relation holds in between.
    for (w, d) in [(0.5, 30.0), (1.2, 5.0), (0.3, 100.0)] {
        let k = wavenumber(w, d, g);
        assert!(
            (g * k * (k * d).tanh() / (w * w) - 1.0).abs() < 1e-13,
            "{w} {d}"
        );
    }
}
