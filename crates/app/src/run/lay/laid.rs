//! What a lay records: the series of each record (`LayRecords`), what each material point of the
//! pipe went through (`LaidNodes`), and the numbers of the lay (`LaySummary`).
//!
//! **As-laid embedment.** A node's penetration of the invert (positive down) at rest after the
//! touchdown has passed: taken when the node is frozen (it lies at least `freeze_behind` behind
//! the touchdown and moved less than `freeze_tolerance` over the last payout of one element), or
//! at the end of the run for a node that lies that far behind the touchdown but still moves.
//!
//! **Steady part.** The nodes off the seabed at the start (on the vessel or in the free span)
//! that were laid.
//!
//! **Lay factor.** The largest seabed contact force per unit length a node felt, over the
//! submerged weight per unit length `W'` (the touchdown lay factor of Randolph & White 2008). The
//! **dynamic embedment factor** is the mean as-laid embedment over the self-weight embedment
//! `z(W')` of the backbone.
//!
//! **Uplift–repenetration episodes.** The times a node's seabed history entered repenetration
//! (from uplift or from out of contact) after an uplift of at least 0.1 % of the diameter since
//! the uplift began (smaller reversals are the solver's tolerance, not the sea's motion).

use catena_fe::assembly::LineResults;
use catena_fe::model::LineModel;
use catena_seabed::law::SeabedHistory;
use catena_seabed::rq::Mode;
use serde::Serialize;

/// The series recorded every `output_interval`.
#[derive(Debug, Clone, Default, Serialize)]
pub struct LayRecords {
    /// Time, s.
    pub time: Vec<f64>,
    /// Pipe paid out through the tower's exit since the start, m.
    pub paid_out: Vec<f64>,
    /// The vessel's travel along +x since the start, m.
    pub vessel_x: Vec<f64>,
    /// Top tension (the tower's reaction), N.
    pub top_tension: Vec<f64>,
    /// Payout rate, m/s (negative: paid in).
    pub payout_rate: Vec<f64>,
    /// x of the touchdown point (the first node from the top in contact), m (NaN: none).
    pub touchdown_x: Vec<f64>,
    /// Unstretched arc length from the tower's exit to the touchdown point, m.
    pub touchdown_arc: Vec<f64>,
    /// Nodes in the solve.
    pub window_nodes: Vec<f64>,
    /// The sag bend's moment (the most negative moment of the free span), N·m.
    pub sag_moment: Vec<f64>,
}

/// What each material node of the pipe went through (node 0 the pipe's last end, on the vessel).
#[derive(Debug, Clone, Serialize)]
pub struct LaidNodes {
    /// Unstretched arc length from the pipe's last end, m.
    pub arc: Vec<f64>,
    /// Unstretched distance from the initiation anchor along the pipe (KP), m.
    pub kp: Vec<f64>,
    /// As-laid embedment of the invert, m, positive down (NaN: not laid).
    pub as_laid: Vec<f64>,
    /// x where the node came to rest, m (NaN: not laid).
    pub laid_x: Vec<f64>,
    /// The largest seabed contact force per unit length the node felt, N/m.
    pub max_contact: Vec<f64>,
    /// Uplift–repenetration episodes.
    pub episodes: Vec<u32>,
    /// The soil strength factor at rest (1: intact; NaN without degradation or contact).
    pub strength: Vec<f64>,
    /// Whether the node was off the seabed at the start (on the vessel or in the free span): the
    /// steady part is made of the laid ones.
    pub landed: Vec<bool>,
    #[serde(skip)]
    pub(super) last_mode: Vec<u8>,
    /// The penetration where the current uplift began.
    #[serde(skip)]
    pub(super) uplift_from: Vec<f64>,
    /// The pipe's last end's node: the nodes above it are a lay-down's wire, never laid.
    pub pipe_end: usize,
}

impl LaidNodes {
    /// The nodes of the mesh `full`, the first `o` of them on the vessel at the start (from
    /// `pipe_end` on, the pipe; a lay-down's wire above), the others those of the statics with
    /// these contact forces.
    pub fn new(full: &LineModel, (o, pipe_end): (usize, usize), static_contact: &[f64]) -> Self {
        let n = full.nodes();
        let total = full.length();
        Self {
            arc: full.arc.clone(),
            kp: full.arc.iter().map(|a| total - a).collect(),
            as_laid: vec![f64::NAN; n],
            laid_x: vec![f64::NAN; n],
            max_contact: vec![0.0; n],
            episodes: vec![0; n],
            strength: vec![f64::NAN; n],
            landed: (0..n)
                .map(|i| i < o || static_contact.get(i - o).is_some_and(|&p| p <= 0.0))
                .collect(),
            last_mode: vec![0; n],
            uplift_from: vec![0.0; n],
            pipe_end,
        }
    }

    /// Takes a converged step of the window from material node `first`: contact forces and
    /// episodes (an uplift counts when it reached `min_uplift`, m).
    pub fn observe(&mut self, first: usize, res: &LineResults, min_uplift: f64) {
        let (up, rep) = (Mode::Uplift.code(), Mode::Repenetration.code());
        for (i, (&p, &mode)) in res.seabed_force.iter().zip(&res.mode).enumerate() {
            let g = first + i;
            if p > self.max_contact[g] {
                self.max_contact[g] = p;
            }
            let last = self.last_mode[g];
            let z = res.penetration[i];
            if mode == up && last != up {
                self.uplift_from[g] = z;
            }
            if mode == rep && last != rep && last != 0 {
                // The uplift's lowest point is now (the reversal): its size since it began.
                if self.uplift_from[g] - z >= min_uplift {
                    self.episodes[g] += 1;
                }
            }
            self.last_mode[g] = mode;
        }
    }

    /// Records node `g` as laid at `(x, z)` with its history: the penetration of the invert of the
    /// pipe below the node (the node at the pipe's end, between the pipe and a lay-down's wire,
    /// has the mean of their diameters for its contact; its as-laid embedment is the pipe's).
    pub fn lay(&mut self, full: &LineModel, g: usize, (x, z): (f64, f64), h: &SeabedHistory) {
        if g < self.pipe_end {
            return;
        }
        let d = super::frames::contact_od(full, g);
        self.as_laid[g] = full
            .penetration(g, x, z)
            .map_or(f64::NAN, |p| p + 0.5 * (d - full.node_od[g]));
        self.laid_x[g] = x;
        if let SeabedHistory::RandolphQuiggin(r) = h {
            if r.contacted && r.wear.xi > 0.0 {
                self.strength[g] = r.wear.strength;
            }
        }
    }
}

/// The numbers of a lay (`summary.json` `lay`).
#[derive(Debug, Clone, Default, Serialize)]
pub struct LaySummary {
    /// Pipe paid out, m.
    pub paid_out: f64,
    /// The vessel's travel, m.
    pub vessel_travel: f64,
    /// Nodes laid in the steady part (paid out during the lay and come to rest).
    pub steady_nodes: usize,
    /// As-laid embedment over the steady part: mean, smallest, largest, m.
    pub as_laid_mean: f64,
    /// Smallest, m.
    pub as_laid_min: f64,
    /// Largest, m.
    pub as_laid_max: f64,
    /// Submerged weight per unit length, N/m.
    pub submerged_weight: f64,
    /// The self-weight embedment `z(W')` on the backbone, m.
    pub self_weight_embedment: f64,
    /// The static embedment with force concentration: `z` at the statics' largest contact force, m.
    pub static_embedment: f64,
    /// The statics' largest contact force over `W'`.
    pub static_lay_factor: f64,
    /// The touchdown lay factor: the largest contact force a steady node felt over `W'`.
    pub lay_factor: f64,
    /// Randolph & White (2008), DNV-RP-F114 §4.2.5.2: `0.6 + 0.4 λ^0.25`, `λ = EI·k/T0²`, with k the
    /// backbone's secant at the embedment under the factored force (implicit; 1 ≤ k_lay ≤ 3).
    pub lay_factor_closed_form: f64,
    /// `λ = EI·k/T0²` of the closed form.
    pub lambda: f64,
    /// The dynamic embedment factor: mean as-laid over self-weight embedment.
    pub dynamic_embedment_factor: f64,
    /// Top tension: smallest, largest, N.
    pub top_tension_min: f64,
    /// Largest, N.
    pub top_tension_max: f64,
    /// The sag bend's largest moment (magnitude of the most negative), N·m.
    pub sag_moment_max: f64,
    /// The sag bend's largest strain: bending `|M|·D/(2EI)` plus axial `T/EA` there.
    pub sag_strain_max: f64,
    /// Mean uplift–repenetration episodes per steady node.
    pub episodes_mean: f64,
}

/// Mean, smallest and largest of the finite values.
pub fn stats(v: impl Iterator<Item = f64>) -> (f64, f64, f64, usize) {
    let (mut s, mut lo, mut hi, mut n) = (0.0, f64::INFINITY, f64::NEG_INFINITY, 0);
    for x in v.filter(|x| x.is_finite()) {
        s += x;
        lo = lo.min(x);
        hi = hi.max(x);
        n += 1;
    }
    if n == 0 {
        (f64::NAN, f64::NAN, f64::NAN, 0)
    } else {
        (s / n as f64, lo, hi, n)
    }
}
