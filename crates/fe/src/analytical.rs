//! Closed-form solutions: the catenary in its three forms (touching down on a flat rigid seabed,
//! elastic with a stretched grounded part, and hanging free between two points), the touchdown
//! boundary-layer moment, and helpers. Used to seed static solves and as test anchors
//! (`docs/cases.md` §5).
//!
//! Frame: `x` horizontal from the anchor towards the top, `z` up. Arc length `s` from the top.
//! Angles `θ` are those of the tangent pointing down the line (towards the anchor), counter-clockwise
//! from `+x`, taken in `(−3π/2, −π/2)` so that they are continuous along a riser
//! (`θ = −π` where the line lies flat heading to the anchor).
//!
//! **Inextensible catenary with touchdown** (`a = H/w`, `h` the top's height above the contact level,
//! `X` the horizontal span from anchor to top, `L` the length):
//!
//! ```text
//! s_susp = sqrt(h² + 2 a h),   X = (L − s_susp) + a·asinh(s_susp / a),   T_top = w (a + h)
//! ```
//!
//! **Elastic catenary (Irvine)**, `s` the unstretched arc from the touchdown point:
//!
//! ```text
//! x(s) = a·asinh(s/a) + H s/EA,   z(s) = a (sqrt(1 + (s/a)²) − 1) + w s²/(2 EA)
//! X = x(s_susp) + (L − s_susp)(1 + H/EA)
//! ```
//!
//! **Touchdown boundary layer** on a linear tensionless seabed of stiffness `k` per unit length:
//! `λ = sqrt(EI/H)`, `K = k EI/H²`, `p = sqrt((sqrt(K) + 1/2)/2)`, `M_TDP = (EI w/H)/(p + 1/2)`.

use std::f64::consts::PI;

/// An inextensible catenary touching down on a flat seabed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TouchdownCatenary {
    /// Submerged weight per unit length w, N/m.
    pub w: f64,
    /// `a = H/w`, m.
    pub a: f64,
    /// Height of the top above the contact level, m.
    pub h: f64,
    /// Length of the line, m.
    pub length: f64,
    /// Suspended length, m.
    pub suspended: f64,
}

/// Why a catenary has no solution of the requested kind.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum CatenaryError {
    /// The line is shorter than the straight distance between its ends.
    #[error("the line ({length} m) is shorter than the distance between its ends ({chord} m)")]
    TooShort {
        /// Line length, m.
        length: f64,
        /// Distance between the ends, m.
        chord: f64,
    },
    /// The line is longer than the height plus the horizontal span: it would pile up on the seabed.
    #[error(
        "the line ({length} m) is longer than the height plus the horizontal span ({reach} m)"
    )]
    TooLong {
        /// Line length, m.
        length: f64,
        /// Height plus span, m.
        reach: f64,
    },
    /// The line does not reach the seabed (use the free-hanging catenary).
    #[error("the line does not touch down")]
    NoTouchdown,
    /// Bad numbers (non-positive weight, length or height).
    #[error("invalid catenary data: {0}")]
    Invalid(&'static str),
}

/// The sign change of `f` in `[lo, hi]` (the shared bisection, `catena_seabed::roots`).
fn bisect(lo: f64, hi: f64, f: impl Fn(f64) -> f64) -> f64 {
    let flo = f(lo) > 0.0;
    let (a, b) = catena_seabed::roots::bisect(lo, hi, |m| (f(m) > 0.0) != flo);
    0.5 * (a + b)
}

impl TouchdownCatenary {
    /// Solves for the catenary with the top at horizontal distance `span` and height `h` above the
    /// contact level, and the rest of the line lying on the seabed towards the anchor.
    pub fn solve(w: f64, span: f64, h: f64, length: f64) -> Result<Self, CatenaryError> {
        if !(w > 0.0 && h > 0.0 && length > 0.0 && span > 0.0) {
            return Err(CatenaryError::Invalid("w, span, h and length must be > 0"));
        }
        let chord = (span * span + h * h).sqrt();
        if length <= chord {
            return Err(CatenaryError::TooShort { length, chord });
        }
        if length >= span + h {
            return Err(CatenaryError::TooLong {
                length,
                reach: span + h,
            });
        }
        let a_max = (length * length - h * h) / (2.0 * h);
        let f = |a: f64| {
            let s = (h * h + 2.0 * a * h).sqrt();
            (length - s) + a * (s / a).asinh() - span
        };
        if f(a_max) < 0.0 {
            return Err(CatenaryError::NoTouchdown);
        }
        let a = bisect(a_max * 1e-12, a_max, f);
        Ok(Self {
            w,
            a,
            h,
            length,
            suspended: (h * h + 2.0 * a * h).sqrt(),
        })
    }

    /// Horizontal tension H, N.
    pub fn horizontal_tension(&self) -> f64 {
        self.w * self.a
    }

    /// Top tension `w (a + h)`, N.
    pub fn top_tension(&self) -> f64 {
        self.w * (self.a + self.h)
    }

    /// The top angle from the vertical, rad: `tan φ = a / s_susp`.
    pub fn top_angle_from_vertical(&self) -> f64 {
        (self.a / self.suspended).atan()
    }

    /// Position `(x, z)` relative to the touchdown point and tangent angle at arc length `s` from
    /// the top. The grounded part has `z = 0` and `x < 0`.
    pub fn point(&self, s: f64) -> (f64, f64, f64) {
        let sp = self.suspended - s;
        if sp >= 0.0 {
            let u = sp / self.a;
            (
                self.a * u.asinh(),
                self.a * ((1.0 + u * u).sqrt() - 1.0),
                -PI + u.atan(),
            )
        } else {
            (sp, 0.0, -PI)
        }
    }
}

/// The elastic catenary with touchdown (Irvine): horizontal tension, suspended (unstretched) length
/// and top tension for a line of axial stiffness `ea`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElasticTouchdownCatenary {
    /// Horizontal tension H, N.
    pub h_tension: f64,
    /// Unstretched suspended length, m.
    pub suspended: f64,
    /// Top tension `sqrt(H² + (w s)²)`, N.
    pub top_tension: f64,
}

impl ElasticTouchdownCatenary {
    /// Solves the two conditions (top height `h`, horizontal span `span`) for `H` and `s_susp`.
    pub fn solve(w: f64, ea: f64, span: f64, h: f64, length: f64) -> Result<Self, CatenaryError> {
        let rigid = TouchdownCatenary::solve(w, span, h, length)?;
        let z_of = |hh: f64, s: f64| {
            let a = hh / w;
            a * ((1.0 + (s / a) * (s / a)).sqrt() - 1.0) + w * s * s / (2.0 * ea)
        };
        let s_of = |hh: f64| bisect(0.0, length * 2.0, |s| z_of(hh, s) - h);
        let x_res = |hh: f64| {
            let s = s_of(hh);
            let a = hh / w;
            a * (s / a).asinh() + hh * s / ea + (length - s) * (1.0 + hh / ea) - span
        };
        let h0 = rigid.horizontal_tension();
        let (mut lo, mut hi) = (0.5 * h0, 1.5 * h0);
        while x_res(lo) > 0.0 && lo > 1e-6 * h0 {
            lo *= 0.5;
        }
        while x_res(hi) < 0.0 && hi < 1e3 * h0 {
            hi *= 2.0;
        }
        let hh = bisect(lo, hi, x_res);
        let s = s_of(hh);
        Ok(Self {
            h_tension: hh,
            suspended: s,
            top_tension: (hh * hh + (w * s) * (w * s)).sqrt(),
        })
    }
}

/// The inextensible catenary touching down on a plane seabed that rises at the angle `α` towards
/// the anchor, the rest of the line lying on it (frictionless) up to the anchor.
///
/// The anchor is at `(0, 0)` on the contact level (the line's centre on the seabed), which is the
/// plane `z = −x·tan α`; the top at `(X, h)`. The suspended part is a catenary of `a = H/w`, tangent
/// to the plane at the touchdown point: with `u = (x − x_v)/a` from its vertex, `sinh u_d = −tan α`
/// there, so `u_d = −atanh(sin α)`. With the laid length `L_s` (the touchdown at
/// `(L_s cos α, −L_s sin α)`) and `u_T` at the top:
///
/// ```text
/// s_susp = a (sinh u_T + tan α),                 L_s = L − s_susp
/// h + L_s sin α = a (cosh u_T − sec α)           (height)
/// X − L_s cos α = a (u_T + asinh(tan α))        (span)
/// ```
///
/// Eliminating `L_s` from the height condition, `cosh u_T + sin α sinh u_T = (h + L sin α)/a + cos α`,
/// whose left side increases from `cos α` at `u_d`: one root above it. The span condition then fixes
/// `a` (bisection). The laid line's tension grows by its down-slope weight from the touchdown's
/// `H sec α` to the anchor's `H sec α + w L_s sin α`. With `α = 0` it is [`TouchdownCatenary`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlopedTouchdownCatenary {
    /// Weight per unit length, N/m.
    pub w: f64,
    /// `a = H/w`, m.
    pub a: f64,
    /// The seabed's rise towards the anchor, rad.
    pub alpha: f64,
    /// Suspended length (top to touchdown), m.
    pub suspended: f64,
    /// Laid length (touchdown to anchor), m.
    pub laid: f64,
    /// `u_T`, the top's position on the catenary.
    pub u_top: f64,
}

impl SlopedTouchdownCatenary {
    /// Solves for the catenary with the top at horizontal distance `span` from the anchor and height
    /// `h` above the anchor's contact level, on a seabed rising at `alpha` (rad, `|α| < π/2`;
    /// negative: falling) towards the anchor.
    pub fn solve(
        w: f64,
        alpha: f64,
        span: f64,
        h: f64,
        length: f64,
    ) -> Result<Self, CatenaryError> {
        if !(w > 0.0 && h > 0.0 && length > 0.0 && span > 0.0) {
            return Err(CatenaryError::Invalid("w, span, h and length must be > 0"));
        }
        if alpha.is_nan() || alpha.abs() >= std::f64::consts::FRAC_PI_2 {
            return Err(CatenaryError::Invalid("the slope must be within ±π/2"));
        }
        let (s, c, t) = (alpha.sin(), alpha.cos(), alpha.tan());
        let u_d = -s.atanh();
        // The top's u for a given a (the height condition), and the laid length.
        let top = |a: f64| {
            let rhs = (h + length * s) / a + c;
            let lhs = |u: f64| u.cosh() + s * u.sinh();
            let mut hi = u_d + 1.0;
            while lhs(hi) < rhs {
                hi = u_d + 2.0 * (hi - u_d);
            }
            let u = bisect(u_d, hi, |u| lhs(u) - rhs);
            (u, length - a * (u.sinh() + t))
        };
        let span_residual = |a: f64| {
            let (u, laid) = top(a);
            a * (u + t.asinh()) + laid * c - span
        };
        let a_lo = length * 1e-9;
        if span_residual(a_lo) > 0.0 {
            return Err(CatenaryError::TooLong {
                length,
                reach: span + h,
            });
        }
        let mut a_hi = length;
        while span_residual(a_hi) < 0.0 {
            if top(a_hi).1 < 0.0 || a_hi > 1e9 * length {
                return Err(CatenaryError::NoTouchdown);
            }
            a_hi *= 2.0;
        }
        let a = bisect(a_lo, a_hi, span_residual);
        let (u_top, laid) = top(a);
        if laid < 0.0 {
            return Err(CatenaryError::NoTouchdown);
        }
        Ok(Self {
            w,
            a,
            alpha,
            suspended: length - laid,
            laid,
            u_top,
        })
    }

    /// Horizontal tension H in the suspended part, N.
    pub fn horizontal_tension(&self) -> f64 {
        self.w * self.a
    }

    /// Top tension `H cosh u_T`, N.
    pub fn top_tension(&self) -> f64 {
        self.w * self.a * self.u_top.cosh()
    }

    /// Tension at the touchdown point, `H sec α`, N.
    pub fn touchdown_tension(&self) -> f64 {
        self.horizontal_tension() / self.alpha.cos()
    }

    /// Tension at the anchor, `H sec α + w L_s sin α`, N.
    pub fn anchor_tension(&self) -> f64 {
        self.touchdown_tension() + self.w * self.laid * self.alpha.sin()
    }

    /// The touchdown point's horizontal distance from the anchor, `L_s cos α`, m.
    pub fn touchdown_x(&self) -> f64 {
        self.laid * self.alpha.cos()
    }

    /// Position `(x, z)` relative to the anchor and tangent angle (the module's convention) at arc
    /// length `s` from the top: on the catenary `sinh u = sinh u_T − s/a` above the touchdown, on
    /// the plane below it.
    pub fn point(&self, s: f64) -> (f64, f64, f64) {
        let (sa, ca) = self.alpha.sin_cos();
        let (xd, zd) = (self.laid * ca, -self.laid * sa);
        if s <= self.suspended {
            let a = self.a;
            let sh = self.u_top.sinh() - s / a;
            let (u, u_d) = (sh.asinh(), -sa.atanh());
            (
                xd + a * (u - u_d),
                zd + a * ((1.0 + sh * sh).sqrt() - 1.0 / ca),
                -PI + sh.atan(),
            )
        } else {
            let d = s - self.suspended;
            (xd - d * ca, zd + d * sa, -PI - self.alpha)
        }
    }
}

/// A catenary hanging free between two points: the lower end at `(0, 0)`, the upper at `(span, h)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FreeCatenary {
    /// `a = H/w`, m.
    pub a: f64,
    /// Horizontal position of the vertex, m.
    pub x_vertex: f64,
    /// Length, m.
    pub length: f64,
}

impl FreeCatenary {
    /// Solves `sqrt(L² − h²) = 2 a sinh(span/(2a))` and places the vertex at
    /// `span/2 − a·atanh(h/L)`.
    pub fn solve(span: f64, h: f64, length: f64) -> Result<Self, CatenaryError> {
        if !(span > 0.0 && length > 0.0) {
            return Err(CatenaryError::Invalid("span and length must be > 0"));
        }
        let chord = (span * span + h * h).sqrt();
        if length <= chord {
            return Err(CatenaryError::TooShort { length, chord });
        }
        let target = (length * length - h * h).sqrt();
        // 2a sinh(span/2a) decreases from infinity (a -> 0) to span (a -> infinity).
        let g = |ln_a: f64| {
            let a = ln_a.exp();
            let x = span / (2.0 * a);
            if x > 700.0 {
                f64::INFINITY
            } else {
                2.0 * a * x.sinh() - target
            }
        };
        let ln_a = bisect((span * 1e-6).ln(), (span * 1e6).ln(), g);
        let a = ln_a.exp();
        Ok(Self {
            a,
            x_vertex: 0.5 * span - a * (h / length).atanh(),
            length,
        })
    }

    /// Position and tangent angle at arc length `s` from the **upper** end.
    pub fn point(&self, s: f64) -> (f64, f64, f64) {
        let a = self.a;
        let sv = (self.x_vertex / a).sinh();
        // Arc length from the lower end: S(x) = a (sinh((x − xv)/a) + sinh(xv/a)).
        let big_s = self.length - s;
        let x = self.x_vertex + a * (big_s / a - sv).asinh();
        let u = (x - self.x_vertex) / a;
        let z = a * (u.cosh() - (self.x_vertex / a).cosh());
        (x, z, -PI + u.sinh().atan())
    }
}

/// The touchdown boundary-layer moment `M_TDP = (EI w/H)/(p + 1/2)` for a linear tensionless seabed
/// of stiffness `k` per unit length (valid for `K = k EI/H² > 1/4`), N·m (a magnitude; the moment is a
/// sag, negative in catena's convention).
pub fn touchdown_moment(ei: f64, w: f64, h: f64, k: f64) -> f64 {
    let big_k = k * ei / (h * h);
    let p = ((big_k.sqrt() + 0.5) / 2.0).sqrt();
    (ei * w / h) / (p + 0.5)
}

/// Natural frequency (rad/s) of mode `n` of a tensioned pinned–pinned beam:
/// `ω_n = (nπ/L)²·sqrt(EI/m)·sqrt(1 + T L²/(n²π²EI))`.
pub fn tensioned_beam_frequency(n: usize, l: f64, ei: f64, m: f64, t: f64) -> f64 {
    let k = n as f64 * PI / l;
    k * k * (ei / m).sqrt() * (1.0 + t / (k * k * ei)).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The 1000 m SCR of cases.md §2.2: H = 207.95 kN, top tension 1197.5 kN, suspended 1167.7 m
    /// (to 0.05 %), 10.0° from vertical.
    #[test]
    fn scr1000_catenary_numbers() {
        let c = TouchdownCatenary::solve(1010.0, 933.79, 980.0, 1600.0).expect("solves");
        assert!(
            (c.horizontal_tension() / 207.95e3 - 1.0).abs() < 5e-4,
            "{}",
            c.horizontal_tension()
        );
        assert!(
            (c.top_tension() / 1197.5e3 - 1.0).abs() < 5e-4,
            "{}",
            c.top_tension()
        );
        assert!((c.suspended / 1167.7 - 1.0).abs() < 5e-4, "{}", c.suspended);
        assert!((c.top_angle_from_vertical().to_degrees() - 10.0).abs() < 0.01);
        // The top point is at (span − grounded, h) from the touchdown point.
        let (x, z, _) = c.point(0.0);
        assert!((x + (1600.0 - c.suspended) - 933.79).abs() < 1e-6);
        assert!((z - 980.0).abs() < 1e-6);
    }

    /// A very stiff elastic catenary tends to the inextensible one (relative 1e-6).
    #[test]
    fn elastic_catenary_limit() {
        let r = TouchdownCatenary::solve(1010.0, 933.79, 980.0, 1600.0).expect("solves");
        let e =
            ElasticTouchdownCatenary::solve(1010.0, 1e15, 933.79, 980.0, 1600.0).expect("solves");
        assert!((e.h_tension / r.horizontal_tension() - 1.0).abs() < 1e-6);
        assert!((e.top_tension / r.top_tension() - 1.0).abs() < 1e-6);
    }

    /// The catenary on a slope: with `α = 0` it is the flat one (1e-9 relative); on a 3° slope the
    /// chain marched up from its touchdown (tension `(H, −H tan α + w s)`, 200 000 midpoint steps,
    /// an integration independent of the closed form) reaches the top (to 1 mm), and the laid part
    /// balances its down-slope weight.
    #[test]
    fn sloped_catenary_flat_limit_and_marched_chain() {
        let flat = TouchdownCatenary::solve(1010.0, 933.79, 980.0, 1600.0).expect("solves");
        let zero =
            SlopedTouchdownCatenary::solve(1010.0, 0.0, 933.79, 980.0, 1600.0).expect("solves");
        assert!(
            (zero.a / flat.a - 1.0).abs() < 1e-9,
            "{} {}",
            zero.a,
            flat.a
        );
        assert!((zero.suspended / flat.suspended - 1.0).abs() < 1e-9);
        assert!((zero.top_tension() / flat.top_tension() - 1.0).abs() < 1e-9);
        let (w, alpha) = (1010.0, 3f64.to_radians());
        let c = SlopedTouchdownCatenary::solve(w, alpha, 933.79, 980.0, 1600.0).expect("solves");
        let hh = c.horizontal_tension();
        let n = 200_000;
        let ds = c.suspended / n as f64;
        let (mut x, mut z) = (c.laid * alpha.cos(), -c.laid * alpha.sin());
        for i in 0..n {
            let v = -hh * alpha.tan() + w * (i as f64 + 0.5) * ds;
            let t = (hh * hh + v * v).sqrt();
            x += ds * hh / t;
            z += ds * v / t;
        }
        assert!(
            (x - 933.79).abs() < 1e-3 && (z - 980.0).abs() < 1e-3,
            "{x} {z}"
        );
        let v_top = -hh * alpha.tan() + w * c.suspended;
        assert!(((hh * hh + v_top * v_top).sqrt() / c.top_tension() - 1.0).abs() < 1e-9);
        // The slope holds the line deeper: more hangs, the top pulls harder.
        assert!(c.suspended > flat.suspended && c.top_tension() > flat.top_tension());
        assert!(
            (c.anchor_tension() - c.touchdown_tension() - w * c.laid * alpha.sin()).abs() < 1e-6
        );
    }

    /// A free catenary passes through both ends and has the right length (1e-9 relative).
    #[test]
    fn free_catenary_ends_and_length() {
        let c = FreeCatenary::solve(300.0, 120.0, 400.0).expect("solves");
        let (x0, z0, _) = c.point(0.0);
        let (x1, z1, _) = c.point(400.0);
        assert!(
            (x0 - 300.0).abs() < 1e-6 && (z0 - 120.0).abs() < 1e-6,
            "{x0} {z0}"
        );
        assert!(x1.abs() < 1e-6 && z1.abs() < 1e-6, "{x1} {z1}");
        let n = 100_000;
        let mut len = 0.0;
        let mut p = c.point(0.0);
        for i in 1..=n {
            let q = c.point(400.0 * i as f64 / n as f64);
            len += ((q.0 - p.0).powi(2) + (q.1 - p.1).powi(2)).sqrt();
            p = q;
        }
        assert!((len - 400.0).abs() < 1e-4, "{len}");
    }
}
