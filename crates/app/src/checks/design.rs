//! Strength checks of the pipe wall (pure): the DNV-ST-F201 LRFD combined-loading criterion and the
//! API STD 2RD von Mises criterion, at one node from its load effects and pressures. The observer
//! that applies them along the line at every step is `crate::run::observers::design`.
//!
//! **Pressures** at a node at height `z` above the datum (water depth `d`), with the check's
//! internal (design) pressure `p_d` at the still water level and the contents density `ρ_c`:
//!
//! ```text
//! p_e  = ρ_w g (d − z)                 external (hydrostatic)
//! p_ld = p_d + ρ_c g (d − z)           local internal design pressure
//! ```
//!
//! **DNV-ST-F201** (Riser Systems, 2018; the same criteria as DNV-OS-F201, 2010, §5 C). The wall
//! for the resistance is `t2 = t − t_corr`; the material strengths `f_y = SMYS·α_U`,
//! `f_u = SMTS·α_U` (no temperature derating). Resistances:
//!
//! ```text
//! p_b(t) = (2/√3)·(2t/(D − t))·min(f_y, f_u/1.15)          burst
//! M_k = f_y·α_c·(D − t2)²·t2                               plastic bending moment
//! T_k = f_y·α_c·π·(D − t2)·t2                              plastic axial force
//! α_c = (1 − β) + β·f_u/f_y                                flow stress parameter
//! β   = (0.4 + q_h)                    D/t2 < 15
//!     = (0.4 + q_h)·(60 − D/t2)/45     15 ≤ D/t2 ≤ 60
//!     = 0                              D/t2 > 60
//! q_h = (p_ld − p_e)/p_b(t2)·2/√3 for p_ld > p_e, else 0
//! p_c: (p_c − p_el)(p_c² − p_p²) = p_c·p_el·p_p·f_0·D/t2,  collapse
//!      p_el = 2E(t2/D)³/(1 − ν²),  p_p = f_y·α_fab·2t2/D
//! ```
//!
//! Design load effects: the functional part is the static state, the environmental part the
//! dynamic increment over it: `M_d = γ_F·M_F + γ_E·M_E`, `T_ed = γ_F·T_eF + γ_E·T_eE` (defaults
//! γ_F = 1.1, γ_E = 1.3, load effect combination a). With `γ = γ_SC·γ_m` (γ_m = 1.15; γ_SC 1.04,
//! 1.14, 1.26 for the low, normal (medium) and high safety classes), the utilisation is the left
//! side of
//!
//! ```text
//! internal overpressure (p_ld ≥ p_e):
//!   γ²·{ |M_d|/M_k·√(1 − ((p_ld − p_e)/p_b(t2))²) + (T_ed/T_k)² }² + γ²·((p_ld − p_e)/p_b(t2))² ≤ 1
//! external overpressure (p_e > p_ld):
//!   γ²·{ |M_d|/M_k + (T_ed/T_k)² }² + γ²·((p_e − p_min)/p_c(t2))² ≤ 1
//! ```
//!
//! with `p_min = p_ld` (the local internal pressure: the contents column and the design pressure;
//! an emptied riser is a case with `internal_pressure` and the contents set accordingly).
//!
//! **DNV-ST-F101** (Submarine pipeline systems, 2021, §5.4.6–5.4.7), the pipe during
//! installation. Load-controlled combined loading (LCC), with the same `M_k = α_c·M_p`,
//! `T_k = α_c·S_p` and `p_b`, `p_c` as above, `γ = γ_SC·γ_m`:
//!
//! ```text
//! internal overpressure:  { γ|M_d|/(α_c M_p) + (γ T_ed/(α_c S_p))² }² + (α_p (p_i − p_e)/(α_c p_b))² ≤ 1
//! external overpressure:  { γ|M_d|/(α_c M_p) + (γ T_ed/(α_c S_p))² }² + (γ (p_e − p_min)/p_c)² ≤ 1
//! α_p = 1 − β_p                     (p_i − p_e)/p_b < 2/3
//!     = 1 − 3β_p(1 − (p_i − p_e)/p_b)   otherwise;   β_p = 0.5, (60 − D/t2)/90, 0 (D/t2 < 15, ≤ 60, > 60)
//! M_d = γ_F γ_C M_F + γ_E M_E,   T_ed = γ_F γ_C T_F + γ_E T_E
//! ```
//!
//! Where it differs from F201: the tension term is `(γ T/T_k)²` (F201: `γ (T/T_k)²`, the safety
//! factor outside the square), the internal overpressure's pressure term is `α_p Δp/(α_c p_b)` with
//! no safety factor and the bending term no `√(1 − (Δp/p_b)²)` (F201: `γ Δp/p_b` and the root), and
//! the condition factor γ_C (default 1) multiplies the functional load effects. With external
//! overpressure (an empty pipe being laid) the two differ only in the tension term and γ_C.
//! Displacement-controlled (DCC, the sag bend's strain): `ε_Rd = ε_c/γ_ε`, `ε_c = 0.78 (t/D − 0.01)
//! (1 + 5σ_h/f_y) α_h^−1.5` (girth weld factor 1), `σ_h = (p_min − p_e)(D − t)/(2t)`, γ_ε 2.0, 2.5,
//! 3.3 for the low, normal and high safety classes; with external overpressure the utilisation is
//! `(ε/ε_Rd)^0.8 + (p_e − p_min)/(p_c/(γ_m γ_SC))`.
//!
//! **API STD 2RD** (Dynamic Risers for Floating Production Systems, 2013, §5.2; the stress criteria
//! of API RP 2RD, 1998): the von Mises stress of the three principal stresses in the wall (wall
//! `t = t_nom − t_corr`, the outer diameter kept),
//!
//! ```text
//! σ_r = −(p_e·D_o + p_ld·D_i)/(D_o + D_i)                 radial
//! σ_h = (p_ld − p_e)·D_o/(2t) − p_ld                       hoop
//! σ_a = T_w/A ± M·(D_o/2)/I,   T_w = T_e + p_ld·A_i − p_e·A_o   axial, at either side of the bend
//! σ_vm = √(½[(σ_a − σ_h)² + (σ_h − σ_r)² + (σ_r − σ_a)²])
//! ```
//!
//! against `C·SMYS`, `C` the design factor of the load case (`C_a·C_f`: 0.67 operating, 0.8 extreme,
//! 1.0 survival): the utilisation is `σ_vm/(C·SMYS)`, the larger of the two sides.
//!
//! **Compression.** Where the effective tension falls below `−P_E`, `P_E = π²EI/L_e²` the Euler load
//! of the local element (pinned over its own length `L_e`), the pipe may buckle between nodes; the
//! observer reports when and where.

use catena_fe::statics::LineResults;
use serde::{Deserialize, Serialize};

use crate::checks::fatigue::stress::PipeSection;

/// The design code of a check.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Code {
    /// DNV-ST-F201 LRFD combined loading.
    DnvStF201,
    /// DNV-ST-F101 load-controlled combined loading (and, in a lay, the displacement-controlled
    /// strain criterion).
    DnvStF101,
    /// API STD 2RD von Mises.
    ApiStd2rd,
}

impl Code {
    /// The name used in scene files and outputs.
    pub fn name(self) -> &'static str {
        match self {
            Code::DnvStF201 => "dnv-st-f201",
            Code::DnvStF101 => "dnv-st-f101",
            Code::ApiStd2rd => "api-std-2rd",
        }
    }
}

/// The term of a criterion that contributes most at a node.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
pub enum Term {
    /// Nothing evaluated yet.
    #[default]
    None,
    /// The bending moment (DNV: `|M_d|/M_k`).
    Bending,
    /// The effective tension (DNV: `(T_ed/T_k)²`).
    Tension,
    /// The pressure difference (DNV: over burst or collapse).
    Pressure,
    /// API: the axial stress is the largest principal stress.
    Axial,
    /// API: the hoop stress is the largest principal stress.
    Hoop,
    /// API: the radial stress is the largest principal stress.
    Radial,
}

impl Term {
    /// The largest of a DNV criterion's three terms (ties: bending, then tension).
    fn largest(bending: f64, tension: f64, pressure: f64) -> Self {
        if bending >= tension && bending >= pressure {
            Term::Bending
        } else if tension >= pressure {
            Term::Tension
        } else {
            Term::Pressure
        }
    }
}

impl Term {
    /// The name used in outputs.
    pub fn name(self) -> &'static str {
        match self {
            Term::None => "none",
            Term::Bending => "bending",
            Term::Tension => "tension",
            Term::Pressure => "pressure",
            Term::Axial => "axial",
            Term::Hoop => "hoop",
            Term::Radial => "radial",
        }
    }

    /// A small integer for datasets (the order of [`Term::ALL`]).
    pub fn index(self) -> u8 {
        Term::ALL.iter().position(|t| *t == self).unwrap_or(0) as u8
    }

    /// Every term, in the order of [`Term::index`].
    pub const ALL: [Term; 7] = [
        Term::None,
        Term::Bending,
        Term::Tension,
        Term::Pressure,
        Term::Axial,
        Term::Hoop,
        Term::Radial,
    ];
}

/// What a `[design_check]` asks for (checked by the scene).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DesignSpec {
    /// The code.
    pub code: Code,
    /// Specified minimum yield strength, Pa.
    pub smys: f64,
    /// Specified minimum tensile strength, Pa.
    pub smts: f64,
    /// Internal (design) pressure at the still water level, Pa.
    pub internal_pressure: f64,
    /// Corrosion allowance, m (taken off the wall).
    pub corrosion_allowance: f64,
    /// The check starts at this time, s.
    pub start: f64,
    /// DNV: the safety class factor γ_SC.
    pub gamma_sc: f64,
    /// DNV: the material resistance factor γ_m.
    pub gamma_m: f64,
    /// DNV: the functional load factor γ_F.
    pub gamma_f: f64,
    /// DNV: the environmental load factor γ_E.
    pub gamma_e: f64,
    /// DNV: the material strength factor α_U.
    pub alpha_u: f64,
    /// DNV: the fabrication factor α_fab (collapse).
    pub alpha_fab: f64,
    /// DNV: the initial ovality f_0 (collapse).
    pub ovality: f64,
    /// Young's modulus, Pa (collapse; Euler loads use the line's EI).
    pub youngs_modulus: f64,
    /// Poisson's ratio (collapse).
    pub poisson: f64,
    /// API: the design factor `C` on SMYS.
    pub design_factor: f64,
    /// DNV-ST-F101: the condition load effect factor γ_C (on the functional load effects).
    #[serde(default = "one")]
    pub gamma_c: f64,
    /// DNV-ST-F101: the strain resistance factor γ_ε of the displacement-controlled criterion.
    #[serde(default = "strain_factor_normal")]
    pub gamma_eps: f64,
    /// DNV-ST-F101: the largest ratio of yield to tensile strength α_h.
    #[serde(default = "alpha_h")]
    pub alpha_h: f64,
}

fn one() -> f64 {
    1.0
}

fn strain_factor_normal() -> f64 {
    2.5
}

fn alpha_h() -> f64 {
    0.92
}

/// The strain resistance factor γ_ε of DNV-ST-F101 for a safety class (`normal` is `medium`).
pub fn strain_resistance_factor(class: &str) -> Option<f64> {
    match class {
        "low" => Some(2.0),
        "normal" | "medium" => Some(2.5),
        "high" => Some(3.3),
        _ => None,
    }
}

/// The safety class factor γ_SC of DNV-ST-F201 for a class name (`normal` is `medium`).
pub fn safety_class_factor(class: &str) -> Option<f64> {
    match class {
        "low" => Some(1.04),
        "normal" | "medium" => Some(1.14),
        "high" => Some(1.26),
        _ => None,
    }
}

/// One node's section and pressures for a check: outer diameter and (corroded) wall, m; the
/// pressures `p_ld` and `p_e`, Pa.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wall {
    /// Outer diameter, m.
    pub od: f64,
    /// Wall for the resistance (`t − t_corr`), m.
    pub t: f64,
    /// Local internal design pressure, Pa.
    pub p_ld: f64,
    /// External pressure, Pa.
    pub p_e: f64,
}

/// A utilisation and its dominant term.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Utilisation {
    /// The criterion's left side (≤ 1 passes).
    pub value: f64,
    /// The term that contributes most.
    pub term: Term,
}

/// DNV's burst resistance `p_b(t)`, Pa.
pub fn burst(spec: &DesignSpec, od: f64, t: f64) -> f64 {
    let (fy, fu) = (spec.smys * spec.alpha_u, spec.smts * spec.alpha_u);
    2.0 / 3f64.sqrt() * (2.0 * t / (od - t)) * fy.min(fu / 1.15)
}

/// DNV's collapse resistance `p_c(t)`, Pa: the root in `(0, min(p_el, p_p))` of the cubic.
pub fn collapse(spec: &DesignSpec, od: f64, t: f64) -> f64 {
    let fy = spec.smys * spec.alpha_u;
    let p_el = 2.0 * spec.youngs_modulus * (t / od).powi(3) / (1.0 - spec.poisson.powi(2));
    let p_p = fy * spec.alpha_fab * 2.0 * t / od;
    let g = |p: f64| (p - p_el) * (p * p - p_p * p_p) - p * p_el * p_p * spec.ovality * od / t;
    // g(0) > 0 > g(min(p_el, p_p)).
    let (lo, hi) = catena_seabed::roots::bisect(0.0, p_el.min(p_p), |p| g(p) <= 0.0);
    0.5 * (lo + hi)
}

/// What one node's wall resists: the criteria's constants of its section and material, computed
/// once per node (the burst and collapse pressures, the factors of the plastic moment and
/// tension, the section's area and inertia), so that a step evaluates only what its pressures and
/// load effects change. [`dnv`] and [`api`] evaluate through it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Resistance {
    od: f64,
    t: f64,
    di: f64,
    pb: f64,
    pc: f64,
    /// β's factor of `0.4 + q_h`: 1, `(60 − D/t)/45` or 0.
    beta_factor: f64,
    fu_over_fy: f64,
    /// `f_y·(D − t)²·t` and `f_y·π·(D − t)·t`: `M_k` and `T_k` over `α_c`.
    mk_unit: f64,
    tk_unit: f64,
    gamma: f64,
    area: f64,
    inertia: f64,
    /// API: `C·SMYS`.
    allowable: f64,
    /// DNV-ST-F101: β of the pressure factor α_p (0.5, `(60 − D/t)/90` or 0).
    beta_p: f64,
    /// DNV-ST-F101: `f_y`, `t/D`, and the strain criterion's `α_h^−1.5/γ_ε`.
    fy: f64,
    t_over_d: f64,
    strain_factor: f64,
}

impl Resistance {
    /// The constants of a wall of outer diameter `od` and thickness `t` (m) for `spec`.
    pub fn new(spec: &DesignSpec, od: f64, t: f64) -> Self {
        let (fy, fu) = (spec.smys * spec.alpha_u, spec.smts * spec.alpha_u);
        let dt = od / t;
        let beta_factor = if dt < 15.0 {
            1.0
        } else if dt <= 60.0 {
            (60.0 - dt) / 45.0
        } else {
            0.0
        };
        let di = od - 2.0 * t;
        let pi = std::f64::consts::PI;
        Self {
            od,
            t,
            di,
            pb: burst(spec, od, t),
            pc: collapse(spec, od, t),
            beta_factor,
            fu_over_fy: fu / fy,
            mk_unit: fy * (od - t).powi(2) * t,
            tk_unit: fy * pi * (od - t) * t,
            gamma: spec.gamma_sc * spec.gamma_m,
            area: pi / 4.0 * (od * od - di * di),
            inertia: pi / 64.0 * (od.powi(4) - di.powi(4)),
            allowable: spec.design_factor * spec.smys,
            beta_p: if dt < 15.0 {
                0.5
            } else if dt <= 60.0 {
                (60.0 - dt) / 90.0
            } else {
                0.0
            },
            fy,
            t_over_d: t / od,
            strain_factor: spec.alpha_h.powf(-1.5) / spec.gamma_eps,
        }
    }

    /// The pressure difference `Δp = p_ld − p_e` over the burst resistance, and the flow stress
    /// parameter `α_c` at it (`q_h` from an internal overpressure, 0 otherwise): what F201's and
    /// F101's criteria share.
    #[inline]
    fn flow_stress(&self, dp: f64) -> (f64, f64) {
        let r = dp / self.pb;
        let qh = if dp > 0.0 {
            r * (2.0 / 3f64.sqrt())
        } else {
            0.0
        };
        let beta = (0.4 + qh) * self.beta_factor;
        (r, (1.0 - beta) + beta * self.fu_over_fy)
    }

    /// The DNV-ST-F101 load-controlled combined-loading utilisation at the pressures `p_ld`
    /// (the internal pressure, also `p_min`), `p_e` (Pa) for the design moment `md` (N·m) and
    /// effective tension `ted` (N) (see the module docs).
    #[inline]
    pub fn f101(&self, p_ld: f64, p_e: f64, md: f64, ted: f64) -> Utilisation {
        let dp = p_ld - p_e;
        let (r, alpha_c) = self.flow_stress(dp);
        let g = self.gamma;
        let bending = g * md.abs() / (alpha_c * self.mk_unit);
        let tension = (g * ted / (alpha_c * self.tk_unit)).powi(2);
        let pressure = if dp >= 0.0 {
            let alpha_p = if r < 2.0 / 3.0 {
                1.0 - self.beta_p
            } else {
                1.0 - 3.0 * self.beta_p * (1.0 - r)
            };
            alpha_p * r / alpha_c
        } else {
            g * (-dp) / self.pc
        };
        let value = (bending + tension).powi(2) + pressure.powi(2);
        Utilisation {
            value,
            term: Term::largest(bending, tension, pressure),
        }
    }

    /// DNV-ST-F101's design compressive strain resistance `ε_c/γ_ε` at the pressures `p_ld`
    /// (`p_min`) and `p_e` (Pa): `ε_c = 0.78·(t/D − 0.01)·(1 + 5σ_h/f_y)·α_h^−1.5` (girth weld
    /// factor 1), `σ_h = (p_min − p_e)·(D − t)/(2t)`.
    #[inline]
    pub fn f101_strain_resistance(&self, p_ld: f64, p_e: f64) -> f64 {
        let sh = (p_ld - p_e) * (self.od - self.t) / (2.0 * self.t);
        0.78 * (self.t_over_d - 0.01) * (1.0 + 5.0 * sh / self.fy) * self.strain_factor
    }

    /// DNV-ST-F101's displacement-controlled utilisation for the design strain `strain` at the
    /// pressures `p_ld`, `p_e` (Pa): `ε/ε_Rd` with internal overpressure; with external
    /// overpressure `(ε/ε_Rd)^0.8 + (p_e − p_min)/(p_c/(γ_m γ_SC))`.
    #[inline]
    pub fn f101_strain(&self, strain: f64, p_ld: f64, p_e: f64) -> f64 {
        let ratio = strain.abs() / self.f101_strain_resistance(p_ld, p_e);
        if p_ld >= p_e {
            ratio
        } else {
            ratio.powf(0.8) + (p_e - p_ld) * self.gamma / self.pc
        }
    }

    /// The DNV-ST-F201 utilisation at the pressures `p_ld`, `p_e` (Pa) for the design moment `md`
    /// (N·m) and effective tension `ted` (N).
    #[inline]
    pub fn dnv(&self, p_ld: f64, p_e: f64, md: f64, ted: f64) -> Utilisation {
        let dp = p_ld - p_e;
        let (r, alpha_c) = self.flow_stress(dp);
        let mk = self.mk_unit * alpha_c;
        let tk = self.tk_unit * alpha_c;
        let g = self.gamma;
        let tension = (ted / tk).powi(2);
        let (bending, pressure) = if dp >= 0.0 {
            ((md.abs() / mk) * (1.0 - r * r).max(0.0).sqrt(), r)
        } else {
            (md.abs() / mk, -dp / self.pc)
        };
        let value = (g * (bending + tension)).powi(2) + (g * pressure).powi(2);
        Utilisation {
            value,
            term: Term::largest(bending, tension, pressure),
        }
    }

    /// The API STD 2RD utilisation at the pressures `p_ld`, `p_e` (Pa) for the wall tension `tw`
    /// (N) and moment `m` (N·m), the larger of the two sides of the bend.
    #[inline]
    pub fn api(&self, p_ld: f64, p_e: f64, tw: f64, m: f64) -> Utilisation {
        let (d, t, di) = (self.od, self.t, self.di);
        let sr = -(p_e * d + p_ld * di) / (d + di);
        let sh = (p_ld - p_e) * d / (2.0 * t) - p_ld;
        let bend = (m * 0.5 * d / self.inertia).abs();
        let mean = tw / self.area;
        let vm =
            |sa: f64| (0.5 * ((sa - sh).powi(2) + (sh - sr).powi(2) + (sr - sa).powi(2))).sqrt();
        let (a1, a2) = (mean + bend, mean - bend);
        let (v1, v2) = (vm(a1), vm(a2));
        let (v, sa) = if v1 >= v2 { (v1, a1) } else { (v2, a2) };
        let term = if sa.abs() >= sh.abs() && sa.abs() >= sr.abs() {
            Term::Axial
        } else if sh.abs() >= sr.abs() {
            Term::Hoop
        } else {
            Term::Radial
        };
        Utilisation {
            value: v / self.allowable,
            term,
        }
    }
}

/// The DNV-ST-F201 combined-loading utilisation for the design moment `md` (N·m) and effective
/// tension `ted` (N) (see the module docs).
pub fn dnv(spec: &DesignSpec, w: &Wall, md: f64, ted: f64) -> Utilisation {
    Resistance::new(spec, w.od, w.t).dnv(w.p_ld, w.p_e, md, ted)
}

/// The API STD 2RD von Mises utilisation for the wall tension `tw` (N) and moment `m` (N·m), the
/// larger of the two sides of the bend (see the module docs).
pub fn api(spec: &DesignSpec, w: &Wall, tw: f64, m: f64) -> Utilisation {
    Resistance::new(spec, w.od, w.t).api(w.p_ld, w.p_e, tw, m)
}

/// The Euler load of a pinned length `l` of bending stiffness `ei`, `π²EI/l²`, N.
pub fn euler_load(ei: f64, l: f64) -> f64 {
    std::f64::consts::PI.powi(2) * ei / (l * l)
}

/// A check along the line: each node's section (corroded) and contents, its functional load
/// effects (the static state), and the code's parameters. Built from a run's specification and
/// statics; shared by the observer and the HDF5 recorder, so both give the same numbers.
#[derive(Debug, Clone, PartialEq)]
pub struct Evaluator {
    /// The check.
    pub spec: DesignSpec,
    /// Each node's section for the check: the corroded wall, the check's internal pressure.
    pub sections: Vec<PipeSection>,
    /// Each node's resistance constants.
    pub resistance: Vec<Resistance>,
    /// Each node's functional moment (static), N·m.
    pub static_moment: Vec<f64>,
    /// Each node's functional effective tension (static), N.
    pub static_tension: Vec<f64>,
}

impl Evaluator {
    /// The check along a line whose nodes have the sections `sections` (uncorroded, as the scene
    /// gives them) and the static moments and effective tensions `static_moment`,
    /// `static_tension`.
    pub fn new(
        spec: DesignSpec,
        sections: impl Iterator<Item = PipeSection>,
        static_moment: &[f64],
        static_tension: &[f64],
    ) -> Self {
        let sections: Vec<PipeSection> = sections
            .map(|s| PipeSection {
                wall: s.wall - spec.corrosion_allowance,
                internal_pressure: spec.internal_pressure,
                ..s
            })
            .collect();
        let resistance = sections
            .iter()
            .map(|s| Resistance::new(&spec, s.od, s.wall))
            .collect();
        Self {
            spec,
            sections,
            resistance,
            static_moment: static_moment.to_vec(),
            static_tension: static_tension.to_vec(),
        }
    }

    /// The utilisation at node `i` for its effective tension `te` (N), moment `m` (N·m) and height
    /// `z` (m).
    #[inline]
    pub fn at(&self, i: usize, te: f64, m: f64, z: f64) -> Utilisation {
        let s = &self.sections[i];
        let head = (s.water_depth - z).max(0.0);
        let p_ld = s.internal_pressure + s.contents_density * s.gravity * head;
        let p_e = s.water_density * s.gravity * head;
        let r = &self.resistance[i];
        match self.spec.code {
            Code::DnvStF201 => {
                let (mf, tf) = (self.static_moment[i], self.static_tension[i]);
                let (gf, ge) = (self.spec.gamma_f, self.spec.gamma_e);
                r.dnv(p_ld, p_e, gf * mf + ge * (m - mf), gf * tf + ge * (te - tf))
            }
            Code::DnvStF101 => {
                let (mf, tf) = (self.static_moment[i], self.static_tension[i]);
                let (gf, ge) = (self.spec.gamma_f * self.spec.gamma_c, self.spec.gamma_e);
                r.f101(p_ld, p_e, gf * mf + ge * (m - mf), gf * tf + ge * (te - tf))
            }
            Code::ApiStd2rd => r.api(p_ld, p_e, te + s.wall_minus_effective(z), m),
        }
    }

    /// The utilisation at every node of a step's results, into `out`.
    pub fn along(&self, r: &LineResults, out: &mut [f64]) {
        for (i, u) in out.iter_mut().enumerate() {
            *u = self.at(i, r.tension[i], r.moment[i], r.z[i]).value;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(code: Code) -> DesignSpec {
        DesignSpec {
            code,
            smys: 448e6,
            smts: 531e6,
            internal_pressure: 15e6,
            corrosion_allowance: 0.0,
            start: 0.0,
            gamma_sc: 1.14,
            gamma_m: 1.15,
            gamma_f: 1.1,
            gamma_e: 1.3,
            alpha_u: 0.96,
            alpha_fab: 1.0,
            ovality: 0.005,
            youngs_modulus: 207e9,
            poisson: 0.3,
            design_factor: 0.8,
            gamma_c: 1.0,
            gamma_eps: 2.5,
            alpha_h: 0.92,
        }
    }

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a / b - 1.0).abs() < tol
    }

    /// DNV-ST-F101's combined loading, written out by hand for the 12-inch pipe of `cases/lay/`
    /// (D 323.9 mm, t 20.6 mm, X65: SMYS 450 MPa, SMTS 535 MPa, α_U 0.96) empty at 140 m (external
    /// overpressure) and with 20 MPa inside (internal overpressure), at M_d = 500 kN·m and
    /// T_ed = 300 kN; and the strain criterion at ε = 0.2 %. The two codes differ where the module
    /// docs say: F201's tension term keeps γ outside the square.
    #[test]
    fn f101_combined_loading_and_strain_by_hand() {
        let mut s = spec(Code::DnvStF101);
        (s.smys, s.smts, s.internal_pressure) = (450e6, 535e6, 0.0);
        let (d, t) = (0.3239, 0.0206);
        let r = Resistance::new(&s, d, t);
        let (fy, fu) = (450e6 * 0.96, 535e6 * 0.96);
        let g = 1.14 * 1.15;
        let (md, ted) = (500e3, 300e3);
        let mp = fy * (d - t) * (d - t) * t;
        let sp = fy * std::f64::consts::PI * (d - t) * t;
        let pb = 2.0 / 3f64.sqrt() * 2.0 * t / (d - t) * fy.min(fu / 1.15);
        // External overpressure: q_h = 0, β = 0.4·(60 − D/t)/45.
        let pe = 1025.0 * 9.81 * 140.0;
        let beta = 0.4 * (60.0 - d / t) / 45.0;
        let ac = 1.0 - beta + beta * fu / fy;
        let pc = collapse(&s, d, t);
        let by_hand =
            (g * md / (ac * mp) + (g * ted / (ac * sp)).powi(2)).powi(2) + (g * pe / pc).powi(2);
        let u = r.f101(0.0, pe, md, ted);
        assert!(
            close(u.value, by_hand, 1e-12),
            "{} against {by_hand}",
            u.value
        );
        assert_eq!(u.term, Term::Bending);
        // F201 at the same loads: γ outside the tension term's square.
        let f201 =
            (g * (md / (ac * mp) + (ted / (ac * sp)).powi(2))).powi(2) + (g * pe / pc).powi(2);
        assert!(close(r.dnv(0.0, pe, md, ted).value, f201, 1e-12));
        assert!(u.value > f201);
        // Internal overpressure, 20 MPa: q_h, α_c, and α_p with β_p = (60 − D/t)/90.
        let pi = 20e6;
        let ratio = (pi - pe) / pb;
        let qh = ratio * 2.0 / 3f64.sqrt();
        let beta = (0.4 + qh) * (60.0 - d / t) / 45.0;
        let ac = 1.0 - beta + beta * fu / fy;
        let beta_p = (60.0 - d / t) / 90.0;
        let ap = if ratio < 2.0 / 3.0 {
            1.0 - beta_p
        } else {
            1.0 - 3.0 * beta_p * (1.0 - ratio)
        };
        let by_hand = (g * md / (ac * mp) + (g * ted / (ac * sp)).powi(2)).powi(2)
            + (ap * ratio / ac).powi(2);
        assert!(close(r.f101(pi, pe, md, ted).value, by_hand, 1e-12));
        // The strain criterion, empty: ε_c = 0.78 (t/D − 0.01)(1 + 5σ_h/f_y) α_h^−1.5, γ_ε 2.5.
        let sh = -pe * (d - t) / (2.0 * t);
        let eps_rd = 0.78 * (t / d - 0.01) * (1.0 + 5.0 * sh / fy) * 0.92f64.powf(-1.5) / 2.5;
        let by_hand = (0.002 / eps_rd).powf(0.8) + pe * g / pc;
        assert!(close(r.f101_strain(0.002, 0.0, pe), by_hand, 1e-12));
    }

    /// DNV-ST-F201, internal overpressure, worked by hand for one node of the paper's pipe
    /// (D 0.228 m, t 25.4 mm, X65: SMYS 448 MPa, SMTS 531 MPa, α_U 0.96, normal class), with
    /// p_ld 20 MPa, p_e 10 MPa, a static moment −50 kN·m rising to −150 kN·m and a static effective
    /// tension 300 kN rising to 500 kN:
    /// f_y = 430.08 MPa, f_u = 509.76 MPa; p_b = (2/√3)(2·0.0254/0.2026)·430.08 MPa = 124.52 MPa;
    /// q_h = 10/124.52·2/√3 = 0.09273; D/t = 8.976 < 15: β = 0.49273; α_c = 0.50727 + 0.49273·
    /// 1.18527 = 1.09129; M_k = 430.08e6·1.09129·0.2026²·0.0254 = 489.33 kN·m; T_k = 430.08e6·
    /// 1.09129·π·0.2026·0.0254 = 7 587.7 kN; M_d = 1.1·50 + 1.3·100 = 185 kN·m; T_ed = 1.1·300 +
    /// 1.3·200 = 590 kN; γ = 1.311; u = (1.311·(185/488.78·√(1 − 0.080308²) + (590/7587.7)²))² +
    /// (1.311·0.080308)² = 0.26306. Each number is recomputed below line by line, to 1e-9.
    #[test]
    fn dnv_internal_overpressure_worked_example() {
        let s = spec(Code::DnvStF201);
        let w = Wall {
            od: 0.228,
            t: 0.0254,
            p_ld: 20e6,
            p_e: 10e6,
        };
        // By hand.
        let (fy, fu): (f64, f64) = (448e6 * 0.96, 531e6 * 0.96);
        let pb = 2.0 / 3f64.sqrt() * (2.0 * 0.0254 / (0.228 - 0.0254)) * fy.min(fu / 1.15);
        assert!(close(pb, 124.52e6, 1e-4), "{pb}");
        let qh = 10e6 / pb * 2.0 / 3f64.sqrt();
        let beta = 0.4 + qh;
        let ac = (1.0 - beta) + beta * fu / fy;
        let mk = fy * ac * 0.2026f64.powi(2) * 0.0254;
        let tk = fy * ac * std::f64::consts::PI * 0.2026 * 0.0254;
        assert!(close(mk, 489.33e3, 1e-4), "{mk}");
        assert!(close(tk, 7587.7e3, 1e-4), "{tk}");
        let (md, ted) = (1.1 * 50e3 + 1.3 * 100e3, 1.1 * 300e3 + 1.3 * 200e3);
        let g = 1.14 * 1.15;
        let r = 10e6 / pb;
        let want =
            (g * (md / mk * (1.0 - r * r).sqrt() + (ted / tk).powi(2))).powi(2) + (g * r).powi(2);
        assert!(close(want, 0.26306, 1e-4), "{want}");
        let u = dnv(&s, &w, -md, ted);
        assert!(close(u.value, want, 1e-9), "{} vs {want}", u.value);
        assert_eq!(u.term, Term::Bending);
        // Compression enters squared: the same utilisation.
        assert!(close(dnv(&s, &w, -md, -ted).value, want, 1e-12));
    }

    /// DNV-ST-F201, external overpressure, by hand: the same pipe empty at 1000 m (p_ld 0,
    /// p_e 10.05 MPa), M_d 100 kN·m, T_ed 200 kN. Collapse: p_el = 2·207e9·(0.0254/0.228)³/0.91
    /// = 629.0 MPa, p_p = 430.08e6·2·0.0254/0.228 = 95.825 MPa, p_c the cubic's root (checked by
    /// substitution, and below both); no q_h: β = 0.4, α_c = 1.07411.
    #[test]
    fn dnv_external_overpressure_worked_example() {
        let s = spec(Code::DnvStF201);
        let w = Wall {
            od: 0.228,
            t: 0.0254,
            p_ld: 0.0,
            p_e: 10.05e6,
        };
        let fy = 448e6 * 0.96;
        let p_el = 2.0 * 207e9 * (0.0254f64 / 0.228).powi(3) / (1.0 - 0.09);
        let p_p = fy * 2.0 * 0.0254 / 0.228;
        assert!(close(p_el, 629.0e6, 1e-3) && close(p_p, 95.825e6, 1e-4));
        let pc = collapse(&s, 0.228, 0.0254);
        let g = (pc - p_el) * (pc * pc - p_p * p_p) - pc * p_el * p_p * 0.005 * 0.228 / 0.0254;
        assert!(g.abs() < 1e-9 * p_el * p_p * p_p, "{g}");
        assert!(pc < p_p && pc > 0.8 * p_p, "{pc}");
        let ac = 0.6 + 0.4 * 531.0 / 448.0;
        assert!(close(ac, 1.07411, 1e-5));
        let mk = fy * ac * 0.2026f64.powi(2) * 0.0254;
        let tk = fy * ac * std::f64::consts::PI * 0.2026 * 0.0254;
        let gm = 1.14 * 1.15;
        let want = (gm * (100e3 / mk + (200e3 / tk).powi(2))).powi(2) + (gm * 10.05e6 / pc).powi(2);
        let u = dnv(&s, &w, 100e3, 200e3);
        assert!(close(u.value, want, 1e-9), "{} vs {want}", u.value);
    }

    /// API STD 2RD by hand: the same pipe, p_ld 20 MPa, p_e 10 MPa, wall tension 1 MN and a moment
    /// of 200 kN·m, design factor 0.8: σ_r = −(10·0.228 + 20·0.1772)/0.4052 MPa = −14.373 MPa,
    /// σ_h = 10·0.228/0.0508 − 20 = 24.882 MPa, A = 0.016167 m², I = 8.4253e-5 m⁴,
    /// σ_a = 61.855 ± 270.61 MPa; the tension side governs: σ_vm = 328.98 MPa, u = 0.91790.
    #[test]
    fn api_von_mises_worked_example() {
        let s = spec(Code::ApiStd2rd);
        let w = Wall {
            od: 0.228,
            t: 0.0254,
            p_ld: 20e6,
            p_e: 10e6,
        };
        let (d, di) = (0.228f64, 0.1772f64);
        let sr = -(10e6 * d + 20e6 * di) / (d + di);
        let sh = 10e6 * d / 0.0508 - 20e6;
        let a = std::f64::consts::PI / 4.0 * (d * d - di * di);
        let i = std::f64::consts::PI / 64.0 * (d.powi(4) - di.powi(4));
        let sa = 1e6 / a + 200e3 * 0.114 / i;
        assert!(
            close(sr, -14.373e6, 1e-4) && close(sh, 24.882e6, 1e-4),
            "{sr} {sh}"
        );
        let vm = (0.5 * ((sa - sh).powi(2) + (sh - sr).powi(2) + (sr - sa).powi(2))).sqrt();
        let want = vm / (0.8 * 448e6);
        assert!(close(want, 0.91790, 1e-4), "{want}");
        let u = api(&s, &w, 1e6, 200e3);
        assert!(close(u.value, want, 1e-9), "{} vs {want}", u.value);
        assert_eq!(u.term, Term::Axial);
        // The sign of the moment does not matter; without it the pressure terms still count.
        assert!(close(api(&s, &w, 1e6, -200e3).value, want, 1e-12));
        assert!(api(&s, &w, 0.0, 0.0).value > 0.0);
    }

    /// The Euler load of a 0.5 m element of the paper's pipe (EI 17.69 MN·m²): π²EI/L² = 698.4 MN.
    #[test]
    fn euler_load_of_an_element() {
        assert!(close(euler_load(17.69e6, 0.5), 698.37e6, 1e-4));
    }
}
