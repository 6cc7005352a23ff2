//! The Randolph & Quiggin (2009) non-linear hysteretic seabed law (OMAE2009-79259).
//!
//! Read exactly as `docs/seabed-model.md` fixes it; equation numbers are the paper's.
//! Notation: `ζ = z·Kmax/D`; `k = Kmax/D` so that `dζ/dz = k`.
//!
//! **Ultimate limits (eqs 1–2).**
//! `su(z) = su0 + ρ_su·z`; `Nc = a·(z/D)^b` for `z/D ≥ 0.1`, `Nc = a·0.1^b·sqrt(10·z/D)` below, `0` for
//! `z ≤ 0`; `Pu = Nc·su·D`; `Pu_suc = −fsuc·Pu`.
//!
//! **Initial penetration (eqs 3–4), the backbone.** `P_IP = ζ/(1+ζ)·Pu(z)`.
//!
//! **Uplift (eqs 5–9)**, from an episode start `(z0, P0)`:
//! `u = ζ0 − ζ`, `B = P0 − Pu_suc(z)`, `A_UL = B/Pu(z0)`, `P5 = P0 − u/(A_UL+u)·B` (or `Pu_suc` if `B ≤ 0`);
//! `E_UL = exp(min(0, (z − z_P0,eff)/(λsuc·z_max,eff)))`, `P_min = E_UL·Pu_suc(z)`, **`P = max(P5, P_min)`**.
//! `z_c`, where `P5` first reaches zero moving up from `z0`, is computed once per episode
//! ([`RandolphQuiggin::suction_onset`]), when a trial first needs it (the force depends on it only
//! once `z ≤ z_c`, and lift-off records it: until then the history marks it pending,
//! `RqHistory::z_c_pending`); once `z ≤ z_c`, `z_P0,eff = max(z_P0, z_c)`.
//!
//! **Repenetration (eqs 10–14)**, from `(z0, P0)`:
//! `u = ζ − ζ0`, `Pu* = Pu(z)` if `P0 ≤ 0` or there is no `z*`, else `Pu(z*)`;
//! `A_RP = (Pu − P0)/Pu*`, `P10 = P0 + u/(A_RP+u)·(Pu − P0)` (or `Pu` if `A_RP ≤ 0`);
//! `E_RP = exp(min(0, (z − z_P0)/(λsuc·max(z_max, z)) − λrep))`, `P_max = E_RP·P_IP(z)`,
//! **`P = min(P10, P_max)`**, with the continuity guard: if `P0 > P_max(z)` the cap is `P0`.
//!
//! **Transitions** are judged against the committed `z_prev` (see the table in the spec and
//! [`RandolphQuiggin::evaluate`]). Every branch has an analytic tangent `dP/dz`.
//!
//! Decisions where the paper is silent (from the spec): `z_P0 = 0` until suction first occurs;
//! re-contact after lift-off starts Repenetration from `z0 = 0, P0 = 0, z* = none`; the continuity
//! guard; `z_c` is the *first* root of `P5`. The optional lift-off smoothing
//! ([`RqParams::liftoff_smoothing`], off by default) caps uplift `P` by `P_IP(z)`, removing the small
//! force jump the literal eq. 5 gives at lift-off.

use serde::{Deserialize, Serialize};

use crate::degradation::{Degradation, Wear};
use crate::{check, ParamError};

/// The lift-off band, in units of `D/Kmax` (`1/k`): over the last `LIFTOFF_BAND/k` of an uplift
/// above the mudline a positive force `P` is scaled by `z·k/LIFTOFF_BAND` to zero. The literal eq. 5
/// keeps `P5(0⁺) > 0` (up to a third of `P0` on a stiff clay), a jump to the lift-off's `P = 0` that no
/// equilibrium can sit on: Newton's method then alternates between the two sides for ever, at any
/// time step (issue 14's hard soils). The band, 10⁻³ of the normalised stiffness length (1.1 µm for
/// the 1000 m SCR), makes the force continuous with a positive slope there and changes nothing
/// outside it.
pub const LIFTOFF_BAND: f64 = 1e-3;

/// The model parameters (the paper's Tables 1–4). Strengths in Pa, so `P` comes out in N/m.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RqParams {
    /// Contact (outer) diameter `D`, m.
    pub diameter: f64,
    /// Undrained shear strength at the mudline `su0`, Pa.
    pub su0: f64,
    /// Strength gradient `ρ_su`, Pa/m.
    pub su_gradient: f64,
    /// Bearing-factor coefficient `a`.
    pub a: f64,
    /// Bearing-factor exponent `b`, in (0, 1).
    pub b: f64,
    /// Normalised maximum stiffness `Kmax`.
    pub k_max: f64,
    /// Suction ratio `fsuc`, in [0, 1].
    pub f_suc: f64,
    /// Normalised suction decay distance `λsuc`.
    pub lambda_suc: f64,
    /// Normalised repenetration offset `λrep`.
    pub lambda_rep: f64,
    /// Cap uplift `P` by `P_IP(z)` (the spec's optional lift-off smoothing). Default off.
    #[serde(default)]
    pub liftoff_smoothing: bool,
    /// Cyclic degradation of the strength and its regain at rest ([`crate::degradation`]); `None`:
    /// the paper's law.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub degradation: Option<Degradation>,
    /// A suction ratio that depends on the uplift's rate ([`RateSuction`]); `None`: `f_suc` at
    /// every rate.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rate_suction: Option<RateSuction>,
}

/// A suction ratio that depends on the normalised uplift velocity `V = v·D/c_v`: the drainage
/// backbone of penetrometer tests (House, Oliveira & Randolph 2001; Finnie & Randolph 1994) written
/// for the suction ratio,
///
/// ```text
/// f(V) = f_dr + (f_suc − f_dr) / (1 + (V50/V)^c),
/// ```
///
/// drained (`f_dr`) when slow, undrained (the table's `f_suc`) when fast, half-way at `V50`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RateSuction {
    /// The drained suction ratio `f_dr`, in [0, f_suc].
    pub drained_ratio: f64,
    /// The coefficient of consolidation `c_v`, m²/s.
    pub cv: f64,
    /// The normalised velocity `V50` at half-way, > 0.
    pub v50: f64,
    /// The backbone's exponent `c`, > 0.
    pub exponent: f64,
}

impl RateSuction {
    /// The suction ratio at an uplift velocity `v` (m/s, ≥ 0) for a pipe of diameter `d` whose
    /// undrained ratio is `f_und`.
    pub fn ratio(&self, v: f64, d: f64, f_und: f64) -> f64 {
        let big_v = v * d / self.cv;
        if big_v <= 0.0 {
            return self.drained_ratio;
        }
        self.drained_ratio
            + (f_und - self.drained_ratio) / (1.0 + (self.v50 / big_v).powf(self.exponent))
    }
}

impl RqParams {
    /// The paper's Table 1 (the Figure 3 example).
    pub fn table1() -> Self {
        Self {
            diameter: 0.35,
            su0: 5000.0,
            su_gradient: 1500.0,
            a: 6.0,
            b: 0.25,
            k_max: 200.0,
            f_suc: 0.6,
            lambda_suc: 0.4,
            lambda_rep: 0.2,
            liftoff_smoothing: false,
            degradation: None,
            rate_suction: None,
        }
    }

    /// The paper's Table 2 (model tests in kaolin, Figures 4–6).
    pub fn table2() -> Self {
        Self {
            diameter: 0.025,
            su0: 3560.0,
            su_gradient: 0.0,
            a: 6.0,
            b: 0.2,
            k_max: 250.0,
            f_suc: 0.7,
            lambda_suc: 0.7,
            lambda_rep: 0.4,
            liftoff_smoothing: false,
            degradation: None,
            rate_suction: None,
        }
    }

    /// Checks every parameter; the error names the key and what was expected.
    pub fn validate(&self) -> Result<(), ParamError> {
        check(self.diameter > 0.0, "diameter", self.diameter, "D > 0 (m)")?;
        check(self.su0 >= 0.0, "su0", self.su0, "su0 >= 0 (Pa)")?;
        check(
            self.su_gradient >= 0.0,
            "su_gradient",
            self.su_gradient,
            "su_gradient >= 0 (Pa/m)",
        )?;
        check(
            self.su0 > 0.0 || self.su_gradient > 0.0,
            "su0",
            self.su0,
            "su0 and su_gradient not both zero (the soil would have no strength)",
        )?;
        check(self.a > 0.0, "a", self.a, "a > 0")?;
        check(self.b > 0.0 && self.b < 1.0, "b", self.b, "0 < b < 1")?;
        check(self.k_max > 0.0, "k_max", self.k_max, "k_max > 0")?;
        check(
            (0.0..=1.0).contains(&self.f_suc),
            "f_suc",
            self.f_suc,
            "0 <= f_suc <= 1",
        )?;
        check(
            self.lambda_suc > 0.0,
            "lambda_suc",
            self.lambda_suc,
            "lambda_suc > 0",
        )?;
        check(
            self.lambda_rep >= 0.0,
            "lambda_rep",
            self.lambda_rep,
            "lambda_rep >= 0",
        )?;
        if let Some(d) = &self.degradation {
            d.validate()?;
        }
        if let Some(r) = &self.rate_suction {
            check(
                (0.0..=self.f_suc).contains(&r.drained_ratio),
                "rate_suction.drained_ratio",
                r.drained_ratio,
                "a drained suction ratio in [0, f_suc]",
            )?;
            check(
                r.cv > 0.0,
                "rate_suction.cv",
                r.cv,
                "a coefficient of consolidation cv > 0 (m²/s)",
            )?;
            check(
                r.v50 > 0.0,
                "rate_suction.v50",
                r.v50,
                "a normalised velocity V50 > 0",
            )?;
            check(
                r.exponent > 0.0,
                "rate_suction.exponent",
                r.exponent,
                "a backbone exponent c > 0",
            )?;
        }
        Ok(())
    }
}

/// The contact mode of a node (the paper's Figure 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Mode {
    /// No contact: `P = 0`.
    NotInContact,
    /// First, monotonic penetration on the backbone curve.
    InitialPenetration,
    /// Moving up since the last reversal.
    Uplift,
    /// Moving down again after an uplift or a re-contact.
    Repenetration,
}

impl Mode {
    /// The name used in CSV and HDF5 output.
    pub fn name(self) -> &'static str {
        match self {
            Mode::NotInContact => "not_in_contact",
            Mode::InitialPenetration => "initial_penetration",
            Mode::Uplift => "uplift",
            Mode::Repenetration => "repenetration",
        }
    }

    /// A small integer code for compact output (0 to 3, in the order of [`Mode::name`]'s list).
    pub fn code(self) -> u8 {
        match self {
            Mode::NotInContact => 0,
            Mode::InitialPenetration => 1,
            Mode::Uplift => 2,
            Mode::Repenetration => 3,
        }
    }
}

/// Which formula a trial force came from (for tests, plots and diagnostics).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Branch {
    /// `P = 0`.
    NoContact,
    /// Eq. 3, the backbone.
    Backbone,
    /// Eq. 5.
    Uplift,
    /// Eq. 8, the decaying suction floor `P_min`.
    SuctionFloor,
    /// Eq. 10.
    Repenetration,
    /// Eq. 13, the cap `P_max`.
    RepenetrationCap,
    /// The continuity guard: `P` held at `P0`.
    RepenetrationHold,
    /// The optional lift-off smoothing: uplift `P` capped by `P_IP(z)`.
    LiftoffSmoothing,
}

/// The committed history of one node: everything the law needs to evaluate the next trial.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RqHistory {
    /// The mode after the last converged step.
    pub mode: Mode,
    /// Penetration at the last converged step, m.
    pub z_prev: f64,
    /// Resistance at the last converged step, N/m.
    pub p_prev: f64,
    /// Penetration at the start of the current episode, m.
    pub z0: f64,
    /// Resistance at the start of the current episode, N/m.
    pub p0: f64,
    /// `z0` of the preceding uplift (uplift episodes carry their own `z0` here), m.
    pub z_star: Option<f64>,
    /// Where suction starts in the current uplift episode, m (see `z_c_pending`).
    pub z_c: Option<f64>,
    /// `z_c` not computed yet: it is [`RandolphQuiggin::suction_onset`]`(z0, P0)` of the episode,
    /// and no trial has needed it so far (the uplift has not come near it). Computed when a trial
    /// first does, to the same value; most uplifts of a node resting on the seabed reverse long
    /// before (`false` in checkpoints written before the field existed).
    #[serde(default)]
    pub z_c_pending: bool,
    /// Largest penetration ever, statics included, m.
    pub z_max: f64,
    /// Largest penetration at which suction has started in any uplift, m (0 until it first occurs).
    pub z_p0: f64,
    /// Has the node ever been in contact.
    pub contacted: bool,
    /// The soil's degradation at the node ([`crate::degradation`]): intact without the option.
    #[serde(default)]
    pub wear: Wear,
    /// The penetration rate `ż` at the last converged step, m/s (positive down); kept only with
    /// rate-dependent suction (0 otherwise).
    #[serde(default)]
    pub rate: f64,
}

/// The last [`RandolphQuiggin::suction_onset`] a node's trials computed and the committed
/// `(z_prev, P_prev)` it was computed from (their bits): every trial of a step that starts an
/// uplift needs the same onset, from the same committed history, and its scan is the law's most
/// expensive part. A pure cache: a trial with or without it gives the same values to the bit.
/// Scratch of the caller's (one per node), never part of the history.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct OnsetMemo {
    last: Option<([u64; 5], Option<f64>)>,
}

/// What a trial at `z` knows of its uplift's suction onset.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Onset {
    /// The onset ([`RandolphQuiggin::suction_onset`]).
    Known(Option<f64>),
    /// Below `z`, or none: the trial's force does not depend on it.
    Below,
}

impl Onset {
    /// The onset of a scan run to the mudline (which always decides it).
    fn decided(self) -> Option<f64> {
        match self {
            Onset::Known(z_c) => z_c,
            Onset::Below => unreachable!("a scan to the mudline decides the onset"),
        }
    }
}

impl OnsetMemo {
    /// [`RandolphQuiggin::suction_onset`]`(z0, p0)`, from the memo when it holds that pair.
    fn onset(&mut self, law: &RandolphQuiggin, z0: f64, p0: f64) -> Option<f64> {
        self.onset_at(law, z0, p0, f64::NEG_INFINITY).decided()
    }

    /// The onset as far as a trial at `z` needs it ([`RandolphQuiggin::scan_onset`]), from the
    /// memo when it holds that pair; an onset found is kept.
    fn onset_at(&mut self, law: &RandolphQuiggin, z0: f64, p0: f64, z: f64) -> Onset {
        // The law's strength and suction ratio are part of the key: with degradation or
        // rate-dependent suction the same episode start can meet another law.
        let key = [
            z0.to_bits(),
            p0.to_bits(),
            law.p.f_suc.to_bits(),
            law.p.su0.to_bits(),
            law.p.su_gradient.to_bits(),
        ];
        match self.last {
            Some((k, z_c)) if k == key => Onset::Known(z_c),
            _ => {
                let o = law.scan_onset(z0, p0, z);
                if let Onset::Known(z_c) = o {
                    self.last = Some((key, z_c));
                }
                o
            }
        }
    }
}

impl RqHistory {
    /// A node that has never touched the seabed, at penetration `z` (≤ 0 expected).
    pub fn untouched(z: f64) -> Self {
        Self {
            mode: Mode::NotInContact,
            z_prev: z,
            p_prev: 0.0,
            z0: 0.0,
            p0: 0.0,
            z_star: None,
            z_c: None,
            z_c_pending: false,
            z_max: 0.0,
            z_p0: 0.0,
            contacted: false,
            wear: Wear::default(),
            rate: 0.0,
        }
    }
}

impl Default for RqHistory {
    fn default() -> Self {
        Self::untouched(0.0)
    }
}

/// The result of a trial evaluation: the force, its tangent and the history to commit if the step
/// converges.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RqTrial {
    /// Soil resistance `P`, N/m (excludes buoyancy).
    pub p: f64,
    /// `dP/dz`, N/m².
    pub tangent: f64,
    /// The formula `p` came from.
    pub branch: Branch,
    /// The history to commit if the step converges.
    pub next: RqHistory,
}

/// The law with its parameters validated and its constants precomputed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "RqParams", into = "RqParams")]
pub struct RandolphQuiggin {
    p: RqParams,
    /// `Kmax/D`, 1/m.
    k: f64,
    /// `a·0.1^b·sqrt(10/D)`: the shallow bearing factor is `c_shallow·sqrt(z)`.
    c_shallow: f64,
}

impl TryFrom<RqParams> for RandolphQuiggin {
    type Error = ParamError;
    fn try_from(p: RqParams) -> Result<Self, ParamError> {
        Self::new(p)
    }
}

impl From<RandolphQuiggin> for RqParams {
    fn from(l: RandolphQuiggin) -> Self {
        l.p
    }
}

impl RandolphQuiggin {
    /// Validates the parameters and builds the law.
    pub fn new(p: RqParams) -> Result<Self, ParamError> {
        p.validate()?;
        Ok(Self {
            p,
            k: p.k_max / p.diameter,
            c_shallow: p.a * 0.1f64.powf(p.b) * (10.0 / p.diameter).sqrt(),
        })
    }

    /// The parameters.
    pub fn params(&self) -> &RqParams {
        &self.p
    }

    /// Bearing factor `Nc(z)` and `dNc/dz` (1/m). Continuous at `z/D = 0.1`, where its slope jumps.
    #[inline]
    pub fn nc(&self, z: f64) -> (f64, f64) {
        let d = self.p.diameter;
        if z <= 0.0 {
            (0.0, 0.0)
        } else if z >= 0.1 * d {
            let r = z / d;
            // The tables' b = 0.25 by two square roots (a fifth of `powf`'s time; within an ulp).
            let rb = if self.p.b == 0.25 {
                r.sqrt().sqrt()
            } else {
                r.powf(self.p.b)
            };
            let nc = self.p.a * rb;
            (nc, self.p.b * nc / z)
        } else {
            let s = z.sqrt();
            (self.c_shallow * s, 0.5 * self.c_shallow / s)
        }
    }

    /// Ultimate penetration resistance `Pu(z) = Nc·su·D` (N/m) and its derivative (N/m²).
    #[inline]
    pub fn pu(&self, z: f64) -> (f64, f64) {
        if z <= 0.0 {
            return (0.0, 0.0);
        }
        let (nc, dnc) = self.nc(z);
        let su = self.p.su0 + self.p.su_gradient * z;
        let d = self.p.diameter;
        (nc * su * d, (dnc * su + nc * self.p.su_gradient) * d)
    }

    /// The backbone `P_IP(z) = ζ/(1+ζ)·Pu(z)` and its derivative.
    #[inline]
    pub fn p_ip(&self, z: f64) -> (f64, f64) {
        if z <= 0.0 {
            return (0.0, 0.0);
        }
        let (pu, dpu) = self.pu(z);
        let zeta = self.k * z;
        let h = zeta / (1.0 + zeta);
        let dh = self.k / ((1.0 + zeta) * (1.0 + zeta));
        (h * pu, dh * pu + h * dpu)
    }

    /// The history of a node at the start of a dynamic run, from its static penetration `z_s`
    /// (the spec's decision): Initial Penetration at `P_IP(z_s)` if `z_s > 0`, else untouched.
    pub fn start_of_dynamics(&self, z_s: f64) -> RqHistory {
        if z_s > 0.0 {
            RqHistory {
                mode: Mode::InitialPenetration,
                z_prev: z_s,
                p_prev: self.p_ip(z_s).0,
                z0: 0.0,
                p0: 0.0,
                z_star: None,
                z_c: None,
                z_c_pending: false,
                z_max: z_s,
                z_p0: 0.0,
                contacted: true,
                wear: Wear::default(),
                rate: 0.0,
            }
        } else {
            RqHistory::untouched(z_s)
        }
    }

    /// Eq. 5 alone (no suction floor): `P5(z)` and its derivative for an uplift from `(z0, p0)`.
    #[inline]
    fn p5(&self, z0: f64, p0: f64, pu0: f64, z: f64) -> (f64, f64) {
        let (pu, dpu) = self.pu(z);
        let fsuc = self.p.f_suc;
        let b = p0 + fsuc * pu;
        let db = fsuc * dpu;
        if b <= 0.0 || pu0 <= 0.0 {
            return (-fsuc * pu, -fsuc * dpu);
        }
        let u = self.k * (z0 - z);
        let du = -self.k;
        let a = b / pu0;
        let da = db / pu0;
        let den = a + u;
        let h = u / den;
        let dh = (a * du - u * da) / (den * den);
        (p0 - h * b, -(dh * b + h * db))
    }

    /// `z_c`: the first penetration, moving up from `z0`, at which eq. 5 reaches `P = 0`
    /// (`Some(z0)` if `P0 ≤ 0`; `None` if it never does above the mudline).
    ///
    /// Scans in uplift distance from `z0` (steps growing from `10⁻³` to `¼` of `D/Kmax`, and never
    /// below `10⁻⁵·D`, so that the scan advances whatever `Kmax`) and then closes the first sign
    /// change to machine precision by Newton's method kept inside the bracket ([`bracketed_root`]).
    /// A pair of roots closer together than the scan step could be missed; that needs `P5` to graze
    /// zero, where suction is negligible anyway.
    ///
    /// A scan point is evaluated only when `P5` could be `≤ 0` there: with `Pu` increasing in `z`,
    /// at an uplift `u` `P5 ≥ P0 − u/(A_min + u)·B0`, `A_min = P0/Pu(z0)`, `B0 = P0 + f_suc·Pu(z0)`;
    /// while that bound exceeds `10⁻¹²·B0` (far above rounding) the point is passed over. The
    /// scan's points and the bracket it closes are the same, so the onset is the same to the bit
    /// (`the_onset_scan_skips_only_positive_points`).
    pub fn suction_onset(&self, z0: f64, p0: f64) -> Option<f64> {
        self.scan_onset(z0, p0, f64::NEG_INFINITY).decided()
    }

    /// The onset's scan, stopped when it passes below `z` without a sign change: the onset is then
    /// below `z` or absent, which is all a trial at `z` needs ([`Onset::Below`]). Otherwise the
    /// onset of [`RandolphQuiggin::suction_onset`], the same to the bit (the same points, the same
    /// first bracket).
    fn scan_onset(&self, z0: f64, p0: f64, z: f64) -> Onset {
        if p0 <= 0.0 {
            return Onset::Known(Some(z0));
        }
        if self.p.f_suc <= 0.0 {
            // B = P0 > 0, so P5 = P0·(1 − h) > 0 for every finite uplift.
            return Onset::Known(None);
        }
        let pu0 = self.pu(z0).0;
        let unit = 1.0 / self.k;
        let max_step = (0.25 * unit).max(1e-5 * self.p.diameter);
        // Never zero, even when D/Kmax underflows (`hi − 0 = hi` would scan for ever).
        let mut step = (1e-3 * unit).clamp(1e-3 * max_step, max_step);
        let mut hi = z0; // P5(hi) > 0
        let (a_min, b0) = (p0 / pu0, p0 + self.p.f_suc * pu0);
        let positive = |lo: f64| {
            let u = self.k * (z0 - lo);
            pu0 > 0.0 && p0 - u / (a_min + u) * b0 > 1e-12 * b0
        };
        loop {
            if hi <= 0.0 {
                return Onset::Known(None);
            }
            let lo = (hi - step).max(0.0);
            if lo > 0.0 && !positive(lo) && self.p5(z0, p0, pu0, lo).0 <= 0.0 {
                // P5(lo) <= 0 < P5(hi): the root, as the bracket's upper end.
                return Onset::Known(Some(bracketed_root(|z| self.p5(z0, p0, pu0, z), lo, hi)));
            }
            if lo < z {
                // Any root is below lo, so below z.
                return Onset::Below;
            }
            hi = lo;
            step = (step * 2.0).min(max_step);
        }
    }

    /// Uplift from the episode start `(z0, p0)`: `P = max(P5, P_min)` and its tangent.
    /// Returns `(P, dP/dz, branch, z_P0,eff)`.
    fn uplift(
        &self,
        z0: f64,
        p0: f64,
        z_c: Option<f64>,
        z_p0: f64,
        z_max: f64,
        z: f64,
    ) -> (f64, f64, Branch, f64) {
        let pu0 = self.pu(z0).0;
        let (p5, dp5) = self.p5(z0, p0, pu0, z);
        let z_p0_eff = match z_c {
            Some(zc) if z <= zc => z_p0.max(zc),
            _ => z_p0,
        };
        let z_max_eff = z_max.max(z0).max(z);
        let scale = self.p.lambda_suc * z_max_eff;
        let x = (z - z_p0_eff) / scale;
        let (e, de) = if x < 0.0 {
            let e = x.exp();
            (e, e / scale)
        } else {
            (1.0, 0.0)
        };
        let (pu, dpu) = self.pu(z);
        let fsuc = self.p.f_suc;
        let pmin = -e * fsuc * pu;
        let dpmin = -(de * pu + e * dpu) * fsuc;
        let (mut p, mut dp, mut branch) = if p5 >= pmin {
            (p5, dp5, Branch::Uplift)
        } else {
            (pmin, dpmin, Branch::SuctionFloor)
        };
        if self.p.liftoff_smoothing {
            let (pip, dpip) = self.p_ip(z);
            if p > pip {
                (p, dp, branch) = (pip, dpip, Branch::LiftoffSmoothing);
            }
        }
        // The lift-off band: a positive uplift force is taken linearly to zero over the last
        // `LIFTOFF_BAND·D/Kmax` above the mudline, so that the force is continuous at lift-off.
        let band = LIFTOFF_BAND / self.k;
        if p > 0.0 && z < band {
            let s = z / band;
            (p, dp) = (p * s, dp * s + p / band);
        }
        (p, dp, branch, z_p0_eff)
    }

    /// Repenetration from the episode start `(z0, p0)` with the preceding uplift's `z*`:
    /// `P = min(P10, P_max)` (or the held `P0`) and its tangent.
    fn repenetration(
        &self,
        z0: f64,
        p0: f64,
        z_star: Option<f64>,
        z_p0: f64,
        z_max: f64,
        z: f64,
    ) -> (f64, f64, Branch) {
        let (pu, dpu) = self.pu(z);
        let (pus, dpus) = match z_star {
            Some(zs) if p0 > 0.0 => (self.pu(zs).0, 0.0),
            _ => (pu, dpu),
        };
        let c = pu - p0;
        let dc = dpu;
        let (p10, dp10) = if pus > 0.0 && c > 0.0 {
            let a = c / pus;
            let da = dc / pus - c * dpus / (pus * pus);
            let u = self.k * (z - z0);
            let du = self.k;
            let den = a + u;
            let h = u / den;
            let dh = (a * du - u * da) / (den * den);
            (p0 + h * c, dh * c + h * dc)
        } else {
            (pu, dpu)
        };
        let m = z_max.max(z);
        let lsuc = self.p.lambda_suc;
        let x = (z - z_p0) / (lsuc * m) - self.p.lambda_rep;
        let (e, de) = if x < 0.0 {
            let dx = if z > z_max {
                z_p0 / (lsuc * z * z)
            } else {
                1.0 / (lsuc * m)
            };
            let e = x.exp();
            (e, e * dx)
        } else {
            (1.0, 0.0)
        };
        let (pip, dpip) = self.p_ip(z);
        let pmax = e * pip;
        let dpmax = de * pip + e * dpip;
        let (cap, dcap, cap_branch) = if p0 > pmax {
            (p0, 0.0, Branch::RepenetrationHold)
        } else {
            (pmax, dpmax, Branch::RepenetrationCap)
        };
        if p10 <= cap {
            (p10, dp10, Branch::Repenetration)
        } else {
            (cap, dcap, cap_branch)
        }
    }

    /// A trial at penetration `z` from the committed history `h`. Pure: `h` is not touched; the
    /// history to commit, if the step converges, is in the result.
    ///
    /// Transitions, judged against the committed `z_prev`:
    /// - NotInContact: `z ≤ 0` stays; `z > 0` goes to Initial Penetration if never contacted, else to
    ///   Repenetration from `z0 = 0, P0 = 0, z* = none`;
    /// - Initial Penetration or Repenetration: `z < z_prev` starts an uplift at `(z_prev, P_prev)`;
    ///   if also `z ≤ 0`, that uplift ends in lift-off within the same step;
    /// - Uplift: `z > z_prev` starts a repenetration at `(z_prev, P_prev)` with `z* = z0`;
    ///   `z ≤ 0` is lift-off, recording `z_P0 = max(z_P0, z_c)`;
    /// - `z == z_prev` keeps the mode.
    pub fn evaluate(&self, h: &RqHistory, z: f64) -> RqTrial {
        self.evaluate_with(h, z, &mut OnsetMemo::default())
    }

    /// [`RandolphQuiggin::evaluate`], taking the suction onset from `memo` when it holds the one
    /// this history needs (the same values to the bit).
    pub fn evaluate_with(&self, h: &RqHistory, z: f64, memo: &mut OnsetMemo) -> RqTrial {
        self.evaluate_rate(h, z, 0.0, memo)
    }

    /// A trial at penetration `z` moving at `z_rate` (m/s, positive down) from the committed
    /// history: with rate-dependent suction ([`RateSuction`]) the step's suction ratio is that of
    /// the committed uplift velocity (`max(−ż_prev, 0)`: explicit, so that a step's trials share
    /// one law and its tangent is the law's), the episode's suction onset found again for it, and
    /// `z_rate` kept in the next history; without it, `z_rate` is not used.
    pub fn evaluate_rate(
        &self,
        h: &RqHistory,
        z: f64,
        z_rate: f64,
        memo: &mut OnsetMemo,
    ) -> RqTrial {
        let Some(rs) = &self.p.rate_suction else {
            return self.evaluate_soil(h, z, memo);
        };
        let f = rs.ratio((-h.rate).max(0.0), self.p.diameter, self.p.f_suc);
        let law = Self {
            p: RqParams { f_suc: f, ..self.p },
            ..*self
        };
        // The onset depends on the ratio: an uplift finds it again for this step's.
        let h2 = if h.mode == Mode::Uplift {
            RqHistory {
                z_c: None,
                z_c_pending: true,
                ..*h
            }
        } else {
            *h
        };
        let mut t = law.evaluate_soil(&h2, z, memo);
        t.next.rate = z_rate;
        t
    }

    /// The law on the soil as it is: degraded or intact. Inlined into [`Self::evaluate_rate`] (a
    /// call of its own cost the paper's law 2 % of a storm's instructions, issue 31); the
    /// degrading branch stays a call.
    #[inline(always)]
    fn evaluate_soil(&self, h: &RqHistory, z: f64, memo: &mut OnsetMemo) -> RqTrial {
        match &self.p.degradation {
            None => self.evaluate_intact(h, z, memo),
            Some(d) => self.evaluate_degrading(d, h, z, memo),
        }
    }

    /// The law on soil of strength factor `delta` (`su0` and `ρ_su` scaled; every other constant
    /// the same).
    fn weakened(&self, delta: f64) -> Self {
        Self {
            p: RqParams {
                su0: delta * self.p.su0,
                su_gradient: delta * self.p.su_gradient,
                ..self.p
            },
            ..*self
        }
    }

    /// A trial with cyclic degradation ([`crate::degradation`]): the episode's strength factor is
    /// set from the committed `ξ` when the trial starts an episode (a reversal or a re-contact) and
    /// kept otherwise; the paper's law runs on that strength; the step's plastic displacement is
    /// added to `ξ` in the next history.
    #[inline(never)]
    fn evaluate_degrading(
        &self,
        d: &Degradation,
        h: &RqHistory,
        z: f64,
        memo: &mut OnsetMemo,
    ) -> RqTrial {
        let starts = match h.mode {
            Mode::NotInContact => z > 0.0,
            Mode::InitialPenetration | Mode::Repenetration => z < h.z_prev,
            Mode::Uplift => z > h.z_prev,
        };
        let strength = if starts {
            d.strength(h.wear.xi)
        } else {
            h.wear.strength
        };
        let law = self.weakened(strength);
        let mut t = law.evaluate_intact(h, z, memo);
        let (z1, z2) = (h.z_prev.max(0.0), z.max(0.0));
        let dz = z2 - z1;
        let z_ref = z1.max(z2).max(t.next.z0).max(t.next.z_star.unwrap_or(0.0));
        let k_e = law.k * law.pu(z_ref).0;
        let plastic = if k_e > 0.0 {
            (dz - (t.p - h.p_prev) / k_e).abs().min(dz.abs())
        } else {
            dz.abs()
        };
        t.next.wear = Wear {
            xi: h.wear.xi + plastic / self.p.diameter,
            strength,
        };
        t
    }

    /// The history of a node after a rest of `t` seconds (a calm interval): with regain, the lost
    /// strength recovered by `U(t)` ([`Degradation::rested`]), in force from the node's next
    /// episode; otherwise unchanged.
    pub fn rest(&self, h: &RqHistory, t: f64) -> RqHistory {
        match &self.p.degradation {
            Some(d) => RqHistory {
                wear: Wear {
                    xi: d.rested(h.wear.xi, t),
                    ..h.wear
                },
                ..*h
            },
            None => *h,
        }
    }

    /// The paper's law (no degradation) from the committed history.
    fn evaluate_intact(&self, h: &RqHistory, z: f64, memo: &mut OnsetMemo) -> RqTrial {
        match h.mode {
            Mode::NotInContact => {
                if z <= 0.0 {
                    self.lift_off(h, h.z_p0, z)
                } else if !h.contacted {
                    self.backbone(h, z)
                } else {
                    self.repen_trial(h, 0.0, 0.0, None, z)
                }
            }
            Mode::InitialPenetration | Mode::Repenetration => {
                if z < h.z_prev {
                    if z <= 0.0 {
                        let z_c = memo.onset(self, h.z_prev, h.p_prev);
                        let z_p0 = z_c.map_or(h.z_p0, |zc| h.z_p0.max(zc));
                        self.lift_off(h, z_p0, z)
                    } else {
                        let onset = memo.onset_at(self, h.z_prev, h.p_prev, z);
                        self.uplift_trial(h, h.z_prev, h.p_prev, onset, z)
                    }
                } else if h.mode == Mode::InitialPenetration {
                    self.backbone(h, z)
                } else {
                    self.repen_trial(h, h.z0, h.p0, h.z_star, z)
                }
            }
            Mode::Uplift => {
                if z > h.z_prev {
                    self.repen_trial(h, h.z_prev, h.p_prev, Some(h.z0), z)
                } else if z <= 0.0 {
                    let z_c = if h.z_c_pending {
                        memo.onset(self, h.z0, h.p0)
                    } else {
                        h.z_c
                    };
                    let z_p0 = z_c.map_or(h.z_p0, |zc| h.z_p0.max(zc));
                    self.lift_off(h, z_p0, z)
                } else {
                    let onset = if h.z_c_pending {
                        memo.onset_at(self, h.z0, h.p0, z)
                    } else {
                        Onset::Known(h.z_c)
                    };
                    self.uplift_trial(h, h.z0, h.p0, onset, z)
                }
            }
        }
    }

    fn lift_off(&self, h: &RqHistory, z_p0: f64, z: f64) -> RqTrial {
        RqTrial {
            p: 0.0,
            tangent: 0.0,
            branch: Branch::NoContact,
            next: RqHistory {
                mode: Mode::NotInContact,
                z_prev: z,
                p_prev: 0.0,
                z0: 0.0,
                p0: 0.0,
                z_star: None,
                z_c: None,
                z_c_pending: false,
                z_max: h.z_max,
                z_p0,
                contacted: h.contacted,
                wear: h.wear,
                rate: h.rate,
            },
        }
    }

    fn backbone(&self, h: &RqHistory, z: f64) -> RqTrial {
        let (p, tangent) = self.p_ip(z);
        RqTrial {
            p,
            tangent,
            branch: Branch::Backbone,
            next: RqHistory {
                mode: Mode::InitialPenetration,
                z_prev: z,
                p_prev: p,
                z0: 0.0,
                p0: 0.0,
                z_star: None,
                z_c: None,
                z_c_pending: false,
                z_max: h.z_max.max(z),
                z_p0: h.z_p0,
                contacted: true,
                wear: h.wear,
                rate: h.rate,
            },
        }
    }

    fn uplift_trial(&self, h: &RqHistory, z0: f64, p0: f64, onset: Onset, z: f64) -> RqTrial {
        // An onset below z leaves the force as no onset does; it stays to be found.
        let (z_c, z_c_pending) = match onset {
            Onset::Known(z_c) => (z_c, false),
            Onset::Below => (None, true),
        };
        let (p, tangent, branch, z_p0) = self.uplift(z0, p0, z_c, h.z_p0, h.z_max, z);
        RqTrial {
            p,
            tangent,
            branch,
            next: RqHistory {
                mode: Mode::Uplift,
                z_prev: z,
                p_prev: p,
                z0,
                p0,
                z_star: Some(z0),
                z_c,
                z_c_pending,
                z_max: h.z_max.max(z),
                z_p0,
                contacted: true,
                wear: h.wear,
                rate: h.rate,
            },
        }
    }

    fn repen_trial(&self, h: &RqHistory, z0: f64, p0: f64, z_star: Option<f64>, z: f64) -> RqTrial {
        let (p, tangent, branch) = self.repenetration(z0, p0, z_star, h.z_p0, h.z_max, z);
        RqTrial {
            p,
            tangent,
            branch,
            next: RqHistory {
                mode: Mode::Repenetration,
                z_prev: z,
                p_prev: p,
                z0,
                p0,
                z_star,
                z_c: None,
                z_c_pending: false,
                z_max: h.z_max.max(z),
                z_p0: h.z_p0,
                contacted: true,
                wear: h.wear,
                rate: h.rate,
            },
        }
    }
}

pub use crate::roots::bracketed_root;

#[cfg(test)]
mod onset_tests {
    use super::*;
    use crate::roots::bracketed_root;

    /// The scan as it was before points were passed over: every point evaluated.
    fn onset_every_point(l: &RandolphQuiggin, z0: f64, p0: f64) -> Option<f64> {
        if p0 <= 0.0 {
            return Some(z0);
        }
        if l.p.f_suc <= 0.0 {
            return None;
        }
        let pu0 = l.pu(z0).0;
        let unit = 1.0 / l.k;
        let max_step = (0.25 * unit).max(1e-5 * l.p.diameter);
        let mut step = (1e-3 * unit).clamp(1e-3 * max_step, max_step);
        let mut hi = z0;
        loop {
            if hi <= 0.0 {
                return None;
            }
            let lo = (hi - step).max(0.0);
            if lo > 0.0 && l.p5(z0, p0, pu0, lo).0 <= 0.0 {
                return Some(bracketed_root(|z| l.p5(z0, p0, pu0, z), lo, hi));
            }
            hi = lo;
            step = (step * 2.0).min(max_step);
        }
    }

    /// Over soils from Table 1's to a stiff clay with zero surface strength, suction factors from
    /// 0.05 to 1, episode starts from a hundredth of D to one D deep and resistances from a
    /// thousandth of `Pu` to above it: the onset is the one of the scan that evaluates every point,
    /// to the bit.
    #[test]
    fn the_onset_scan_skips_only_positive_points() {
        let mut cases = 0;
        for (su0, gradient, b, k_max) in [
            (1000.0, 1300.0, 0.25, 200.0),
            (0.0, 6000.0, 0.35, 400.0),
            (5000.0, 0.0, 0.15, 100.0),
        ] {
            for f_suc in [0.05, 0.2, 0.6, 1.0] {
                for lambda_suc in [0.2, 1.0] {
                    let l = RandolphQuiggin::new(RqParams {
                        su0,
                        su_gradient: gradient,
                        b,
                        k_max,
                        f_suc,
                        lambda_suc,
                        ..RqParams::table1()
                    })
                    .expect("valid");
                    let d = l.p.diameter;
                    for z0 in [0.01 * d, 0.1 * d, 0.37 * d, d] {
                        let pu0 = l.pu(z0).0;
                        for share in [1e-3, 0.1, 0.5, 0.9, 1.0, 1.3] {
                            let p0 = share * pu0;
                            let (new, old) =
                                (l.suction_onset(z0, p0), onset_every_point(&l, z0, p0));
                            assert_eq!(new.map(f64::to_bits), old.map(f64::to_bits), "{z0} {p0}");
                            cases += usize::from(old.is_some());
                        }
                    }
                }
            }
        }
        assert!(cases > 200, "{cases} onsets found");
    }

    /// An uplift whose onset is still to be found gives, at every penetration (above the onset,
    /// past it, in the lift-off band, lifted off), the force, tangent, branch and next history of
    /// the same uplift with its onset computed at the start, to the bit; it finds the onset when a
    /// trial first needs it.
    #[test]
    fn a_pending_onset_is_the_onset() {
        for f_suc in [0.2, 0.6, 1.0] {
            let l = RandolphQuiggin::new(RqParams {
                f_suc,
                ..RqParams::table1()
            })
            .expect("valid");
            let z0 = 0.05;
            let p0 = l.p_ip(z0).0;
            let z_c = l.suction_onset(z0, p0);
            assert!(z_c.is_some());
            let eager = RqHistory {
                mode: Mode::Uplift,
                z_prev: z0,
                p_prev: p0,
                z0,
                p0,
                z_star: Some(z0),
                z_c,
                z_max: z0,
                contacted: true,
                ..RqHistory::untouched(0.0)
            };
            let lazy = RqHistory {
                z_c: None,
                z_c_pending: true,
                ..eager
            };
            let mut found = 0;
            for k in 0..=60 {
                let z = z0 * (1.0 - k as f64 / 50.0);
                let (e, p) = (l.evaluate(&eager, z), l.evaluate(&lazy, z));
                assert_eq!(p.p.to_bits(), e.p.to_bits(), "{k}");
                assert_eq!(p.tangent.to_bits(), e.tangent.to_bits(), "{k}");
                assert_eq!(p.branch, e.branch, "{k}");
                let mut n = p.next;
                if n.z_c_pending {
                    assert!(z > z_c.expect("onset"), "pending at {z}, past the onset");
                    (n.z_c, n.z_c_pending) = (e.next.z_c, false);
                } else {
                    found += 1;
                }
                assert_eq!(n, e.next, "{k}");
            }
            assert!(found > 10, "{found}");
        }
    }
}
