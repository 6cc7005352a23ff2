use super::top_down::{factor_band_dyn, solve_band_dyn};
use super::*;

/// A block-tridiagonal SPD system like a beam's (3 dof per node): the sparse LDLᵀ solution matches
/// the product check `A x = b` to 1e-10, refactoring twice with new values, with the AMD and the
/// natural (identity) ordering, both from the upper triangle.
#[test]
fn ldlt_solves_banded_spd_system() {
    let nodes = 50;
    let n = 3 * nodes;
    let pairs = (0..nodes - 1)
        .flat_map(|e| (0..6).flat_map(move |a| (0..6).map(move |b| (3 * e + a, 3 * e + b))));
    let mut a = SparseSym::from_couplings(n, pairs);
    for natural in [false, true] {
        let mut solver = LdltSolver::with_ordering(&a, natural).expect("symbolic");
        for round in 0..2 {
            a.clear();
            for e in 0..nodes - 1 {
                for i in 0..6 {
                    for j in i..6 {
                        let (r, c) = (3 * e + i, 3 * e + j);
                        let v = if i == j {
                            10.0 + round as f64
                        } else {
                            0.5 / (1 + i + j) as f64
                        };
                        let s = a.slot(r, c).expect("in pattern");
                        a.values[s] += v;
                    }
                }
            }
            solver.factor(&a).expect("factor");
            let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
            let mut x = b.clone();
            solver.solve_in_place(&mut x);
            let mut ax = vec![0.0; n];
            a.mul(&x, &mut ax);
            let err = ax
                .iter()
                .zip(&b)
                .map(|(p, q)| (p - q).abs())
                .fold(0.0, f64::max);
            assert!(err < 1e-10, "natural order {natural}, round {round}: {err}");
        }
    }
}

/// The band solver and faer's agree on a beam-like system (and on `A x = b` to 1e-10), with
/// the band's own layout for a pattern that skips entries inside the band; a wide pattern goes
/// to faer.
#[test]
fn refactoring_a_band_with_holes_is_a_fresh_factorisation() {
    // Equation 1's couplings with equations 2 and 3 dropped: holes inside the skyline of
    // columns 2 and 3, which the factor fills in. A second factorisation in the same solver
    // must start from zeros there.
    let nodes = 10;
    let n = 3 * nodes;
    let pairs = (0..nodes - 1)
        .flat_map(|e| (0..6).flat_map(move |a| (0..6).map(move |b| (3 * e + a, 3 * e + b))))
        .filter(|&(i, j)| !matches!((i.min(j), i.max(j)), (1, 2) | (1, 3)));
    let mut a = SparseSym::from_couplings(n, pairs);
    assert!(a.slot(1, 3).is_none() && a.slot(0, 3).is_some());
    let fill = |a: &mut SparseSym, seed: usize| {
        for k in 0..a.values.len() {
            a.values[k] = 0.3 * (((k + seed) * 7919 % 101) as f64 / 101.0 - 0.5);
        }
        for i in 0..a.n {
            let d = a.slot(i, i).expect("diagonal");
            a.values[d] = 4.0 + ((i + seed) % 5) as f64;
        }
    };
    fill(&mut a, 0);
    let mut reused = BandLdlt::new(&a);
    assert!(!reused.holes.is_empty());
    reused.factor(&a).expect("first");
    fill(&mut a, 3);
    reused.factor(&a).expect("second");
    let mut fresh = BandLdlt::new(&a);
    fresh.factor(&a).expect("fresh");
    let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&reused.band), bits(&fresh.band));
}

#[test]
fn band_and_sparse_agree() {
    let nodes = 60;
    let n = 3 * nodes;
    // Elements couple nodes e and e+1; one equation in four is dropped from the couplings of
    // the first element (a prescribed dof leaves a hole in the band).
    let pairs = (0..nodes - 1)
        .flat_map(|e| (0..6).flat_map(move |a| (0..6).map(move |b| (3 * e + a, 3 * e + b))))
        .filter(|&(i, j)| !(i < 6 && j < 6 && (i == 1 || j == 1) && i != j));
    let mut a = SparseSym::from_couplings(n, pairs);
    assert_eq!(a.half_bandwidth(), 5);
    for k in 0..a.values.len() {
        a.values[k] = 0.3 * ((k * 7919 % 101) as f64 / 101.0 - 0.5);
    }
    for i in 0..n {
        let d = a.slot(i, i).expect("diagonal");
        a.values[d] = 4.0 + (i % 5) as f64 - 6.0 * f64::from(u8::from(i == 17));
    }
    let mut band = LinearSolver::new(&a).expect("band");
    assert!(matches!(band, LinearSolver::Band(_)));
    let mut sparse = LdltSolver::with_ordering(&a, true).expect("sparse");
    band.factor(&a).expect("band factor");
    sparse.factor(&a).expect("sparse factor");
    let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).cos()).collect();
    let (mut x1, mut x2) = (b.clone(), b.clone());
    band.solve_in_place(&mut x1);
    sparse.solve_in_place(&mut x2);
    let mut ax = vec![0.0; n];
    a.mul(&x1, &mut ax);
    for i in 0..n {
        assert!((ax[i] - b[i]).abs() < 1e-10, "residual at {i}");
        assert!((x1[i] - x2[i]).abs() < 1e-10 * (1.0 + x2[i].abs()), "{i}");
    }
    // Wide: a coupling of the first and the last equation.
    let wide = SparseSym::from_couplings(n, [(0, n - 1)]);
    assert!(matches!(
        LinearSolver::new(&wide).expect("wide"),
        LinearSolver::Sparse(_)
    ));
}

/// The unrolled half-width-5 factorisation and solve are the general loops' to the bit, on
/// beam-like patterns with holes in the skyline (a prescribed dof) and on short lines (fewer
/// equations than the unrolled window), with negative pivots among them.
#[test]
fn unrolled_band_is_the_general_band_to_the_bit() {
    // A line's pattern (copied into the band in blocks) and one with couplings taken out
    // (scattered through the map, holes zeroed).
    for (nodes, holed) in [1, 2, 3, 4, 7, 61]
        .into_iter()
        .flat_map(|n| [(n, true), (n, false)])
    {
        let n = 3 * nodes;
        let pairs = (0..nodes.max(2) - 1)
            .flat_map(|e| (0..6).flat_map(move |a| (0..6).map(move |b| (3 * e + a, 3 * e + b))))
            .filter(|&(i, j)| i < n && j < n)
            .filter(|&(i, j)| {
                !(holed && (i == 1 || j == 1 || i == 8 || j == 8) && i != j && i.max(j) < 12)
            });
        let mut a = SparseSym::from_couplings(n, pairs);
        for k in 0..a.values.len() {
            a.values[k] = 0.3 * ((k * 7919 % 101) as f64 / 101.0 - 0.5) * (1.0 + k as f64).sqrt();
        }
        for i in 0..n {
            let d = a.slot(i, i).expect("diagonal");
            a.values[d] = 4.0 + (i % 5) as f64 - 9.0 * f64::from(u8::from(i % 17 == 5));
        }
        let mut ldlt = BandLdlt::new(&a);
        if ldlt.w != 5 {
            continue;
        }
        assert_eq!(ldlt.blocks, !holed, "{nodes} nodes");
        // Top-down (a long line is factorised from both ends: the next test).
        assert_eq!(ldlt.twist.is_some(), !holed && n >= TWIST_MIN);
        ldlt.twist = None;
        // Factorised twice: the second time on the first's band.
        ldlt.factor(&a).expect("factor");
        ldlt.factor(&a).expect("factor");
        let mut general = ldlt.band.clone();
        general.fill(0.0);
        for (v, &m) in a.values.iter().zip(&ldlt.map) {
            general[m] = *v;
        }
        factor_band_dyn(&ldlt.first, 5, &mut general).expect("general factor");
        // The factor within each column's skyline (above it, a block copy leaves the
        // previous column's values, never read).
        let skyline = |v: &[f64]| {
            (0..n)
                .flat_map(|c| (ldlt.first[c]..=c).map(move |r| c * 6 + r + 5 - c))
                .map(|m| v[m].to_bits())
                .collect::<Vec<_>>()
        };
        assert_eq!(
            skyline(&ldlt.band),
            skyline(&general),
            "factor, {nodes} nodes"
        );
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).cos() * 1e3).collect();
        let (mut x1, mut x2) = (b.clone(), b.clone());
        ldlt.solve_in_place(&mut x1);
        solve_band_dyn(&ldlt.first, 5, &general, &mut x2);
        assert_eq!(bits(&x1), bits(&x2), "solve, {nodes} nodes");
    }
}

/// A line's pattern (3 unknowns a node, elements coupling neighbours) of `nodes` nodes, with
/// the values of [`unrolled_band_is_the_general_band_to_the_bit`] scaled by `seed`: negative
/// pivots among them.
fn line_system(nodes: usize, seed: usize) -> SparseSym {
    let n = 3 * nodes;
    let pairs = (0..nodes - 1)
        .flat_map(|e| (0..6).flat_map(move |a| (0..6).map(move |b| (3 * e + a, 3 * e + b))));
    let mut a = SparseSym::from_couplings(n, pairs);
    for k in 0..a.values.len() {
        a.values[k] =
            0.3 * (((k + seed) * 7919 % 101) as f64 / 101.0 - 0.5) * (1.0 + k as f64).sqrt();
    }
    for i in 0..n {
        let d = a.slot(i, i).expect("diagonal");
        a.values[d] = 4.0 + (i % 5) as f64 - 9.0 * f64::from(u8::from((i + seed) % 17 == 5));
    }
    a
}

/// A line's pattern of `nodes` nodes with its couplings zero and its diagonal 2 but a zero at
/// equation `e`: each pivot is its diagonal whatever the order, so the zero pivot is at `e`.
fn decoupled(nodes: usize, e: usize) -> SparseSym {
    let mut a = line_system(nodes, 0);
    a.values.fill(0.0);
    for i in 0..a.n {
        let d = a.slot(i, i).expect("diagonal");
        a.values[d] = if i == e { 0.0 } else { 2.0 };
    }
    a
}

/// The twisted factorisation (from both ends, [`factor_twisted5`]) solves a line's system as
/// the top-down one does, to rounding: `A x = b` to 1e-11 relative and the two solutions to
/// 1e-11 of the largest unknown, on lines of 14 to 401 nodes (every meeting place modulo a
/// node's three unknowns, both parities of the length), with negative pivots, factorised twice
/// in the same solver (a second block copy over the first factor; the places above the
/// skyline must be zeroed again for the solve).
#[test]
fn twisted_band_is_the_band_to_rounding() {
    for nodes in [14, 15, 16, 17, 18, 19, 40, 101, 401] {
        for seed in [0, 3] {
            let a = line_system(nodes, seed);
            let n = a.n;
            let mut twisted = BandLdlt::new(&a);
            assert!(twisted.blocks && twisted.twist.is_some(), "{nodes} nodes");
            let mut top_down = twisted.clone();
            top_down.twist = None;
            twisted
                .factor(&line_system(nodes, seed + 1))
                .expect("first");
            twisted.factor(&a).expect("twisted");
            top_down.factor(&a).expect("top-down");
            let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).cos() * 1e3).collect();
            let (mut x1, mut x2) = (b.clone(), b.clone());
            twisted.solve_in_place(&mut x1);
            top_down.solve_in_place(&mut x2);
            let mut ax = vec![0.0; n];
            a.mul(&x1, &mut ax);
            let scale = x2.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            for i in 0..n {
                assert!(
                    (ax[i] - b[i]).abs() < 1e-11 * 1e3 * scale.max(1.0),
                    "{nodes} nodes, residual at {i}: {}",
                    ax[i] - b[i]
                );
                assert!(
                    (x1[i] - x2[i]).abs() < 1e-11 * scale,
                    "{nodes} nodes, unknown {i}: {} against {}",
                    x1[i],
                    x2[i]
                );
            }
            assert_ne!(x1, x2, "a different order rounds differently somewhere");
        }
    }
}

/// The twisted factorisation names the zero pivot wherever it is: in the top end, in the
/// bottom end (general and unrolled rows) and in the middle block.
#[test]
fn twisted_band_reports_a_zero_pivot() {
    let nodes = 30;
    let n = 3 * nodes;
    let m = (n - 5) / 2;
    for e in [2, 7, m - 1, m, m + 2, m + 4, m + 5, n - 8, n - 3, n - 1] {
        let a = decoupled(nodes, e);
        let mut band = BandLdlt::new(&a);
        assert_eq!(band.twist, Some(m));
        assert_eq!(
            band.factor(&a),
            Err(SolveError::Singular { equation: e }),
            "{e}"
        );
    }
}

/// A singular band matrix names its zero pivot.
#[test]
fn band_reports_a_zero_pivot() {
    let mut a = SparseSym::from_couplings(3, [(0, 1), (1, 2)]);
    for (i, j, v) in [
        (0, 0, 1.0),
        (0, 1, 1.0),
        (1, 1, 1.0),
        (1, 2, 0.5),
        (2, 2, 2.0),
    ] {
        let s = a.slot(i, j).expect("slot");
        a.values[s] = v;
    }
    let mut b = BandLdlt::new(&a);
    assert_eq!(b.factor(&a), Err(SolveError::Singular { equation: 1 }));
}

/// An indefinite (but nonsingular) matrix still factors: LDLᵀ takes negative pivots.
#[test]
fn ldlt_handles_negative_pivots() {
    let mut a = SparseSym::from_couplings(3, [(0, 1), (1, 2)]);
    let vals = [
        (0, 0, 2.0),
        (0, 1, 1.0),
        (1, 1, -3.0),
        (1, 2, 1.0),
        (2, 2, 4.0),
    ];
    for (i, j, v) in vals {
        let s = a.slot(i, j).expect("slot");
        a.values[s] = v;
    }
    let mut solver = LdltSolver::new(&a).expect("symbolic");
    solver.factor(&a).expect("factor");
    let mut band = BandLdlt::new(&a);
    band.factor(&a).expect("band factor");
    let b = [1.0, 2.0, 3.0];
    for use_band in [false, true] {
        let mut x = b;
        if use_band {
            band.solve_in_place(&mut x);
        } else {
            solver.solve_in_place(&mut x);
        }
        let mut ax = [0.0; 3];
        a.mul(&x, &mut ax);
        for i in 0..3 {
            assert!((ax[i] - b[i]).abs() < 1e-12, "band {use_band}");
        }
    }
}

/// The twisted band on two threads ([`BandLdlt::use_partner`]) gives the one-thread twisted
/// band's factor and solution to the bit: lines of 14 to 401 nodes (every meeting place modulo a
/// node's three unknowns), negative pivots, factorised twice in the same solver and solved twice
/// per factorisation; a band too short to be twisted stays on one thread.
#[test]
fn split_band_is_the_twisted_band_to_the_bit() {
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    for nodes in [14, 15, 16, 17, 18, 19, 40, 101, 401] {
        for seed in [0, 3] {
            let a = line_system(nodes, seed);
            let n = a.n;
            let mut one = BandLdlt::new(&a);
            let mut two = one.clone();
            assert!(two.use_partner().expect("thread"), "{nodes} nodes");
            assert!(two.has_partner() && !two.clone().has_partner());
            for (round, values) in [line_system(nodes, seed + 1), a.clone()].iter().enumerate() {
                one.factor(values).expect("one thread");
                two.factor(values).expect("two threads");
                assert_eq!(*one.middle, *two.middle, "{nodes} nodes, round {round}");
                let m = one.twist.expect("twisted");
                let top = 0..6 * (m + 10);
                assert_eq!(
                    bits(&one.band[top.clone()]),
                    bits(&two.band[top]),
                    "{nodes} nodes, round {round}: the top store"
                );
                for k in 0..2 {
                    let b: Vec<f64> = (0..n)
                        .map(|i| (i as f64 * 0.37 + k as f64).cos() * 1e3)
                        .collect();
                    let (mut x1, mut x2) = (b.clone(), b);
                    one.solve_in_place(&mut x1);
                    two.solve_in_place(&mut x2);
                    assert_eq!(
                        bits(&x1),
                        bits(&x2),
                        "{nodes} nodes, round {round}, solve {k}"
                    );
                }
            }
        }
    }
    let mut short = BandLdlt::new(&line_system(12, 0));
    assert!(!short.use_partner().expect("no thread"));
    assert!(!short.has_partner());
}

/// On two threads the factorisation names a zero pivot in either end and in the middle block.
#[test]
fn split_band_reports_a_zero_pivot() {
    let nodes = 30;
    let n = 3 * nodes;
    let m = (n - 5) / 2;
    let mut band = BandLdlt::new(&line_system(nodes, 0));
    assert!(band.use_partner().expect("thread"));
    for e in [2, 7, m - 1, m, m + 2, m + 4, m + 5, n - 8, n - 3, n - 1] {
        let a = decoupled(nodes, e);
        assert_eq!(
            band.factor(&a),
            Err(SolveError::Singular { equation: e }),
            "{e}"
        );
    }
    band.factor(&line_system(nodes, 0))
        .expect("a regular one after");
}

/// Side `side`'s solutions of [`band_sides_are_the_twisted_band_to_the_bit`]: each system
/// factorised, then solved for two right-hand sides.
fn side_solutions(
    mut band: BandLdlt,
    side: usize,
    seat: &mut crate::partner::Seat,
    systems: &[SparseSym],
) -> Vec<Vec<f64>> {
    let mut out = Vec::new();
    for a in systems {
        band.factor_side(a, side, seat).expect("a factorisation");
        for k in 0..2 {
            let mut x = sides_rhs(a.n, k);
            band.solve_side(side, seat, &mut x);
            out.push(x);
        }
    }
    out
}

/// The right-hand sides of [`band_sides_are_the_twisted_band_to_the_bit`].
fn sides_rhs(n: usize, k: usize) -> Vec<f64> {
    (0..n)
        .map(|i| (i as f64 * 0.37 + k as f64).cos() * 1e3)
        .collect()
}

/// The twisted band by two threads that each hold a copy and meet at a pair of seats
/// ([`BandLdlt::factor_side`], [`BandLdlt::solve_side`]): the top side's unknowns `0..m+5` and
/// the bottom side's `m+5..n` are the one-thread solution to the bit, on lines of 14 to 401 nodes,
/// factorised twice and solved twice each time; a zero pivot is named alike on both sides,
/// wherever it is.
#[test]
fn band_sides_are_the_twisted_band_to_the_bit() {
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    for nodes in [14, 17, 19, 40, 101, 401] {
        let systems = [line_system(nodes, 1), line_system(nodes, 0)];
        let mut one = BandLdlt::new(&systems[0]);
        let (n, p) = (systems[0].n, one.twist.expect("twisted") + 5);
        let (mut seat0, mut seat1) = crate::partner::seats(31);
        let other = {
            let (systems, bottom) = (systems.clone(), one.clone());
            std::thread::spawn(move || side_solutions(bottom, 1, &mut seat1, &systems))
        };
        let tops = side_solutions(one.clone(), 0, &mut seat0, &systems);
        let bottoms = other.join().expect("the bottom side");
        let mut k = 0;
        for a in &systems {
            one.factor(a).expect("one thread");
            for r in 0..2 {
                let mut x = sides_rhs(n, r);
                one.solve_in_place(&mut x);
                assert_eq!(bits(&tops[k][..p]), bits(&x[..p]), "{nodes} nodes, top");
                assert_eq!(
                    bits(&bottoms[k][p..]),
                    bits(&x[p..]),
                    "{nodes} nodes, bottom"
                );
                k += 1;
            }
        }
    }
    let nodes = 30;
    let n = 3 * nodes;
    let m = (n - 5) / 2;
    let band = BandLdlt::new(&line_system(nodes, 0));
    for e in [2, m - 1, m, m + 4, m + 5, n - 3] {
        let a = decoupled(nodes, e);
        let (mut s0, mut s1) = crate::partner::seats(31);
        let (mut top, mut bottom) = (band.clone(), band.clone());
        let b = a.clone();
        let other = std::thread::spawn(move || bottom.factor_side(&b, 1, &mut s1));
        let want = Err(SolveError::Singular { equation: e });
        assert_eq!(top.factor_side(&a, 0, &mut s0), want, "top side, {e}");
        assert_eq!(other.join().expect("bottom"), want, "bottom side, {e}");
    }
}
