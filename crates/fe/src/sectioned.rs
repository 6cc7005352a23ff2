//! The catenary of a line of sections: the static seed of a line whose submerged weight changes
//! along it (a touchdown joint, a buoyancy section: the steel lazy wave), hanging from its top to a
//! touchdown on a flat seabed and lying on it to the anchor.
//!
//! Without bending stiffness and current, the horizontal tension `H` is the same everywhere and the
//! vertical force grows with the weight below: from the touchdown (where `V = 0`) up the arc,
//! `V(s) = ∫ w ds`, negative over a net-buoyant length. On an element of weight `w` per unit length,
//! stretched by the tension at its middle `T = √(H² + V²)` (`ℓ* = ℓ(1 + T/EA)`, `w* = wℓ/ℓ*`), the
//! line is an exact catenary piece:
//!
//! ```text
//! Δx = (H/w*)·(asinh(V₁/H) − asinh(V₀/H)),   Δz = (√(H² + V₁²) − √(H² + V₀²))/w*
//! ```
//!
//! (for `w → 0` the straight `Δx = ℓ*H/T`, `Δz = ℓ*V/T`). The grounded length lies flat, stretched
//! by `H/EA`. Two unknowns, `H` and the touchdown's arc length `s_td`, meet the top's two
//! coordinates: for a given `H` the top's height grows with the hanging length when the element
//! at the touchdown is heavy (every `V` above it grows), so `s_td` is found by bisection; the top's
//! x then grows with `H`, found by a scan and bisection on `ln H`. Each is a bracketed bisection
//! ([`catena_seabed::roots::bisect`]): it ends whatever the input, and says when there is no
//! solution (a top the line cannot reach, a line buoyant at its touchdown). The grounded length
//! holds no net-buoyant element (a buoyancy section lying on the seabed is no equilibrium: the
//! touchdown is sought below the last one).

use crate::model::LineModel;

/// Node positions and tangent angles `q` (3 per node) for `H` and `s_td` (see the module docs), and
/// the top's position reached.
fn shape(model: &LineModel, h: f64, s_td: f64, (xa, z_c): (f64, f64), q: &mut [f64]) -> (f64, f64) {
    let n = model.nodes();
    let arc = &model.arc;
    let theta_flat = -std::f64::consts::PI;
    // The grounded length, from the anchor up to the touchdown.
    let mut x = xa;
    q[3 * (n - 1)] = xa;
    q[3 * (n - 1) + 1] = z_c;
    q[3 * (n - 1) + 2] = theta_flat;
    let mut e = n - 1;
    while e > 0 {
        let el = &model.elements[e - 1];
        if arc[e - 1] < s_td {
            // The element across the touchdown: its grounded part.
            x += (arc[e] - s_td).max(0.0) * (1.0 + h / el.section.ea);
            break;
        }
        x += el.l0 * (1.0 + h / el.section.ea);
        q[3 * (e - 1)] = x;
        q[3 * (e - 1) + 1] = z_c;
        q[3 * (e - 1) + 2] = theta_flat;
        e -= 1;
    }
    // The hanging length, from the touchdown up to the top.
    let (mut z, mut v) = (z_c, 0.0);
    while e > 0 {
        let el = &model.elements[e - 1];
        let l = arc[e].min(s_td) - arc[e - 1];
        let v1 = v + el.weight * l;
        let vm = v + 0.5 * el.weight * l;
        let t = (h * h + vm * vm).sqrt();
        let ls = l * (1.0 + t / el.section.ea);
        let ws = el.weight * l / ls;
        if (ws * ls).abs() < 1e-9 * h {
            x += ls * h / t;
            z += ls * vm / t;
        } else {
            x += h / ws * ((v1 / h).asinh() - (v / h).asinh());
            z += ((h * h + v1 * v1).sqrt() - (h * h + v * v).sqrt()) / ws;
        }
        v = v1;
        q[3 * (e - 1)] = x;
        q[3 * (e - 1) + 1] = z;
        q[3 * (e - 1) + 2] = theta_flat + (v / h).atan();
        e -= 1;
    }
    (x, z)
}

/// The seed of a line of sections with its top at `top` and its anchor at `(xa, z_c)` on a flat
/// seabed at the height `z_c` of the pipe's centre there: `(q, H, s_td)`, or `None` when no such
/// shape exists (the top out of reach, the anchor lifted, a buoyant touchdown).
pub fn seed(
    model: &LineModel,
    top: (f64, f64),
    (xa, z_c): (f64, f64),
) -> Option<(Vec<f64>, f64, f64)> {
    let n = model.nodes();
    let length = model.length();
    let mut q = vec![0.0; 3 * n];
    let w_scale = model
        .elements
        .iter()
        .map(|e| e.weight.abs())
        .fold(0.0, f64::max)
        * length;
    if w_scale.is_nan() || w_scale <= 0.0 || top.1 <= z_c {
        return None;
    }
    // The grounded length may hold no net-buoyant element: the touchdown lies at or below the
    // last one's lower end.
    let s_min = model
        .elements
        .iter()
        .enumerate()
        .filter(|(_, e)| e.weight <= 0.0)
        .map(|(e, _)| model.arc[e + 1])
        .fold(0.0, f64::max);
    if s_min >= length {
        return None;
    }
    // For a given H: the touchdown whose top reaches the top's height and its top's x less the
    // top's (`Reach`); or the line reaches above the top even with the least hanging length
    // (`Steep`: H must grow), or not even with all of it (`Flat`: H must shrink).
    enum Fit {
        Steep,
        Reach(f64, f64),
        Flat,
    }
    let touchdown_for = |h: f64, q: &mut [f64]| -> Fit {
        let height = |s: f64, q: &mut [f64]| shape(model, h, s, (xa, z_c), q).1 - top.1;
        let full = height(length, q);
        if full.is_nan() || full < 0.0 {
            return Fit::Flat;
        }
        if height(s_min, q) > 0.0 {
            return Fit::Steep;
        }
        let (lo, hi) = catena_seabed::roots::bisect(s_min, length, |s| {
            let r = height(s, q);
            r >= 0.0 || r.is_nan()
        });
        // `lo` hangs too little, `hi` enough: two neighbouring numbers.
        let s = 0.5 * (lo + hi);
        let (x, _) = shape(model, h, s, (xa, z_c), q);
        Fit::Reach(x - top.0, s)
    };
    let beyond = |f: &Fit| match f {
        Fit::Steep => false,
        Fit::Reach(r, _) => *r >= 0.0 || r.is_nan(),
        Fit::Flat => true,
    };
    // The top's x grows with H: scan ln H for the first H that reaches beyond the top.
    let (ln_lo, ln_hi) = ((w_scale * 1e-7).ln(), (w_scale * 10.0).ln());
    let steps = 64;
    let mut bracket = None;
    let mut prev = ln_lo;
    for k in 0..=steps {
        let ln_h = ln_lo + (ln_hi - ln_lo) * k as f64 / steps as f64;
        if beyond(&touchdown_for(ln_h.exp(), &mut q)) {
            if k > 0 {
                bracket = Some((prev, ln_h));
            }
            break;
        }
        prev = ln_h;
    }
    let (a, b) = bracket?;
    let (lo, _) =
        catena_seabed::roots::bisect(a, b, |ln_h| beyond(&touchdown_for(ln_h.exp(), &mut q)));
    let h = lo.exp();
    let Fit::Reach(r, s_td) = touchdown_for(h, &mut q) else {
        return None;
    };
    // The bracket's lower end falls short by at most the bisection's resolution; a miss of more
    // than a thousandth of the span means the scan found no root.
    if r.abs() > 1e-3 * (top.0 - xa).abs().max(1.0) {
        return None;
    }
    shape(model, h, s_td, (xa, z_c), &mut q);
    Some((q, h, s_td))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analytical::TouchdownCatenary;
    use crate::beam::Section;
    use crate::model::{LineSpec, Segment, Support};

    fn line(segments: Vec<Segment>) -> LineModel {
        LineModel::build(&LineSpec {
            segments,
            top: Support::Pinned,
            anchor: Support::Pinned,
            seabed: None,
            flexjoint: None,
        })
        .expect("test data")
    }

    /// A uniform inextensible line: the sectioned catenary is the touchdown catenary (H to 1e-6).
    #[test]
    fn uniform_line_is_the_touchdown_catenary() {
        let sec = Section { ea: 1e15, ei: 1e6 };
        let m = line(vec![Segment::uniform(1600.0, 4.0, sec, 1000.0, 100.0, 0.2)]);
        let (_, h, s_td) = seed(&m, (900.0, 1000.0), (0.0, 0.0)).expect("test data");
        let c = TouchdownCatenary::solve(1000.0, 900.0, 1000.0, 1600.0).expect("test data");
        assert!(
            (h / (1000.0 * c.a) - 1.0).abs() < 1e-6,
            "H {h} vs {}",
            1000.0 * c.a
        );
        assert!(
            (s_td - c.suspended).abs() < 1e-3,
            "{s_td} vs {}",
            c.suspended
        );
    }

    /// A lazy wave: the seed hangs from the top to a sag bend, rises over the buoyant length to a
    /// hog bend above it and falls to the touchdown, beyond the buoyancy; at every hanging node
    /// `tan θ` is the weight below it over H.
    #[test]
    fn lazy_wave_has_a_sag_and_a_hog() {
        let sec = Section {
            ea: 3.4e9,
            ei: 1.8e7,
        };
        let m = line(vec![
            Segment::uniform(1100.0, 5.0, sec, 1010.0, 145.0, 0.23),
            Segment::uniform(300.0, 5.0, sec, -1200.0, 400.0, 0.9),
            Segment::uniform(900.0, 5.0, sec, 1010.0, 145.0, 0.23),
        ]);
        let top = (1500.0, 980.0);
        let (q, h, s_td) = seed(&m, top, (0.0, 0.1)).expect("test data");
        assert!((q[0] - top.0).abs() < 1.0 && (q[1] - top.1).abs() < 1e-3);
        let z: Vec<f64> = (0..m.nodes()).map(|i| q[3 * i + 1]).collect();
        // Interior extrema of the hanging length: one minimum (sag), then one maximum (hog).
        let ext: Vec<(usize, bool)> = (1..m.nodes() - 1)
            .filter(|&i| m.arc[i] < s_td - 5.0)
            .filter_map(|i| {
                if z[i] < z[i - 1] && z[i] <= z[i + 1] {
                    Some((i, false))
                } else if z[i] > z[i - 1] && z[i] >= z[i + 1] {
                    Some((i, true))
                } else {
                    None
                }
            })
            .collect();
        assert_eq!(ext.len(), 2, "{ext:?}");
        let ((sag, false), (hog, true)) = (ext[0], ext[1]) else {
            panic!("{ext:?}")
        };
        assert!(
            z[hog] > z[sag] + 10.0 && z[sag] > 1.0,
            "sag {} hog {}",
            z[sag],
            z[hog]
        );
        assert!(s_td > 1400.0, "touchdown at {s_td}");
        // tan θ = V/H with V the weight hanging below the node.
        for i in [10, sag, hog, (hog + m.nodes()) / 2] {
            let v: f64 = m
                .elements
                .iter()
                .enumerate()
                .map(|(e, el)| {
                    el.weight * (m.arc[e + 1].min(s_td) - m.arc[e].max(m.arc[i])).max(0.0)
                })
                .sum();
            let t = (q[3 * i + 2] + std::f64::consts::PI).tan();
            assert!(
                (t - v / h).abs() < 1e-9 * (1.0 + (v / h).abs()),
                "node {i}: {t} vs {}",
                v / h
            );
        }
    }

    /// A top out of reach (higher than the line is long) has no seed.
    #[test]
    fn unreachable_top_has_none() {
        let sec = Section { ea: 1e12, ei: 1e6 };
        let m = line(vec![Segment::uniform(100.0, 5.0, sec, 1000.0, 100.0, 0.2)]);
        assert!(seed(&m, (50.0, 200.0), (0.0, 0.0)).is_none());
    }
}
